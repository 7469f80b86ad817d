// A harmonic plane wave through a joint between quiet boundaries (issue
// 23): two elastic columns, 1 m x 1 m in cross-section, 40 m each, zones
// of 1 m (rho = 2600 kg/m^3, cp = 5000 m/s, nu = 0: one-dimensional
// waves at cp with free sides), joined by a horizontal joint of normal
// stiffness kn that carries an in-situ stress of 1 MPa (a pressure of 1
// MPa on the base and the top). The base and the top are quiet; a
// harmonic 'Stress wave' of 13 kPa at 50 Hz enters through the base
// (incident velocity v_in = sigma0 / (rho cp) = 1e-3 m/s). What the joint
// reflects leaves through the base and what it transmits through the top,
// so the upper column carries the transmitted wave alone: its amplitude
// over v_in must be |T| = 2 kn / sqrt(4 kn^2 + (omega Z)^2), Z = rho cp
// (a spring between two equal half-spaces), within 2 %, at kn = 1e9 Pa/m
// (|T| = 0.44) and 4e9 Pa/m (0.89), tet4, hex-mixed and tet10. Measured: half the range of the
// mean vertical velocity of the cross-section 20 m above the joint, over
// two periods from three periods after the wave's arrival there. The
// energy account, with the dashpots' work in its damping term, closes to
// 1e-6 of its largest term at the end.
// Before: no quiet boundary (FacePressure had no 'quiet').

#include <talus/base/parallel_environment.h>
#include <talus/scene/block_system.h>
#include <talus/scene/build_blocks.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "../tests.h"

using namespace talus;

namespace
{
constexpr double rho = 2600.0, cp = 5000.0, frequency = 50.0, sigma0 = 1.3e4;
constexpr double lower = 40.0, upper = 40.0, probe = 20.0, stress = 1e6; // m, Pa

double energy_error = 0.0; ///< of the last run, over the account's largest term

/// The amplitude of the transmitted wave at the probe over v_in.
double transmitted(double kn, ZoneElement element)
{
  Scene scene;
  scene.parameter_file = "quiet_joint_01";
  scene.brick = Box{Vec3::Zero(), Vec3(1, 1, lower + upper)};
  scene.density = rho;
  JointPlaneSpec joint;
  joint.origin = Vec3(0, 0, lower);
  scene.joint_planes.push_back(joint);
  scene.joint_plane_sections.push_back("Joint 1");
  scene.deformable.groups = {"rock"};
  scene.deformable.edge_length = 1.0;
  scene.deformable.material.element = element;
  scene.deformable.material.density = rho;
  scene.deformable.material.set_young_poisson(rho * cp * cp, 0.0);
  scene.solver.dynamic = true;
  scene.solver.steps = 1000000;
  scene.solver.gravity = Vec3::Zero();
  scene.solver.joint.normal_stiffness = kn;
  scene.solver.joint.shear_stiffness = kn;
  scene.solver.contact.tolerance = 0.01;
  scene.has_initial_stress = true;
  scene.initial_stress.base[2] = -stress;
  const Box base{Vec3(-1, -1, -0.01), Vec3(2, 2, 0.01)};
  const Box top{Vec3(-1, -1, lower + upper - 0.01), Vec3(2, 2, lower + upper + 0.01)};
  for (int end = 0; end < 2; ++end)
  {
    const Box& b = end == 0 ? base : top;
    FacePressure pressure;
    pressure.region = b;
    pressure.pressure = stress;
    scene.face_pressures.push_back(pressure);
    FacePressure quiet;
    quiet.region = b;
    quiet.quiet = true;
    if (end == 0)
    {
      quiet.wave.kind = WaveSignal::Kind::harmonic;
      quiet.wave.amplitude = sigma0;
      quiet.wave.frequency = frequency;
    }
    scene.face_pressures.push_back(quiet);
  }
  BuildReport built;
  BlockModel model = build_blocks(scene, built);
  resolve_group_names(scene, model);
  BlockSystem system = build_block_system(scene, model);
  RigidSolver& solver = *system.solver;
  DeformableSolver& zones = *system.zones;
  const TetMesh& mesh = system.mesh;
  std::vector<unsigned int> probed;
  for (unsigned int g = 0; g < mesh.n_gridpoints(); ++g)
    if (std::abs(mesh.position[3 * g + 2] - (lower + probe)) < 1e-9)
      probed.push_back(g);
  const double period = 1.0 / frequency;
  const double from = (lower + probe) / cp + 3.0 * period, to = from + 2.0 * period;
  double low = 0.0, high = 0.0, worst_error = 0.0;
  while (solver.time() < to)
  {
    solver.step();
    if (solver.time() > from)
    {
      const std::vector<double> v = zones.velocities();
      double mean = 0.0;
      for (unsigned int g : probed)
        mean += v[3 * g + 2] / probed.size();
      low = std::min(low, mean);
      high = std::max(high, mean);
    }
  }
  EnergyAccount e = solver.energy_account();
  worst_error = std::abs(e.error()) / e.scale();
  energy_error = worst_error;
  std::fprintf(stderr,
               "  kn %.3g: %lu steps of %.4g s, %u zones, %u quiet faces, %u sub-contacts; "
               "energy error %.2e of the largest term, quiet dissipation %.4g J\n",
               kn, solver.steps_done(), solver.dt(), mesh.n_zones(), zones.quiet_faces(),
               solver.contacts().n_subcontacts(), worst_error, zones.quiet_dissipation());
  return 0.5 * (high - low) / (sigma0 / (rho * cp));
}
} // namespace

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  const double omega = 2.0 * M_PI * frequency, Z = rho * cp;
  const char* names[] = {"tet4", "hex-mixed", "tet10"};
  const ZoneElement elements[] = {ZoneElement::tet4, ZoneElement::hex_mixed, ZoneElement::tet10};
  for (int k = 0; k < 3; ++k)
    for (double kn : {1e9, 4e9})
    {
      const double exact = 2.0 * kn / std::sqrt(4.0 * kn * kn + omega * Z * omega * Z);
      char name[100];
      std::snprintf(name, sizeof name, "%s, kn = %.0e Pa/m: transmitted amplitude over |T|",
                    names[k], kn);
      talus_test::check_within(name, transmitted(kn, elements[k]), exact, 0.02);
      std::printf("%s, kn = %.0e Pa/m: energy account (quiet dissipation in its damping) within "
                  "1e-6 of its largest term: %s\n",
                  names[k], kn, talus_test::verdict(energy_error <= 1e-6));
    }
}
