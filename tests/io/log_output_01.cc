// A run whose standard output and standard error go to files or pipes (a
// run in the background, a batch job) is never silent: each summary line
// arrives as it is printed, not when the run ends, and a progress line
// (step, time, ratio, rate, time left) comes every TALUS_PROGRESS_SECONDS
// (10 s by default) on standard error (issue 20, item 13). Runs talus on a
// long scene with both streams on pipes, reads until the summary's time step
// line and two progress lines have come while talus still runs, then stops
// it with SIGTERM.

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fcntl.h>
#include <fstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include "../tests.h"

int main()
{
  std::ofstream("log_output_01.prm") << "subsection Model\n"
                                        "  set Brick min = 0, 0, 0\n"
                                        "  set Brick max = 1, 1, 2\n"
                                        "end\n"
                                        "subsection Joint 1\n"
                                        "  set Dip = 0\n"
                                        "  set Origin = 0, 0, 1\n"
                                        "end\n"
                                        "subsection Group 1\n"
                                        "  set Name = floor\n"
                                        "  set Corner min = 0, 0, 0\n"
                                        "  set Corner max = 1, 1, 1\n"
                                        "end\n"
                                        "subsection Solver\n"
                                        "  set Mode = dynamic\n"
                                        "  set Steps = 100000000\n"
                                        "  set Fixed groups = floor\n"
                                        "end\n"
                                        "subsection Output\n"
                                        "  set Directory = log_output_01_output\n"
                                        "  set Write VTU = false\n"
                                        "end\n";
  // Runs talus with TALUS_PROGRESS_SECONDS = `progress` until `enough`
  // says what it read suffices (or 60 s), stops it with SIGTERM and says
  // whether it was still running when that was read.
  const auto watch = [](const char* progress, auto enough, std::string& out, std::string& err)
  {
    int out_pipe[2], err_pipe[2];
    if (pipe(out_pipe) != 0 || pipe(err_pipe) != 0)
      std::exit(2);
    const pid_t child = fork();
    if (child == 0)
    {
      dup2(out_pipe[1], 1);
      dup2(err_pipe[1], 2);
      close(out_pipe[0]);
      close(err_pipe[0]);
      setenv("TALUS_PROGRESS_SECONDS", progress, 1);
      execl(TALUS_EXECUTABLE, "talus", "log_output_01.prm", static_cast<char*>(nullptr));
      _exit(127);
    }
    close(out_pipe[1]);
    close(err_pipe[1]);
    fcntl(out_pipe[0], F_SETFL, O_NONBLOCK);
    fcntl(err_pipe[0], F_SETFL, O_NONBLOCK);
    const auto start = std::chrono::steady_clock::now();
    bool running = true, read_enough = false;
    while (std::chrono::steady_clock::now() - start < std::chrono::seconds(60))
    {
      char buffer[4096];
      for (ssize_t n; (n = read(out_pipe[0], buffer, sizeof buffer)) > 0;)
        out.append(buffer, static_cast<std::size_t>(n));
      for (ssize_t n; (n = read(err_pipe[0], buffer, sizeof buffer)) > 0;)
        err.append(buffer, static_cast<std::size_t>(n));
      if (waitpid(child, nullptr, WNOHANG) == child)
      {
        running = false;
        break;
      }
      if ((read_enough = enough()))
        break;
      usleep(20000);
    }
    if (running)
    {
      kill(child, SIGTERM);
      waitpid(child, nullptr, 0);
    }
    close(out_pipe[0]);
    close(err_pipe[0]);
    return running && read_enough;
  };

  // Progress off: the summary's lines must come on their own.
  std::string out, err;
  const bool summary = watch(
      "0", [&] { return out.find("Time step:") != std::string::npos; }, out, err);
  std::printf("summary line 'Time step' read while talus runs: %s\n", summary ? "yes" : "NO");

  // Progress every 0.2 s: lines on standard error while it runs.
  std::string out2, err2;
  const auto progress_lines = [&]
  {
    unsigned int n = 0;
    for (std::size_t at = 0; (at = err2.find("talus: step ", at)) != std::string::npos; ++at)
      ++n;
    return n;
  };
  const bool progress = watch(
      "0.2", [&] { return progress_lines() >= 2; }, out2, err2);
  const std::size_t first = err2.find("talus: step ");
  const std::string line =
      first == std::string::npos ? "" : err2.substr(first, err2.find('\n', first) - first);
  std::printf("progress lines read while talus runs: %s; the first names step, t, ratio, steps/s "
              "and time left: %s\n",
              progress ? "at least 2" : "FEWER THAN 2",
              line.find(" t = ") != std::string::npos &&
                      line.find(" ratio ") != std::string::npos &&
                      line.find(" steps/s ") != std::string::npos &&
                      line.find(" s left") != std::string::npos
                  ? "yes"
                  : "NO");
  std::fprintf(stderr, "first progress line: %s\n", line.c_str());
  return 0;
}
