#pragma once

// Private to source/io: the entries of 'Joint properties' and of the named
// joint materials ('Joint material N'), and the rules that give contacts
// their material ('Material' of 'Joint set N' and 'Joint N', and 'Group
// contact N').

#include <talus/scene/scene.h>

#include "parameter_file.h"

#include <string>
#include <vector>

namespace talus
{

/// Declares the Coulomb-slip entries in the current subsection.
void declare_joint_properties(ParameterFile& prm);
/// Reads them from the current subsection; an entry the file does not set
/// takes its value from `inherit` (when given) instead of the default.
JointProperties parse_joint_properties(ParameterFile& prm, const std::string& section,
                                       const JointProperties* inherit);

void declare_joint_material(ParameterFile& prm, const std::string& section);
/// Adds the material of 'Joint material N' to the scene (its name and
/// properties, which default to those of 'Joint properties').
void parse_joint_material(ParameterFile& prm, const std::string& section, Scene& scene);

/// 'Material' of a joint set or single joint (in the current subsection).
void declare_joint_material_entry(ParameterFile& prm);
/// The material index that entry names (JointMaterialRule::none when
/// empty); refuses an unknown name.
unsigned char parse_joint_material_entry(ParameterFile& prm, const Scene& scene);

/// Throws unless `name` is the default group or a 'Group N' name; `entry`
/// is the entry of the current subsection that names it (scene_reader.cc).
void check_group_name(const ParameterFile& prm, const std::string& entry, const Scene& scene,
                      const std::string& name);

void declare_group_contact(ParameterFile& prm, const std::string& section);
void parse_group_contact(ParameterFile& prm, const std::string& section, Scene& scene);

} // namespace talus
