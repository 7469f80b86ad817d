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
//
// A deformable body split among ranks sums its gridpoints' and zones'
// terms (the unbalanced ratio's mean force, energies, reactions) rank by
// rank, in another order than one run: its scene says "# parallel test:
// relative R", and then each history value must be the serial one to R,
// relative as above, and a summary line that is not the serial one's must
// differ only in numbers, each to R of its own size.

#include <algorithm>
#include <array>
#include <cctype>
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

/// Where two histories differ: per column the largest difference over the
/// rows, relative as said at the top, written to `out` (standard error,
/// where the test's output does not look); returns the largest.
double show_differences(const std::string& name, const std::string& serial,
                        const std::string& split, FILE* out)
{
  const Table a = parse(serial), b = parse(split);
  if (a.columns != b.columns || a.rows.size() != b.rows.size())
  {
    std::fprintf(out, "%s: other columns or another number of rows (%zu, %zu)\n", name.c_str(),
                 a.rows.size(), b.rows.size());
    return 1e300;
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
      std::fprintf(out, "%s: %s differs by up to %.2g\n", name.c_str(), a.columns[c].c_str(),
                   largest[c]);
  std::fprintf(
      out, "%s: largest difference of an energy column: %.2g of the row's largest energy term\n",
      name.c_str(), worst_energy);
  double worst = 0.0;
  for (std::size_t c = 0; c < n; ++c)
    worst = std::max(worst, largest[c]);
  return worst;
}

/// Whether two summary lines differ only in numbers, each by at most
/// `relative` of its size.
bool same_but_rounding(const std::string& a, const std::string& b, double relative)
{
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size())
  {
    char* end_a = nullptr;
    char* end_b = nullptr;
    const bool digit = std::isdigit(static_cast<unsigned char>(a[i])) ||
                       ((a[i] == '-' || a[i] == '.') && i + 1 < a.size() &&
                        std::isdigit(static_cast<unsigned char>(a[i + 1])));
    if (digit)
    {
      const double x = std::strtod(a.c_str() + i, &end_a), y = std::strtod(b.c_str() + j, &end_b);
      if (end_b == b.c_str() + j || std::abs(x - y) > relative * std::max(std::abs(x), std::abs(y)))
        return false;
      i = static_cast<std::size_t>(end_a - a.c_str());
      j = static_cast<std::size_t>(end_b - b.c_str());
      continue;
    }
    if (a[i] != b[j])
      return false;
    ++i;
    ++j;
  }
  return i == a.size() && j == b.size();
}

bool summaries_match(const std::string& a, const std::string& b, double relative)
{
  if (a == b)
    return true;
  if (relative <= 0.0)
    return false;
  std::istringstream la(a), lb(b);
  std::string x, y;
  while (true)
  {
    const bool more_a = static_cast<bool>(std::getline(la, x)),
               more_b = static_cast<bool>(std::getline(lb, y));
    if (more_a != more_b)
      return false;
    if (!more_a)
      return true;
    if (x != y && !same_but_rounding(x, y, relative))
      return false;
  }
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
  // "# parallel test: rebalance": the ranks' regions must be cut again for
  // uneven work in every split run (RankBalance; the same line), or a body
  // alone's zones split again after an excavation, its work more even.
  bool rebalance = false;
  // "# parallel test: zones move": deformable blocks must have changed rank,
  // the zones split again at some migration event.
  bool zones_move = false;
  double relative = 0.0; // "# parallel test: relative R"
  // "# parallel test: same files": every file the serial run writes (the
  // output's VTU, PVD and parameter files too) must be written by every
  // split run with the same bytes; "# parallel test: same files NAME": those
  // whose names hold NAME (a run's own frames are pieces per rank).
  bool same_files = false;
  std::string same_files_named;
  // "# parallel test: steps N": every run stops after N steps
  // (TALUS_MAX_STEPS), for a long verification scene shared with another
  // test.
  std::string steps;
  std::ifstream in(prm);
  for (std::string line; std::getline(in, line);)
    if (line.rfind("# parallel test: migrations", 0) == 0)
      migrations = true;
    else if (line.rfind("# parallel test: zones move", 0) == 0)
      zones_move = true;
    else if (line.rfind("# parallel test: rebalance", 0) == 0)
      rebalance = true;
    else if (line.rfind("# parallel test: relative", 0) == 0)
      relative = std::strtod(line.c_str() + 25, nullptr);
    else if (line.rfind("# parallel test: same files", 0) == 0)
    {
      same_files = true;
      std::istringstream(line.substr(27)) >> same_files_named;
    }
    else if (line.rfind("# parallel test: steps", 0) == 0)
    {
      std::istringstream value(line.substr(22));
      unsigned long n = 0;
      if (!(value >> n) || n == 0)
      {
        std::fprintf(stderr,
                     "%s: '%s': allowed: '# parallel test: steps N', N a whole number > 0\n",
                     prm.c_str(), line.c_str());
        return 2;
      }
      steps = "TALUS_MAX_STEPS=" + std::to_string(n) + " ";
    }
    else if (line.rfind("# parallel test: ranks", 0) == 0)
    {
      std::istringstream list(line.substr(22));
      for (int n; list >> n;)
        ranks.push_back(n);
    }
  const std::string talus = TALUS_EXECUTABLE, mpiexec = MPIEXEC_EXECUTABLE;
  const std::string quiet = "TALUS_PROGRESS_SECONDS=0 TALUS_HISTORY_DIGITS=17 " + steps;
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
    const bool same = split.exit_code == serial.exit_code &&
                      summaries_match(serial.summary, split.summary, relative);
    if (relative > 0.0)
      std::printf("%d ranks: exit code %d, summary the serial run's line for line (numbers to %g): "
                  "%s\n",
                  n, split.exit_code, relative, same ? "yes" : "NO");
    else
      std::printf("%d ranks: exit code %d, summary the serial run's line for line: %s\n", n,
                  split.exit_code, same ? "yes" : "NO");
    if (!same)
      std::fprintf(stderr, "--- serial:\n%s--- %d ranks:\n%s", serial.summary.c_str(), n,
                   split.summary.c_str());
    bool same_history = !histories.empty() && history_files(folder) == histories;
    for (const std::string& name : histories)
    {
      const std::string a = read_file("serial_output/" + name), b = read_file(folder + "/" + name);
      double worst = 0.0;
      if (a != b)
      {
        // Within the scene's tolerance the figures go to a file of their
        // own (the test compares standard output and error).
        FILE* out = stderr;
        if (relative > 0.0)
          out = std::fopen((folder + "_differences.txt").c_str(), "w");
        std::fprintf(out, "--- %d ranks:\n", n);
        worst = show_differences(name, a, b, out);
        if (out != stderr)
        {
          std::fclose(out);
          if (worst > relative) // failed: shown
            std::fputs(read_file(folder + "_differences.txt").c_str(), stderr);
        }
      }
      same_history &= relative > 0.0 ? worst <= relative : a == b;
    }
    if (relative > 0.0)
      std::printf("%d ranks: history the serial run's to %g, every column: %s\n", n, relative,
                  same_history ? "yes" : "NO");
    else
      std::printf("%d ranks: history the serial run's to the last bit, every column: %s\n", n,
                  same_history ? "yes" : "NO");
    all &= same && same_history;
    if (same_files)
    {
      const auto named = [&](std::vector<std::string> all_names)
      {
        std::vector<std::string> kept;
        for (std::string& name : all_names)
          if (name.find(same_files_named) != std::string::npos)
            kept.push_back(std::move(name));
        return kept;
      };
      const std::vector<std::string> names = named(files("serial_output"));
      bool all_same = !names.empty() && named(files(folder)) == names;
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
    if (migrations || rebalance || zones_move)
    {
      // "talus: on N ranks: E migration events (the sum of their steps S), C
      // owner changes, R rebalances (...)[; the zones split again at Z of
      // the events]"
      std::ifstream err(folder + ".err");
      unsigned long events = 0, steps = 0, changed = 0, rebalances = 0, splits = 0;
      int on = 0;
      for (std::string line; std::getline(err, line);)
        if (line.find("migration events") != std::string::npos)
        {
          std::sscanf(line.c_str(),
                      "talus: on %d ranks: %lu migration events (the sum of their steps %lu), "
                      "%lu owner changes, %lu rebalances",
                      &on, &events, &steps, &changed, &rebalances);
          const std::string split = "the zones split again at ";
          const std::size_t at = line.find(split);
          if (at != std::string::npos)
            splits = std::strtoul(line.c_str() + at + split.size(), nullptr, 10);
        }
        else if (line.find("rebalances of the body's zones") != std::string::npos)
        {
          // "talus: on N ranks: R rebalances of the body's zones after
          // excavations (... B before the last rebalance, A after it; ...)":
          // counted only when the work became more even.
          double before = 0.0, after = 0.0;
          const std::size_t at = line.find("the mean: ");
          if (std::sscanf(line.c_str(), "talus: on %d ranks: %lu rebalances", &on, &rebalances) ==
                  2 &&
              at != std::string::npos &&
              std::sscanf(line.c_str() + at, "the mean: %lf before the last rebalance, %lf after",
                          &before, &after) == 2 &&
              !(after < before))
            rebalances = 0;
        }
      if (migrations)
      {
        std::printf("%d ranks: blocks changed rank: %s\n", n, changed > 0 ? "yes" : "NO");
        all &= changed > 0;
      }
      if (rebalance)
      {
        std::printf("%d ranks: regions cut again for uneven work: %s\n", n,
                    rebalances > 0 ? "yes" : "NO");
        all &= rebalances > 0;
      }
      if (zones_move)
      {
        std::printf("%d ranks: deformable blocks changed rank, the zones split again: %s\n", n,
                    splits > 0 ? "yes" : "NO");
        all &= splits > 0;
      }
    }
  }
  std::printf("%s\n", all ? "OK" : "FAILED");
  return all ? 0 : 1;
}
