// Exact mass properties of a unit cube, a unit right tetrahedron and a
// rotated rectangular prism against their closed forms.

#include <talus/geometry/mass_properties.h>

#include <Eigen/Geometry>

#include "../tests.h"

using namespace talus;

void check_tensor(const std::string& name, const Eigen::Matrix3d& computed,
                  const Eigen::Matrix3d& exact)
{
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j)
      talus_test::check(name + "(" + std::to_string(i) + "," + std::to_string(j) + ")",
                        computed(i, j), exact(i, j), 1e-12);
}

int main()
{
  {
    const MassProperties m = compute_mass_properties(ConvexPolyhedron::box(Vec3(0, 0, 0), Vec3(1, 1, 1)));
    talus_test::check("cube volume", m.volume, 1.0, 1e-14);
    for (int d = 0; d < 3; ++d)
      talus_test::check("cube centroid " + std::to_string(d), m.centroid[d], 0.5, 1e-14);
    // I = m (a^2 + b^2) / 12 = 1/6 on the diagonal, no products of inertia.
    check_tensor("cube inertia", m.inertia, Eigen::Matrix3d::Identity() / 6.0);
  }
  {
    const MassProperties m = compute_mass_properties(
        ConvexPolyhedron::tetrahedron(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)));
    talus_test::check("tetrahedron volume", m.volume, 1.0 / 6.0, 1e-14);
    for (int d = 0; d < 3; ++d)
      talus_test::check("tetrahedron centroid " + std::to_string(d), m.centroid[d], 0.25, 1e-14);
    // About the centroid: integral of x^2 = 1/160, of x y = -1/480, so
    // I_xx = 2/160 = 1/80 and I_xy = +1/480.
    Eigen::Matrix3d exact = Eigen::Matrix3d::Constant(1.0 / 480.0);
    exact.diagonal().setConstant(1.0 / 80.0);
    check_tensor("tetrahedron inertia", m.inertia, exact);
  }
  {
    // A 1 x 2 x 3 prism (triangular fan faces are not needed: prism() builds
    // it from its base) rotated by 30 deg about (1, 1, 1) and moved away from
    // the origin: I = R diag(V (b^2 + c^2)/12, ...) R^T about (1.5, -2, 7).
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(M_PI / 6.0, Vec3(1, 1, 1).normalized()).toRotationMatrix();
    const Vec3 shift(1.5, -2.0, 7.0);
    const double a = 1.0, b = 2.0, c = 3.0;
    std::vector<Vec3> base;
    for (const Vec3& p : {Vec3(0, 0, 0), Vec3(a, 0, 0), Vec3(a, b, 0), Vec3(0, b, 0)})
      base.push_back(R * (p - Vec3(a / 2, b / 2, c / 2)) + shift);
    const ConvexPolyhedron prism = ConvexPolyhedron::prism(base, R * Vec3(0, 0, c));
    prism.validate("rotated prism");
    const MassProperties m = compute_mass_properties(prism);
    const double V = a * b * c;
    talus_test::check("prism volume", m.volume, V, 1e-13);
    for (int d = 0; d < 3; ++d)
      talus_test::check("prism centroid " + std::to_string(d), m.centroid[d], shift[d], 1e-13);
    const Vec3 principal(V * (b * b + c * c) / 12, V * (a * a + c * c) / 12, V * (a * a + b * b) / 12);
    check_tensor("prism inertia", m.inertia, R * principal.asDiagonal() * R.transpose());
    // Principal moments come sorted: 5/2*... = (a^2+b^2), (a^2+c^2), (b^2+c^2) times V/12.
    talus_test::check("prism principal 0", m.principal_moments[0], principal[2], 1e-12);
    talus_test::check("prism principal 1", m.principal_moments[1], principal[1], 1e-12);
    talus_test::check("prism principal 2", m.principal_moments[2], principal[0], 1e-12);
    // The axis of the smallest moment is the long (c) edge direction.
    talus_test::check("prism axis of least inertia . c-direction",
                      std::abs(m.principal_axes.col(0).dot(R * Vec3(0, 0, 1))), 1.0, 1e-12);
  }
}
