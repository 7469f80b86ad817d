#pragma once

namespace talus
{

/// Eigenvalues and eigenvectors of a symmetric 3x3 tensor t, given as six
/// numbers (xx, yy, zz, xy, yz, zx), without iteration: the eigenvalue set
/// furthest from the other two by the trigonometric solution of the
/// characteristic cubic, its eigenvector by the cross product of two rows
/// of (t - lambda I), and the other two from the 2x2 problem in the plane
/// normal to it (one Jacobi rotation). The values are then Rayleigh
/// quotients of the vectors, so they are accurate to round-off of |t| even
/// where two values (nearly) coincide, and the vectors of a (nearly)
/// repeated pair span their plane to round-off. About a fifth of the cost
/// of Eigen's iterative SelfAdjointEigenSolver on a 3x3.
///
/// On return values[0] <= values[1] <= values[2] (same unit as t) and
/// axes[p] is the unit eigenvector of values[p] (sign arbitrary).
void symmetric_eigen3(const double* t, double* values, double (*axes)[3]);

} // namespace talus
