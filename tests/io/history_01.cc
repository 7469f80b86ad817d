// History CSV (header, rows, a wrong row length refused) and the progress
// line's text; off a terminal, the progress is a full line (with the
// unbalanced ratio) every interval, so that a run logging to a file is
// never silent (issue 20, item 13).

#include <talus/io/history_file.h>

#include <chrono>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

int main()
{
  using namespace talus;
  {
    HistoryFile h("history.csv", {"step", "time (s)", "x displacement (m)"}, 2);
    h.record({0, 0.0, 0.0});
    h.record({10, 1e-3, -2.5e-6});
    h.record({20, 2e-3, -1.0e-5});
    try
    {
      h.record({30, 3e-3});
    }
    catch (const std::exception& e)
    {
      std::cout << "refused: " << e.what() << '\n';
    }
    std::cout << "rows: " << h.n_rows() << '\n';
  }
  std::ifstream in("history.csv");
  std::cout << in.rdbuf();
  std::cout << ProgressLine::format(2500, 10000, 0.125, 3.2e-4, 500.0) << '\n';
  std::cout << ProgressLine::format(10000, 10000, 0.5, 1e-6, 1234.5) << '\n';

  // A log every 1 ms, updated every 5 ms: one line per update.
  std::ostringstream log;
  {
    ProgressLine progress(300, log, 1e-3);
    for (unsigned long step = 100; step <= 300; step += 100)
    {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      progress.update(step, 1e-3 * step, 1.0 / step);
    }
  }
  unsigned int lines = 0, with_ratio = 0;
  std::istringstream text(log.str());
  for (std::string line; std::getline(text, line);)
  {
    ++lines;
    with_ratio += line.rfind("talus: step ", 0) == 0 && line.find(" ratio ") != std::string::npos;
  }
  std::cout << "log lines: " << lines << ", starting 'talus: step' with the ratio: " << with_ratio
            << '\n';
  // With no interval, nothing.
  std::ostringstream quiet;
  {
    ProgressLine progress(300, quiet, 0.0);
    progress.update(100, 0.1, 0.5);
  }
  std::cout << "log with interval 0: " << (quiet.str().empty() ? "empty" : quiet.str()) << '\n';
}
