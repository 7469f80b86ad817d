// A velocity history on a deformable column's base (issue 23): an elastic
// column 1 m x 1 m x 4 m (tet4 zones of 1 m, rho = 1000 kg/m^3, E = 1e9
// Pa, no gravity) whose base gridpoints ('Boundary 1', velocity, x, y and
// z held) follow a time function: a harmonic velocity (value input,
// 'Velocity' 0.01, 0, 0 times sin(2 pi 20 t) until 0.1 s), then a half-sine
// acceleration pulse (acceleration input, 'Velocity' 1, 0, 0 times the
// integral of 2 sin(pi t / 0.05) over 0.05 s). The base must move by the
// integral of the velocity, in closed form, within 1e-3 at each of 10
// times to 0.12 s (largest relative error over the largest displacement),
// and the energy account closes within 1e-4 of its largest term with the
// work of the moving base in the boundaries' work. Before issue 23 talus
// refused 'Time function' ('Time function' is not an entry of 'Boundary 1').

#include <talus/base/parallel_environment.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

#include "../tests.h"
#include "zone_scene.h"

namespace
{
constexpr double pi = 3.14159265358979323846;

void run(const std::string& name, const std::string& motion,
         const std::function<double(double)>& base_displacement)
{
  ZoneScene s(
      "base_motion_column.prm",
      "subsection Model\n  set Brick min = 0, 0, 0\n  set Brick max = 1, 1, 4\nend\n"
      "subsection Material\n  set Density = 1000\nend\n"
      "subsection Deformable\n  set Groups = rock\n  set Edge length = 1\n"
      "  set Element = tet4\n  set Young's modulus = 1e9\n  set Poisson's ratio = 0.25\nend\n"
      "subsection Boundary 1\n  set Corner min = -0.01, -0.01, -0.01\n"
      "  set Corner max = 1.01, 1.01, 0.01\n  set Condition = velocity\n" +
          motion +
          "end\n"
          "subsection Solver\n  set Mode = dynamic\n  set Gravity = 0, 0, 0\nend\n");
  talus::DeformableSolver& solver = *s.solver;
  const talus::TetMesh& mesh = s.mesh;
  const unsigned int ng = mesh.n_gridpoints();
  double worst = 0.0, largest = 0.0, worst_error = 0.0;
  unsigned int n_base = 0;
  for (int k = 1; k <= 10; ++k)
  {
    while (solver.time() < 0.012 * k - 0.5 * solver.dt())
    {
      solver.step();
      talus::EnergyAccount e;
      solver.add_energy(e);
      worst_error = std::max(worst_error, std::abs(e.error()) / e.scale());
    }
    const std::vector<double> u = solver.displacements();
    const double expected = base_displacement(solver.time());
    n_base = 0;
    for (unsigned int g = 0; g < ng; ++g)
      if (mesh.position[3 * g + 2] < 0.01)
      {
        worst = std::max(worst, std::abs(u[3 * g] - expected));
        ++n_base;
      }
    largest = std::max(largest, std::abs(expected));
  }
  std::fprintf(stderr,
               "%s: %u base gridpoints, %lu steps of %.4g s; base displacement error at most %.3g "
               "m of %.4g m; energy error at most %.2e of the largest term\n",
               name.c_str(), n_base, solver.steps_done(), solver.dt(), worst, largest, worst_error);
  std::printf("%s: base displacement within 1e-3 of the integral of its velocity: %s; energy "
              "account error within 1e-4 of its largest term: %s\n",
              name.c_str(), talus_test::verdict(n_base > 0 && worst <= 1e-3 * largest),
              talus_test::verdict(worst_error <= 1e-4));
}
} // namespace

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  {
    // v = 0.01 sin(omega t) to 0.1 s (two cycles): u = 0.01 (1 - cos(omega t)) / omega.
    const double omega = 2.0 * pi * 20.0;
    run("harmonic velocity",
        "  set Velocity = 0.01, 0, 0\n  set Time function = harmonic\n  set Frequency = 20\n"
        "  set End time of motion = 0.1\n",
        [=](double t) { return 0.01 * (1.0 - std::cos(omega * std::min(t, 0.1))) / omega; });
  }
  {
    // a = 2 sin(pi t / T) for T = 0.05 s: v = 2 T / pi (1 - cos(pi t / T)),
    // u = 2 T / pi (t - T / pi sin(pi t / T)), then v = 4 T / pi.
    const double T = 0.05;
    run("acceleration pulse",
        "  set Velocity = 1, 0, 0\n  set Time function = pulse\n  set Input = acceleration\n"
        "  set Amplitude = 2\n  set Pulse duration = 0.05\n",
        [=](double t)
        {
          return t < T ? 2.0 * T / pi * (t - T / pi * std::sin(pi * t / T))
                       : 2.0 * T / pi * (T + 2.0 * (t - T));
        });
  }
}
