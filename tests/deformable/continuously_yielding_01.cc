// A continuously yielding joint under a deformable plate on a rigid base:
// the sub-contacts on the plate's surface gridpoints take the same joint
// model as those between rigid blocks. The scene of
// parameters/verification/continuously_yielding.prm with its plate made
// deformable (tet4 zones, E = 10 GPa) and sheared 3 mm at 1 mm/s by its top
// face. The plate's own shear strain (below 1e-6) is negligible beside the
// joint's. After 3 mm every sub-contact must sit on its own bound
// sigma_i tan(phi_m(u_p,i)), and the mean shear stress must have peaked
// and softened to the residual sigma_n tan(phi).

#include <talus/base/parallel_environment.h>
#include <talus/joint/continuously_yielding.h>
#include <talus/scene/block_system.h>
#include <talus/scene/build_blocks.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

#include "../rigid/cy_reference.h"
#include "../tests.h"

using namespace talus;

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  const std::string file = "continuously_yielding_01_scene.prm";
  {
    // The shipped scene with its plate deformable and sheared by its top
    // face instead of a block load; the base stays rigid and fixed.
    std::ifstream in(std::string(SOURCE_DIR) +
                     "/../../parameters/verification/continuously_yielding.prm");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t load = text.find("subsection Load 1");
    text.erase(load, text.find("end\n", load) + 4 - load);
    std::ofstream out(file);
    out << text << R"(
subsection Deformable
  set Groups          = plate
  set Element         = tet4
  set Edge length     = 0.5
  set Young's modulus = 1e10
  set Poisson's ratio = 0.25
end
subsection Boundary 1
  set Corner min      = -1, -1, 1.199
  set Corner max      =  3,  3, 1.201
  set Condition       = velocity
  set Velocity        = 0.001, 0, 0
  set Held components = x, y
end
)";
  }
  Scene scene = read_scene(file, false);
  BuildReport built;
  BlockModel model = build_blocks(scene, built);
  resolve_group_names(scene, model);
  BlockSystem system = build_block_system(scene, model);
  RigidSolver& s = *system.solver;
  const JointProperties& j = scene.solver.joint_materials.at(0);
  const double deg = M_PI / 180.0, area = 4.0;
  const double sigma = scene.density * model.volume[1] * 9.81 / area;
  const ContactSet& c = s.contacts();
  const auto shear_stress = [&]()
  {
    double f = 0.0;
    for (unsigned int i = 0; i < c.n_subcontacts(); ++i)
      f -= c.sc_fs[3 * i];
    return f / area;
  };
  // The joint's shear displacement: the mean of the plate's bottom
  // gridpoints (the base is fixed).
  const TetMesh& mesh = system.mesh;
  const auto bottom_shear = [&]()
  {
    const std::vector<double> d = system.zones->displacements();
    double sum = 0.0;
    unsigned int n = 0;
    for (unsigned int g = 0; g < mesh.n_gridpoints(); ++g)
      if (std::abs(mesh.position[3 * g + 2] - 1.0) < 1e-9)
      {
        sum += d[3 * g];
        ++n;
      }
    return sum / n;
  };
  CyReference ref{sigma, j.shear_stiffness, j.friction_angle * deg, j.initial_friction_angle * deg,
                  j.roughness};
  double peak = 0.0, peak_ref = 0.0, u = 0.0;
  while (u < 0.003)
  {
    s.step();
    u = bottom_shear();
    ref.shear_to(u);
    const double tau = shear_stress();
    peak = std::max(peak, tau);
    peak_ref = std::max(peak_ref, ref.tau);
  }
  // Every sub-contact on its own bound sigma_i tan(phi_m(u_p,i)) after
  // 3 mm of shear, with the plastic shear it holds.
  double off_bound = 0.0, u_p_min = 1e300;
  for (unsigned int i = 0; i < c.n_subcontacts(); ++i)
  {
    const double* y = &c.sc_yield[yield_state_size * i];
    const double phi_m =
        (j.friction_angle + (j.initial_friction_angle - j.friction_angle) *
                                std::exp(-y[plastic_shear_displacement] / j.roughness)) *
        deg;
    const double fs = std::hypot(c.sc_fs[3 * i], c.sc_fs[3 * i + 1]);
    off_bound = std::max(off_bound, talus_test::relative_error(fs, c.sc_fn[i] * std::tan(phi_m)));
    u_p_min = std::min(u_p_min, y[plastic_shear_displacement]);
    std::fprintf(stderr, "sub-contact %u at (%.3g, %.3g): sigma %.5g Pa, u_p %.4g m\n", i,
                 c.sc_position[i][0], c.sc_position[i][1], c.sc_fn[i] / c.sc_area[i],
                 y[plastic_shear_displacement]);
  }
  std::fprintf(stderr, "peak %.6g Pa (uniform sigma_n: %.6g Pa), end %.6g Pa\n", peak, peak_ref,
               shear_stress());
  std::printf("%u sub-contacts on the plate's gridpoints, each on its bound "
              "sigma_i tan(phi_m(u_p,i)) within 1e-9: %s\n",
              c.n_subcontacts(), talus_test::verdict(off_bound <= 1e-9));
  std::printf("each has taken more than 4 R of plastic shear: %s\n",
              talus_test::verdict(u_p_min > 4.0 * j.roughness));
  // The plate's shear at its top tilts it onto its leading edge, so the
  // normal stress is not uniform and the sub-contacts peak one after the
  // other: the mean peaks lower than under a uniform sigma_n, but well
  // above the residual, and the residual is N tan(phi) / A all the same.
  std::printf("peak of the mean shear stress above 1.1 sigma_n tan(phi) and below the "
              "uniform-stress peak: %s\n",
              talus_test::verdict(peak > 1.1 * sigma * std::tan(j.friction_angle * deg) &&
                                  peak < peak_ref));
  talus_test::check_error("residual mean shear stress against sigma_n tan(phi) (Pa)",
                          shear_stress(), sigma * std::tan(j.friction_angle * deg), 1e-2);
}
