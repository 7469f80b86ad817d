#pragma once

// Private to source/io: the entries of 'Stage N' (what changes at a stage's
// start and how its calculation runs) and its nested 'Excavation M'.

#include <talus/scene/scene.h>

#include "parameter_file.h"

#include <string>
#include <vector>

namespace talus
{

/// Declares the entries of stage `section` and of the excavations
/// `excavations` nested in it.
void declare_stage(ParameterFile& prm, const std::string& section,
                   const std::vector<std::string>& excavations);

/// Reads stage `section` into scene.stages (after 'Solver', whose values
/// the stage's unset entries take, and after the joint sets and joints).
void parse_stage(ParameterFile& prm, const std::string& section,
                 const std::vector<std::string>& excavations, Scene& scene);

/// Reads the 'Rock materials' of stage `section` into `stage` (after the
/// 'Rock material N', whose names it takes).
void parse_stage_rock_materials(ParameterFile& prm, const std::string& section, Scene& scene,
                                StageSpec& stage);

} // namespace talus
