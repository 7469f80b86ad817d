#pragma once

// The history file of a run read back for the stage tests: its rows as
// numbers and its column names, and a run of a scene whose summary is
// not what the test compares.

#include <talus/run/simulation.h>
#include <talus/scene/scene.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace
{
using namespace talus;

/// The history file's rows as numbers, and its column names.
std::vector<std::vector<double>> read_history(const std::string& file,
                                              std::vector<std::string>& columns)
{
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  std::stringstream header(line);
  for (std::string c; std::getline(header, c, ',');)
    columns.push_back(c);
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line))
  {
    std::vector<double> row;
    std::stringstream values(line);
    for (std::string v; std::getline(values, v, ',');)
      row.push_back(std::stod(v));
    rows.push_back(row);
  }
  return rows;
}

double column(const std::vector<double>& row, const std::vector<std::string>& columns,
              const std::string& name)
{
  for (std::size_t k = 0; k < columns.size(); ++k)
    if (columns[k] == name)
      return row.at(k);
  std::printf("no column %s\n", name.c_str());
  return NAN;
}

/// Runs `scene` with standard output sent nowhere; returns the exit code.
int run_quietly(const Scene& scene)
{
  std::filesystem::create_directories(scene.output.directory);
  std::fflush(stdout);
  const int saved = dup(1);
  std::freopen("/dev/null", "w", stdout);
  const int code = Simulation(scene).run();
  std::fflush(stdout);
  dup2(saved, 1);
  close(saved);
  return code;
}

/// The last row of stage `stage` (the history's column "stage").
const std::vector<double>& last_of_stage(const std::vector<std::vector<double>>& rows,
                                         const std::vector<std::string>& columns, int stage)
{
  const std::vector<double>* found = &rows.front();
  for (const std::vector<double>& r : rows)
    if (column(r, columns, "stage") == stage)
      found = &r;
  return *found;
}
} // namespace
