#pragma once

#include <talus/zone/tet_mesh.h>

namespace talus
{

/// Scratch of one batch of constant-strain tetrahedra between the two
/// kernel passes: shape-function gradients (3 per node, 12 per zone, 1/m)
/// and volume (m^3) in the current configuration.
struct Tet4Scratch
{
  std::vector<double> gradient, volume, strain_increment;
  void resize(unsigned int zones)
  {
    gradient.resize(12 * zones);
    volume.resize(zones);
    strain_increment.resize(6 * zones);
  }
};

/// Pass 1 for zones [first, first + n): from the current gridpoint
/// positions `x` and velocities `v` (3 per gridpoint), the shape-function
/// gradients and volume, the strain increment D dt (eq. 58, times dt) into
/// scratch, and the co-rotational (Jaumann) turn of the stored stress by
/// the spin, so that a rigid rotation leaves the stress unchanged.
void tet4_strain_increments(const TetMesh& mesh, unsigned int first, unsigned int n,
                            const double* x, const double* v, double dt, double* stress,
                            Tet4Scratch& scratch);

/// Pass 2: nodal forces of the zones' stresses, f_n = -V sigma grad N_n
/// (eq. 55 for a constant-stress tetrahedron), added to `force` (3 per
/// gridpoint, N); their magnitudes are added to `force_size` (for the
/// unbalanced-force ratio) when it is not null.
void tet4_nodal_forces(const TetMesh& mesh, unsigned int first, unsigned int n,
                       const double* stress, const Tet4Scratch& scratch, double* force,
                       double* force_size = nullptr);

} // namespace talus
