// Partial density scaling of dynamics (issue 23, eq. 89): a column 1 m x
// 1 m x 12 m of elastic zones of 0.25 m (rho = 1000 kg/m^3, E = 1e9 Pa, nu
// = 0, every gridpoint held in x and y: one-dimensional, cp = 1000 m/s),
// with a few deliberately small zones: the gridpoint on the column's edge
// at (0, 0, 0.25) is moved down to z = 0.005, which flattens the zones
// between it and the base corner into slivers that set eq. 84's step. A
// half-sine pulse of stress, 0.1 MPa and 5 ms, enters through the quiet
// base and crosses the slivers. Run at the automatic step (eq. 84, set by
// the slivers) and with partial density scaling at 4 times that step.
// Judged, for tet4, tet10, hex-mixed and tet4 with nodal mixed
// discretization:
// - the scaled run takes the step asked for;
// - the mass added is below 1 % of the column's;
// - the wave's arrival at the middle (the first time the middle
//   cross-section's mean velocity reaches half of sigma0 / (rho cp)),
//   scaled against unscaled, within 1 %;
// - the energy account of the scaled run (kinetic energy with the scaled
//   masses, which the forces accelerate) within 1e-3 of its largest term,
//   every tenth step (nodal mixed discretization too, since its account
//   takes the work of the nodal-averaged strain; 7e-3 off before).
// Before: talus refused 'Partial density scaling' (an unknown entry), and a
// 'Time step' above eq. 84 in dynamics.

#include <talus/base/exceptions.h>
#include <talus/base/parallel_environment.h>
#include <talus/scene/block_system.h>
#include <talus/scene/build_blocks.h>
#include <talus/solver/deformable_solver.h>
#include <talus/zone/tet10_mesh.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

#include "../tests.h"

namespace
{
constexpr double rho = 1000.0, young = 1e9, length = 12.0, width = 1.0;
constexpr double sigma0 = 1e5, duration = 5e-3;

std::string scene(const std::string& element, double time_step)
{
  std::ostringstream s;
  s.precision(17);
  s << "subsection Model\n  set Brick min = 0, 0, 0\n  set Brick max = " << width << ", " << width
    << ", " << length << "\nend\n"
    << "subsection Material\n  set Density = " << rho << "\nend\n"
    << "subsection Deformable\n  set Groups = rock\n  set Edge length = 0.25\n"
    << "  set Element = " << (element == "tet4 nodal mixed" ? "tet4" : element) << "\n"
    << "  set Nodal mixed discretization = " << (element == "tet4 nodal mixed" ? "true" : "false")
    << "\n"
    << "  set Young's modulus = " << young << "\n  set Poisson's ratio = 0\nend\n"
    << "subsection Boundary 1\n  set Corner min = -1, -1, -1\n"
    << "  set Corner max = 2, 2, 20\n  set Condition = fixed\n  set Held components = x, y\nend\n"
    << "subsection Boundary 2\n  set Corner min = -0.01, -0.01, -0.005\n"
    << "  set Corner max = 1.01, 1.01, 0.005\n  set Condition = quiet\n"
    << "  set Stress wave = half-sine\n  set Wave amplitude = " << sigma0
    << "\n  set Wave duration = " << duration << "\nend\n"
    << "subsection Solver\n  set Mode = dynamic\n  set Gravity = 0, 0, 0\n";
  if (time_step > 0.0)
    s << "  set Time step = " << time_step << "\n  set Partial density scaling = true\n";
  s << "end\n";
  return s.str();
}

/// The mesh of the column with the edge gridpoint at (0, 0, 0.25) moved to
/// z = 0.005 (10-node zones: their edge midpoints follow).
talus::TetMesh sliver_mesh(const talus::Scene& sc, const talus::BlockModel& model)
{
  talus::MeshReport report;
  talus::TetMesh mesh = talus::mesh_deformable_blocks(sc, model, {0}, report);
  for (unsigned int g = 0; g < mesh.n_gridpoints(); ++g)
    if (std::abs(mesh.position[3 * g]) < 1e-9 && std::abs(mesh.position[3 * g + 1]) < 1e-9 &&
        std::abs(mesh.position[3 * g + 2] - 0.25) < 1e-9)
      mesh.position[3 * g + 2] = 0.005;
  for (unsigned int z = 0; z < mesh.n_zones() && mesh.quadratic(); ++z)
    for (int e = 0; e < 6; ++e)
      for (int d = 0; d < 3; ++d)
        mesh.position[3 * mesh.zone_edge_gridpoint[z][e] + d] =
            0.5 * (mesh.position[3 * mesh.zone_gridpoint[z][talus::tet10_edge[e][0]] + d] +
                   mesh.position[3 * mesh.zone_gridpoint[z][talus::tet10_edge[e][1]] + d]);
  return mesh;
}

struct Result
{
  double dt = 0.0, arrival = 0.0, fraction = 0.0, worst_error = 0.0;
  unsigned int scaled = 0;
};

/// Runs the column at `time_step` (0: automatic, unscaled) until the wave
/// has reached the middle.
Result run(const std::string& element, double time_step)
{
  const std::string file = "partial_density_scaling.prm";
  {
    std::FILE* f = std::fopen(file.c_str(), "w");
    std::fputs(scene(element, time_step).c_str(), f);
    std::fclose(f);
  }
  talus::Scene sc = talus::read_scene(file, false);
  talus::BuildReport built;
  talus::BlockModel model = talus::build_blocks(sc, built);
  talus::resolve_group_names(sc, model);
  const talus::TetMesh mesh = sliver_mesh(sc, model);
  talus::ZoneMaterials materials = talus::zone_materials(sc, model, mesh);
  talus::DeformableSolver solver(mesh, std::move(materials.materials), std::move(materials.of_zone),
                                 sc.solver, sc.gridpoint_conditions, sc.face_pressures);
  std::vector<unsigned int> middle;
  for (unsigned int g = 0; g < mesh.n_gridpoints(); ++g)
    if (std::abs(mesh.position[3 * g + 2] - 0.5 * length) < 1e-9)
      middle.push_back(g);
  const double half = 0.5 * sigma0 / (rho * std::sqrt(young / rho));
  Result r;
  r.dt = solver.dt();
  r.fraction = solver.added_mass().fraction();
  r.scaled = solver.added_mass().gridpoints;
  double t_before = 0.0, v_before = 0.0;
  while (r.arrival == 0.0 && solver.time() < 2.0 * length / std::sqrt(young / rho))
  {
    solver.step();
    const std::vector<double> v = solver.velocities();
    double mean = 0.0;
    for (unsigned int g : middle)
      mean += v[3 * g + 2] / middle.size();
    const double t = solver.time() - 0.5 * solver.dt(); // v of the last half step
    // The crossing, linear between the two half steps.
    if (mean >= half)
      r.arrival = t_before + (t - t_before) * (half - v_before) / (mean - v_before);
    t_before = t;
    v_before = mean;
    if (solver.steps_done() % 10 == 0 || r.arrival > 0.0)
    {
      talus::EnergyAccount e;
      solver.add_energy(e);
      r.worst_error = std::max(r.worst_error, std::abs(e.error()) / e.scale());
    }
  }
  std::fprintf(stderr,
               "%s at %.4g s: %lu steps, %u gridpoints scaled, added %.3g of the mass, largest "
               "factor %.3g; arrival %.6g s (L / 2 cp + T / 6 = %.6g s); energy error %.2e\n",
               element.c_str(), r.dt, solver.steps_done(), r.scaled, r.fraction,
               solver.added_mass().largest_factor, r.arrival,
               0.5 * length / std::sqrt(young / rho) + duration / 6.0, r.worst_error);
  return r;
}
} // namespace

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  for (const char* element : {"tet4", "tet10", "hex-mixed", "tet4 nodal mixed"})
  {
    const Result plain = run(element, 0.0);
    const double asked = 4.0 * plain.dt;
    Result scaled;
    try
    {
      scaled = run(element, asked);
    }
    catch (const talus::InputError& e)
    {
      std::printf("%s: refused: %s\n", element, e.what());
      continue;
    }
    std::printf(
        "%s: the scaled run takes 4 times the automatic step: %s; some gridpoints "
        "scaled, under 1 %% of the mass added: %s; arrival at the middle within 1 %% of "
        "the unscaled run: %s; energy account within 1e-3: %s\n",
        element, talus_test::verdict(std::abs(scaled.dt / asked - 1.0) < 1e-12),
        talus_test::verdict(scaled.scaled > 0 && scaled.fraction < 0.01),
        talus_test::verdict(plain.arrival > 0.0 &&
                            std::abs(scaled.arrival / plain.arrival - 1.0) <= 0.01),
        talus_test::verdict(scaled.worst_error <= 1e-3));
  }
}
