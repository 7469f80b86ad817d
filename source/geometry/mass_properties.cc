#include <talus/geometry/mass_properties.h>

#include <Eigen/Eigenvalues>

namespace talus
{

MassProperties compute_mass_properties(const ConvexPolyhedron& p)
{
  MassProperties m;
  // Work relative to an interior point to keep round-off small far from the origin.
  const Vec3 o = p.vertex_mean();
  double volume = 0.0;
  Vec3 first = Vec3::Zero();                          // integral of x dV
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();   // integral of x x^T dV
  for (unsigned int f = 0; f < p.n_faces(); ++f)
  {
    const Vec3 a = p.vertex(p.face_vertex(f, 0)) - o;
    for (unsigned int k = 1; k + 1 < p.face_size(f); ++k)
    {
      const Vec3 b = p.vertex(p.face_vertex(f, k)) - o;
      const Vec3 c = p.vertex(p.face_vertex(f, k + 1)) - o;
      // Tetrahedron (0, a, b, c): V = det/6, integral x dV = V (a+b+c)/4,
      // integral x x^T dV = V/20 (a a^T + b b^T + c c^T + s s^T), s = a+b+c.
      const double v = a.dot(b.cross(c)) / 6.0;
      const Vec3 s = a + b + c;
      volume += v;
      first += v * s / 4.0;
      second += v / 20.0 *
                (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
    }
  }
  m.volume = volume;
  const Vec3 c = first / volume;
  m.centroid = o + c;
  // Second moment about the centroid (parallel-axis shift), then inertia.
  const Eigen::Matrix3d central = second - volume * c * c.transpose();
  m.inertia = central.trace() * Eigen::Matrix3d::Identity() - central;

  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(m.inertia);
  m.principal_moments = solver.eigenvalues();
  m.principal_axes = solver.eigenvectors();
  if (m.principal_axes.determinant() < 0.0)
    m.principal_axes.col(2) *= -1.0;
  return m;
}

} // namespace talus
