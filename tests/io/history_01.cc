// History CSV (header, rows, a wrong row length refused) and the progress
// line's text.

#include <talus/io/history_file.h>

#include <fstream>
#include <iostream>

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
  std::cout << ProgressLine::format(2500, 10000, 0.125, 500.0) << '\n';
  std::cout << ProgressLine::format(10000, 10000, 0.5, 1234.5) << '\n';
}
