#pragma once

// Private to source/io: the entries of an input that varies in time, which
// 'Boundary N' and 'Load N' share ('Time function' and what each takes).

#include <talus/model/time_history.h>

#include "parameter_file.h"

#include <string>

namespace talus
{

/// Declares 'Time function' and its entries in the current subsection;
/// `what` names the constant that the function multiplies ("'Velocity'").
void declare_time_function(ParameterFile& prm, const std::string& what);

/// Reads the time function of the current subsection, checked: a table
/// from its CSV file (relative to the folder of the file that names it:
/// the parameter file or one it includes), a harmonic or a pulse,
/// integrated when 'Input = acceleration'.
/// `acceleration_allowed`: the input drives a velocity (otherwise an
/// acceleration input is refused, with `why_not` as the allowed values).
TimeFunction parse_time_function(const ParameterFile& prm, bool acceleration_allowed,
                                 const std::string& why_not);

} // namespace talus
