#pragma once

#include <talus/zone/stress_batch.h>
#include <talus/zone/zone_material.h>

namespace talus
{

/// Eq. 59: incremental isotropic elasticity on a batch of zones.
void elastic_update(const ZoneMaterial& material, StressBatch& batch);

/// Applies the material's zone model to a whole batch (chosen once per
/// batch).
void apply_zone_model(const ZoneMaterial& material, StressBatch& batch);

} // namespace talus
