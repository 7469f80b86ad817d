#pragma once

// Private to source/io: the 'Water' subsection (the phreatic surface and the
// water's density), read into scene.solver.water.

#include <talus/scene/scene.h>

#include "parameter_file.h"

namespace talus
{

void declare_water(ParameterFile& prm);
/// Reads 'Water' into scene.solver.water, checked; after 'Solver' (it takes
/// the gravity's magnitude from there), the joints and 'Deformable'.
void parse_water(ParameterFile& prm, Scene& scene);
/// The same into `w`, from the 'Water' inside the current subsection (a
/// stage's).
void parse_water(ParameterFile& prm, const Scene& scene, WaterSpec& w);

} // namespace talus
