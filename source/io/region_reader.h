#pragma once

// Private to source/io: the region entries that 'Excavation N' and 'Group
// N' share ('Shape' and what each shape takes).

#include <talus/geometry/region.h>

#include "parameter_file.h"

#include <string>

namespace talus
{

/// Declares 'Shape' (box, cylinder, half-space, polyhedron, prism) and the
/// entries of each in the current subsection; `what` ends the sentences
/// that document them ("the region to remove").
void declare_region(ParameterFile& prm, const std::string& what);

/// Reads the region of the current subsection, checked; `brick` bounds a
/// half-space or polyhedron; `description` says what it is for the summary.
ConvexRegion parse_region(const ParameterFile& prm, const Box& brick, std::string& description);

} // namespace talus
