// Cuts along the axes leave exact coordinates, so that the same contact is
// discretized alike wherever it lies. A joint of dip 90 had a normal with a
// vertical part of cos(pi/2) = 6.1e-17 and the cut points were interpolated
// along the edges, so the unit cubes cut from a brick had vertices off
// their integer places by up to 9e-15 m, more or less depending on where
// they lay. Diagonal neighbours touching along an edge then overlapped or
// parted by a hair: their contact got two sub-contacts or none by
// position, and a stack of cubes split among two ranks by x gave one rank
// 3.4 % more sub-contacts (issue 24's rigid benchmark).
//
// Checked: the normals of the horizontal and of the four vertical joint
// directions are exact axes; a 10 x 10 x 11 brick cut by three orthogonal
// sets of spacing 1 has every vertex on integer coordinates; and a stack
// of those cubes (floor fixed, gravity) has, at its first step, mirror-image
// contacts: as many sub-contacts in the half x < 5 as in the half x > 5,
// and in y likewise. (Once the cubes settle, their positions carry the
// rounding of the forces, which is not mirror-symmetric.)

#include <talus/geometry/block_generator.h>
#include <talus/solver/rigid_solver.h>

#include <cmath>

#include "../tests.h"

using namespace talus;

int main()
{
  bool axes = true;
  const std::pair<double, double> dips[] = {{0, 0}, {0, 137}, {90, 0}, {90, 90}, {90, 180},
                                            {90, 270}};
  const Vec3 expected[] = {Vec3(0, 0, 1), Vec3(0, 0, 1),  Vec3(0, 1, 0),
                           Vec3(1, 0, 0), Vec3(0, -1, 0), Vec3(-1, 0, 0)};
  for (int k = 0; k < 6; ++k)
  {
    const Vec3 n = normal_from_dip(dips[k].first, dips[k].second);
    axes &= n == expected[k];
  }
  std::printf("normals of dips 0 and 90 at dip directions 0, 90, 180, 270 are axes: %s\n",
              talus_test::verdict(axes));
  // Other angles go through sin and cos as before.
  const Vec3 oblique = normal_from_dip(30.0, 45.0);
  std::printf("dip 30 towards 45: unit normal %s\n",
              talus_test::verdict(std::abs(oblique.norm() - 1.0) < 1e-15 &&
                                  std::abs(oblique[2] - std::sqrt(3.0) / 2.0) < 1e-15));

  const unsigned int n = 10;
  BlockGenerator g(ConvexPolyhedron::box(Vec3::Zero(), Vec3(n, n, n + 1)), {});
  g.cut_joint_set({0.0, 0.0, 1.0, Vec3::Zero(), 0, false, {}});
  g.cut_joint_set({90.0, 0.0, 1.0, Vec3::Zero(), 0, false, {}});
  g.cut_joint_set({90.0, 90.0, 1.0, Vec3::Zero(), 0, false, {}});
  BlockModel model;
  const unsigned int cubes = model.group_index("cubes"), floor = model.group_index("floor");
  unsigned long off = 0, vertices = 0;
  for (const ConvexPolyhedron& b : g.blocks())
  {
    model.add_block(b, b.vertex_mean()[2] < 1.0 ? floor : cubes);
    for (const Vec3& v : b.vertices())
    {
      ++vertices;
      off += (v.array() != v.array().round()).any();
    }
  }
  std::printf("%u cubes, %lu vertices, %lu off integer coordinates\n", model.n_blocks(), vertices,
              off);

  SolverSettings s;
  s.dynamic = false;
  s.contact.tolerance = 0.01;
  s.joint.normal_stiffness = s.joint.shear_stiffness = 1e9;
  s.fixed_groups = {floor};
  RigidSolver solver(model, 2650.0, s);
  {
    solver.step();
    const unsigned int step = 1;
    // Sub-contacts by the side of the middle their contact's pair lies on.
    const ContactSet& c = solver.contacts();
    unsigned long half[3][2] = {{0, 0}, {0, 0}, {0, 0}};
    for (unsigned int i = 0; i < c.n_subcontacts(); ++i)
    {
      const unsigned int slot = c.sc_contact[i];
      const Vec3 mid = 0.5 * (model.centroid[c.block_a[slot]] + model.centroid[c.block_b[slot]]);
      for (int d = 0; d < 2; ++d)
        if (mid[d] != 0.5 * n)
          ++half[d][mid[d] > 0.5 * n];
    }
    std::printf("step %u: %u sub-contacts; x < 5 and x > 5: %lu and %lu (%s); y < 5 and y > 5: "
                "%lu and %lu (%s)\n",
                step, c.n_subcontacts(), half[0][0], half[0][1],
                talus_test::verdict(half[0][0] == half[0][1]), half[1][0], half[1][1],
                talus_test::verdict(half[1][0] == half[1][1]));
  }
}
