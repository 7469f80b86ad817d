#pragma once

// The explicit kernel of 10-node (quadratic) tetrahedral zones: matrix-free
// like the 4-node kernel (tet4_kernel.h), but with four Gauss points per
// zone (the rule of deal.II's QGaussSimplex<3>(2), exact for the stiffness
// of a straight-sided quadratic tetrahedron), each with its own strain,
// spin, stress and plastic state. Nodes as in tet10_mesh.h.

#include <talus/zone/tet_mesh.h>
#include <talus/zone/viscous_stress.h>

#include <vector>

namespace talus
{

/// Gauss point q of the 4-point rule has barycentric coordinate
/// tet10_gauss_b at vertex q and tet10_gauss_a at the three others; each
/// has weight 1/4 of the zone's volume.
inline constexpr double tet10_gauss_a = 0.1381966011250105151795; // (5 - sqrt 5) / 20
inline constexpr double tet10_gauss_b = 0.5854101966249684544613; // (5 + 3 sqrt 5) / 20

/// Scratch of one batch of 10-node zones between the two kernel passes:
/// per zone and Gauss point the inverse Jacobian of the current geometry
/// (9, 1/m... d xi / d x) and the quadrature weight times det J (1, m^3),
/// stored group by group (W zones a group, component-major: value c of
/// Gauss point q of zone k at 40 (k - k % W) + (10 q + c) W + k % W), and
/// the strain increments, 6 per Gauss point, Gauss point 4 k + q (the
/// layout StressBatch reads).
struct Tet10Scratch
{
  static constexpr unsigned int max_lanes = 8;
  std::vector<double> geometry, strain_increment;
  void resize(unsigned int zones)
  {
    const unsigned int padded = (zones + max_lanes - 1) / max_lanes * max_lanes;
    geometry.resize(40 * padded);
    strain_increment.resize(24 * padded);
  }
};

/// Pass 1 for zones [first, first + n) (of a quadratic mesh): from the
/// gridpoint positions `x` and velocities `v` (3 per gridpoint), at every
/// Gauss point the current geometry for pass 2, the velocity gradient on
/// the geometry halfway through the last motion (x - v dt / 2, so that a
/// rigid rotation gives no strain), the strain increment D dt (eq. 58) into
/// scratch and the Jaumann turn of the Gauss point's stress (`stress`: 6
/// per Gauss point, 24 per zone, for the whole mesh).
void tet10_strain_increments(const TetMesh& mesh, unsigned int first, unsigned int n,
                             const double* x, const double* v, double dt, double* stress,
                             Tet10Scratch& scratch);

/// Pass 2: nodal forces by quadrature of the Gauss stresses,
/// f_n = -sum_q w_q det J_q sigma_q grad N_n(xi_q) (eq. 55 integrated),
/// added to `force` (3 per gridpoint, N); magnitudes added to `force_size`
/// when not null.
void tet10_nodal_forces(const TetMesh& mesh, unsigned int first, unsigned int n,
                        const double* stress, const Tet10Scratch& scratch, double* force,
                        double* force_size = nullptr);

/// Pass 2 of dynamics with Rayleigh's stiffness-proportional term, in one
/// pass over the zones: the nodal forces of the stresses as
/// tet10_nodal_forces, and those of the viscous stress of each Gauss
/// point's strain increment in scratch (`viscous`, viscous_stress.h) added
/// to `damping_force` (3 per gridpoint, N), bitwise as viscous_stress and a
/// second tet10_nodal_forces would add them.
void tet10_nodal_forces_viscous(const TetMesh& mesh, unsigned int first, unsigned int n,
                                const double* stress, const Tet10Scratch& scratch,
                                const ViscousModuli& viscous, double* force, double* force_size,
                                double* damping_force);

/// Lumped mass (kg) of the ten nodes of zone z of density rho (kg/m^3), by
/// HRZ diagonal scaling, and an upper bound of each node's stiffness (N/m)
/// for the stable step (Gershgorin row sums of the zone's stiffness with
/// bulk modulus K and shear modulus G, Pa); see tet10_kernel.cc.
void tet10_mass_and_stiffness(const TetMesh& mesh, unsigned int z, double rho, double K, double G,
                              double mass[10], double stiffness[10]);

/// Initial positions of the four Gauss points of zone z (m).
void tet10_gauss_points(const TetMesh& mesh, unsigned int z, double point[4][3]);

} // namespace talus
