#pragma once

#include <functional>
#include <iosfwd>
#include <string>

namespace talus
{

/// Writes a file all at once or not at all: the content goes to a temporary
/// file beside the target, which is renamed over it only when complete, so a
/// killed run never leaves a half-written file. Throws InputError naming the
/// file when it cannot be written.
void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write);

/// Creates `directory` (and parents) if needed and checks that it is
/// writable; throws InputError naming it otherwise.
/// Also removes the temporaries of killed runs (remove_stale_temporaries).
void prepare_output_directory(const std::string& directory);

/// Removes the files `<name>.tmp<pid>` in `directory` whose process no
/// longer runs: write_file_atomically's temporaries of a run killed while
/// writing (kill -9). Returns how many were removed.
unsigned int remove_stale_temporaries(const std::string& directory);

} // namespace talus
