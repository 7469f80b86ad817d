// Fuzz test: feeds talus hundreds of mutated copies of the shipped parameter
// files (parameters/*.prm, parameters/verification/*.prm) and of a gmsh mesh
// file, and checks how every run ends. Allowed: exit code 0 (the input was
// good enough to run) or 4 (a static run that the step cap stopped before
// its target ratio), or exit code 1 with exactly one line on standard
// error, "talus: error: ...", naming the mutated file, or exit code 3 with
// such a line (a run that the input made diverge or fling a block through
// another, stopped at its first bad step, e.g. a force of 1e12 N on a
// block of a few tonnes). Anything else - a
// signal (crash), another exit code (an internal error), a message of
// several lines or none, a run still going after the time limit - is a
// failure and is printed in full, so the output differs from the expected one.
//
// The mutations are deterministic (a fixed pseudo-random sequence), so the
// counts printed at the end are too. Runs are kept short: TALUS_MAX_STEPS caps
// every scene's 'Steps', and each run is killed after a time limit.

#include <algorithm>
#include <array>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;

namespace
{

/// splitmix64: the same sequence on every machine and compiler (unlike the
/// distributions of <random>).
struct Random
{
  std::uint64_t state;
  std::uint64_t next()
  {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  std::size_t below(std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(next() % n); }
  template <typename T>
  const T& pick(const std::vector<T>& v)
  {
    return v[below(v.size())];
  }
};

std::vector<std::string> split_lines(const std::string& text)
{
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    lines.push_back(line);
  return lines;
}

std::string join_lines(const std::vector<std::string>& lines)
{
  std::string text;
  for (const std::string& l : lines)
    text += l + "\n";
  return text;
}

std::string read_text(const fs::path& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

bool is_set_line(const std::string& line)
{
  const auto b = line.find_first_not_of(" \t");
  return b != std::string::npos && line.compare(b, 4, "set ") == 0 &&
         line.find('=') != std::string::npos;
}

/// Indices of lines satisfying `keep`.
template <typename Keep>
std::vector<std::size_t> lines_where(const std::vector<std::string>& lines, Keep keep)
{
  std::vector<std::size_t> at;
  for (std::size_t i = 0; i < lines.size(); ++i)
    if (keep(lines[i]))
      at.push_back(i);
  return at;
}

/// The value of a 'set' line (between '=' and a comment) as [begin, end).
std::pair<std::size_t, std::size_t> value_span(const std::string& line)
{
  const std::size_t eq = line.find('=') + 1;
  std::size_t end = line.find('#', eq);
  if (end == std::string::npos)
    end = line.size();
  return {eq, end};
}

/// Spans of the numbers in `text` from `from` on (digits with sign, point and exponent).
std::vector<std::pair<std::size_t, std::size_t>> number_spans(const std::string& text,
                                                              std::size_t from, std::size_t to)
{
  std::vector<std::pair<std::size_t, std::size_t>> spans;
  for (std::size_t i = from; i < to;)
  {
    if (std::isdigit(static_cast<unsigned char>(text[i])) ||
        ((text[i] == '-' || text[i] == '.') && i + 1 < to &&
         std::isdigit(static_cast<unsigned char>(text[i + 1]))))
    {
      std::size_t j = i + 1;
      while (j < to &&
             (std::isdigit(static_cast<unsigned char>(text[j])) || text[j] == '.' ||
              text[j] == 'e' || text[j] == 'E' ||
              ((text[j] == '-' || text[j] == '+') && (text[j - 1] == 'e' || text[j - 1] == 'E'))))
        ++j;
      spans.emplace_back(i, j);
      i = j;
    }
    else
      ++i;
  }
  return spans;
}

/// Replaces one number on a random 'set' line with `make(old)`; false if
/// the file has no number to replace.
template <typename Make>
bool replace_number(std::vector<std::string>& lines, Random& random, Make make)
{
  std::vector<std::pair<std::size_t, std::pair<std::size_t, std::size_t>>> all;
  for (std::size_t i = 0; i < lines.size(); ++i)
    if (is_set_line(lines[i]))
    {
      const auto [b, e] = value_span(lines[i]);
      for (const auto& s : number_spans(lines[i], b, e))
        all.emplace_back(i, s);
    }
  if (all.empty())
    return false;
  const auto& [line, span] = all[random.below(all.size())];
  std::string& l = lines[line];
  l = l.substr(0, span.first) + make(l.substr(span.first, span.second - span.first)) +
      l.substr(span.second);
  return true;
}

const std::vector<std::string> kind_names{"delete a line",
                                          "duplicate a line",
                                          "truncate",
                                          "swap two values",
                                          "huge number",
                                          "negative number",
                                          "zero",
                                          "nan or inf",
                                          "text for a value",
                                          "unbalanced sections",
                                          "unknown or odd names",
                                          "byte flips",
                                          "empty or garbage file",
                                          "odd statements"};

/// Mutates a parameter file's text in the way `kind` names.
std::string mutate_parameters(const std::string& text, unsigned int kind, Random& random)
{
  std::vector<std::string> lines = split_lines(text);
  const auto any_line = [&]() { return random.below(lines.size()); };
  const auto set_lines = lines_where(lines, is_set_line);
  switch (kind)
  {
  case 0:
    lines.erase(lines.begin() + static_cast<long>(any_line()));
    break;
  case 1:
  {
    const std::size_t at = any_line();
    lines.insert(lines.begin() + static_cast<long>(at), lines[at]);
    break;
  }
  case 2:
    return text.substr(0, random.below(text.size()));
  case 3:
  {
    const std::size_t a = random.pick(set_lines), b = random.pick(set_lines);
    const auto [ab, ae] = value_span(lines[a]);
    const auto [bb, be] = value_span(lines[b]);
    const std::string va = lines[a].substr(ab, ae - ab), vb = lines[b].substr(bb, be - bb);
    lines[a] = lines[a].substr(0, ab) + vb + lines[a].substr(ae);
    lines[b] = lines[b].substr(0, bb) + va + lines[b].substr(be);
    break;
  }
  case 4:
  {
    static const std::vector<std::string> huge{
        "1e300",      "1e308", "-1e300", "1e400", "123456789012345678901234567890",
        "4294967296", "1e12"};
    replace_number(lines, random, [&](const std::string&) { return random.pick(huge); });
    break;
  }
  case 5:
    replace_number(lines, random,
                   [](const std::string& old)
                   { return old[0] == '-' ? old.substr(1) : "-" + old; });
    break;
  case 6:
    replace_number(lines, random, [](const std::string&) { return std::string("0"); });
    break;
  case 7:
  {
    static const std::vector<std::string> odd{"nan", "NaN", "inf", "-inf", "1e-400", "0x1p3"};
    replace_number(lines, random, [&](const std::string&) { return random.pick(odd); });
    break;
  }
  case 8:
  {
    static const std::vector<std::string> text_values{
        "abc", "", "1 2 3", "1,,2", ";", "true", "1, 2, 3, 4", "\"1\"", ",", "x, y, z"};
    const std::size_t at = random.pick(set_lines);
    const auto [b, e] = value_span(lines[at]);
    lines[at] = lines[at].substr(0, b) + " " + random.pick(text_values) + lines[at].substr(e);
    break;
  }
  case 9:
  {
    const auto ends = lines_where(lines, [](const std::string& l) { return l == "end"; });
    switch (random.below(4))
    {
    case 0:
      lines.erase(lines.begin() + static_cast<long>(random.pick(ends)));
      break;
    case 1:
      lines.insert(lines.begin() + static_cast<long>(any_line()), "end");
      break;
    case 2:
      lines.insert(lines.begin() + static_cast<long>(any_line()), "subsection Solver");
      break;
    default:
      lines.push_back("subsection Model");
    }
    break;
  }
  case 10:
  {
    static const std::vector<std::string> names{
        "subsection Joint set 0",    "subsection Joint set 99999999999999999999",
        "subsection Joint set -1",   "subsection Group 1x",
        "subsection Blocks",         "subsection Load 4294967297",
        "subsection Excavation 007", "subsection"};
    const auto sections =
        lines_where(lines, [](const std::string& l) { return l.rfind("subsection", 0) == 0; });
    if (random.below(2) == 0 && !sections.empty())
      lines[random.pick(sections)] = random.pick(names);
    else
    {
      std::string& l = lines[random.pick(set_lines)];
      const std::size_t eq = l.find('=');
      l.insert(eq > 0 && l[eq - 1] == ' ' ? eq - 1 : eq, random.below(2) ? "x" : " Speed");
    }
    break;
  }
  case 11:
  {
    std::string flipped = text;
    const std::size_t n = 1 + random.below(4);
    for (std::size_t k = 0; k < n && !flipped.empty(); ++k)
      flipped[random.below(flipped.size())] ^= static_cast<char>(1u << random.below(8));
    return flipped;
  }
  case 12:
  {
    switch (random.below(5))
    {
    case 0:
      return "";
    case 1:
      return "\n\n   \n";
    case 2:
      return "# nothing but a comment\n";
    case 3:
    {
      std::string garbage;
      for (int k = 0; k < 200; ++k)
        garbage.push_back(static_cast<char>(random.below(256)));
      return garbage;
    }
    default:
      return std::string(1000, '\0');
    }
  }
  default:
  {
    static const std::vector<std::string> statements{
        "set Steps = 10",
        "set = 3",
        "=",
        "subsection Model\nsubsection Model\nend\nend",
        "set Density = 1 # comment = 2",
        "set Density",
        "end end",
        "subsection Solver\n  set Steps = 5\n  set Steps = 7\nend",
        std::string(100000, 'x'),
        "\t set\tDensity\t=\t2600",
        "set Density == 2600"};
    lines.insert(lines.begin() + static_cast<long>(any_line()), random.pick(statements));
  }
  }
  return join_lines(lines);
}

/// Mutates a gmsh file: broken counts, node numbers, coordinates, sections.
std::string mutate_mesh(const std::string& text, unsigned int kind, Random& random)
{
  std::vector<std::string> lines = split_lines(text);
  const std::size_t at = random.below(lines.size());
  switch (kind % 8)
  {
  case 0:
    lines.erase(lines.begin() + static_cast<long>(at));
    break;
  case 1:
    lines.insert(lines.begin() + static_cast<long>(at), lines[at]);
    break;
  case 2:
    return text.substr(0, random.below(text.size()));
  case 3:
  {
    static const std::vector<std::string> values{"0",   "-1",         "99999999999", "1e300",
                                                 "nan", "4294967295", "abc",         "9"};
    std::vector<std::pair<std::size_t, std::pair<std::size_t, std::size_t>>> all;
    for (std::size_t i = 0; i < lines.size(); ++i)
      for (const auto& s : number_spans(lines[i], 0, lines[i].size()))
        all.emplace_back(i, s);
    const auto& [line, span] = all[random.below(all.size())];
    std::string& l = lines[line];
    l = l.substr(0, span.first) + random.pick(values) + l.substr(span.second);
    break;
  }
  case 4:
  {
    std::string flipped = text;
    for (std::size_t k = 0; k < 1 + random.below(3); ++k)
      flipped[random.below(flipped.size())] ^= static_cast<char>(1u << random.below(8));
    return flipped;
  }
  case 5:
    // Two tetrahedra sharing the same corners: the body is not a valid mesh.
    lines.insert(lines.end() - 1, "6 4 2 1 1 1 2 3 6");
    for (std::string& l : lines)
      if (l == "5")
        l = "6";
    break;
  case 6:
    // A node moved: a flat or inverted zone, or a body that is not closed.
    for (std::string& l : lines)
      if (l.rfind("7 ", 0) == 0 && l.size() < 12)
        l = random.below(2) ? "7 0.5 0.5 0.5" : "7 0 0 0";
    break;
  default:
    lines.insert(lines.begin() + static_cast<long>(at),
                 random.below(2) ? "$Nodes" : "$EndElements");
  }
  return join_lines(lines);
}

/// Points the output folder to "run_files": relative, and no single bit flip
/// of its letters gives '/', so no mutation writes outside the work folder.
std::string with_safe_output(const std::string& text)
{
  std::vector<std::string> lines = split_lines(text);
  for (std::string& l : lines)
    if (l.find("set Directory") != std::string::npos)
      l = "  set Directory = run_files";
  return join_lines(lines);
}

struct Outcome
{
  int exit_code = -1; ///< -1: killed by a signal or the time limit
  int signal = 0;
  bool timed_out = false;
  std::string error_text;
};

/// Runs talus on `prm` with `folder` as its working folder; standard output
/// is dropped, standard error kept.
Outcome run_talus(const std::string& prm, const std::string& folder, double limit_seconds)
{
  const std::string err_file = folder + "/stderr.txt";
  std::fflush(stdout); // else the child would write out what is buffered
  const pid_t child = fork();
  if (child == 0)
  {
    if (chdir(folder.c_str()) != 0)
      _exit(126);
    if (!freopen("/dev/null", "w", stdout) || !freopen(err_file.c_str(), "w", stderr))
      _exit(126);
#if !defined(__SANITIZE_ADDRESS__)
    // A mutation that asks for a huge model fails inside this limit instead
    // of taking the machine's memory (AddressSanitizer needs more address space).
    const rlim_t bytes = 4ul << 30;
    const rlimit limit{bytes, bytes};
    setrlimit(RLIMIT_AS, &limit);
#endif
    execl(TALUS_EXECUTABLE, "talus", prm.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  Outcome outcome;
  int status = 0;
  const auto start = std::chrono::steady_clock::now();
  while (waitpid(child, &status, WNOHANG) == 0)
  {
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >
        limit_seconds)
    {
      kill(child, SIGKILL);
      waitpid(child, &status, 0);
      outcome.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (!outcome.timed_out && WIFEXITED(status))
    outcome.exit_code = WEXITSTATUS(status);
  else if (!outcome.timed_out)
    outcome.signal = WTERMSIG(status);
  outcome.error_text = read_text(err_file);
  return outcome;
}

struct Tally
{
  unsigned int mutations = 0, refused = 0, stopped = 0, ran = 0, failed = 0;
};

/// Judges one run: prints nothing for a good ending, everything for a bad one.
void judge(const Outcome& o, const std::string& name, const std::string& what, Tally& tally)
{
  ++tally.mutations;
  std::string problem;
  if (o.timed_out)
    problem = "still running at the time limit";
  else if (o.signal != 0)
    problem = "killed by signal " + std::to_string(o.signal);
  else if (o.exit_code == 0 || o.exit_code == 4) // 4: a static run capped before equilibrium
  {
    ++tally.ran;
    return;
  }
  else if (o.exit_code != 1 && o.exit_code != 3)
    problem = "exit code " + std::to_string(o.exit_code);
  else
  {
    const std::string code = "exit code " + std::to_string(o.exit_code);
    const bool one_line = !o.error_text.empty() && o.error_text.back() == '\n' &&
                          o.error_text.find('\n') == o.error_text.size() - 1;
    if (!one_line)
      problem = code + " but the message is not one line";
    else if (o.error_text.rfind("talus: error", 0) != 0)
      problem = code + " but the message does not start with 'talus: error'";
    else if (o.error_text.find(name) == std::string::npos)
      problem = "the message does not name the file";
    else
    {
      ++(o.exit_code == 1 ? tally.refused : tally.stopped);
      return;
    }
  }
  ++tally.failed;
  std::printf("FAILED %s (%s): %s\n  stderr: %s\n", name.c_str(), what.c_str(), problem.c_str(),
              o.error_text.c_str());
}

} // namespace

int main()
{
  const fs::path source = fs::path(SOURCE_DIR) / ".." / "..";
  std::vector<fs::path> inputs;
  for (const fs::path& folder : {source / "parameters", source / "parameters" / "verification"})
    for (const auto& entry : fs::directory_iterator(folder))
      if (entry.path().extension() == ".prm")
        inputs.push_back(entry.path());
  std::sort(inputs.begin(), inputs.end());

  setenv("TALUS_MAX_STEPS", "20", 1);
  setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
  setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
  const fs::path work = fs::absolute("mutants");
  fs::remove_all(work);
  fs::create_directories(work);
#if defined(__SANITIZE_ADDRESS__)
  // Under AddressSanitizer (cmake -DTALUS_SANITIZE=ON) talus runs 10-20 times
  // slower: a good 20-step run of the tunnel scene took more than 60 s there.
  const double limit_seconds = 900.0;
#else
  const double limit_seconds = 60.0;
#endif

  // Parameter files: every kind of mutation on every file in turn.
  const unsigned int n_parameter_mutations = 14 * 16;
  Tally parameters;
  std::map<std::string, std::array<unsigned int, 3>> per_kind; // refused, stopped, ran
  for (unsigned int m = 0; m < n_parameter_mutations; ++m)
  {
    const unsigned int kind = m % kind_names.size();
    const fs::path& base = inputs[(m / kind_names.size() + m) % inputs.size()];
    Random random{0x7A105ull * (m + 1)};
    const std::string text = mutate_parameters(with_safe_output(read_text(base)), kind, random);
    char name[64];
    std::snprintf(name, sizeof name, "m%03u_", m);
    const std::string file = name + base.filename().string();
    std::ofstream(work / file, std::ios::binary) << text;
    const Tally before = parameters;
    judge(run_talus((work / file).string(), work.string(), limit_seconds), file,
          kind_names[kind] + " of " + base.filename().string(), parameters);
    per_kind[kind_names[kind]][0] += parameters.refused - before.refused;
    per_kind[kind_names[kind]][1] += parameters.stopped - before.stopped;
    per_kind[kind_names[kind]][2] += parameters.ran - before.ran;
  }

  // Mesh files: a one-block deformable scene reading a mutated gmsh file.
  const std::string mesh_text =
      read_text(source / "tests" / "deformable" / "unit_cube_5_tetrahedra.msh");
  const unsigned int n_mesh_mutations = 32;
  Tally meshes;
  for (unsigned int m = 0; m < n_mesh_mutations; ++m)
  {
    Random random{0x6D35ull * (m + 1)};
    char name[64];
    std::snprintf(name, sizeof name, "mesh%02u", m);
    const std::string mesh = mutate_mesh(mesh_text, m, random);
    std::ofstream(work / (std::string(name) + ".msh"), std::ios::binary) << mesh;
    const std::string prm = std::string(name) + ".prm";
    std::ofstream(work / prm) << "subsection Deformable\n  set Groups = rock\n  set Mesh file = "
                              << name << ".msh\nend\n"
                              << "subsection Boundary 1\n  set Corner min = -1, -1, -0.001\n"
                              << "  set Corner max = 2, 2, 0.001\nend\n"
                              << "subsection Solver\n  set Steps = 20\nend\n"
                              << "subsection Output\n  set Directory = mesh_output\nend\n";
    judge(run_talus((work / prm).string(), work.string(), limit_seconds), prm,
          "mesh mutation " + std::to_string(m % 8), meshes);
  }

  // Paths that name no parameter file.
  Tally paths;
  fs::create_directories(work / "folder.prm");
  for (const std::string name : {"missing.prm", "folder.prm"})
    judge(run_talus((work / name).string(), work.string(), limit_seconds), name, "not a file",
          paths);

  for (const auto& [kind, counts] : per_kind)
    std::printf("%-22s %3u refused with a message, %u stopped with one, %3u ran\n", kind.c_str(),
                counts[0], counts[1], counts[2]);
  for (const auto& [what, t] : {std::pair<const char*, const Tally&>{"mutated parameter files",
                                                                     parameters},
                                {"mutated mesh files", meshes},
                                {"paths that are no parameter file", paths}})
    std::printf("%u %s: %u refused with a message, %u stopped with one, %u ran, %u failed\n",
                t.mutations, what, t.refused, t.stopped, t.ran, t.failed);
  // The mutated files stay for a look when a run failed.
  if (parameters.failed + meshes.failed + paths.failed == 0)
    fs::remove_all(work);
  else
    std::printf("the mutated files are in %s\n", work.c_str());
  return 0;
}
