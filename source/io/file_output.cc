#include <talus/base/exceptions.h>
#include <talus/io/file_output.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <system_error>
#include <unistd.h>

namespace talus
{

void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write)
{
  const std::string temporary = path + ".tmp" + std::to_string(::getpid());
  {
    std::ofstream out(temporary, std::ios::binary);
    if (!out)
      throw InputError(path + ": cannot create the file (is its folder writable?)");
    write(out);
    out.flush();
    if (!out)
    {
      out.close();
      std::remove(temporary.c_str());
      throw InputError(path + ": writing failed (disk full?)");
    }
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0)
  {
    std::remove(temporary.c_str());
    throw InputError(path + ": cannot replace the file");
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
