#include <talus/base/exceptions.h>
#include <talus/io/file_output.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>
#include <unistd.h>

namespace talus
{

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write)
{
  // Same folder as the target, so that the rename cannot cross file systems;
  // the process id keeps two runs writing into one folder apart.
  const std::string temporary = path + ".tmp" + std::to_string(::getpid());
  try
  {
    std::ofstream out(temporary, std::ios::binary);
    if (!out)
      throw InputError(path + ": cannot create the file (" + std::strerror(errno) + ")");
    write(out);
    out.close();
    if (!out)
      throw InputError(path + ": writing failed (disk full?)");
  }
  catch (...)
  {
    std::remove(temporary.c_str()); // the old file, if any, stays as it was
    throw;
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0)
  {
    const int error = errno;
    std::remove(temporary.c_str());
    throw InputError(path + ": cannot replace the file (" + std::strerror(error) + ")");
  }
}

void prepare_output_directory(const std::string& directory)
{
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  if (ec || !std::filesystem::is_directory(directory))
    throw InputError(directory + ": cannot create the output folder (" +
                     (ec ? ec.message() : std::string("a file of that name exists")) + ")");
  if (::access(directory.c_str(), W_OK) != 0)
    throw InputError(directory + ": the output folder is not writable");
  remove_stale_temporaries(directory);
}

unsigned int remove_stale_temporaries(const std::string& directory)
{
  // write_file_atomically names its temporaries <file>.tmp<pid>; one whose
  // process is gone was left by a run killed while writing (kill -9).
  unsigned int removed = 0;
  std::error_code ec;
  for (std::filesystem::directory_iterator it(directory, ec), end; !ec && it != end;
       it.increment(ec))
  {
    const std::string name = it->path().filename().string();
    const std::size_t at = name.rfind(".tmp");
    if (at == std::string::npos || at + 4 == name.size() ||
        name.find_first_not_of("0123456789", at + 4) != std::string::npos ||
        name.size() - at - 4 > 9)
      continue;
    const pid_t pid = static_cast<pid_t>(std::stol(name.substr(at + 4)));
    if (pid <= 0 || pid == ::getpid() || ::kill(pid, 0) == 0 || errno != ESRCH)
      continue;
    std::error_code remove_error;
    if (it->is_regular_file(remove_error) && std::filesystem::remove(it->path(), remove_error))
      ++removed;
  }
  return removed;
}

} // namespace talus
