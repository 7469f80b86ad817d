#include <talus/base/exceptions.h>

#include <cstdio>

namespace talus
{

InputError InputError::at(const std::string& file, unsigned int line, const std::string& section,
                          const std::string& entry, const std::string& problem,
                          const std::string& allowed)
{
  std::string where = file;
  if (line > 0)
    where += ":" + std::to_string(line);
  std::string what = where + ": entry '" + entry + "'";
  if (!section.empty())
    what += " in subsection '" + section + "'";
  what += ": " + problem;
  if (!allowed.empty())
    what += "; allowed: " + allowed;
  return InputError(what);
}

std::string number(double x)
{
  char text[32];
  std::snprintf(text, sizeof text, "%g", x);
  return text;
}

} // namespace talus
