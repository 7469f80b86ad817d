// Output is written atomically: a writer that fails part-way leaves the old
// file as it was and no temporary file; a file that cannot be put in place is
// refused with its name and the reason; a history on disk is always whole
// rows; and a process killed (SIGKILL) at random moments while it rewrites a
// large file and its history never leaves either of them cut short.

#include <talus/base/exceptions.h>
#include <talus/io/file_output.h>
#include <talus/io/history_file.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace fs = std::filesystem;

namespace
{

std::string read_text(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

unsigned int temporaries(const std::string& folder)
{
  unsigned int n = 0;
  for (const auto& entry : fs::directory_iterator(folder))
    n += entry.path().filename().string().find(".tmp") != std::string::npos;
  return n;
}

/// True when every line of the history has `columns` values and the file
/// ends with a line break.
bool whole_rows(const std::string& text, unsigned int columns)
{
  if (text.empty() || text.back() != '\n')
    return false;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (static_cast<unsigned int>(std::count(line.begin(), line.end(), ',')) + 1 != columns)
      return false;
  return true;
}

constexpr std::size_t big_lines = 200000; // about 4 MB: a write takes milliseconds

std::string big_file(unsigned int version)
{
  std::string text = "<VTKFile version=\"" + std::to_string(version) + "\">\n";
  for (std::size_t i = 0; i < big_lines; ++i)
    text += "  0.123456789 1.23456789 12.3456789\n";
  return text + "</VTKFile>\n";
}

} // namespace

int main()
{
  using namespace talus;
  const std::string folder = "atomic_files";
  fs::remove_all(folder);
  fs::create_directories(folder);

  // A writer that stops part-way (an exception): the old content stays.
  const std::string file = folder + "/result.vtu";
  write_file_atomically(file, [](std::ostream& out) { out << "old, complete\n"; });
  try
  {
    write_file_atomically(file,
                          [](std::ostream& out)
                          {
                            out << "new, half written";
                            throw std::runtime_error("stopped part-way");
                          });
  }
  catch (const std::runtime_error& e)
  {
    std::cout << "writer failed: " << e.what() << '\n';
  }
  std::cout << "file after the failed write: " << read_text(file);
  std::cout << "temporary files left: " << temporaries(folder) << '\n';

  // A target that cannot be replaced: a folder of that name.
  fs::create_directories(folder + "/taken.pvd");
  try
  {
    write_file_atomically(folder + "/taken.pvd", [](std::ostream& out) { out << "x\n"; });
  }
  catch (const InputError& e)
  {
    std::cout << "refused: " << e.what() << '\n';
  }
  std::cout << "temporary files left: " << temporaries(folder) << '\n';

  // A history: the header is on disk at once; rows after flush() or at the end.
  const std::string history = folder + "/history.csv";
  {
    HistoryFile h(history, {"step", "time (s)", "ratio"}, 1);
    std::cout << "history at start: " << read_text(history);
    for (int step = 1; step <= 3; ++step)
      h.record({double(step), 1e-3 * step, 1.0 / step});
    h.flush();
    std::cout << "history after flush:\n" << read_text(history);
    h.record({4, 4e-3, 0.25});
  }
  std::cout << "history at the end:\n" << read_text(history);

  // Kill a writer at random moments: the big file and the history must be
  // whole every time (the old or the new version, never a part).
  const unsigned int kills = 20;
  unsigned int big_whole = 0, history_whole = 0;
  for (unsigned int k = 0; k < kills; ++k)
  {
    const std::string big = folder + "/big.vtu", rows = folder + "/rows.csv";
    fs::remove(big);
    fs::remove(rows);
    const pid_t child = fork();
    if (child == 0)
    {
      HistoryFile h(rows, {"step", "a", "b"}, 1);
      for (unsigned int version = 0;; ++version)
      {
        write_file_atomically(big, [&](std::ostream& out) { out << big_file(version); });
        h.record({double(version), 0.5 * version, 2.0 * version});
        h.flush();
      }
    }
    // Let the child write two versions, then kill it somewhere in a later
    // write (a write of the large file takes a few milliseconds).
    while (std::count_if(std::istreambuf_iterator<char>(*std::make_unique<std::ifstream>(rows)),
                         std::istreambuf_iterator<char>(), [](char c) { return c == '\n'; }) < 3)
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    std::this_thread::sleep_for(std::chrono::microseconds(300 + 700 * (k % 10)));
    kill(child, SIGKILL);
    waitpid(child, nullptr, 0);
    const std::string text = read_text(big);
    const bool whole = text.size() > 30 &&
                       text.compare(text.size() - 11, 11, "</VTKFile>\n") == 0 &&
                       std::count(text.begin(), text.end(), '\n') == long(big_lines + 2);
    big_whole += whole;
    history_whole += whole_rows(read_text(rows), 3);
  }
  std::cout << kills << " kills while writing: the large file whole " << big_whole
            << " times, the history whole " << history_whole << " times\n";
  fs::remove_all(folder);
}
