#include <talus/zone/lanes.h>
#include <talus/zone/tet4_kernel.h>

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace talus
{

namespace
{
// The kernels work on W zones at once, one lane per zone, in GCC/Clang
// vector types: each operation below is one vector instruction, with the
// same arithmetic per lane as one zone at a time. W is the hardware's
// width: with wider generic vectors (split by the compiler) GCC 12 fuses
// multiplies and adds differently from the scalar code, so the results
// would no longer be bitwise those of one zone at a time. Loops over lanes
// written for the auto-vectoriser were not vectorised by GCC 12, hence the
// explicit types.
constexpr unsigned int W = lane_count;
static_assert(Tet4Scratch::max_lanes % W == 0, "scratch holds whole groups");

/// Groups ahead whose zone stresses are prefetched. The stresses are read
/// by gathers, which the hardware prefetcher does not follow: on a mesh
/// larger than the caches each group otherwise waits for memory (at
/// 5 million zones a fifth of this kernel's samples sat on the first
/// stress gather). Eight groups (64 zones, 3 KB of stress with AVX-512)
/// measured best of 4, 8 and 16; the cycle gained 2-7 % (median of
/// interleaved runs, n = 20 and 100, elastic and Mohr-Coulomb).
constexpr unsigned int prefetch_groups = 8;

/// Prefetches the numbers of a gridpoint field (3 per gridpoint) at the
/// corners of zone z for reading. The corners are found through the zone
/// table, which the hardware prefetcher cannot follow: on a large mesh each
/// layer's new gridpoints otherwise come from memory while the kernel waits
/// on them.
inline void prefetch_corners(const TetMesh& mesh, std::size_t z, const double* field,
                             unsigned int stride = 3)
{
  if (z < mesh.n_zones())
    for (unsigned int g : mesh.zone_gridpoint[z])
    {
      const double* p = field + stride * std::size_t(g);
      __builtin_prefetch(p);
      if (stride > 2) // a row of three may cross into the next line (a pair does not)
        __builtin_prefetch(p + 2);
    }
}

/// The zones [k0, k0 + W) of a batch as one group: their gridpoints, lane
/// by lane; lanes past the batch's end repeat its last zone, so that every
/// lane computes something harmless and nothing is written for them.
struct Group
{
#if defined(__AVX512F__) && defined(__AVX512VL__)
  // The gathers below load each corner's row by its gridpoint number, so
  // the numbers are read straight from the zone table (4 per zone): moving
  // them into vector registers first and back out cost a vector-to-integer
  // transfer for every row.
  const unsigned int* rows;   ///< 4 gridpoints per lane
  unsigned int padded[4 * W]; ///< a short group's rows, its last zone repeated
  LaneMask zone;              ///< 6 (zone - k0): the offset of each zone in a zone field
  unsigned int count;         ///< lanes that are real zones

  Group(const TetMesh& mesh, unsigned int first, unsigned int k0, unsigned int n)
      : count(std::min(W, n - k0))
  {
    static_assert(sizeof(mesh.zone_gridpoint[0]) == 4 * sizeof(unsigned int),
                  "four packed unsigned ints per zone");
    if (count == W)
    {
      rows = mesh.zone_gridpoint[first + k0].data();
      zone = LaneMask{0, 6, 12, 18, 24, 30, 36, 42};
      return;
    }
    for (unsigned int l = 0; l < W; ++l)
    {
      const unsigned int k = std::min(l, count - 1);
      for (int a = 0; a < 4; ++a)
        padded[4 * l + a] = mesh.zone_gridpoint[first + k0 + k][a];
      zone[l] = 6 * k;
    }
    rows = padded;
  }
  Group(const Group&) = delete;

  unsigned int gridpoint(int a, unsigned int l) const
  {
    return rows[4 * l + a];
  }
#else
  unsigned int gridpoints[4][W];
  LaneMask corner[4]; ///< 3 gridpoint: the offset of each corner in a gridpoint field
  LaneMask zone;      ///< 6 (zone - k0): the offset of each zone in a zone field
  unsigned int count; ///< lanes that are real zones

  Group(const TetMesh& mesh, unsigned int first, unsigned int k0, unsigned int n)
      : count(std::min(W, n - k0))
  {
#if (defined(__clang__) || __GNUC__ >= 12) && !defined(__AVX512F__)
    if (count == W)
    {
      // The zones' gridpoint numbers, corner-major, by shuffles in
      // registers: element-wise assembly through the stack would stall the
      // first gather of every group.
      static_assert(sizeof(mesh.zone_gridpoint[0]) == 4 * sizeof(unsigned int),
                    "four packed unsigned ints per zone");
      typedef unsigned int FourZones __attribute__((vector_size(16 * sizeof(unsigned int))));
      typedef unsigned int Corners __attribute__((vector_size(W * sizeof(unsigned int))));
      FourZones zones_0_3;
      std::memcpy(&zones_0_3, mesh.zone_gridpoint.data() + first + k0, sizeof zones_0_3);
      const Corners by_corner[4] = {__builtin_shufflevector(zones_0_3, zones_0_3, 0, 4, 8, 12),
                                    __builtin_shufflevector(zones_0_3, zones_0_3, 1, 5, 9, 13),
                                    __builtin_shufflevector(zones_0_3, zones_0_3, 2, 6, 10, 14),
                                    __builtin_shufflevector(zones_0_3, zones_0_3, 3, 7, 11, 15)};
      zone = LaneMask{0, 6, 12, 18};
      for (int a = 0; a < 4; ++a)
      {
        std::memcpy(gridpoints[a], &by_corner[a], sizeof by_corner[a]);
        corner[a] = __builtin_convertvector(by_corner[a], LaneMask) * 3;
      }
      return;
    }
#endif
    for (unsigned int l = 0; l < W; ++l)
    {
      const unsigned int k = std::min(l, count - 1);
      const auto& g = mesh.zone_gridpoint[first + k0 + k];
      for (int a = 0; a < 4; ++a)
      {
        gridpoints[a][l] = g[a];
        corner[a][l] = 3 * std::int64_t(g[a]);
      }
      zone[l] = 6 * k;
    }
  }

  unsigned int gridpoint(int a, unsigned int l) const
  {
    return gridpoints[a][l];
  }
#endif

  /// The three components of a gridpoint field (3 per gridpoint) at the
  /// four corners.
  void gather_corners(const double* field, Lanes (&out)[4][3]) const
  {
#if defined(__AVX512F__) && defined(__AVX512VL__)
    // Each gridpoint's three numbers by one masked load (nothing read past
    // them), the eight rows then transposed in registers: cheaper than
    // three gathers of eight, which dominate the kernels otherwise.
    const __m512i x_rows = _mm512_set_epi64(13, 12, 5, 4, 9, 8, 1, 0);
    const __m512i z_rows = _mm512_set_epi64(15, 14, 7, 6, 11, 10, 3, 2);
    for (int a = 0; a < 4; ++a)
    {
      __m256d row[8];
      for (unsigned int l = 0; l < W; ++l)
        row[l] = _mm256_maskz_loadu_pd(0x7, field + 3 * std::size_t(gridpoint(a, l)));
      // Rows l and l + 4 side by side: (x y z 0 | x y z 0).
      __m512d pair[4];
      for (int l = 0; l < 4; ++l)
        pair[l] = _mm512_maskz_insertf64x4(
            0xff, _mm512_maskz_insertf64x4(0xff, _mm512_setzero_pd(), row[l], 0), row[l + 4], 1);
      // (x0 x1 z0 z1 | x4 x5 z4 z5), (y0 y1 0 0 | y4 y5 0 0), and for 2, 3, 6, 7.
      // (The masked forms: the plain ones make GCC 12 warn of an
      // uninitialised source.)
      const __m512d xz01 = _mm512_maskz_unpacklo_pd(0xff, pair[0], pair[1]);
      const __m512d y01 = _mm512_maskz_unpackhi_pd(0xff, pair[0], pair[1]);
      const __m512d xz23 = _mm512_maskz_unpacklo_pd(0xff, pair[2], pair[3]);
      const __m512d y23 = _mm512_maskz_unpackhi_pd(0xff, pair[2], pair[3]);
      out[a][0] = (Lanes)_mm512_permutex2var_pd(xz01, x_rows, xz23);
      out[a][1] = (Lanes)_mm512_permutex2var_pd(y01, x_rows, y23);
      out[a][2] = (Lanes)_mm512_permutex2var_pd(xz01, z_rows, xz23);
    }
#else
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d)
        out[a][d] = gather_lanes(field + d, corner[a]);
#endif
  }

  /// One number per gridpoint, `stride` numbers apart in `field`, at the
  /// four corners.
  void gather_corner_values(const double* field, unsigned int stride, Lanes (&out)[4]) const
  {
#if defined(__AVX512F__) && defined(__AVX512VL__)
    // Each corner's gridpoint numbers picked out of the rows of lanes 0-3
    // and 4-7 in registers, then one gather per corner.
    typedef unsigned int FourZones __attribute__((vector_size(16 * sizeof(unsigned int))));
    typedef unsigned int Corners __attribute__((vector_size(W * sizeof(unsigned int))));
    FourZones lanes_0_3, lanes_4_7;
    std::memcpy(&lanes_0_3, rows, sizeof lanes_0_3);
    std::memcpy(&lanes_4_7, rows + 16, sizeof lanes_4_7);
    const Corners by_corner[4] = {
        __builtin_shufflevector(lanes_0_3, lanes_4_7, 0, 4, 8, 12, 16, 20, 24, 28),
        __builtin_shufflevector(lanes_0_3, lanes_4_7, 1, 5, 9, 13, 17, 21, 25, 29),
        __builtin_shufflevector(lanes_0_3, lanes_4_7, 2, 6, 10, 14, 18, 22, 26, 30),
        __builtin_shufflevector(lanes_0_3, lanes_4_7, 3, 7, 11, 15, 19, 23, 27, 31)};
    for (int a = 0; a < 4; ++a)
    {
      const Corners index = by_corner[a] * stride;
      out[a] = (Lanes)_mm512_mask_i32gather_pd(_mm512_setzero_pd(), 0xff, (__m256i)index, field,
                                               sizeof(double));
    }
#else
    for (int a = 0; a < 4; ++a)
    {
      LaneMask index;
      for (unsigned int l = 0; l < W; ++l)
        index[l] = std::int64_t(stride) * gridpoint(a, l);
      out[a] = gather_lanes(field, index);
    }
#endif
  }

  /// Six stress (or strain) components of the group's zones, from the zone
  /// array (6 per zone, starting at zone k0) to lanes and back.
  void load_six(const double* zone_values, Lanes (&out)[6]) const
  {
    for (int c = 0; c < 6; ++c)
      out[c] = gather_lanes(zone_values + c, zone);
  }
  void store_six(const Lanes (&in)[6], double* zone_values) const
  {
#if defined(__AVX512F__)
    const __mmask8 real = static_cast<__mmask8>((1u << count) - 1);
    for (int c = 0; c < 6; ++c)
      _mm512_mask_i64scatter_pd(zone_values + c, real, (__m512i)zone, (__m512d)in[c],
                                sizeof(double));
#else
    for (unsigned int l = 0; l < count; ++l)
      for (int c = 0; c < 6; ++c)
        zone_values[6 * l + c] = in[c][l];
#endif
  }
};

/// Gradients of the four shape functions of the tetrahedra with corners
/// p[0..3] into gr (1/m); returns 6 V (m^3). The gradients of N1..N3 are the
/// rows of the inverse of the matrix whose columns are the edges from
/// corner 0; N0's is minus their sum.
inline Lanes shape_gradients(const Lanes (&p)[4][3], Lanes (&gr)[4][3])
{
  Lanes e[3][3];
  for (int d = 0; d < 3; ++d)
  {
    e[d][0] = p[1][d] - p[0][d];
    e[d][1] = p[2][d] - p[0][d];
    e[d][2] = p[3][d] - p[0][d];
  }
  const Lanes c00 = e[1][1] * e[2][2] - e[1][2] * e[2][1];
  const Lanes c01 = e[1][2] * e[2][0] - e[1][0] * e[2][2];
  const Lanes c02 = e[1][0] * e[2][1] - e[1][1] * e[2][0];
  const Lanes det = e[0][0] * c00 + e[0][1] * c01 + e[0][2] * c02;
  const Lanes inv = 1.0 / det;
  gr[1][0] = c00 * inv;
  gr[1][1] = (e[0][2] * e[2][1] - e[0][1] * e[2][2]) * inv;
  gr[1][2] = (e[0][1] * e[1][2] - e[0][2] * e[1][1]) * inv;
  gr[2][0] = c01 * inv;
  gr[2][1] = (e[0][0] * e[2][2] - e[0][2] * e[2][0]) * inv;
  gr[2][2] = (e[0][2] * e[1][0] - e[0][0] * e[1][2]) * inv;
  gr[3][0] = c02 * inv;
  gr[3][1] = (e[0][1] * e[2][0] - e[0][0] * e[2][1]) * inv;
  gr[3][2] = (e[0][0] * e[1][1] - e[0][1] * e[1][0]) * inv;
  for (int d = 0; d < 3; ++d)
    gr[0][d] = -(gr[1][d] + gr[2][d] + gr[3][d]);
  return det;
}

/// Shape-function gradients gm on the geometry halfway through the last
/// motion, x - v dt / 2 (x at p, v at vel, dt in s): there a rigid rotation
/// gives an exactly antisymmetric velocity gradient, so no strain, for any
/// step size. Shared by the strain pass and nodal mixed discretization's
/// sums, which must round alike.
inline void mid_step_gradients(const Lanes (&p)[4][3], const Lanes (&vel)[4][3], double dt,
                               Lanes (&gm)[4][3])
{
  Lanes mid[4][3];
  for (int a = 0; a < 4; ++a)
    for (int d = 0; d < 3; ++d)
      mid[a][d] = p[a][d] - 0.5 * dt * vel[a][d];
  shape_gradients(mid, gm);
}
/// The value as rounded so far: the compiler may not fuse the operation
/// that made it with the one that uses it (a multiply-add rounds once), so
/// a sum of stored products here is rounded as one of products read back
/// from memory.
inline Lanes rounded(Lanes value)
{
#if defined(__AVX__)
  asm("" : "+v"(value)); // kept in its register
#else
  asm("" : "+m"(value)); // no register holds a whole Lanes: through memory
#endif
  return value;
}
} // namespace

void tet4_strain_increments(const TetMesh& mesh, unsigned int first, unsigned int n,
                            const double* x, const double* v, double dt, double* stress,
                            Tet4Scratch& s, double* volumetric, const double* average_pairs)
{
  for (unsigned int k0 = 0; k0 < n; k0 += W)
  {
    // Within the stress array (6 per zone of the mesh), past this batch too.
    const std::size_t ahead = std::size_t(first) + k0 + prefetch_groups * W;
    if (ahead + W <= mesh.n_zones())
      for (std::size_t b = 0; b < 6 * W * sizeof(double); b += 64)
        __builtin_prefetch(reinterpret_cast<const char*>(stress + 6 * ahead) + b, 1);
    prefetch_corners(mesh, ahead, x);
    prefetch_corners(mesh, ahead, v);
    if (average_pairs)
      prefetch_corners(mesh, ahead, average_pairs, 2);
    const Group group(mesh, first, k0, n);
    Lanes p[4][3], vel[4][3];
    group.gather_corners(x, p);
    group.gather_corners(v, vel);
    // Current geometry: gradients and volume for the nodal forces.
    Lanes gr[4][3];
    store_lanes(s.volume.data() + k0, shape_gradients(p, gr) / 6.0);
    double* gr_out = s.gradient.data() + 12 * k0; // 12 rows of W lanes
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d)
        store_lanes(gr_out + (3 * a + d) * W, gr[a][d]);
    // The motion of the last step, x - v dt -> x, on the mid-step geometry.
    Lanes gm[4][3];
    mid_step_gradients(p, vel, dt, gm);
    // Velocity gradient L_ij = sum_n v_n,i dN_n/dx_j.
    Lanes L[3][3] = {};
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          L[i][j] += vel[a][i] * gm[a][j];
    // Eq. 58: strain rate and spin; the increment of this step.
    Lanes de[6] = {L[0][0] * dt,
                   L[1][1] * dt,
                   L[2][2] * dt,
                   0.5 * (L[0][1] + L[1][0]) * dt,
                   0.5 * (L[1][2] + L[2][1]) * dt,
                   0.5 * (L[2][0] + L[0][2]) * dt};
    if (volumetric || average_pairs) // nodal mixed discretization only
    {
      // tr(D dt) / 3 of the stored increments, as tet4_volumetric_increments
      // and replace_volumetric_strain round it.
      const Lanes volumetric_part = (rounded(de[0]) + rounded(de[1]) + rounded(de[2])) / 3.0;
      if (volumetric)
        store_lanes(volumetric + k0, volumetric_part);
      if (average_pairs)
      {
        // Eqs. 70-71, operation for operation as replace_volumetric_strain.
        Lanes average[4];
        group.gather_corner_values(average_pairs, 2, average);
        Lanes mean = {};
        for (int a = 0; a < 4; ++a)
          mean += 0.25 * average[a];
        const Lanes shift = mean - volumetric_part;
        for (int c = 0; c < 3; ++c)
          de[c] = rounded(de[c]) + shift;
      }
    }
    group.store_six(de, s.strain_increment.data() + 6 * k0);
    const Lanes w01 = 0.5 * (L[0][1] - L[1][0]) * dt; // W_xy dt
    const Lanes w12 = 0.5 * (L[1][2] - L[2][1]) * dt; // W_yz dt
    const Lanes w20 = 0.5 * (L[2][0] - L[0][2]) * dt; // W_zx dt
    // Jaumann (co-rotational) turn of the stress by the spin:
    // sigma += (W sigma - sigma W) dt.
    Lanes sg[6];
    double* zone_stress = stress + 6 * (first + k0);
    group.load_six(zone_stress, sg);
    const Lanes sxx = sg[0], syy = sg[1], szz = sg[2], sxy = sg[3], syz = sg[4], szx = sg[5];
    sg[0] += 2.0 * (w01 * sxy - w20 * szx);
    sg[1] += 2.0 * (w12 * syz - w01 * sxy);
    sg[2] += 2.0 * (w20 * szx - w12 * syz);
    sg[3] += w01 * (syy - sxx) + w12 * szx - w20 * syz;
    sg[4] += w12 * (szz - syy) + w20 * sxy - w01 * szx;
    sg[5] += w20 * (sxx - szz) + w01 * syz - w12 * sxy;
    group.store_six(sg, zone_stress);
  }
}

void tet4_volumetric_increments(const TetMesh& mesh, unsigned int first, unsigned int n,
                                const double* x, const double* v, double dt, double* volumetric,
                                double* volume)
{
  // The arithmetic of tet4_strain_increments restricted to what the
  // volumetric part needs (the diagonal of L), operation for operation.
  for (unsigned int k0 = 0; k0 < n; k0 += W)
  {
    const std::size_t ahead = std::size_t(first) + k0 + prefetch_groups * W;
    prefetch_corners(mesh, ahead, x);
    prefetch_corners(mesh, ahead, v);
    const Group group(mesh, first, k0, n);
    Lanes p[4][3], vel[4][3];
    group.gather_corners(x, p);
    group.gather_corners(v, vel);
    Lanes gr[4][3];
    store_lanes(volume + k0, shape_gradients(p, gr) / 6.0);
    Lanes gm[4][3];
    mid_step_gradients(p, vel, dt, gm);
    Lanes L[3] = {};
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i)
        L[i] += vel[a][i] * gm[a][i];
    const Lanes sum = rounded(L[0] * dt) + rounded(L[1] * dt) + rounded(L[2] * dt);
    store_lanes(volumetric + k0, sum / 3.0);
  }
}

void tet4_geometry(const TetMesh& mesh, unsigned int first, unsigned int n, const double* x,
                   Tet4Scratch& s)
{
  for (unsigned int k0 = 0; k0 < n; k0 += W)
  {
    const Group group(mesh, first, k0, n);
    Lanes p[4][3];
    group.gather_corners(x, p);
    Lanes gr[4][3];
    store_lanes(s.volume.data() + k0, shape_gradients(p, gr) / 6.0);
    double* gr_out = s.gradient.data() + 12 * k0;
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d)
        store_lanes(gr_out + (3 * a + d) * W, gr[a][d]);
  }
}

namespace
{
/// Eq. 55 for the group's zones: the force of stress sg on each corner
/// a, V sigma grad N_a (to be subtracted), gr the group's 12 gradient rows.
inline void corner_forces(const Lanes (&sg)[6], const double* gr, const Lanes& V, Lanes (&fz)[4][3])
{
  for (int a = 0; a < 4; ++a)
  {
    const Lanes gx = load_lanes(gr + (3 * a) * W), gy = load_lanes(gr + (3 * a + 1) * W),
                gz = load_lanes(gr + (3 * a + 2) * W);
    fz[a][0] = V * (sg[0] * gx + sg[3] * gy + sg[5] * gz);
    fz[a][1] = V * (sg[3] * gx + sg[1] * gy + sg[4] * gz);
    fz[a][2] = V * (sg[5] * gx + sg[4] * gy + sg[2] * gz);
  }
}

/// Subtracts the corner forces from `force` (3 per gridpoint, unless null) and, when
/// `force_size` is not null, adds their magnitudes there: zone by zone,
/// corner by corner, the same order of summation at each gridpoint as one
/// zone at a time.
inline void scatter_corner_forces(const Group& group, const Lanes (&fz)[4][3], double* force,
                                  double* force_size)
{
  if (force != nullptr)
    for (unsigned int l = 0; l < group.count; ++l)
      for (int a = 0; a < 4; ++a)
      {
        double* f = force + 3 * group.gridpoint(a, l);
        for (int d = 0; d < 3; ++d)
          f[d] -= fz[a][d][l];
      }
  if (force_size != nullptr)
  {
    Lanes size[4][3];
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d)
        size[a][d] = lane_abs(fz[a][d]);
    for (unsigned int l = 0; l < group.count; ++l)
      for (int a = 0; a < 4; ++a)
      {
        double* fs = force_size + 3 * group.gridpoint(a, l);
        for (int d = 0; d < 3; ++d)
          fs[d] += size[a][d][l];
      }
  }
}
} // namespace

void tet4_nodal_forces(const TetMesh& mesh, unsigned int first, unsigned int n,
                       const double* stress, const Tet4Scratch& s, double* force,
                       double* force_size)
{
  for (unsigned int k0 = 0; k0 < n; k0 += W)
  {
    const Group group(mesh, first, k0, n);
    Lanes sg[6];
    group.load_six(stress + 6 * (first + k0), sg);
    Lanes fz[4][3];
    corner_forces(sg, s.gradient.data() + 12 * k0, load_lanes(s.volume.data() + k0), fz);
    scatter_corner_forces(group, fz, force, force_size);
  }
}

void tet4_nodal_forces_viscous(const TetMesh& mesh, unsigned int first, unsigned int n,
                               const double* stress, const Tet4Scratch& s,
                               const ViscousModuli& viscous, double* force, double* force_size,
                               double* damping_force)
{
  for (unsigned int k0 = 0; k0 < n; k0 += W)
  {
    const Group group(mesh, first, k0, n);
    const double* gr = s.gradient.data() + 12 * k0;
    const Lanes V = load_lanes(s.volume.data() + k0);
    // The viscous stress of the zones' strain increments (viscous_stress,
    // operation for operation), its forces apart.
    Lanes de[6], sv[6];
    group.load_six(s.strain_increment.data() + 6 * k0, de);
    const Lanes volumetric = viscous.lambda * (de[0] + de[1] + de[2]);
    for (int c = 0; c < 3; ++c)
      sv[c] = volumetric + viscous.two_g * de[c];
    for (int c = 3; c < 6; ++c)
      sv[c] = viscous.two_g * de[c];
    Lanes fv[4][3];
    corner_forces(sv, gr, V, fv);
    if (stress == nullptr)
    {
      scatter_corner_forces(group, fv, damping_force, nullptr);
      continue;
    }
    Lanes sg[6];
    group.load_six(stress + 6 * (first + k0), sg);
    Lanes fz[4][3];
    corner_forces(sg, gr, V, fz);
    // Both forces of a corner at once (each array summed in the order of
    // scatter_corner_forces).
    for (unsigned int l = 0; l < group.count; ++l)
      for (int a = 0; a < 4; ++a)
      {
        const std::size_t g = 3 * std::size_t(group.gridpoint(a, l));
        for (int d = 0; d < 3; ++d)
        {
          force[g + d] -= fz[a][d][l];
          damping_force[g + d] -= fv[a][d][l];
        }
      }
    if (force_size != nullptr)
      scatter_corner_forces(group, fz, nullptr, force_size);
  }
}

} // namespace talus
