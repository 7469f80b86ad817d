#include <talus/base/exceptions.h>
#include <talus/base/memory.h>

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace talus
{

namespace
{
/// The kB value of `key` in a /proc file such as /proc/meminfo, in bytes;
/// negative when absent.
double proc_value(const char* file, const std::string& key)
{
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);)
    if (line.rfind(key + ":", 0) == 0)
    {
      std::istringstream fields(line.substr(key.size() + 1));
      double kb = -1.0;
      fields >> kb;
      return kb * 1024.0;
    }
  return -1.0;
}
} // namespace

double available_memory()
{
  double room = proc_value("/proc/meminfo", "MemAvailable");
  if (room < 0.0)
    room = 1e300;
  // A limit counts against what the process has already taken.
  for (const auto& [resource, used_key] :
       {std::make_pair(RLIMIT_AS, "VmSize"), std::make_pair(RLIMIT_DATA, "VmData")})
  {
    rlimit limit{};
    if (getrlimit(resource, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
      room = std::min(room, static_cast<double>(limit.rlim_cur) -
                                std::max(0.0, proc_value("/proc/self/status", used_key)));
  }
  return std::max(room, 0.0);
}

std::string memory_text(double bytes)
{
  const char* unit[] = {"bytes", "kB", "MB", "GB", "TB"};
  int u = 0;
  while (bytes >= 1000.0 && u < 4)
  {
    bytes /= 1000.0;
    ++u;
  }
  char text[32];
  std::snprintf(text, sizeof text, u == 0 ? "%.0f %s" : "%.3g %s", bytes, unit[u]);
  return text;
}

double peak_memory()
{
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0)
      return 1024.0 * std::strtod(line.c_str() + 6, nullptr); // given in kB
  return 0.0;
}

} // namespace talus
