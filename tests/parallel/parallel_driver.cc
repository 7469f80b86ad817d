// Runs a scene (argument: its .prm) with talus on one rank and under
// mpiexec on the ranks its line "# parallel test: ranks N M ..." names, each
// into an output folder of its own (TALUS_OUTPUT_DIRECTORY), and prints
// whether each split run's summary is the serial run's, line for line (the
// "   Time =" lines aside, and the folder's name). The comparison is made in
// the build that runs it, so its verdicts hold on any machine and build.
// Every run writes its history with 17 significant digits
// (TALUS_HISTORY_DIGITS), and each split run's history files must be the
// serial run's byte for byte: every column, energies included, to the last
// bit. A difference is shown on standard error: per column, the largest
// over the rows, relative to the largest energy term of the row (the
// columns in J) or to the column's largest value (the others).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <dirent.h>
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

/// The names of the files in `folder` that end in `tail`, sorted.
std::vector<std::string> files(const std::string& folder, const std::string& tail = "")
{
  std::vector<std::string> names;
  if (DIR* dir = opendir(folder.c_str()))
  {
    while (const dirent* entry = readdir(dir))
    {
      const std::string name = entry->d_name;
      if (name != "." && name != ".." && name.size() > tail.size() &&
          name.compare(name.size() - tail.size(), tail.size(), tail) == 0)
        names.push_back(name);
    }
    closedir(dir);
  }
  std::sort(names.begin(), names.end());
  return names;
}

/// The names of the history files in `folder`, sorted.
std::vector<std::string> history_files(const std::string& folder)
{
  return files(folder, "_history.csv");
}

std::string read_file(const std::string& path)
{
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// A CSV file as its header's names and rows of numbers.
struct Table
{
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
};

Table parse(const std::string& text)
{
  Table t;
  std::istringstream lines(text);
  std::string line;
  if (std::getline(lines, line))
  {
    std::istringstream names(line);
    for (std::string name; std::getline(names, name, ',');)
      t.columns.push_back(name);
  }
  while (std::getline(lines, line))
  {
    std::vector<double> row;
    std::istringstream values(line);
    for (std::string value; std::getline(values, value, ',');)
      row.push_back(std::strtod(value.c_str(), nullptr));
    t.rows.push_back(row);
  }
  return t;
}

/// Standard error: where two histories differ, per column the largest
/// difference over the rows, relative as said at the top.
void show_differences(const std::string& name, const std::string& serial, const std::string& split)
{
  const Table a = parse(serial), b = parse(split);
  if (a.columns != b.columns || a.rows.size() != b.rows.size())
  {
    std::fprintf(stderr, "%s: other columns or another number of rows (%zu, %zu)\n", name.c_str(),
                 a.rows.size(), b.rows.size());
    return;
  }
  const std::size_t n = a.columns.size();
  std::vector<double> largest(n, 0.0), scale(n, 0.0);
  for (const std::vector<double>& row : a.rows)
    for (std::size_t c = 0; c < n && c < row.size(); ++c)
      scale[c] = std::max(scale[c], std::abs(row[c]));
  double worst_energy = 0.0;
  for (std::size_t r = 0; r < a.rows.size(); ++r)
  {
    double energy = 0.0; // the row's largest energy term
    for (std::size_t c = 0; c < n && c < a.rows[r].size(); ++c)
      if (a.columns[c].find("(J)") != std::string::npos)
        energy = std::max(energy, std::abs(a.rows[r][c]));
    for (std::size_t c = 0; c < n && c < a.rows[r].size() && c < b.rows[r].size(); ++c)
    {
      const bool is_energy = a.columns[c].find("(J)") != std::string::npos;
      const double against = is_energy ? energy : scale[c];
      const double d = std::abs(a.rows[r][c] - b.rows[r][c]);
      largest[c] = std::max(largest[c], against > 0.0 ? d / against : d);
      if (is_energy)
        worst_energy = std::max(worst_energy, largest[c]);
    }
  }
  for (std::size_t c = 0; c < n; ++c)
    if (largest[c] > 0.0)
      std::fprintf(stderr, "%s: %s differs by up to %.2g\n", name.c_str(), a.columns[c].c_str(),
                   largest[c]);
  std::fprintf(
      stderr, "%s: largest difference of an energy column: %.2g of the row's largest energy term\n",
      name.c_str(), worst_energy);
}

} // namespace

int main(int argc, char** argv)
{
  if (argc != 2)
    return 2;
  const std::string prm = argv[1];
  std::vector<int> ranks;
  // "# parallel test: migrations": blocks must change rank in every split
  // run (its "migration events" line on standard error).
  bool migrations = false;
  // "# parallel test: same files": every file the serial run writes (the
  // output's VTU, PVD and parameter files too) must be written by every
  // split run with the same bytes.
  bool same_files = false;
  std::ifstream in(prm);
  for (std::string line; std::getline(in, line);)
    if (line.rfind("# parallel test: migrations", 0) == 0)
      migrations = true;
    else if (line.rfind("# parallel test: same files", 0) == 0)
      same_files = true;
    else if (line.rfind("# parallel test: ranks", 0) == 0)
    {
      std::istringstream list(line.substr(22));
      for (int n; list >> n;)
        ranks.push_back(n);
    }
  const std::string talus = TALUS_EXECUTABLE, mpiexec = MPIEXEC_EXECUTABLE;
  const std::string quiet = "TALUS_PROGRESS_SECONDS=0 TALUS_HISTORY_DIGITS=17 ";
  const Run serial =
      run(quiet + "TALUS_OUTPUT_DIRECTORY=serial_output " + talus + " " + prm + " 2> serial.err",
          "serial_output");
  const std::vector<std::string> histories = history_files("serial_output");
  std::printf("serial run: exit code %d, %u summary lines, %zu history files\n", serial.exit_code,
              count_lines(serial.summary), histories.size());
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
    bool same_history = !histories.empty() && history_files(folder) == histories;
    for (const std::string& name : histories)
    {
      const std::string a = read_file("serial_output/" + name), b = read_file(folder + "/" + name);
      if (a != b)
      {
        std::fprintf(stderr, "--- %d ranks:\n", n);
        show_differences(name, a, b);
      }
      same_history &= a == b;
    }
    std::printf("%d ranks: history the serial run's to the last bit, every column: %s\n", n,
                same_history ? "yes" : "NO");
    all &= same && same_history;
    if (same_files)
    {
      const std::vector<std::string> names = files("serial_output");
      bool all_same = !names.empty() && files(folder) == names;
      for (const std::string& name : names)
        if (read_file("serial_output/" + name) != read_file(folder + "/" + name))
        {
          std::fprintf(stderr, "--- %d ranks: %s differs\n", n, name.c_str());
          all_same = false;
        }
      std::printf("%d ranks: %zu files, each the serial run's byte for byte: %s\n", n, names.size(),
                  all_same ? "yes" : "NO");
      all &= all_same;
    }
    if (migrations)
    {
      // "talus: on N ranks: E migration events (the sum of their steps S), C owner changes"
      std::ifstream err(folder + ".err");
      unsigned long events = 0, steps = 0, changed = 0; // (the counts: in the .err file)
      int on = 0;
      for (std::string line; std::getline(err, line);)
        if (line.find("migration events") != std::string::npos)
          std::sscanf(line.c_str(),
                      "talus: on %d ranks: %lu migration events (the sum of their steps %lu), "
                      "%lu owner changes",
                      &on, &events, &steps, &changed);
      std::printf("%d ranks: blocks changed rank: %s\n", n, changed > 0 ? "yes" : "NO");
      all &= changed > 0;
    }
  }
  std::printf("%s\n", all ? "OK" : "FAILED");
  return all ? 0 : 1;
}
