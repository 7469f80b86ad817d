#include <talus/zone/tet4_kernel.h>

#include <cmath>

namespace talus
{

namespace
{
/// Gradients of the four shape functions of the tetrahedron with corners
/// p[0..3] (3 numbers each) into gr (12 numbers, 1/m); returns 6 V (m^3).
/// The gradients of N1..N3 are the rows of the inverse of the matrix whose
/// columns are the edges from corner 0; N0's is minus their sum.
inline double shape_gradients(const double* p0, const double* p1, const double* p2,
                              const double* p3, double* gr)
{
  double e[3][3];
  for (int d = 0; d < 3; ++d)
  {
    e[d][0] = p1[d] - p0[d];
    e[d][1] = p2[d] - p0[d];
    e[d][2] = p3[d] - p0[d];
  }
  const double c00 = e[1][1] * e[2][2] - e[1][2] * e[2][1];
  const double c01 = e[1][2] * e[2][0] - e[1][0] * e[2][2];
  const double c02 = e[1][0] * e[2][1] - e[1][1] * e[2][0];
  const double det = e[0][0] * c00 + e[0][1] * c01 + e[0][2] * c02;
  const double inv = 1.0 / det;
  gr[3] = c00 * inv;
  gr[4] = (e[0][2] * e[2][1] - e[0][1] * e[2][2]) * inv;
  gr[5] = (e[0][1] * e[1][2] - e[0][2] * e[1][1]) * inv;
  gr[6] = c01 * inv;
  gr[7] = (e[0][0] * e[2][2] - e[0][2] * e[2][0]) * inv;
  gr[8] = (e[0][2] * e[1][0] - e[0][0] * e[1][2]) * inv;
  gr[9] = c02 * inv;
  gr[10] = (e[0][1] * e[2][0] - e[0][0] * e[2][1]) * inv;
  gr[11] = (e[0][0] * e[1][1] - e[0][1] * e[1][0]) * inv;
  for (int d = 0; d < 3; ++d)
    gr[d] = -(gr[3 + d] + gr[6 + d] + gr[9 + d]);
  return det;
}
} // namespace

void tet4_strain_increments(const TetMesh& mesh, unsigned int first, unsigned int n,
                            const double* x, const double* v, double dt, double* stress,
                            Tet4Scratch& s)
{
  for (unsigned int k = 0; k < n; ++k)
  {
    const auto& g = mesh.zone_gridpoint[first + k];
    // Current geometry: gradients and volume for the nodal forces.
    double* gr = s.gradient.data() + 12 * k;
    s.volume[k] = shape_gradients(x + 3 * g[0], x + 3 * g[1], x + 3 * g[2], x + 3 * g[3], gr) / 6.0;
    // The motion of the last step, x - v dt -> x, measured on the geometry
    // halfway through it: a rigid rotation then gives an exactly
    // antisymmetric velocity gradient, so no strain, for any step size.
    double mid[4][3], gm[12];
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d)
        mid[a][d] = x[3 * g[a] + d] - 0.5 * dt * v[3 * g[a] + d];
    shape_gradients(mid[0], mid[1], mid[2], mid[3], gm);
    // Velocity gradient L_ij = sum_n v_n,i dN_n/dx_j.
    double L[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    for (int a = 0; a < 4; ++a)
    {
      const double* va = v + 3 * g[a];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          L[i][j] += va[i] * gm[3 * a + j];
    }
    // Eq. 58: strain rate and spin; the increment of this step.
    double* de = s.strain_increment.data() + 6 * k;
    de[0] = L[0][0] * dt;
    de[1] = L[1][1] * dt;
    de[2] = L[2][2] * dt;
    de[3] = 0.5 * (L[0][1] + L[1][0]) * dt;
    de[4] = 0.5 * (L[1][2] + L[2][1]) * dt;
    de[5] = 0.5 * (L[2][0] + L[0][2]) * dt;
    const double w01 = 0.5 * (L[0][1] - L[1][0]) * dt; // W_xy dt
    const double w12 = 0.5 * (L[1][2] - L[2][1]) * dt; // W_yz dt
    const double w20 = 0.5 * (L[2][0] - L[0][2]) * dt; // W_zx dt
    // Jaumann (co-rotational) turn of the stress by the spin:
    // sigma += (W sigma - sigma W) dt.
    double* sg = stress + 6 * (first + k);
    const double sxx = sg[0], syy = sg[1], szz = sg[2], sxy = sg[3], syz = sg[4], szx = sg[5];
    sg[0] += 2.0 * (w01 * sxy - w20 * szx);
    sg[1] += 2.0 * (w12 * syz - w01 * sxy);
    sg[2] += 2.0 * (w20 * szx - w12 * syz);
    sg[3] += w01 * (syy - sxx) + w12 * szx - w20 * syz;
    sg[4] += w12 * (szz - syy) + w20 * sxy - w01 * szx;
    sg[5] += w20 * (sxx - szz) + w01 * syz - w12 * sxy;
  }
}

void tet4_nodal_forces(const TetMesh& mesh, unsigned int first, unsigned int n,
                       const double* stress, const Tet4Scratch& s, double* force,
                       double* force_size)
{
  for (unsigned int k = 0; k < n; ++k)
  {
    const auto& g = mesh.zone_gridpoint[first + k];
    const double* sg = stress + 6 * (first + k);
    const double* gr = s.gradient.data() + 12 * k;
    const double V = s.volume[k];
    for (int a = 0; a < 4; ++a)
    {
      const double gx = gr[3 * a], gy = gr[3 * a + 1], gz = gr[3 * a + 2];
      const double fx = V * (sg[0] * gx + sg[3] * gy + sg[5] * gz);
      const double fy = V * (sg[3] * gx + sg[1] * gy + sg[4] * gz);
      const double fz = V * (sg[5] * gx + sg[4] * gy + sg[2] * gz);
      double* f = force + 3 * g[a];
      f[0] -= fx;
      f[1] -= fy;
      f[2] -= fz;
      if (force_size != nullptr)
      {
        double* fs = force_size + 3 * g[a];
        fs[0] += std::abs(fx);
        fs[1] += std::abs(fy);
        fs[2] += std::abs(fz);
      }
    }
  }
}

} // namespace talus
