#pragma once

#include <talus/zone/stress_batch.h>
#include <talus/zone/zone_material.h>

namespace talus
{

/// Isotropic incremental elasticity (eq. 59) for every zone of the batch:
/// stress += lambda tr(deps) I + 2 G deps, with lambda = K - 2G/3 (Pa).
/// Leaves `state` and `plastic_volumetric` alone.
void elastic_update(const ZoneMaterial& material, StressBatch& batch);

/// Mohr-Coulomb with tension cut-off and non-associated flow for every zone
/// of the batch: elastic trial (eq. 59), then a plastic correction in
/// principal stress space (shear yield surface, tension cut-off, and their
/// edges and corners) and rotation back to the zone's axes. Sets the state
/// flags when `state` is given (the "past" flags are sticky) and writes the
/// trace of this step's plastic strain increment to `plastic_volumetric`
/// when given (dilation positive, zero for an elastic step).
void mohr_coulomb_update(const ZoneMaterial& material, StressBatch& batch);

/// Applies the material's zone model to the whole batch: the model is
/// chosen here once, so the loop over zones inside each model has no
/// dispatch.
void apply_zone_model(const ZoneMaterial& material, StressBatch& batch);

} // namespace talus
