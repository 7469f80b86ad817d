#include <talus/zone/lanes.h>
#include <talus/zone/tet10_kernel.h>
#include <talus/zone/tet10_mesh.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace talus
{

namespace
{
// W zones at once, one lane per zone, as in the 4-node kernel (see there
// why explicit vector types and the hardware's width).
constexpr unsigned int W = lane_count;
static_assert(Tet10Scratch::max_lanes % W == 0, "scratch holds whole groups");

/// Zones [k0, k0 + W) of a batch: their ten gridpoints lane by lane; lanes
/// past the batch's end repeat its last zone and write nothing.
struct Group
{
  unsigned int gridpoint[10][W];
  LaneMask node[10]; ///< 3 gridpoint: offset of each node in a gridpoint field
  LaneMask point;    ///< 24 (zone - k0): offset of each zone's first Gauss point
  unsigned int count;

  Group(const TetMesh& mesh, unsigned int first, unsigned int k0, unsigned int n)
      : count(std::min(W, n - k0))
  {
    for (unsigned int l = 0; l < W; ++l)
    {
      const unsigned int k = std::min(l, count - 1), z = first + k0 + k;
      for (int a = 0; a < 4; ++a)
        gridpoint[a][l] = mesh.zone_gridpoint[z][a];
      for (int e = 0; e < 6; ++e)
        gridpoint[4 + e][l] = mesh.zone_edge_gridpoint[z][e];
      for (int a = 0; a < 10; ++a)
        node[a][l] = 3 * std::int64_t(gridpoint[a][l]);
      point[l] = 24 * k;
    }
  }

  void gather_nodes(const double* field, Lanes (&out)[10][3]) const
  {
    for (int a = 0; a < 10; ++a)
      for (int d = 0; d < 3; ++d)
        out[a][d] = gather_lanes(field + d, node[a]);
  }

  /// The 24 stress (or strain) numbers of each zone (6 per Gauss point).
  void load_points(const double* values, Lanes (&out)[4][6]) const
  {
    for (int q = 0; q < 4; ++q)
      for (int c = 0; c < 6; ++c)
        out[q][c] = gather_lanes(values + 6 * q + c, point);
  }
  void store_points(const Lanes (&in)[4][6], double* values) const
  {
    for (unsigned int l = 0; l < count; ++l)
      for (int q = 0; q < 4; ++q)
        for (int c = 0; c < 6; ++c)
          values[24 * l + 6 * q + c] = in[q][c][l];
  }
};

/// Barycentric coordinate m of Gauss point q.
constexpr double bary(int q, int m)
{
  return q == m ? tet10_gauss_b : tet10_gauss_a;
}

/// A_m = sum_n f_n dN_n/dL_m at Gauss point q, for a nodal field f (one
/// component), with N_i = L_i (2 L_i - 1) at vertex i and N = 4 L_i L_j at
/// the midpoint of edge i-j: only the vertex m and the three edges at m
/// contribute. The reference derivatives follow as
/// dN/dxi_k = dN/dL_(k+1) - dN/dL_0 (L_0 = 1 - xi - eta - zeta).
template <int q>
inline void barycentric_derivatives(const Lanes (&f)[10][3], Lanes (&A)[4][3])
{
  for (int d = 0; d < 3; ++d)
  {
    A[0][d] = (4.0 * bary(q, 0) - 1.0) * f[0][d] + 4.0 * bary(q, 1) * f[4][d] +
              4.0 * bary(q, 2) * f[6][d] + 4.0 * bary(q, 3) * f[7][d];
    A[1][d] = (4.0 * bary(q, 1) - 1.0) * f[1][d] + 4.0 * bary(q, 0) * f[4][d] +
              4.0 * bary(q, 2) * f[5][d] + 4.0 * bary(q, 3) * f[8][d];
    A[2][d] = (4.0 * bary(q, 2) - 1.0) * f[2][d] + 4.0 * bary(q, 1) * f[5][d] +
              4.0 * bary(q, 0) * f[6][d] + 4.0 * bary(q, 3) * f[9][d];
    A[3][d] = (4.0 * bary(q, 3) - 1.0) * f[3][d] + 4.0 * bary(q, 0) * f[7][d] +
              4.0 * bary(q, 1) * f[8][d] + 4.0 * bary(q, 2) * f[9][d];
  }
}

/// Reference gradient of a nodal field at Gauss point q:
/// F[d][k] = sum_n f_n,d dN_n/dxi_k (the Jacobian dx_d/dxi_k for positions).
template <int q>
inline void reference_gradient(const Lanes (&f)[10][3], Lanes (&F)[3][3])
{
  Lanes A[4][3];
  barycentric_derivatives<q>(f, A);
  for (int d = 0; d < 3; ++d)
    for (int k = 0; k < 3; ++k)
      F[d][k] = A[k + 1][d] - A[0][d];
}

/// Inverse of J (Jinv[k][d] = dxi_k/dx_d); returns det J.
inline Lanes invert(const Lanes (&J)[3][3], Lanes (&Jinv)[3][3])
{
  const Lanes c00 = J[1][1] * J[2][2] - J[1][2] * J[2][1];
  const Lanes c01 = J[1][2] * J[2][0] - J[1][0] * J[2][2];
  const Lanes c02 = J[1][0] * J[2][1] - J[1][1] * J[2][0];
  const Lanes det = J[0][0] * c00 + J[0][1] * c01 + J[0][2] * c02;
  const Lanes inv = 1.0 / det;
  Jinv[0][0] = c00 * inv;
  Jinv[0][1] = (J[0][2] * J[2][1] - J[0][1] * J[2][2]) * inv;
  Jinv[0][2] = (J[0][1] * J[1][2] - J[0][2] * J[1][1]) * inv;
  Jinv[1][0] = c01 * inv;
  Jinv[1][1] = (J[0][0] * J[2][2] - J[0][2] * J[2][0]) * inv;
  Jinv[1][2] = (J[0][2] * J[1][0] - J[0][0] * J[1][2]) * inv;
  Jinv[2][0] = c02 * inv;
  Jinv[2][1] = (J[0][1] * J[2][0] - J[0][0] * J[2][1]) * inv;
  Jinv[2][2] = (J[0][0] * J[1][1] - J[0][1] * J[1][0]) * inv;
  return det;
}

/// Pass 1 at Gauss point q for one group.
template <int q>
inline void strain_at(const Lanes (&p)[10][3], const Lanes (&mid)[10][3], const Lanes (&vel)[10][3],
                      double dt, double* geometry, Lanes (&de)[6], Lanes (&sg)[6])
{
  // Current geometry, for the nodal forces of pass 2.
  Lanes J[3][3], Jinv[3][3];
  reference_gradient<q>(p, J);
  const Lanes det = invert(J, Jinv);
  for (int k = 0; k < 3; ++k)
    for (int d = 0; d < 3; ++d)
      store_lanes(geometry + (10 * q + 3 * k + d) * W, Jinv[k][d]);
  store_lanes(geometry + (10 * q + 9) * W,
              det * (1.0 / 24.0)); // weight 1/24 of the unit tetrahedron
  // Velocity gradient on the mid-step geometry: L = (dv/dxi) (dxi/dx).
  Lanes Jm[3][3], Jm_inv[3][3], Vxi[3][3];
  reference_gradient<q>(mid, Jm);
  invert(Jm, Jm_inv);
  reference_gradient<q>(vel, Vxi);
  Lanes L[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      L[i][j] = Vxi[i][0] * Jm_inv[0][j] + Vxi[i][1] * Jm_inv[1][j] + Vxi[i][2] * Jm_inv[2][j];
  // Eq. 58: strain increment and spin of this step at the Gauss point.
  de[0] = L[0][0] * dt;
  de[1] = L[1][1] * dt;
  de[2] = L[2][2] * dt;
  de[3] = 0.5 * (L[0][1] + L[1][0]) * dt;
  de[4] = 0.5 * (L[1][2] + L[2][1]) * dt;
  de[5] = 0.5 * (L[2][0] + L[0][2]) * dt;
  const Lanes w01 = 0.5 * (L[0][1] - L[1][0]) * dt;
  const Lanes w12 = 0.5 * (L[1][2] - L[2][1]) * dt;
  const Lanes w20 = 0.5 * (L[2][0] - L[0][2]) * dt;
  // Jaumann turn of the Gauss point's stress: sigma += (W sigma - sigma W) dt.
  const Lanes sxx = sg[0], syy = sg[1], szz = sg[2], sxy = sg[3], syz = sg[4], szx = sg[5];
  sg[0] += 2.0 * (w01 * sxy - w20 * szx);
  sg[1] += 2.0 * (w12 * syz - w01 * sxy);
  sg[2] += 2.0 * (w20 * szx - w12 * syz);
  sg[3] += w01 * (syy - sxx) + w12 * szx - w20 * syz;
  sg[4] += w12 * (szz - syy) + w20 * sxy - w01 * szx;
  sg[5] += w20 * (sxx - szz) + w01 * syz - w12 * sxy;
}

/// Pass 2 at Gauss point q: adds the nodal forces of the Gauss stress,
/// -w det J sigma grad N_n, to fz. With P[i][k] = w det J sigma_ij
/// dxi_k/dx_j, f_n,i = -sum_k dN_n/dxi_k P[i][k] = -sum_m dN_n/dL_m Q[i][m]
/// with Q[.][0] = -sum_k P[.][k], Q[.][m] = P[.][m - 1].
template <int q>
inline void forces_at(const double* geometry, const Lanes (&sg)[6], Lanes (&fz)[10][3])
{
  Lanes Jinv[3][3];
  for (int k = 0; k < 3; ++k)
    for (int d = 0; d < 3; ++d)
      Jinv[k][d] = load_lanes(geometry + (10 * q + 3 * k + d) * W);
  const Lanes w = load_lanes(geometry + (10 * q + 9) * W);
  const Lanes s[3][3] = {{sg[0], sg[3], sg[5]}, {sg[3], sg[1], sg[4]}, {sg[5], sg[4], sg[2]}};
  Lanes Q[3][4];
  for (int i = 0; i < 3; ++i)
  {
    for (int k = 0; k < 3; ++k)
      Q[i][k + 1] = w * (s[i][0] * Jinv[k][0] + s[i][1] * Jinv[k][1] + s[i][2] * Jinv[k][2]);
    Q[i][0] = -(Q[i][1] + Q[i][2] + Q[i][3]);
  }
  for (int i = 0; i < 3; ++i)
  {
    for (int m = 0; m < 4; ++m)
      fz[m][i] += (4.0 * bary(q, m) - 1.0) * Q[i][m];
    for (int e = 0; e < 6; ++e)
    {
      const int a = tet10_edge[e][0], b = tet10_edge[e][1];
      fz[4 + e][i] += 4.0 * bary(q, b) * Q[i][a] + 4.0 * bary(q, a) * Q[i][b];
    }
  }
}
} // namespace

void tet10_strain_increments(const TetMesh& mesh, unsigned int first, unsigned int n,
                             const double* x, const double* v, double dt, double* stress,
                             Tet10Scratch& s)
{
  for (unsigned int k0 = 0; k0 < n; k0 += W)
  {
    const Group group(mesh, first, k0, n);
    Lanes p[10][3], vel[10][3], mid[10][3];
    group.gather_nodes(x, p);
    group.gather_nodes(v, vel);
    // The motion of the last step, x - v dt -> x, measured halfway through.
    for (int a = 0; a < 10; ++a)
      for (int d = 0; d < 3; ++d)
        mid[a][d] = p[a][d] - 0.5 * dt * vel[a][d];
    Lanes sg[4][6], de[4][6];
    double* zone_stress = stress + 24 * std::size_t(first + k0);
    group.load_points(zone_stress, sg);
    double* geometry = s.geometry.data() + 40 * std::size_t(k0);
    strain_at<0>(p, mid, vel, dt, geometry, de[0], sg[0]);
    strain_at<1>(p, mid, vel, dt, geometry, de[1], sg[1]);
    strain_at<2>(p, mid, vel, dt, geometry, de[2], sg[2]);
    strain_at<3>(p, mid, vel, dt, geometry, de[3], sg[3]);
    group.store_points(de, s.strain_increment.data() + 24 * std::size_t(k0));
    group.store_points(sg, zone_stress);
  }
}

namespace
{
/// Subtracts the node forces from `force` (3 per gridpoint) and, when
/// `force_size` is not null, adds their magnitudes there, zone by zone.
inline void scatter_node_forces(const Group& group, const Lanes (&fz)[10][3], double* force,
                                double* force_size)
{
  for (unsigned int l = 0; l < group.count; ++l)
    for (int a = 0; a < 10; ++a)
    {
      double* f = force + 3 * group.gridpoint[a][l];
      for (int d = 0; d < 3; ++d)
        f[d] -= fz[a][d][l];
    }
  if (force_size != nullptr)
  {
    Lanes size[10][3];
    for (int a = 0; a < 10; ++a)
      for (int d = 0; d < 3; ++d)
        size[a][d] = lane_abs(fz[a][d]);
    for (unsigned int l = 0; l < group.count; ++l)
      for (int a = 0; a < 10; ++a)
      {
        double* fs = force_size + 3 * group.gridpoint[a][l];
        for (int d = 0; d < 3; ++d)
          fs[d] += size[a][d][l];
      }
  }
}

/// The node forces of the four Gauss points' stresses sg.
inline void node_forces(const double* geometry, const Lanes (&sg)[4][6], Lanes (&fz)[10][3])
{
  forces_at<0>(geometry, sg[0], fz);
  forces_at<1>(geometry, sg[1], fz);
  forces_at<2>(geometry, sg[2], fz);
  forces_at<3>(geometry, sg[3], fz);
}
} // namespace

void tet10_nodal_forces(const TetMesh& mesh, unsigned int first, unsigned int n,
                        const double* stress, const Tet10Scratch& s, double* force,
                        double* force_size)
{
  for (unsigned int k0 = 0; k0 < n; k0 += W)
  {
    const Group group(mesh, first, k0, n);
    Lanes sg[4][6];
    group.load_points(stress + 24 * std::size_t(first + k0), sg);
    Lanes fz[10][3] = {};
    node_forces(s.geometry.data() + 40 * std::size_t(k0), sg, fz);
    scatter_node_forces(group, fz, force, force_size);
  }
}

void tet10_nodal_forces_viscous(const TetMesh& mesh, unsigned int first, unsigned int n,
                                const double* stress, const Tet10Scratch& s,
                                const ViscousModuli& viscous, double* force, double* force_size,
                                double* damping_force)
{
  for (unsigned int k0 = 0; k0 < n; k0 += W)
  {
    const Group group(mesh, first, k0, n);
    const double* geometry = s.geometry.data() + 40 * std::size_t(k0);
    Lanes sg[4][6];
    group.load_points(stress + 24 * std::size_t(first + k0), sg);
    Lanes fz[10][3] = {};
    node_forces(geometry, sg, fz);
    scatter_node_forces(group, fz, force, force_size);
    // The viscous stress of each Gauss point's strain increment
    // (viscous_stress, operation for operation), its forces apart.
    Lanes de[4][6];
    group.load_points(s.strain_increment.data() + 24 * std::size_t(k0), de);
    for (int q = 0; q < 4; ++q)
    {
      const Lanes volumetric = viscous.lambda * (de[q][0] + de[q][1] + de[q][2]);
      for (int c = 0; c < 3; ++c)
        sg[q][c] = volumetric + viscous.two_g * de[q][c];
      for (int c = 3; c < 6; ++c)
        sg[q][c] = viscous.two_g * de[q][c];
    }
    Lanes fv[10][3] = {};
    node_forces(geometry, sg, fv);
    scatter_node_forces(group, fv, damping_force, nullptr);
  }
}

void tet10_mass_and_stiffness(const TetMesh& mesh, unsigned int z, double rho, double K, double G,
                              double mass[10], double stiffness[10])
{
  // The zone as built is straight-sided (midpoints on the edges), so the
  // barycentric gradients are constant: those of the 4-node zone.
  const auto& t = mesh.zone_gridpoint[z];
  double e[3][3]; // e[d][k] = (x_(k+1) - x_0)_d
  for (int d = 0; d < 3; ++d)
    for (int k = 0; k < 3; ++k)
      e[d][k] = mesh.position[3 * t[k + 1] + d] - mesh.position[3 * t[0] + d];
  const double c00 = e[1][1] * e[2][2] - e[1][2] * e[2][1];
  const double c01 = e[1][2] * e[2][0] - e[1][0] * e[2][2];
  const double c02 = e[1][0] * e[2][1] - e[1][1] * e[2][0];
  const double det = e[0][0] * c00 + e[0][1] * c01 + e[0][2] * c02;
  const double V = det / 6.0;
  double gL[4][3]; // grad L_m, 1/m
  gL[1][0] = c00 / det;
  gL[1][1] = (e[0][2] * e[2][1] - e[0][1] * e[2][2]) / det;
  gL[1][2] = (e[0][1] * e[1][2] - e[0][2] * e[1][1]) / det;
  gL[2][0] = c01 / det;
  gL[2][1] = (e[0][0] * e[2][2] - e[0][2] * e[2][0]) / det;
  gL[2][2] = (e[0][2] * e[1][0] - e[0][0] * e[1][2]) / det;
  gL[3][0] = c02 / det;
  gL[3][1] = (e[0][1] * e[2][0] - e[0][0] * e[2][1]) / det;
  gL[3][2] = (e[0][0] * e[1][1] - e[0][1] * e[1][0]) / det;
  for (int d = 0; d < 3; ++d)
    gL[0][d] = -(gL[1][d] + gL[2][d] + gL[3][d]);

  // Lumped masses by HRZ (diagonal scaling): each node takes the zone's
  // mass in proportion to its diagonal consistent-mass entry, int N_n^2 dV
  // = V/70 at a vertex and 8V/105 at an edge midpoint (straight sides), so
  // m/36 at each vertex and 4m/27 at each midpoint. Row-sum lumping would
  // give the vertices -m/20, which explicit stepping cannot use; HRZ keeps
  // every mass positive, keeps the element itself (shape functions, the
  // 4-point rule) as it is, and its first moment is exact (the lumped
  // masses' centre is the zone's centroid), so gravity on the lumped masses
  // has the right resultant and moment and a free fall stays rigid. The
  // alternative, a bubble-enriched element, needs an eleventh node and a
  // higher-order rule in every zone update.
  const double m = rho * V;
  for (int a = 0; a < 4; ++a)
    mass[a] = m / 36.0;
  for (int a = 4; a < 10; ++a)
    mass[a] = 4.0 * m / 27.0;

  // Stable step: central differences are stable for dt <= 2 / omega_max,
  // omega_max^2 the largest eigenvalue of M^-1 K (lumped M). By
  // Gershgorin's theorem applied to the rows of M^-1 K, omega_max^2 <=
  // max_r sum_c |K_rc| / m_r; the assembled row sums are at most the sum of
  // the zones' row sums, so with k_n the largest row sum over the three
  // components of node n (summed over the zones at a gridpoint, eq. 85's
  // role) the step dt = 2 min_n sqrt(m_n / k_n) of eq. 84 is stable, and
  // density scaling m_n = k_n dt^2 / 4 keeps omega_max dt <= 2. The zone
  // stiffness K_(a,i)(b,j) = sum_q V/4 [lambda g_a,i g_b,j + G (delta_ij
  // g_a . g_b + g_a,j g_b,i)], g = grad N at Gauss point q, is exact with
  // the 4-point rule for straight sides; it is formed here once, never in
  // the cycle.
  const double lambda = K - 2.0 * G / 3.0;
  double row[10][3] = {};
  double K_ab[10][10][3][3] = {};
  for (int q = 0; q < 4; ++q)
  {
    double g[10][3];
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d)
        g[a][d] = (4.0 * bary(q, a) - 1.0) * gL[a][d];
    for (int k = 0; k < 6; ++k)
    {
      const int a = tet10_edge[k][0], b = tet10_edge[k][1];
      for (int d = 0; d < 3; ++d)
        g[4 + k][d] = 4.0 * (bary(q, b) * gL[a][d] + bary(q, a) * gL[b][d]);
    }
    const double w = V / 4.0;
    for (int a = 0; a < 10; ++a)
      for (int b = 0; b < 10; ++b)
      {
        const double dot = g[a][0] * g[b][0] + g[a][1] * g[b][1] + g[a][2] * g[b][2];
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            K_ab[a][b][i][j] +=
                w * (lambda * g[a][i] * g[b][j] + G * ((i == j ? dot : 0.0) + g[a][j] * g[b][i]));
      }
  }
  for (int a = 0; a < 10; ++a)
  {
    for (int b = 0; b < 10; ++b)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          row[a][i] += std::abs(K_ab[a][b][i][j]);
    stiffness[a] = std::max({row[a][0], row[a][1], row[a][2]});
  }
}

void tet10_gauss_points(const TetMesh& mesh, unsigned int z, double point[4][3])
{
  // Straight sides: the Gauss points are at their barycentric coordinates.
  for (int q = 0; q < 4; ++q)
    for (int d = 0; d < 3; ++d)
    {
      point[q][d] = 0.0;
      for (int m = 0; m < 4; ++m)
        point[q][d] += bary(q, m) * mesh.position[3 * mesh.zone_gridpoint[z][m] + d];
    }
}

} // namespace talus
