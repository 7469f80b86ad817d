// Loads that vary in time (issue 23): a free rigid 1 m cube (2000 kg, no
// gravity, time step 1e-4 s) takes a traction 1000 Pa x t/(1 s) on its
// face x = 1 ('Boundary 1', traction, a table ramp 0 -> 1 over 1 s) and a
// force 500 N sin(2 pi 2 t) up ('Load 1', harmonic): at 0.5 s its x
// displacement must be 1000 t^3 / (6 m) and its z displacement 500 / (m
// omega) (t - sin(omega t) / omega), both within 1e-3. A deformable
// column (tet4, 1 m x 1 m x 2 m, base fixed, local damping 0.8 in
// dynamics) takes on its top a gridpoint load of 100 N down on each top
// gridpoint and a pressure of 1e4 Pa, both ramped from 0 to 1 over 0.2 s
// by a table: after 1 s its base's reaction must be their sum within 1e-3;
// the energy account closes (error within 1e-4 of its largest term, the
// work of the ramped loads in the boundaries' work). Before issue 23 talus
// refused 'Time function'.

#include <talus/base/parallel_environment.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "../stability/scene_text.h"
#include "../tests.h"
#include "zone_scene.h"

namespace
{
constexpr double pi = 3.14159265358979323846;

void write(const std::string& file, const std::string& text)
{
  std::FILE* f = std::fopen(file.c_str(), "w");
  std::fputs(text.c_str(), f);
  std::fclose(f);
}

void rigid_cube()
{
  TextScene s("loads_in_time_cube.prm",
              "subsection Model\n  set Brick min = 0, 0, 0\n  set Brick max = 1, 1, 1\nend\n"
              "subsection Material\n  set Density = 2000\nend\n"
              "subsection Boundary 1\n  set Corner min = 0.99, -0.01, -0.01\n"
              "  set Corner max = 1.01, 1.01, 1.01\n  set Condition = traction\n"
              "  set Traction = 1000, 0, 0\n  set Time function = table\n"
              "  set Time table = ramp_1s.csv\nend\n"
              "subsection Load 1\n  set Group = rock\n  set Force = 0, 0, 500\n"
              "  set Time function = harmonic\n  set Frequency = 2\n  set Hold rotation = true\n"
              "end\n"
              "subsection Solver\n  set Mode = dynamic\n  set Gravity = 0, 0, 0\n"
              "  set Time step = 1e-4\nend\n");
  talus::RigidSolver& solver = *s.solver;
  solver.set_face_loads(s.scene.face_pressures);
  while (solver.time() < 0.5 - 0.5 * solver.dt())
    solver.step();
  const double m = 2000.0, t = solver.time(), omega = 2.0 * pi * 2.0;
  const double ux = 1000.0 * t * t * t / (6.0 * m);
  const double uz = 500.0 / (m * omega) * (t - std::sin(omega * t) / omega);
  const talus::Vec3 u = solver.displacement[0];
  std::fprintf(stderr,
               "rigid cube at %.6g s: ux %.9g m (expected %.9g), uz %.9g m (expected %.9g)\n", t,
               u.x(), ux, u.z(), uz);
  std::printf("rigid cube: displacement under the ramped traction within 1e-3: %s; under the "
              "harmonic force within 1e-3: %s\n",
              talus_test::verdict(std::abs(u.x() / ux - 1.0) <= 1e-3),
              talus_test::verdict(std::abs(u.z() / uz - 1.0) <= 1e-3));
}

void column()
{
  ZoneScene s("loads_in_time_column.prm",
              "subsection Model\n  set Brick min = 0, 0, 0\n  set Brick max = 1, 1, 2\nend\n"
              "subsection Material\n  set Density = 1000\nend\n"
              "subsection Deformable\n  set Groups = rock\n  set Edge length = 0.5\n"
              "  set Element = tet4\n  set Young's modulus = 1e9\n  set Poisson's ratio = 0.25\n"
              "end\n"
              "subsection Boundary 1\n  set Corner min = -0.01, -0.01, -0.01\n"
              "  set Corner max = 1.01, 1.01, 0.01\n  set Condition = fixed\nend\n"
              "subsection Boundary 2\n  set Corner min = -0.01, -0.01, 1.99\n"
              "  set Corner max = 1.01, 1.01, 2.01\n  set Condition = load\n"
              "  set Force = 0, 0, -100\n  set Time function = table\n"
              "  set Time table = ramp_02s.csv\nend\n"
              "subsection Boundary 3\n  set Corner min = -0.01, -0.01, 1.99\n"
              "  set Corner max = 1.01, 1.01, 2.01\n  set Condition = pressure\n"
              "  set Pressure = 1e4\n  set Time function = table\n"
              "  set Time table = ramp_02s.csv\nend\n"
              "subsection Solver\n  set Mode = dynamic\n  set Gravity = 0, 0, 0\n"
              "  set Dynamic local damping = 0.8\nend\n");
  talus::DeformableSolver& solver = *s.solver;
  const talus::TetMesh& mesh = s.mesh;
  unsigned int n_top = 0;
  for (unsigned int g = 0; g < mesh.n_gridpoints(); ++g)
    n_top += mesh.position[3 * g + 2] > 1.99;
  double worst_error = 0.0;
  while (solver.time() < 1.0)
  {
    solver.step();
    talus::EnergyAccount e;
    solver.add_energy(e);
    worst_error = std::max(worst_error, std::abs(e.error()) / e.scale());
  }
  const bool held[3] = {true, true, true};
  const talus::Vec3 reaction = solver.support_force(s.scene.gridpoint_conditions[0].region, held);
  const double expected = 100.0 * n_top + 1e4;
  std::fprintf(stderr,
               "column: %u top gridpoints, %lu steps; base reaction %.9g N (expected %.9g); "
               "energy error at most %.2e of the largest term\n",
               n_top, solver.steps_done(), reaction.z(), expected, worst_error);
  std::printf("column: base reaction to the ramped load and pressure within 1e-3: %s; energy "
              "account error within 1e-4 of its largest term: %s\n",
              talus_test::verdict(std::abs(std::abs(reaction.z()) / expected - 1.0) <= 1e-3),
              talus_test::verdict(worst_error <= 1e-4));
}
} // namespace

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  write("ramp_1s.csv", "time, factor\n0, 0\n1, 1\n");
  write("ramp_02s.csv", "0, 0\n0.2, 1\n");
  rigid_cube();
  column();
}
