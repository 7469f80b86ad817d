#pragma once

#include <talus/zone/lanes.h>

namespace talus
{

/// Eigenvalues and eigenvectors of symmetric 3x3 tensors, W at once (one
/// per lane), without iteration over the matrix: the eigenvalue furthest
/// from the other two by the trigonometric solution of the characteristic
/// cubic (its cos(acos(r) / 3) by a few Newton steps, no library calls), its
/// eigenvector by the largest cross product of two rows of (t - lambda I),
/// and the other two from the 2x2 problem in the plane normal to it (one
/// Jacobi rotation). The values are then Rayleigh quotients of the vectors,
/// accurate to round-off of |t| even where two values (nearly) coincide,
/// and the vectors of a (nearly) repeated pair span their plane to
/// round-off. No branches: every lane takes the same path.
///
/// t: the six components (xx, yy, zz, xy, yz, zx). On return, lane by lane,
/// values[0] <= values[1] <= values[2] (same unit as t) and axes[p][k] is
/// component k of the unit eigenvector of values[p] (sign arbitrary).
void symmetric_eigen3(const Lanes (&t)[6], Lanes (&values)[3], Lanes (&axes)[3][3]);

/// The same for one tensor t (six numbers as above).
void symmetric_eigen3(const double* t, double* values, double (*axes)[3]);

} // namespace talus
