#pragma once

#include <talus/zone/tet_mesh.h>
#include <talus/zone/viscous_stress.h>

namespace talus
{

/// Scratch of one batch of constant-strain tetrahedra between the two
/// kernel passes: shape-function gradients (3 per node, 12 per zone, 1/m),
/// volume (m^3) in the current configuration, and the strain increment (6
/// per zone). The kernels work on groups of W zones at once (one vector
/// instruction per operation across the group; W = 8 with AVX-512, else 4),
/// so the gradients are stored group by group, component-major within a
/// group: gradient component c (3 node + d) of zone k is at
/// 12 W (k / W) + c W + k % W. Sizes are rounded up to whole groups.
struct Tet4Scratch
{
  static constexpr unsigned int max_lanes = 8; ///< the widest group W
  std::vector<double> gradient, volume, strain_increment;
  void resize(unsigned int zones)
  {
    const unsigned int padded = (zones + max_lanes - 1) / max_lanes * max_lanes;
    gradient.resize(12 * padded);
    volume.resize(padded);
    strain_increment.resize(6 * padded);
  }
};

/// Pass 1 for zones [first, first + n): from the current gridpoint
/// positions `x` and velocities `v` (3 per gridpoint), the shape-function
/// gradients and volume, the strain increment D dt (eq. 58, times dt) into
/// scratch, and the co-rotational (Jaumann) turn of the stored stress by
/// the spin, so that a rigid rotation leaves the stress unchanged. With
/// `volumetric`, also each zone's tr(D dt) / 3 there, rounded as
/// tet4_volumetric_increments rounds it (n values rounded up to whole
/// groups of Tet4Scratch::max_lanes). With `average_pairs` (nodal mixed
/// discretization, eqs. 70-71), each zone's volumetric part is replaced
/// before it is stored by the mean of its gridpoints' averages (the first
/// number of each gridpoint's pair), bitwise as replace_volumetric_strain
/// replaces it afterwards, without a second sweep over the zones.
void tet4_strain_increments(const TetMesh& mesh, unsigned int first, unsigned int n,
                            const double* x, const double* v, double dt, double* stress,
                            Tet4Scratch& scratch, double* volumetric = nullptr,
                            const double* average_pairs = nullptr);

/// For the first sweep of nodal mixed discretization (eqs. 68-69), zones
/// [first, first + n): each zone's volume (m^3, into `volume`) and
/// volumetric strain increment e = tr(D dt) / 3 (into `volumetric`), both
/// rounded exactly as tet4_strain_increments's volume and the mean of its
/// three normal strain increments; the stress is not touched. Both arrays
/// hold n values rounded up to whole groups of Tet4Scratch::max_lanes.
void tet4_volumetric_increments(const TetMesh& mesh, unsigned int first, unsigned int n,
                                const double* x, const double* v, double dt, double* volumetric,
                                double* volume);

/// The shape-function gradients and volume of zones [first, first + n)
/// alone, into scratch (bitwise those of tet4_strain_increments): for
/// nodal forces in a later sweep than the strain increments.
void tet4_geometry(const TetMesh& mesh, unsigned int first, unsigned int n, const double* x,
                   Tet4Scratch& scratch);

/// Pass 2: nodal forces of the zones' stresses, f_n = -V sigma grad N_n
/// (eq. 55 for a constant-stress tetrahedron), added to `force` (3 per
/// gridpoint, N); their magnitudes are added to `force_size` (for the
/// unbalanced-force ratio) when it is not null.
void tet4_nodal_forces(const TetMesh& mesh, unsigned int first, unsigned int n,
                       const double* stress, const Tet4Scratch& scratch, double* force,
                       double* force_size = nullptr);

/// Pass 2 of dynamics with Rayleigh's stiffness-proportional term, in one
/// pass over the zones: the nodal forces of the stresses as
/// tet4_nodal_forces (none when `stress` is null), and those of the
/// viscous stress of each zone's strain increment in scratch (`viscous`,
/// viscous_stress.h) added to `damping_force` (3 per gridpoint, N), bitwise
/// as viscous_stress and a second tet4_nodal_forces would add them.
void tet4_nodal_forces_viscous(const TetMesh& mesh, unsigned int first, unsigned int n,
                               const double* stress, const Tet4Scratch& scratch,
                               const ViscousModuli& viscous, double* force, double* force_size,
                               double* damping_force);

} // namespace talus
