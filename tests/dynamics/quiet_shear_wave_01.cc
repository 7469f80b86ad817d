// A shear wave through quiet boundaries (issue 23): a column 0.5 m x
// 0.5 m x 10 m of elastic zones of 0.25 m (rho = 1000 kg/m^3, E = 1e9 Pa,
// nu = 0, so G = 5e8 Pa and cs = sqrt(G / rho) = 707 m/s), every gridpoint
// held in y and z, so that the column is a one-dimensional shear layer
// moving in x; quiet at its base and its top. A half-sine pulse of shear
// stress tau0 = 0.1 MPa along x, 7 ms long (20 zones), enters through the
// quiet base ('Stress wave' with 'Wave direction = 1, 0, 0': twice the
// incident traction on the base, against its shear dashpots rho cs),
// crosses the column and leaves through the quiet top's shear dashpots.
// Judged, for tet4, hex-mixed and tet10:
// - the travel time to the middle: the centroid in time of the middle
//   cross-section's x velocity less that of the input pulse (T / 2),
//   against (L / 2) / cs, within 2 %;
// - the peak velocity there times rho cs against tau0, within 2 %;
// - the energy left in the column (kinetic and strain) once the pulse has
//   left (at T + 1.5 L / cs), at most 2 % of the energy put in, A tau0^2
//   T / (2 rho cs) (with a top held in x instead, the whole pulse comes
//   back: 1.0 of it is left);
// - the energy account, the dashpots' dissipation in its damping term:
//   its error at most 1e-3 of its largest term over the run.
// Before: talus refused 'Wave direction' (a quiet boundary put in normal
// stress waves only).

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
constexpr double tau0 = 1e5, duration = 7e-3;

std::string scene(const std::string& element)
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
    << "  set Corner max = 2, 2, 12\n  set Condition = fixed\n  set Held components = y, z\nend\n"
    << "subsection Boundary 2\n  set Corner min = -0.01, -0.01, -0.01\n"
    << "  set Corner max = 0.51, 0.51, 0.01\n  set Condition = quiet\n"
    << "  set Stress wave = half-sine\n  set Wave amplitude = " << tau0
    << "\n  set Wave duration = " << duration << "\n  set Wave direction = 1, 0, 0\nend\n"
    << "subsection Boundary 3\n  set Corner min = -0.01, -0.01, 9.99\n"
    << "  set Corner max = 0.51, 0.51, 10.01\n  set Condition = quiet\nend\n"
    << "subsection Solver\n  set Mode = dynamic\n  set Gravity = 0, 0, 0\nend\n";
  return s.str();
}

void run(const std::string& element)
{
  ZoneScene s("quiet_shear_wave.prm", scene(element));
  talus::DeformableSolver& solver = *s.solver;
  const talus::TetMesh& mesh = s.mesh;
  const double cs = std::sqrt(0.5 * young / rho), Z = rho * cs;
  std::vector<unsigned int> middle;
  for (unsigned int g = 0; g < mesh.n_gridpoints(); ++g)
    if (std::abs(mesh.position[3 * g + 2] - 0.5 * length) < 1e-9)
      middle.push_back(g);
  const double end = duration + 1.5 * length / cs;
  PulseRecord pulse{middle, 0};
  while (solver.time() < end)
    pulse.step(solver);
  const double peak = pulse.peak, worst_error = pulse.worst_error;
  talus::EnergyAccount e;
  solver.add_energy(e);
  const double input = width * width * tau0 * tau0 * duration / (2.0 * Z);
  const double left = (e.kinetic + e.zone_elastic) / input;
  const double travel = pulse.centre() - 0.5 * duration, expected = 0.5 * length / cs;
  std::fprintf(stderr,
               "%s: %u zones, %u quiet faces, %lu steps of %.4g s; travel %.6g s (L / 2 cs "
               "%.6g), peak rho cs v / tau0 %.5f, energy left %.3e of the input %.5g J "
               "(quiet dissipation %.5g J), energy error at most %.2e\n",
               element.c_str(), mesh.n_zones(), solver.quiet_faces(), solver.steps_done(),
               solver.dt(), travel, expected, peak * Z / tau0, left, input,
               solver.quiet_dissipation(), worst_error);
  std::printf("%s: travel time within 2 %%: %s; shear stress amplitude rho cs v within 2 %%: %s; "
              "energy left at most 2 %% of the input: %s; energy account within 1e-3: %s\n",
              element.c_str(), talus_test::verdict(std::abs(travel / expected - 1.0) <= 0.02),
              talus_test::verdict(std::abs(peak * Z / tau0 - 1.0) <= 0.02),
              talus_test::verdict(left <= 0.02), talus_test::verdict(worst_error <= 1e-3));
}
} // namespace

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  for (const char* element : {"tet4", "hex-mixed", "tet10"})
    run(element);
}
