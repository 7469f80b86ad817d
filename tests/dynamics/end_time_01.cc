// 'Solver / End time' and the history's input columns (issue 23): a 1 m
// cube on a fixed one under gravity, dynamic, pushed by 'Load 1' with a
// force 'Force' 0, 0, 1000 N times sin(2 pi 50 t) (a harmonic time
// function), every step in the history. With 'End time = 0.01' and
// 'Steps = 100000' the run stops at the step that reaches 0.01 s (half a
// step of slack for round-off, as 'Time limit': its last time within half
// a step of 0.01 s); with 'Steps = 20' the steps
// come first (20 steps, before 0.01 s); in stages, End time stops the
// whole run in the stage that reaches it (stage 2 of 3) and the stages
// after it do not run. The history has a column 'Load 1 input' with sin(2 pi 50 t) at each
// row's time (to the 12 digits it is written with). Before issue 23 talus
// refused 'End time' ('End time' is not an entry of 'Solver').

#include <talus/base/parallel_environment.h>
#include <talus/run/simulation.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../tests.h"

namespace
{
constexpr double pi = 3.14159265358979323846;

void run(const std::string& name, const std::string& solver, const std::string& stages,
         unsigned int expected_steps)
{
  const std::string file = "end_time_" + name + ".prm";
  {
    std::ofstream f(file);
    f << "subsection Model\n  set Brick min = 0, 0, 0\n  set Brick max = 1, 1, 2\nend\n"
         "subsection Joint 1\n  set Dip = 0\n  set Origin = 0, 0, 1\nend\n"
         "subsection Group 1\n  set Name = floor\n  set Corner min = 0, 0, 0\n"
         "  set Corner max = 1, 1, 1\nend\n"
         "subsection Joint properties\n  set Normal stiffness = 1e10\n"
         "  set Shear stiffness = 1e10\nend\n"
         "subsection Load 1\n  set Group = rock\n  set Force = 0, 0, 1000\n"
         "  set Time function = harmonic\n  set Frequency = 50\nend\n"
         "subsection Solver\n  set Mode = dynamic\n  set Fixed groups = floor\n"
         "  set History interval = 1\n"
      << solver << "end\n"
      << stages << "subsection Output\n  set Directory = output_" << name
      << "\n  set Write VTU = false\nend\n";
  }
  // talus's summary to standard error, which is not compared.
  std::fflush(stdout);
  const int saved = dup(1);
  dup2(2, 1);
  int code = 0;
  {
    talus::Simulation simulation(file);
    code = simulation.run();
  }
  std::fflush(stdout);
  dup2(saved, 1);
  close(saved);

  std::ifstream history("output_" + name + "/talus_history.csv");
  std::string line;
  std::getline(history, line);
  std::vector<std::string> columns;
  {
    std::stringstream s(line);
    for (std::string c; std::getline(s, c, ',');)
      columns.push_back(c);
  }
  int time_column = -1, input_column = -1, stage_column = -1;
  for (int c = 0; c < int(columns.size()); ++c)
  {
    if (columns[c] == "time (s)")
      time_column = c;
    if (columns[c] == "Load 1 input")
      input_column = c;
    if (columns[c] == "stage")
      stage_column = c;
  }
  double last = 0.0, before = 0.0, worst = 0.0, last_stage = 0.0;
  unsigned int rows = 0;
  while (std::getline(history, line))
  {
    std::vector<double> row;
    std::stringstream s(line);
    for (std::string c; std::getline(s, c, ',');)
      row.push_back(std::stod(c));
    if (time_column < 0 || input_column < 0 || int(row.size()) <= input_column)
      break;
    if (stage_column >= 0)
      last_stage = row[stage_column];
    before = last;
    last = row[time_column];
    worst = std::max(worst, std::abs(row[input_column] - std::sin(2.0 * pi * 50.0 * last)));
    ++rows;
  }
  const double dt = last - before;
  std::fprintf(stderr,
               "%s: exit code %d, %u rows, last time %.9g s, step %.4g s, last stage %g, input "
               "error %.3g\n",
               name.c_str(), code, rows, last, dt, last_stage, worst);
  const bool stopped = (expected_steps > 0 ? rows == expected_steps + 1 && last < 0.01
                                           : std::abs(last - 0.01) <= 0.5 * dt * (1.0 + 1e-9)) &&
                       (stage_column < 0 || last_stage == 2.0);
  std::printf("%s: exit code %d; stopped %s: %s; 'Load 1 input' is sin(2 pi 50 t): %s\n",
              name.c_str(), code,
              expected_steps > 0 ? "at the step limit before the end time"
                                 : "within half a step of the end time",
              talus_test::verdict(stopped),
              talus_test::verdict(input_column >= 0 && rows > 2 && worst <= 1e-11));
}
} // namespace

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  run("end_first", "  set Steps = 100000\n  set End time = 0.01\n", "", 0);
  run("steps_first", "  set Steps = 20\n  set End time = 0.01\n", "", 20);
  run("stages", "  set Steps = 100000\n  set End time = 0.01\n",
      "subsection Stage 1\n  set Steps = 30\nend\n"
      "subsection Stage 2\n  set Steps = 100000\nend\n"
      "subsection Stage 3\n  set Steps = 100000\nend\n",
      0);
}
