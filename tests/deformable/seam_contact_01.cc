// A deformable block across the joint between two fixed rigid blocks and
// over the far edge of the second (parameters/verification/
// block_across_seam.prm), with 4-node, 10-node and hexahedral zones:
// 1. each contact's sub-contact areas add up to its overlap (3 and 4.6 m^2):
//    a gridpoint's springs take the part of its area over the support (the
//    text after eq. 25), so the line of gridpoints on the joint does not
//    carry its area twice and the edge between two gridpoints loses none;
// 2. no gridpoint carries more than its own area (more would pass the
//    joint stiffness the time step of eq. 85 allows it);
// 3. settled, the supports carry the weight, with the resultant under the
//    block's centroid (x = 3.45 m).

#include <talus/base/parallel_environment.h>
#include <talus/scene/build_blocks.h>
#include <talus/scene/block_system.h>

#include <cmath>
#include <cstdio>
#include <map>

#include "../tests.h"

using namespace talus;

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  for (const auto& [element, name] : {std::pair{ZoneElement::tet4, "tet4"},
                                      std::pair{ZoneElement::tet10, "tet10"},
                                      std::pair{ZoneElement::hex_mixed, "hex-mixed"}})
  {
    Scene scene = read_scene(
        std::string(SOURCE_DIR) + "/../../parameters/verification/block_across_seam.prm", false);
    scene.deformable.material.element = element;
    BuildReport built;
    BlockModel model = build_blocks(scene, built);
    resolve_group_names(scene, model);
    BlockSystem system = build_block_system(scene, model);
    RigidSolver& solver = *system.solver;
    solver.step();
    std::printf("%s (%u zones):\n", name, system.mesh.n_zones());

    unsigned int block = 0; // the deformable one
    for (unsigned int b = 0; b < model.n_blocks(); ++b)
      if (model.group_names[model.group[b]] == "block")
        block = b;
    // Each gridpoint's area on the block's base: its share of the base's
    // boundary triangles (the zone surface is the block's faces now).
    std::map<int, double> own_area;
    const std::vector<int>& vertex_gridpoint = system.vertex_gridpoint;
    for (unsigned int f = model.face_start[block]; f < model.face_start[block + 1]; ++f)
    {
      if (model.face_normal[f].z() > -0.999)
        continue;
      const unsigned int k = model.face_loop_start[f];
      const Vec3& x0 = model.vertex[model.face_vertex[k]];
      const double area = 0.5 * (model.vertex[model.face_vertex[k + 1]] - x0)
                                    .cross(model.vertex[model.face_vertex[k + 2]] - x0)
                                    .norm();
      for (int j = 0; j < 3; ++j)
        own_area[vertex_gridpoint[model.face_vertex[k + j]]] +=
            area * (model.face_corner_share.empty() ? 1.0 / 3.0 : model.face_corner_share[f][j]);
    }

    const ContactSet& c = solver.contacts();
    std::map<unsigned int, double> contact_area; // by the support's block
    std::map<int, double> carried;
    for (unsigned int i = 0; i < c.n_subcontacts(); ++i)
    {
      const unsigned int s = c.sc_contact[i];
      const int side = c.block_a[s] == block ? 0 : 1;
      contact_area[side == 0 ? c.block_b[s] : c.block_a[s]] += c.sc_area[i];
      carried[c.sc_node[6 * i + 3 * side]] += c.sc_area[i];
    }
    for (const auto& [support, area] : contact_area)
    {
      const double expected = model.centroid[support].x() < 2.7 ? 3.0 : 4.6;
      std::printf("  support at x = %.3g m: ", model.centroid[support].x());
      talus_test::check_within("contact area (m^2)", area, expected, 1e-12);
    }
    double worst = 0.0;
    for (const auto& [g, area] : carried)
      worst = std::max(worst, area / own_area[g]);
    std::fprintf(stderr, "%s: largest area of a gridpoint's springs over its own area %.6g\n",
                 name, worst);
    std::printf("  no gridpoint's springs take more than its own area: %s\n",
                talus_test::verdict(worst <= 1.0 + 1e-12));

    unsigned long steps = 1;
    while ((steps < 20 || solver.unbalanced_ratio() >= 1e-6) && steps < 20000)
    {
      solver.step();
      ++steps;
    }
    std::fprintf(stderr, "%s: %lu steps\n", name, steps);
    std::printf("  static run %s\n",
                solver.unbalanced_ratio() < 1e-6 ? "reached ratio 1e-6" : "NOT converged");
    double fn = 0.0, moment = 0.0;
    for (unsigned int i = 0; i < c.n_subcontacts(); ++i)
    {
      fn += c.sc_fn[i];
      moment += c.sc_fn[i] * c.sc_position[i].x();
    }
    const double weight = 4.5 * 2 * 1 * scene.density * 9.81;
    std::printf("  ");
    talus_test::check_within("normal force of the supports (N)", fn, weight, 1e-6);
    std::printf("  ");
    talus_test::check_within("x of their resultant (m)", moment / fn, 3.45, 1e-6);
  }
}
