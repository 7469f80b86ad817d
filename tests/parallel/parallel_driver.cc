// Runs a scene (argument: its .prm) with talus on one rank and under
// mpiexec on the ranks its line "# parallel test: ranks N M ..." names, each
// into an output folder of its own (TALUS_OUTPUT_DIRECTORY), and prints
// whether each split run's summary is the serial run's, line for line (the
// "   Time =" lines aside, and the folder's name). The comparison is made in
// the build that runs it, so its verdicts hold on any machine and build.

#include <array>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <vector>

namespace
{

struct Run
{
  std::string summary; ///< standard output, filtered
  int exit_code = -1;
};

/// Runs `command` through the shell; its standard output without the
/// timing lines, `folder` shown as OUTPUT.
Run run(const std::string& command, const std::string& folder)
{
  Run r;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr)
    return r;
  std::array<char, 4096> buffer{};
  std::string text;
  while (std::fgets(buffer.data(), buffer.size(), pipe) != nullptr)
    text += buffer.data();
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);)
  {
    if (line.rfind("   Time =", 0) == 0)
      continue;
    for (std::size_t at; (at = line.find(folder)) != std::string::npos;)
      line.replace(at, folder.size(), "OUTPUT");
    r.summary += line + "\n";
  }
  return r;
}

unsigned int count_lines(const std::string& text)
{
  unsigned int n = 0;
  for (char c : text)
    n += c == '\n';
  return n;
}

} // namespace

int main(int argc, char** argv)
{
  if (argc != 2)
    return 2;
  const std::string prm = argv[1];
  std::vector<int> ranks;
  // "# parallel test: migrations": blocks must change rank in every split
  // run (its "Migrations:" line on standard error).
  bool migrations = false;
  std::ifstream in(prm);
  for (std::string line; std::getline(in, line);)
    if (line.rfind("# parallel test: migrations", 0) == 0)
      migrations = true;
    else if (line.rfind("# parallel test: ranks", 0) == 0)
    {
      std::istringstream list(line.substr(22));
      for (int n; list >> n;)
        ranks.push_back(n);
    }
  const std::string talus = TALUS_EXECUTABLE, mpiexec = MPIEXEC_EXECUTABLE;
  const std::string quiet = "TALUS_PROGRESS_SECONDS=0 ";
  const Run serial =
      run(quiet + "TALUS_OUTPUT_DIRECTORY=serial_output " + talus + " " + prm + " 2> serial.err",
          "serial_output");
  std::printf("serial run: exit code %d, %u summary lines\n", serial.exit_code,
              count_lines(serial.summary));
  bool all = !ranks.empty();
  for (int n : ranks)
  {
    const std::string folder = "ranks" + std::to_string(n) + "_output";
    const Run split = run(quiet + "TALUS_OUTPUT_DIRECTORY=" + folder + " " + mpiexec + " -n " +
                              std::to_string(n) + " --oversubscribe " + talus + " " + prm + " 2> " +
                              folder + ".err",
                          folder);
    const bool same = split.exit_code == serial.exit_code && split.summary == serial.summary;
    std::printf("%d ranks: exit code %d, summary the serial run's line for line: %s\n", n,
                split.exit_code, same ? "yes" : "NO");
    if (!same)
      std::fprintf(stderr, "--- serial:\n%s--- %d ranks:\n%s", serial.summary.c_str(), n,
                   split.summary.c_str());
    all &= same;
    if (migrations)
    {
      // "Migrations:   E events, C blocks changed rank"
      std::ifstream err(folder + ".err");
      unsigned long events = 0, changed = 0; // (the counts: in the .err file)
      for (std::string line; std::getline(err, line);)
        if (line.rfind("Migrations:", 0) == 0)
          std::sscanf(line.c_str(), "Migrations: %lu events, %lu blocks", &events, &changed);
      std::printf("%d ranks: blocks changed rank: %s\n", n, changed > 0 ? "yes" : "NO");
      all &= changed > 0;
    }
  }
  std::printf("%s\n", all ? "OK" : "FAILED");
  return all ? 0 : 1;
}
