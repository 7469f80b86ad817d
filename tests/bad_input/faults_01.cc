// Faults around runs rather than inside one parameter file: restarts from a
// folder, a forged checkpoint, another working folder or a moved project,
// 'Steps' below the checkpoint's step, temporaries left by kill -9, and
// deformable runs that diverge. Each case prints one line with OK or WRONG;
// how talus ended and its messages go to standard error.

#include "../tests.h"

#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using talus_test::verdict;

namespace
{

struct Result
{
  int exit_code = -1; ///< -1: a signal or the time limit
  int signal = 0;
  bool timed_out = false;
  std::string err;
};

std::string read_text(const fs::path& file)
{
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Runs talus with `args` in `folder`, with `environment` added; standard
/// output is dropped, standard error kept.
Result run_talus(const std::vector<std::string>& args, const fs::path& folder,
                 const std::vector<std::string>& environment = {}, double limit_seconds = 300,
                 const char* standard_output = "/dev/null")
{
  const fs::path err_file = fs::absolute(folder) / "stderr.txt";
  std::fflush(stdout);
  const pid_t child = fork();
  if (child == 0)
  {
    if (chdir(folder.c_str()) != 0 || !freopen(standard_output, "w", stdout) ||
        !freopen(err_file.c_str(), "w", stderr))
      _exit(126);
    for (const std::string& e : environment)
      putenv(const_cast<char*>(e.c_str()));
    std::vector<char*> argv{const_cast<char*>("talus")};
    for (const std::string& a : args)
      argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(TALUS_EXECUTABLE, argv.data());
    _exit(127);
  }
  Result r;
  int status = 0;
  const auto start = std::chrono::steady_clock::now();
  while (waitpid(child, &status, WNOHANG) == 0)
  {
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >
        limit_seconds)
    {
      kill(child, SIGKILL);
      waitpid(child, &status, 0);
      r.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (!r.timed_out && WIFEXITED(status))
    r.exit_code = WEXITSTATUS(status);
  else if (!r.timed_out)
    r.signal = WTERMSIG(status);
  r.err = read_text(err_file);
  fs::remove(err_file);
  return r;
}

void show(const std::string& what, const Result& r)
{
  std::fprintf(stderr, "%s: exit code %d%s%s\n%s", what.c_str(), r.exit_code,
               r.signal ? (", signal " + std::to_string(r.signal)).c_str() : "",
               r.timed_out ? ", timed out" : "", r.err.c_str());
}

bool contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

/// Every file named by the PVD files in `folder` is there.
bool frames_present(const fs::path& folder)
{
  bool all = true;
  for (const auto& entry : fs::directory_iterator(folder))
    if (entry.path().extension() == ".pvd")
    {
      const std::string text = read_text(entry.path());
      for (std::size_t at = 0; (at = text.find("file=\"", at)) != std::string::npos;)
      {
        at += 6;
        const std::string name = text.substr(at, text.find('"', at) - at);
        if (!fs::exists(folder / name))
        {
          std::fprintf(stderr, "%s names %s, which is missing\n", entry.path().filename().c_str(),
                       name.c_str());
          all = false;
        }
      }
    }
  return all;
}

std::uint64_t fnv1a(const char* p, std::size_t n)
{
  std::uint64_t h = 14695981039346656037ull;
  for (std::size_t i = 0; i < n; ++i)
    h = (h ^ static_cast<unsigned char>(p[i])) * 1099511628211ull;
  return h;
}

/// A checkpoint cut after its fingerprints and step, with a header whose size
/// and checksum fit: it passes every check made before the output files are
/// opened and fails while the state is read.
void forge_checkpoint(const fs::path& from, const fs::path& to)
{
  const std::string bytes = read_text(from);
  const std::size_t header = 28;
  std::size_t at = header;
  for (int string = 0; string < 2; ++string) // the tag, then the parameter file
  {
    std::uint64_t n = 0;
    std::memcpy(&n, bytes.data() + at, 8);
    at += 8 + n;
    if (string == 0)
      at += 2 * 4; // the rank and the number of ranks that wrote it (format 9)
  }
  at += 3 * 8; // scene and geometry fingerprints, step
  std::string payload = bytes.substr(header, at - header);
  const std::uint64_t size = payload.size(), hash = fnv1a(payload.data(), payload.size());
  std::string out = bytes.substr(0, 12);
  out.append(reinterpret_cast<const char*>(&size), 8);
  out.append(reinterpret_cast<const char*>(&hash), 8);
  out += payload;
  std::ofstream(to, std::ios::binary) << out;
}

const char* rigid_scene = R"(subsection Model
  set Brick min = 0, 0, 0
  set Brick max = 1, 1, 3
end
subsection Joint set 1
  set Spacing = 1
end
subsection Group 1
  set Name = floor
  set Corner min = 0, 0, 0
  set Corner max = 1, 1, 1
end
subsection Solver
  set Steps = 60
  set Target ratio = 0
  set Fixed groups = floor
  set Output interval = 20
end
subsection Output
  set Directory = out
  set Base name = stack
end
)";

/// A one-block deformable scene that diverges for the reason `entries` give.
std::string deformable_scene(const std::string& entries)
{
  return "subsection Model\n  set Brick min = 0, 0, 0\n  set Brick max = 1, 1, 1\nend\n"
         "subsection Deformable\n  set Groups = rock\n  set Edge length = 0.5\n" +
         entries +
         "end\nsubsection Boundary 1\n  set Corner min = -1, -1, -0.1\n"
         "  set Corner max = 2, 2, 0.1\nend\n" +
         "subsection Solver\n  set Steps = 200\n  set Target ratio = 0\nend\n";
}

void write(const fs::path& file, const std::string& text)
{
  std::ofstream(file) << text;
}

} // namespace

int main()
{
  const fs::path work = fs::absolute("faults_work");
  fs::remove_all(work);
  fs::create_directories(work / "project");
  const fs::path project = work / "project";
  write(project / "stack.prm", rigid_scene);
  const std::vector<std::string> stop_at_30{"TALUS_TEST_SIGNAL_AT_STEP=30"};

  // A run stopped at step 30 with its checkpoint.
  const Result stopped = run_talus({"stack.prm"}, project, stop_at_30);
  show("run stopped at step 30", stopped);
  const fs::path checkpoint = project / "out" / "stack_checkpoint.bin";
  std::printf("a run stopped by SIGTERM leaves its checkpoint: %s\n",
              verdict(stopped.exit_code == 143 && fs::exists(checkpoint)));

  // 17: a folder given as the checkpoint.
  {
    const Result r = run_talus({"--restart", "out"}, project);
    show("restart from a folder", r);
    std::printf("--restart FOLDER is refused with a message (exit code 1): %s\n",
                verdict(r.exit_code == 1 && contains(r.err, "folder, not a checkpoint")));
  }

  // 20, 21: a forged checkpoint is refused and leaves every output as it was.
  {
    forge_checkpoint(checkpoint, project / "forged.bin");
    const std::string history = read_text(project / "out" / "stack_history.csv");
    const std::string pvd = read_text(project / "out" / "stack_blocks.pvd");
    const Result r = run_talus({"--restart", "forged.bin"}, project);
    show("restart from a forged checkpoint", r);
    std::printf("a forged checkpoint is refused: %s\n",
                verdict(r.exit_code == 1 && contains(r.err, "talus: error")));
    std::printf("the refused restart leaves the history and the PVD file as they were: %s\n",
                verdict(read_text(project / "out" / "stack_history.csv") == history &&
                        read_text(project / "out" / "stack_blocks.pvd") == pvd &&
                        history.size() > 100));
    fs::remove(project / "forged.bin");
  }

  // 21: 'Steps' below the checkpoint's step.
  {
    write(work / "short.prm",
          std::string(rigid_scene)
              .replace(std::string(rigid_scene).find("Steps = 60"), 10, "Steps = 20"));
    const Result r =
        run_talus({"--restart", checkpoint.string(), (work / "short.prm").string()}, work);
    show("restart with Steps below the checkpoint's step", r);
    std::printf("'Steps' below the checkpoint's step is refused: %s\n",
                verdict(r.exit_code == 1 && contains(r.err, "at step 30")));
  }

  // 21: a restart from another working folder continues in the checkpoint's
  // folder, and every frame its PVD files name is there.
  {
    fs::create_directories(work / "elsewhere");
    const fs::path copy = work / "copy";
    fs::copy(project, copy, fs::copy_options::recursive);
    const Result r =
        run_talus({"--restart", "../copy/out/stack_checkpoint.bin"}, work / "elsewhere");
    show("restart from another working folder", r);
    std::printf("a restart from another working folder continues in the checkpoint's folder: %s\n",
                verdict(r.exit_code == 0 && !fs::exists(work / "elsewhere" / "out") &&
                        frames_present(copy / "out") &&
                        contains(read_text(copy / "out" / "stack_history.csv"), "\n60,")));
    fs::remove_all(copy);
  }

  // 21: a moved project restarts with its parameter file named.
  {
    const fs::path moved = work / "moved";
    fs::rename(project, moved);
    const Result refused = run_talus({"--restart", "out/stack_checkpoint.bin"}, moved);
    show("restart of a moved project", refused);
    std::printf("a moved project's restart says how to name the parameter file: %s\n",
                verdict(refused.exit_code == 1 && contains(refused.err, "--restart")));
    const Result r = run_talus({"--restart", "out/stack_checkpoint.bin", "stack.prm"}, moved);
    show("restart of a moved project, parameter file named", r);
    std::printf("talus --restart CHECKPOINT SCENE.prm continues a moved project: %s\n",
                verdict(r.exit_code == 0 && frames_present(moved / "out")));
    fs::rename(moved, project);
  }

  // 21: a temporary left by a run killed while writing (kill -9) is removed
  // by the next run into the folder; one of a live process is kept.
  {
    const pid_t gone = fork();
    if (gone == 0)
      _exit(0);
    waitpid(gone, nullptr, 0);
    const fs::path stale = project / "out" / ("stack_history.csv.tmp" + std::to_string(gone));
    const fs::path live = project / "out" / ("stack_history.csv.tmp" + std::to_string(getpid()));
    write(stale, "half a file");
    write(live, "being written");
    const Result r = run_talus({"stack.prm"}, project);
    show("run into a folder with temporaries", r);
    std::printf("a temporary of a killed run is removed, one of a live run kept: %s\n",
                verdict(r.exit_code == 0 && !fs::exists(stale) && fs::exists(live)));
    fs::remove(live);
  }

  // 20: a summary that cannot be written (a full disk) is no success.
  {
    const Result r = run_talus({"stack.prm"}, project, {}, 300, "/dev/full");
    show("run with standard output on a full disk", r);
    std::printf("a run whose summary cannot be written does not end with exit code 0: %s\n",
                verdict(r.exit_code > 0 && contains(r.err, "standard output")));
  }

  // 18: a file of 100,001 joint sets is refused at once (reading it took
  // ParameterHandler hours); the limit here is far above the time it takes.
  {
    std::ofstream file(work / "many_sets.prm");
    file << "subsection Model\n  set Brick min = 0, 0, 0\n  set Brick max = 10, 10, 10\nend\n";
    for (int k = 1; k <= 100001; ++k)
      file << "subsection Joint set " << k << "\n  set Spacing = 1\nend\n";
    file.close();
    const Result r = run_talus({"many_sets.prm"}, work, {}, 60);
    show("a file of 100,001 joint sets", r);
    std::printf("a file of 100,001 joint sets is refused within a minute: %s\n",
                verdict(r.exit_code == 1 && contains(r.err, "at most 10000")));
  }

  // 17: deformable runs that diverge end with the divergence message and
  // exit code 3 (the last good state written), never an internal error.
  const std::vector<std::pair<std::string, std::string>> diverging{
      {"Young's modulus of 1e-30 Pa under gravity", "  set Young's modulus = 1e-30\n"},
      {"a boundary velocity of 1e5 m/s",
       "end\nsubsection Boundary 2\n  set Corner min = -1, -1, 0.9\n  set Corner max = 2, 2, 1.1\n"
       "  set Condition = velocity\n  set Velocity = 0, 0, 1e5\n"}};
  for (const auto& [what, entries] : diverging)
  {
    const fs::path folder = work / "deformable";
    fs::create_directories(folder);
    write(folder / "scene.prm", deformable_scene(entries));
    const Result r = run_talus({"scene.prm"}, folder);
    show(what, r);
    std::printf("a deformable run with %s stops as diverged (exit code 3): %s\n", what.c_str(),
                verdict((r.exit_code == 3 && contains(r.err, "diverged")) ||
                        (r.exit_code == 1 && contains(r.err, "talus: error:"))));
    fs::remove_all(folder);
  }
  {
    const fs::path folder = work / "deformable";
    fs::create_directories(folder);
    write(folder / "scene.prm", deformable_scene("") +
                                    "subsection Boundary 2\n  set Corner min = -1, -1, 0.9\n"
                                    "  set Corner max = 2, 2, 1.1\n  set Condition = pressure\n"
                                    "  set Pressure = 1e300\nend\n");
    const Result r = run_talus({"scene.prm"}, folder);
    show("a pressure of 1e300 Pa", r);
    std::printf("a deformable run with a pressure of 1e300 Pa stops as diverged (exit code 3): "
                "%s\n",
                verdict(r.exit_code == 3 && contains(r.err, "diverged") &&
                        frames_present(folder / "output")));
    fs::remove_all(folder);
  }
  fs::remove_all(work);
}
