#pragma once

// Private to source/io: the zone constitutive entries (of 'Deformable' and
// of 'Rock material N') and the named rock materials: density for rigid and
// deformable blocks, and the zone model and constants for deformable ones,
// per group.

#include <talus/scene/scene.h>

#include "parameter_file.h"

#include <string>

namespace talus
{

/// Declares 'Zone model', 'Young's modulus', 'Poisson's ratio', 'Friction
/// angle', 'Dilation angle', 'Cohesion' and 'Tensile strength' in the
/// current subsection.
void declare_zone_constants(ParameterFile& prm);
/// Reads them into `m`, checked; with `inherit`, an entry the file does not
/// set in `section` keeps the value `m` has.
void parse_zone_constants(ParameterFile& prm, const std::string& section, ZoneMaterial& m,
                          bool inherit);

void declare_rock_material(ParameterFile& prm, const std::string& section);
/// Adds 'Rock material N' to the scene: its density defaults to that of
/// 'Material', its zone constants to those of 'Deformable' (so it must be
/// read after both).
void parse_rock_material(ParameterFile& prm, const std::string& section, Scene& scene);

} // namespace talus
