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

#include <talus/solver/rigid_solver.h>

#include <cmath>

#include "../../contrib/benchmarks/settling_cubes.h"
#include "../tests.h"

using namespace talus;

int main()
{
  bool axes = true;
  const std::pair<double, double> dips[] = {{0, 0},   {0, 137},  {90, 0},
                                            {90, 90}, {90, 180}, {90, 270}};
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

  // The settling cubes of the rigid benchmarks, at n = 10.
  const unsigned int n = 10;
  SolverSettings s;
  BlockModel model = settling_cubes(n, 1, s);
  unsigned long off = 0;
  for (const Vec3& v : model.vertex)
    off += (v.array() != v.array().round()).any();
  std::printf("%u cubes, %u vertices, %lu off integer coordinates\n", model.n_blocks(),
              model.n_vertices(), off);

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
