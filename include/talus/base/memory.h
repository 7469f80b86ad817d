#pragma once

#include <string>

namespace talus
{

/// Memory this process may still take (bytes): the operating system's
/// available memory (MemAvailable of /proc/meminfo), or less when an
/// address-space or data-size limit (ulimit -v, -d) leaves less room above
/// what the process already uses. A very large number when none is known.
double available_memory();

/// The most resident memory this process has held so far (bytes; VmHWM of
/// /proc/self/status), 0 when the system does not say.
double peak_memory();

/// Bytes as a message shows them: "1.5 GB", "320 MB", "12 kB".
std::string memory_text(double bytes);

} // namespace talus
