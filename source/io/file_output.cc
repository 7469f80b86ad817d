#include <talus/base/exceptions.h>
#include <talus/io/file_output.h>

#include <cerrno>
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
}

} // namespace talus
