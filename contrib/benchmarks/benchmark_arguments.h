#pragma once

// The benchmarks' command-line numbers: a whole number within the range the
// benchmark can run, or one line saying which argument is wrong and what is
// allowed, and exit status 2. (Without this check a step count of 0, or a
// word where a number belongs, read as 0 and ran forever.)

#include <cerrno>
#include <cstdio>
#include <cstdlib>

namespace talus
{

inline unsigned long whole_argument(const char* program, const char* text, const char* what,
                                    unsigned long least, unsigned long most)
{
  char* end = nullptr;
  errno = 0;
  const unsigned long value = std::strtoul(text, &end, 10);
  if (end == text || *end != '\0' || errno != 0 || text[0] == '-' || value < least || value > most)
  {
    std::fprintf(stderr, "%s: argument '%s': %s must be a whole number from %lu to %lu\n", program,
                 text, what, least, most);
    std::exit(2);
  }
  return value;
}

} // namespace talus
