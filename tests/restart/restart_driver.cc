// Checks that a stopped and restarted talus run ends exactly where an
// uninterrupted one does. For a scene FILE.prm it
//   1. runs talus on a copy of it to the end and keeps every file written;
//   2. runs it again and stops it with SIGTERM: at a given step (directive
//      "# restart test: signal at step K", through TALUS_TEST_SIGNAL_AT_STEP)
//      or from here while it runs ("# restart test: kill while running");
//      talus must write a checkpoint and exit with 143 (128 + SIGTERM);
//   3. continues it with `talus --restart CHECKPOINT` and compares every
//      file of the first run (histories, PVD and VTU files) byte for byte;
//   4. (with "# restart test: extend to N steps") continues the first run
//      from the checkpoint its 'Checkpoint interval' left at its last step,
//      with 'Steps' raised to N: the history must go on from the first
//      run's rows;
//   5. (with "# restart test: bad checkpoints") feeds talus a truncated
//      checkpoint, a file that is not one, and the checkpoint of a changed
//      parameter file: each must be refused with exit code 1.
// With "# restart test: ranks N" every run is `mpiexec -n N talus ...`: the
// checkpoint is a set of N files (CHECKPOINT.rank-R-of-N), and
// "# restart test: rank refusals" restarts it on N + 1 ranks, on one, with
// a file of the set missing, with files of two steps, and a serial
// checkpoint on N ranks: each must be refused with exit code 1 (no hang).
// The runs on ranks must print the same migration line, unless the scene
// says "# restart test: no migrations" (a deformable body: none at all).
// "# restart test: exit code C": the finished runs must end with C.
// Prints what it compared; the folder it ran in is removed from messages.

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;

namespace
{

std::string read_file(const fs::path& file)
{
  std::ifstream in(file, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void write_file(const fs::path& file, const std::string& text)
{
  std::ofstream(file, std::ios::binary) << text;
}

/// Empty: talus alone; else mpiexec and its arguments, then talus.
std::vector<std::string> launcher;

struct Result
{
  int exit_code = -1; ///< -1: killed by a signal
  int signal = 0;
  std::string messages; ///< standard error
};

/// Runs talus with `args`; `env` (NAME=value) is added to its environment;
/// `while_running` is called with the child's pid after it started.
template <typename WhileRunning>
Result run_talus(const std::vector<std::string>& args, const std::string& env,
                 WhileRunning&& while_running)
{
  int pipe_fd[2];
  if (pipe(pipe_fd) != 0)
    std::exit(2);
  const pid_t child = fork();
  if (child == 0)
  {
    const int null = ::open("/dev/null", O_WRONLY);
    dup2(null, 1);
    dup2(pipe_fd[1], 2);
    close(pipe_fd[0]);
    if (!env.empty())
      putenv(const_cast<char*>(env.c_str()));
    std::vector<char*> argv{const_cast<char*>("talus")};
    if (!launcher.empty())
    {
      // Open MPI refuses root without these.
      putenv(const_cast<char*>("OMPI_ALLOW_RUN_AS_ROOT=1"));
      putenv(const_cast<char*>("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1"));
      argv.clear();
      for (const std::string& a : launcher)
        argv.push_back(const_cast<char*>(a.c_str()));
    }
    for (const std::string& a : args)
      argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(launcher.empty() ? TALUS_EXECUTABLE : launcher[0].c_str(), argv.data());
    _exit(127);
  }
  close(pipe_fd[1]);
  while_running(child);
  Result r;
  char buffer[4096];
  for (ssize_t n; (n = read(pipe_fd[0], buffer, sizeof buffer)) > 0;)
    r.messages.append(buffer, static_cast<std::size_t>(n));
  close(pipe_fd[0]);
  int status = 0;
  waitpid(child, &status, 0);
  if (WIFSIGNALED(status))
    r.signal = WTERMSIG(status);
  else
    r.exit_code = WEXITSTATUS(status);
  return r;
}

Result run_talus(const std::vector<std::string>& args, const std::string& env = "")
{
  return run_talus(args, env, [](pid_t) {});
}

std::string here; ///< the folder the test runs in, with a trailing '/'

/// The line of a run on ranks that counts the migration events.
std::string migration_line(const Result& r)
{
  const std::size_t at = r.messages.find("migration events");
  if (at == std::string::npos)
    return "";
  const std::size_t begin = r.messages.rfind('\n', at) + 1;
  return r.messages.substr(begin, r.messages.find('\n', at) - begin);
}

void show(const char* what, const Result& r)
{
  std::string text = r.messages;
  for (std::size_t at; (at = text.find(here)) != std::string::npos;)
    text.erase(at, here.size());
  std::printf("%s: ", what);
  if (r.exit_code < 0)
    std::printf("killed by signal %d\n", r.signal);
  else
    std::printf("exit code %d\n", r.exit_code);
  std::istringstream lines(text);
  bool launcher_box = false; // mpiexec's own notes, framed by dashes: left out
  for (std::string line; std::getline(lines, line);)
  {
    const bool dashes = line.rfind("--------", 0) == 0;
    launcher_box ^= dashes;
    // The migration's figures (compared between runs below) go to a file
    // of their own: rounding may move them.
    if (line.find("migration events") != std::string::npos)
      std::ofstream("migration_events.txt", std::ios::app) << what << ": " << line << "\n";
    else if (!dashes && !launcher_box)
      std::printf("  | %s\n", line.c_str());
  }
}

/// The value of "set NAME = value" in the parameter text (first match).
std::string entry(const std::string& prm, const std::string& name)
{
  std::istringstream lines(prm);
  for (std::string line; std::getline(lines, line);)
  {
    const std::size_t at = line.find("set " + name);
    const std::size_t eq = line.find('=');
    if (at != std::string::npos && eq != std::string::npos)
    {
      std::string value = line.substr(eq + 1, line.find('#', eq) - eq - 1);
      value.erase(0, value.find_first_not_of(' '));
      value.erase(value.find_last_not_of(' ') + 1);
      return value;
    }
  }
  return "";
}

/// The parameter text with each line "include FILE" replaced by that
/// file's text (FILE relative to `folder`, the including file's), and a
/// relative 'Mesh file' made absolute (it is relative to the file that
/// names it), so that the copy the runs read stands alone.
std::string with_includes(const std::string& prm, const fs::path& folder)
{
  std::istringstream lines(prm);
  std::string text;
  for (std::string line; std::getline(lines, line);)
  {
    const std::size_t first = line.find_first_not_of(' ');
    if (line.rfind("include ", 0) == 0)
    {
      std::string name = line.substr(8);
      name.erase(name.find_last_not_of(" \r") + 1);
      const fs::path file = folder / name;
      text += with_includes(read_file(file), file.parent_path());
    }
    else if (first != std::string::npos && line.compare(first, 13, "set Mesh file") == 0 &&
             line.find('=') != std::string::npos)
    {
      std::string name = line.substr(line.find('=') + 1);
      name.erase(0, name.find_first_not_of(' '));
      name.erase(std::min(name.find('#'), name.size()));
      name.erase(name.find_last_not_of(" \r") + 1);
      const fs::path file = fs::path(name).is_absolute() ? fs::path(name) : folder / name;
      text += line.substr(0, line.find('=') + 1) + " " + file.lexically_normal().string() + "\n";
    }
    else
      text += line + "\n";
  }
  return text;
}

/// Every file of a folder, by name (temporary files left out): the
/// checkpoints alone, or every other file.
std::map<std::string, std::string> folder_files(const fs::path& folder, bool checkpoints = false)
{
  std::map<std::string, std::string> files;
  for (const fs::directory_entry& e : fs::directory_iterator(folder))
  {
    const std::string name = e.path().filename().string();
    if ((name.find("_checkpoint.bin") != std::string::npos) == checkpoints &&
        name.find(".tmp") == std::string::npos)
      files[name] = read_file(e.path());
  }
  return files;
}

} // namespace

int main(int argc, char** argv)
{
  if (argc != 2)
    return 2;
  here = fs::current_path().string() + "/";
  fs::remove("migration_events.txt");
  const std::string source = with_includes(read_file(argv[1]), fs::absolute(argv[1]).parent_path());
  const fs::path scene = fs::absolute("scene.prm");
  write_file(scene, source);
  const fs::path output = fs::absolute(entry(source, "Directory"));
  const std::string base = entry(source, "Base name");
  const fs::path checkpoint = output / (base + "_checkpoint.bin");
  const std::size_t ranks_at = source.find("# restart test: ranks ");
  const int ranks = ranks_at == std::string::npos ? 1 : std::atoi(source.c_str() + ranks_at + 22);
  // "# restart test: no migrations": a deformable body on ranks, whose runs
  // have no blocks to migrate and print no migration line.
  const bool no_migrations = source.find("# restart test: no migrations") != std::string::npos;
  // "# restart test: exit code C": a finished run ends with C (4: a static
  // stage left out of equilibrium, which the summary warns of), not 0.
  const std::size_t code_at = source.find("# restart test: exit code ");
  const int finished = code_at == std::string::npos ? 0 : std::atoi(source.c_str() + code_at + 26);
  const auto on_ranks = [&](int n)
  {
    launcher.clear();
    if (n > 1)
      launcher = {MPIEXEC_EXECUTABLE, "-n", std::to_string(n), "--oversubscribe", TALUS_EXECUTABLE};
  };
  on_ranks(ranks);
  // The checkpoint's files: itself, or the set of one per rank.
  const auto files_of = [&](const fs::path& set)
  {
    std::vector<fs::path> files;
    for (int r = 0; r < ranks; ++r)
      files.push_back(ranks == 1 ? set
                                 : fs::path(set.string() + ".rank-" + std::to_string(r) + "-of-" +
                                            std::to_string(ranks)));
    return files;
  };
  const auto exists_all = [&](const fs::path& set)
  {
    bool all = true;
    for (const fs::path& f : files_of(set))
      all &= fs::exists(f);
    return all;
  };
  bool good = true;
  const auto check = [&](bool ok, const std::string& what)
  {
    std::printf("%s: %s\n", what.c_str(), ok ? "yes" : "NO");
    good &= ok;
  };

  // 1. The uninterrupted run.
  fs::remove_all(output);
  const Result whole = run_talus({scene.string()});
  show("uninterrupted run", whole);
  const std::map<std::string, std::string> reference = folder_files(output);
  // The checkpoints the run leaves (at the end of a stage, or by
  // 'Checkpoint interval'): the restarted run's must be the same bytes,
  // the whole state at the end and not only what the files show of it.
  const std::map<std::string, std::string> reference_checkpoints = folder_files(output, true);
  check(whole.exit_code == finished, "uninterrupted run finished");
  const fs::path last_checkpoint = fs::absolute("last_checkpoint.bin");
  if (std::stoul("0" + entry(source, "Checkpoint interval")) > 0)
  {
    check(exists_all(checkpoint), "checkpoint left by 'Checkpoint interval'");
    for (int r = 0; r < ranks; ++r)
      fs::copy_file(files_of(checkpoint)[r], files_of(last_checkpoint)[r],
                    fs::copy_options::overwrite_existing);
  }

  // 2. The same run, stopped.
  fs::remove_all(output);
  Result stopped;
  const std::string signal_step = [&]
  {
    const std::size_t at = source.find("# restart test: signal at step ");
    return at == std::string::npos ? std::string()
                                   : source.substr(at + 31, source.find('\n', at) - at - 31);
  }();
  if (!signal_step.empty())
    stopped = run_talus({scene.string()}, "TALUS_TEST_SIGNAL_AT_STEP=" + signal_step);
  else
  {
    // Stopped from outside once its cycle has written its first history rows.
    const fs::path history = output / (base + "_history.csv");
    stopped = run_talus({scene.string()}, "",
                        [&](pid_t child)
                        {
                          for (int k = 0; k < 6000; ++k)
                          {
                            std::error_code ec;
                            if (fs::exists(history, ec) && fs::file_size(history, ec) > 1000)
                              break;
                            if (waitpid(child, nullptr, WNOHANG) != 0)
                              return;
                            std::this_thread::sleep_for(std::chrono::milliseconds(10));
                          }
                          kill(child, SIGTERM);
                        });
    // The step it stopped at depends on timing: keep the message's shape only.
    const std::size_t at = stopped.messages.find(" at step ");
    if (at != std::string::npos)
      stopped.messages.replace(at + 9, stopped.messages.find(';', at) - at - 9, "N");
  }
  show("run stopped by SIGTERM", stopped);
  check(stopped.exit_code == 143, "stopped with exit code 143 (128 + SIGTERM)");
  check(exists_all(checkpoint),
        ranks == 1 ? "checkpoint written" : "checkpoint written: one file per rank");
  bool no_temporary = true;
  for (const fs::directory_entry& e : fs::directory_iterator(output))
    no_temporary &= e.path().filename().string().find(".tmp") == std::string::npos;
  check(no_temporary, "no temporary file left behind");
  const std::string saved = read_file(files_of(checkpoint)[0]);
  const fs::path stopped_checkpoint = fs::absolute("stopped_checkpoint.bin");
  for (int r = 0; r < ranks; ++r)
    fs::copy_file(files_of(checkpoint)[r], files_of(stopped_checkpoint)[r],
                  fs::copy_options::overwrite_existing);
  std::printf("checkpoint starts with TALUSCKP: %s\n",
              saved.compare(0, 8, "TALUSCKP") == 0 ? "yes" : "NO");

  // 3. Continued.
  const Result continued = run_talus({"--restart", checkpoint.string()});
  show("restarted run", continued);
  check(continued.exit_code == finished, "restarted run finished");
  if (ranks > 1 && !no_migrations)
    check(!migration_line(whole).empty() && migration_line(continued) == migration_line(whole),
          "migration events at the steps of the run never stopped, as many owner changes");
  if (ranks > 1 && no_migrations) // a deformable body: no blocks, no migration line
    check(migration_line(whole).empty() && migration_line(continued).empty(),
          "no migration events (no blocks to migrate)");
  const std::map<std::string, std::string> after = folder_files(output);
  for (const auto& [name, text] : reference)
  {
    const auto found = after.find(name);
    if (found == after.end())
    {
      std::printf("%s: MISSING after the restart\n", name.c_str());
      good = false;
      continue;
    }
    std::size_t differ = 0;
    while (differ < text.size() && differ < found->second.size() &&
           text[differ] == found->second[differ])
      ++differ;
    const bool same = text == found->second;
    // Lines, not bytes, so that the output does not depend on number widths.
    const auto lines = std::count(text.begin(), text.end(), '\n');
    if (name.find(".vtu") == std::string::npos)
      std::printf("%s (%ld lines): %s\n", name.c_str(), static_cast<long>(lines),
                  same ? "identical to the uninterrupted run"
                       : ("DIFFERS from byte " + std::to_string(differ)).c_str());
    good &= same;
  }
  unsigned int vtu = 0, vtu_same = 0;
  for (const auto& [name, text] : reference)
    if (name.find(".vtu") != std::string::npos)
    {
      ++vtu;
      const auto found = after.find(name);
      vtu_same += found != after.end() && found->second == text;
    }
  std::printf("VTU files identical to the uninterrupted run: %u of %u\n", vtu_same, vtu);
  good &= vtu_same == vtu;
  check(after.size() == reference.size(), "no file more or less than the uninterrupted run");
  if (!reference_checkpoints.empty())
    check(folder_files(output, true) == reference_checkpoints,
          (std::to_string(reference_checkpoints.size()) +
           " checkpoint file(s) at the end, each the uninterrupted run's byte for byte"));

  // 4. A finished run extended.
  const std::size_t extend = source.find("# restart test: extend to ");
  if (extend != std::string::npos)
  {
    const std::string steps =
        source.substr(extend + 26, source.find(' ', extend + 26) - extend - 26);
    std::string longer = source;
    const std::size_t at = longer.find("set Steps");
    const std::size_t value = longer.find('=', at) + 1;
    longer.replace(value, longer.find_first_of("#\n", value) - value, " " + steps);
    write_file(scene, longer);
    const Result r = run_talus({"--restart", last_checkpoint.string()});
    show(("the finished run continued to " + steps + " steps").c_str(), r);
    check(r.exit_code == 0, "continued run finished");
    // The first run's history, less its last row (written again at the end
    // of every run), then the rows of the steps beyond.
    const std::string name = base + "_history.csv";
    std::string first = reference.at(name);
    first.erase(first.rfind('\n', first.size() - 2) + 1);
    const std::string extended = read_file(output / name);
    const auto rows = [](const std::string& t) { return std::count(t.begin(), t.end(), '\n'); };
    std::printf("history rows: %ld before, %ld after\n", static_cast<long>(rows(first)),
                static_cast<long>(rows(extended)));
    check(extended.compare(0, first.size(), first) == 0 && rows(extended) > rows(first),
          "the history goes on from the first run's rows");
    write_file(scene, source);
  }

  // 5. Checkpoints that must be refused.
  if (source.find("# restart test: bad checkpoints") != std::string::npos)
  {
    const std::map<std::string, std::string> before = folder_files(output);
    const fs::path truncated = fs::absolute("truncated_checkpoint.bin");
    write_file(truncated, saved.substr(0, saved.size() / 2));
    Result r1 = run_talus({"--restart", truncated.string()});
    // Its size depends on the length of the folder's name, kept in it.
    for (std::size_t at = r1.messages.find("truncated (");
         at < r1.messages.size() && r1.messages[at] != ')'; ++at)
      if (r1.messages[at] >= '0' && r1.messages[at] <= '9')
        r1.messages[at] = '#';
    show("restart from a truncated checkpoint", r1);
    check(r1.exit_code == 1, "refused with exit code 1");

    const Result r2 = run_talus({"--restart", scene.string()});
    show("restart from a file that is not a checkpoint", r2);
    check(r2.exit_code == 1, "refused with exit code 1");

    std::string flipped = saved;
    flipped[flipped.size() / 2] ^= 0x10;
    const fs::path corrupt = fs::absolute("corrupt_checkpoint.bin");
    write_file(corrupt, flipped);
    const Result r3 = run_talus({"--restart", corrupt.string()});
    show("restart from a checkpoint with one bit changed", r3);
    check(r3.exit_code == 1, "refused with exit code 1");

    std::string changed = source;
    const std::size_t at = changed.find("set Friction angle");
    const std::size_t value = changed.find('=', at) + 1;
    changed.replace(value, changed.find_first_of("#\n", value) - value, " 31 ");
    write_file(scene, changed);
    const Result r4 = run_talus({"--restart", checkpoint.string()});
    show("restart after the friction angle changed", r4);
    check(r4.exit_code == 1, "refused with exit code 1");
    write_file(scene, source);
    check(folder_files(output) == before, "refused restarts left every output file as it was");
  }
  // 6. A set restarted where it does not fit.
  if (source.find("# restart test: rank refusals") != std::string::npos)
  {
    const std::map<std::string, std::string> before = folder_files(output);
    const auto refused = [&](const char* what, const Result& r)
    {
      show(what, r);
      check(r.exit_code == 1, "refused with exit code 1");
    };
    on_ranks(ranks + 1);
    refused(("restart on " + std::to_string(ranks + 1) + " ranks").c_str(),
            run_talus({"--restart", checkpoint.string()}));
    on_ranks(1);
    refused("restart on one rank", run_talus({"--restart", checkpoint.string()}));
    on_ranks(ranks);
    const fs::path last_file = files_of(checkpoint)[ranks - 1];
    const fs::path aside = fs::absolute("aside.bin");
    fs::rename(last_file, aside);
    refused("restart with the last rank's file missing",
            run_talus({"--restart", checkpoint.string()}));
    fs::rename(aside, last_file);
    // Rank 0's file of the stop, the others of the run's end.
    const fs::path mixed = fs::absolute("mixed_checkpoint.bin");
    for (int r = 0; r < ranks; ++r)
      fs::copy_file(r == 0 ? files_of(stopped_checkpoint)[0] : files_of(last_checkpoint)[r],
                    files_of(mixed)[r], fs::copy_options::overwrite_existing);
    refused("restart from a set of two steps", run_talus({"--restart", mixed.string()}));
    check(folder_files(output) == before, "refused restarts left every output file as it was");
    // A serial checkpoint of the scene, at its last step.
    fs::remove_all(output);
    on_ranks(1);
    const Result serial = run_talus({scene.string()});
    check(serial.exit_code == 0 && fs::exists(checkpoint), "serial run left a checkpoint");
    const fs::path single = fs::absolute("serial_checkpoint.bin");
    fs::copy_file(checkpoint, single, fs::copy_options::overwrite_existing);
    on_ranks(ranks);
    refused(("serial checkpoint restarted on " + std::to_string(ranks) + " ranks").c_str(),
            run_talus({"--restart", single.string()}));
  }
  std::printf("%s\n", good ? "OK" : "FAILED");
  return good ? 0 : 1;
}
