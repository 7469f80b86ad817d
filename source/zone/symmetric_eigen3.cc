#include <talus/zone/symmetric_eigen3.h>

namespace talus
{

namespace
{
inline void cross(const Lanes* a, const Lanes* b, Lanes* out)
{
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

inline Lanes dot(const Lanes* a, const Lanes* b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// d x for the symmetric d = (xx, yy, zz, xy, yz, zx).
inline void apply(const Lanes* d, const Lanes* x, Lanes* out)
{
  out[0] = d[0] * x[0] + d[3] * x[1] + d[5] * x[2];
  out[1] = d[3] * x[0] + d[1] * x[1] + d[4] * x[2];
  out[2] = d[5] * x[0] + d[4] * x[1] + d[2] * x[2];
}

/// Swaps value and vector a with b in the lanes where value b < value a.
inline void order_pair(Lanes& value_a, Lanes (&vector_a)[3], Lanes& value_b, Lanes (&vector_b)[3])
{
  const LaneMask swap = value_b < value_a;
  const Lanes low = select(swap, value_b, value_a), high = select(swap, value_a, value_b);
  value_a = low;
  value_b = high;
  for (int k = 0; k < 3; ++k)
  {
    const Lanes first = select(swap, vector_b[k], vector_a[k]);
    vector_b[k] = select(swap, vector_a[k], vector_b[k]);
    vector_a[k] = first;
  }
}
} // namespace

void symmetric_eigen3(const Lanes (&t)[6], Lanes (&values)[3], Lanes (&axes)[3][3])
{
  const Lanes zero = broadcast(0.0), one = broadcast(1.0);
  // Work on the deviator d = t - q I: its values are those of t less q,
  // and the shifts below lose less to cancellation.
  const Lanes q = (t[0] + t[1] + t[2]) / 3.0;
  const Lanes d[6] = {t[0] - q, t[1] - q, t[2] - q, t[3], t[4], t[5]};
  const Lanes p2 =
      (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] + 2.0 * (d[3] * d[3] + d[4] * d[4] + d[5] * d[5])) /
      6.0;
  // Deviator values 2 p cos(theta + 2 pi k / 3), with cos(3 theta) =
  // det(d) / (2 p^3). For det >= 0 the largest value is furthest from the
  // other two, else the smallest; with r = |cos(3 theta)| in [0, 1] that
  // value is +-2 p c, c = cos(acos(r) / 3) in [cos(pi / 6), 1], the largest
  // root of 4 c^3 - 3 c = r (smooth in r there, well conditioned even at a
  // repeated pair, r = 1). An isotropic tensor (p = 0) gives r = 0 and ends
  // with the coordinate axes below.
  const Lanes p2_safe = select(p2 > zero, p2, one);
  const Lanes p = lane_sqrt(p2_safe);
  const Lanes det = d[0] * (d[1] * d[2] - d[4] * d[4]) - d[3] * (d[3] * d[2] - d[4] * d[5]) +
                    d[5] * (d[3] * d[4] - d[1] * d[5]);
  const Lanes r = lane_min(lane_abs(det) / (2.0 * p2_safe * p), one);
  // Quadratic through r = 0, 1/2, 1 (error below 1e-3), then Newton steps
  // (f' >= 6 on the interval: each step squares the error).
  Lanes c = 0.8660254037844386 + r * (0.16084 - 0.02687 * r);
  for (int step = 0; step < 4; ++step)
    c -= (4.0 * c * c * c - 3.0 * c - r) / (12.0 * c * c - 3.0);
  const Lanes lone = lane_copysign(2.0 * p * c, det);

  // Its eigenvector: the largest cross product of two rows of d - lone I
  // (a matrix of rank two, the other two values being at least 1.5 p away).
  const Lanes rows[3][3] = {
      {d[0] - lone, d[3], d[5]}, {d[3], d[1] - lone, d[4]}, {d[5], d[4], d[2] - lone}};
  Lanes candidate[3][3];
  cross(rows[0], rows[1], candidate[0]);
  cross(rows[0], rows[2], candidate[1]);
  cross(rows[1], rows[2], candidate[2]);
  Lanes best = zero;
  Lanes n[3] = {zero, zero, one}; // for a tensor too small to tell: any axis
  for (int k = 0; k < 3; ++k)
  {
    const Lanes size = dot(candidate[k], candidate[k]);
    const LaneMask larger = size > best;
    best = select(larger, size, best);
    for (int j = 0; j < 3; ++j)
      n[j] = select(larger, candidate[k][j], n[j]);
  }
  const Lanes n_scale = one / lane_sqrt(select(best > zero, best, one));
  for (int j = 0; j < 3; ++j)
    n[j] *= n_scale;

  // An orthonormal pair u, v across n: u = n x e, e the coordinate axis
  // least aligned with n (so |u|^2 >= 2/3).
  const Lanes n_abs[3] = {lane_abs(n[0]), lane_abs(n[1]), lane_abs(n[2])};
  const LaneMask y_least = n_abs[1] < n_abs[0];
  const Lanes least_abs = select(y_least, n_abs[1], n_abs[0]);
  const LaneMask z_least = n_abs[2] < least_abs;
  const LaneMask x_least = ~(y_least | z_least);
  const LaneMask y_only = y_least & ~z_least;
  // n x e_x = (0, n2, -n1), n x e_y = (-n2, 0, n0), n x e_z = (n1, -n0, 0).
  Lanes u[3] = {select(z_least, n[1], select(y_only, -n[2], zero)),
                select(z_least, -n[0], select(y_only, zero, n[2])),
                select(x_least, -n[1], select(y_only, n[0], zero))};
  const Lanes u_scale = one / lane_sqrt(dot(u, u));
  for (int j = 0; j < 3; ++j)
    u[j] *= u_scale;
  Lanes v[3];
  cross(n, u, v);

  // The 2x2 problem in that plane, diagonalised by one Jacobi rotation
  // (tangent t of the angle: the smaller root of t^2 + 2 theta t - 1 = 0).
  Lanes du[3], dv[3], dn[3];
  apply(d, u, du);
  apply(d, v, dv);
  apply(d, n, dn);
  const Lanes a11 = dot(u, du), a22 = dot(v, dv), a12 = 0.5 * (dot(u, dv) + dot(v, du));
  const LaneMask coupled = a12 != zero;
  const Lanes theta = (a22 - a11) / (2.0 * select(coupled, a12, one));
  const Lanes theta_abs = lane_abs(theta);
  const LaneMask huge = theta_abs > 1e150; // theta^2 would overflow
  const Lanes root = lane_sqrt(select(huge, one, theta * theta + 1.0));
  const Lanes tangent = select(
      coupled, select(huge, 0.5 / theta, lane_copysign(one, theta) / (theta_abs + root)), zero);
  const Lanes cosine = one / lane_sqrt(tangent * tangent + 1.0), sine = tangent * cosine;
  Lanes value[3] = {a11 - tangent * a12, a22 + tangent * a12, dot(n, dn)};
  Lanes vector[3][3];
  for (int k = 0; k < 3; ++k)
  {
    vector[0][k] = cosine * u[k] - sine * v[k];
    vector[1][k] = sine * u[k] + cosine * v[k];
    vector[2][k] = n[k];
  }
  // Ascending order.
  order_pair(value[0], vector[0], value[1], vector[1]);
  order_pair(value[1], vector[1], value[2], vector[2]);
  order_pair(value[0], vector[0], value[1], vector[1]);
  for (int p = 0; p < 3; ++p)
  {
    values[p] = value[p] + q;
    for (int k = 0; k < 3; ++k)
      axes[p][k] = vector[p][k];
  }
}

void symmetric_eigen3(const double* t, double* values, double (*axes)[3])
{
  Lanes lanes[6], lane_values[3], lane_axes[3][3];
  for (int c = 0; c < 6; ++c)
    lanes[c] = broadcast(t[c]);
  symmetric_eigen3(lanes, lane_values, lane_axes);
  for (int p = 0; p < 3; ++p)
  {
    values[p] = lane_values[p][0];
    for (int k = 0; k < 3; ++k)
      axes[p][k] = lane_axes[p][k][0];
  }
}

} // namespace talus
