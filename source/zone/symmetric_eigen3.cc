#include <talus/zone/symmetric_eigen3.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace talus
{

namespace
{
inline void cross(const double* a, const double* b, double* out)
{
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

inline double dot(const double* a, const double* b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// d x for the symmetric d = (xx, yy, zz, xy, yz, zx).
inline void apply(const double* d, const double* x, double* out)
{
  out[0] = d[0] * x[0] + d[3] * x[1] + d[5] * x[2];
  out[1] = d[3] * x[0] + d[1] * x[1] + d[4] * x[2];
  out[2] = d[5] * x[0] + d[4] * x[1] + d[2] * x[2];
}
} // namespace

void symmetric_eigen3(const double* t, double* values, double (*axes)[3])
{
  // Work on the deviator d = t - q I: its values are those of t less q,
  // and the shifts below lose less to cancellation.
  const double q = (t[0] + t[1] + t[2]) / 3.0;
  const double d[6] = {t[0] - q, t[1] - q, t[2] - q, t[3], t[4], t[5]};
  const double p2 =
      (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] + 2.0 * (d[3] * d[3] + d[4] * d[4] + d[5] * d[5])) /
      6.0;
  double n[3] = {0.0, 0.0, 0.0};
  double best = 0.0;
  if (p2 > 0.0)
  {
    // Deviator values 2 p cos(theta + 2 pi k / 3), with cos(3 theta) =
    // det(d) / (2 p^3). For det >= 0 the largest value is furthest from the
    // other two, else the smallest; with r = |cos(3 theta)| that value is
    // +-2 p cos(acos(r) / 3), well conditioned in r even at a repeated pair.
    const double p = std::sqrt(p2);
    const double det = d[0] * (d[1] * d[2] - d[4] * d[4]) - d[3] * (d[3] * d[2] - d[4] * d[5]) +
                       d[5] * (d[3] * d[4] - d[1] * d[5]);
    const double r = std::min(std::abs(det) / (2.0 * p2 * p), 1.0);
    const double lone = std::copysign(2.0 * p * std::cos(std::acos(r) / 3.0), det);
    // Its eigenvector: the largest cross product of two rows of d - lone I
    // (a matrix of rank two, the other two values being at least 1.5 p
    // away).
    const double rows[3][3] = {
        {d[0] - lone, d[3], d[5]}, {d[3], d[1] - lone, d[4]}, {d[5], d[4], d[2] - lone}};
    double c[3][3];
    cross(rows[0], rows[1], c[0]);
    cross(rows[0], rows[2], c[1]);
    cross(rows[1], rows[2], c[2]);
    int largest = 0;
    for (int k = 0; k < 3; ++k)
    {
      const double size = dot(c[k], c[k]);
      if (size > best)
      {
        best = size;
        largest = k;
      }
    }
    if (best > 0.0)
    {
      const double scale = 1.0 / std::sqrt(best);
      for (int k = 0; k < 3; ++k)
        n[k] = c[largest][k] * scale;
    }
  }
  if (!(best > 0.0))
  {
    // Isotropic (or too small to tell apart): every direction is principal.
    for (int p = 0; p < 3; ++p)
    {
      values[p] = q;
      for (int k = 0; k < 3; ++k)
        axes[p][k] = p == k ? 1.0 : 0.0;
    }
    return;
  }

  // An orthonormal pair u, v across n: u from the coordinate axis least
  // aligned with n.
  int least = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(n[k]) < std::abs(n[least]))
      least = k;
  double axis[3] = {0.0, 0.0, 0.0};
  axis[least] = 1.0;
  double u[3], v[3];
  cross(n, axis, u);
  const double u_scale = 1.0 / std::sqrt(dot(u, u));
  for (int k = 0; k < 3; ++k)
    u[k] *= u_scale;
  cross(n, u, v);

  // The 2x2 problem in that plane, diagonalised by one Jacobi rotation.
  double du[3], dv[3], dn[3];
  apply(d, u, du);
  apply(d, v, dv);
  apply(d, n, dn);
  const double a11 = dot(u, du), a22 = dot(v, dv), a12 = 0.5 * (dot(u, dv) + dot(v, du));
  double tangent = 0.0;
  if (a12 != 0.0)
  {
    const double theta = (a22 - a11) / (2.0 * a12);
    tangent = std::abs(theta) > 1e150
                  ? 0.5 / theta
                  : std::copysign(1.0, theta) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
  }
  const double cosine = 1.0 / std::sqrt(tangent * tangent + 1.0), sine = tangent * cosine;
  double value[3] = {a11 - tangent * a12, a22 + tangent * a12, dot(n, dn)};
  double vector[3][3];
  for (int k = 0; k < 3; ++k)
  {
    vector[0][k] = cosine * u[k] - sine * v[k];
    vector[1][k] = sine * u[k] + cosine * v[k];
    vector[2][k] = n[k];
  }
  // Ascending order.
  int order[3] = {0, 1, 2};
  if (value[order[0]] > value[order[1]])
    std::swap(order[0], order[1]);
  if (value[order[1]] > value[order[2]])
    std::swap(order[1], order[2]);
  if (value[order[0]] > value[order[1]])
    std::swap(order[0], order[1]);
  for (int p = 0; p < 3; ++p)
  {
    values[p] = value[order[p]] + q;
    for (int k = 0; k < 3; ++k)
      axes[p][k] = vector[order[p]][k];
  }
}

} // namespace talus
