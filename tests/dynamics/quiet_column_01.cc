// Quiet boundaries (issue 23): a column 0.5 m x 0.5 m x 10 m of elastic
// zones of 0.25 m (rho = 1000 kg/m^3, E = 1e9 Pa, nu = 0, its sides on
// rollers: every gridpoint held in x and y, so the column is
// one-dimensional with cp = sqrt(E / rho) = 1000 m/s), quiet at its base
// and its top. A half-sine pulse of normal stress sigma0 = 0.1 MPa, 5 ms
// long (20 zones), enters through the quiet base ('Stress wave', applied
// as twice the incident stress on the base's dashpots), crosses the
// column and leaves through the quiet top. Judged, for tet4, hex-mixed
// and tet10:
// - the travel time to the middle: the centroid in time of the middle
//   cross-section's velocity less that of the input pulse (T / 2), against
//   (L / 2) / cp, within 2 %;
// - the peak velocity there times rho cp against sigma0, within 2 %;
// - the energy left in the column (kinetic and strain) after the pulse has
//   left (at T + 1.5 L / cp), at most 2 % of the energy put in, A sigma0^2
//   T / (2 rho cp);
// - the energy account, with the dashpots' dissipation in its damping
//   term: its error at most 1e-3 of its largest term over the run;
// and tet4 once more, read as a static scene (which warns that its quiet
// boundaries act only in dynamic stages) and then turned dynamic, as a
// dynamic stage does.
// Before: talus refused 'Condition = quiet'.

#include <talus/base/parallel_environment.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

#include "../tests.h"
#include "zone_scene.h"

namespace
{
constexpr double rho = 1000.0, young = 1e9, length = 10.0, width = 0.5;
constexpr double sigma0 = 1e5, duration = 5e-3;

std::string scene(const std::string& element, bool staged)
{
  std::ostringstream s;
  s.precision(17);
  s << "subsection Model\n  set Brick min = 0, 0, 0\n  set Brick max = " << width << ", " << width
    << ", " << length << "\nend\n"
    << "subsection Material\n  set Density = " << rho << "\nend\n"
    << "subsection Deformable\n  set Groups = rock\n  set Edge length = 0.25\n"
    << "  set Element = " << element << "\n"
    << "  set Young's modulus = " << young << "\n  set Poisson's ratio = 0\nend\n"
    << "subsection Boundary 1\n  set Corner min = -1, -1, -1\n"
    << "  set Corner max = 2, 2, 12\n  set Condition = fixed\n  set Held components = x, y\nend\n"
    << "subsection Boundary 2\n  set Corner min = -0.01, -0.01, -0.01\n"
    << "  set Corner max = 0.51, 0.51, 0.01\n  set Condition = quiet\n"
    << "  set Stress wave = half-sine\n  set Wave amplitude = " << sigma0
    << "\n  set Wave duration = " << duration << "\nend\n"
    << "subsection Boundary 3\n  set Corner min = -0.01, -0.01, 9.99\n"
    << "  set Corner max = 0.51, 0.51, 10.01\n  set Condition = quiet\nend\n"
    << "subsection Solver\n  set Mode = " << (staged ? "static" : "dynamic")
    << "\n  set Gravity = 0, 0, 0\nend\n";
  return s.str();
}

void run(const std::string& element, bool staged = false)
{
  ZoneScene s("quiet_column.prm", scene(element, staged));
  talus::DeformableSolver& solver = *s.solver;
  const talus::TetMesh& mesh = s.mesh;
  const talus::Scene& sc = s.scene;
  if (staged)
  {
    // A static scene warns that its quiet boundaries do nothing; a stage
    // that turns dynamic (set_dynamic) brings them to work.
    bool warned = false;
    for (const std::string& w : sc.warnings)
      warned |= w.find("quiet boundary acts in dynamic stages only") != std::string::npos;
    std::printf("static scene: quiet boundaries ignored, with a warning: %s\n",
                talus_test::verdict(warned));
    for (const std::string& w : sc.warnings)
      std::fprintf(stderr, "warning: %s\n", w.c_str());
    solver.set_dynamic(true);
  }
  const double cp = std::sqrt(young / rho), Z = rho * cp;
  std::vector<unsigned int> middle;
  for (unsigned int g = 0; g < mesh.n_gridpoints(); ++g)
    if (std::abs(mesh.position[3 * g + 2] - 0.5 * length) < 1e-9)
      middle.push_back(g);
  const double end = duration + 1.5 * length / cp;
  PulseRecord pulse{middle, 2};
  while (solver.time() < end)
    pulse.step(solver);
  const double peak = pulse.peak, worst_error = pulse.worst_error;
  talus::EnergyAccount e;
  solver.add_energy(e);
  const double input = width * width * sigma0 * sigma0 * duration / (2.0 * Z);
  const double left = (e.kinetic + e.zone_elastic) / input;
  const double travel = pulse.centre() - 0.5 * duration, expected = 0.5 * length / cp;
  std::fprintf(stderr,
               "%s: %u zones, %u quiet faces, %lu steps of %.4g s; travel %.6g s (L / 2 cp "
               "%.6g), peak rho cp v / sigma0 %.5f, energy left %.3e of the input %.5g J "
               "(quiet dissipation %.5g J), energy error at most %.2e\n",
               (element + (staged ? " (static, then dynamic)" : "")).c_str(), mesh.n_zones(),
               solver.quiet_faces(), solver.steps_done(), solver.dt(), travel, expected,
               peak * Z / sigma0, left, input, solver.quiet_dissipation(), worst_error);
  std::printf("%s: travel time within 2 %%: %s; stress amplitude rho cp v within 2 %%: %s; "
              "energy left at most 2 %% of the input: %s; energy account within 1e-3: %s\n",
              (element + (staged ? " (static, then dynamic)" : "")).c_str(),
              talus_test::verdict(std::abs(travel / expected - 1.0) <= 0.02),
              talus_test::verdict(std::abs(peak * Z / sigma0 - 1.0) <= 0.02),
              talus_test::verdict(left <= 0.02), talus_test::verdict(worst_error <= 1e-3));
}
} // namespace

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  for (const char* element : {"tet4", "hex-mixed", "tet10"})
    run(element);
  run("tet4", true);
}
