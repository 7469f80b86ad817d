// The stable step of 10-node zones (tet10_mass_and_stiffness): the zone
// stiffness of the kernel itself, column by column (the nodal forces of a
// unit velocity of one component over a tiny step), assembled for a 1 m
// cube of 40 zones, against the nodal stiffness bound k_n (Gershgorin row
// sums) and the HRZ masses m_n:
// - no row sum of the assembled stiffness exceeds its node's bound;
// - with the density-scaled masses m_n = k_n dt^2 / 4 the largest
//   eigenvalue of M^-1 K is at most 4 / dt^2 (printed: lambda dt^2 / 4);
// - with the true masses the step 2 min sqrt(m_n / k_n) is below the
//   critical step 2 / omega_max (printed: their ratio, how conservative).

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <talus/base/parallel_environment.h>
#include <talus/zone/block_mesher.h>
#include <talus/zone/tet10_kernel.h>
#include <talus/zone/tet10_mesh.h>
#include <talus/zone/zone_models.h>
using namespace talus;
int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  BlockModel blocks;
  blocks.add_block(ConvexPolyhedron::box(Vec3::Zero(), Vec3(1, 1, 1)), 0);
  MeshReport report;
  TetMesh mesh = mesh_blocks(blocks, {0}, 0.5, report);
  make_quadratic(mesh);
  ZoneMaterial rock;
  rock.set_young_poisson(1e10, 0.25);
  const unsigned int ng = mesh.n_gridpoints(), nz = mesh.n_zones(), n = 3 * ng;
  std::vector<double> mass(ng, 0.0), stiff(ng, 0.0);
  for (unsigned int z = 0; z < nz; ++z)
  {
    double m[10], k[10];
    tet10_mass_and_stiffness(mesh, z, rock.density, rock.bulk_modulus, rock.shear_modulus, m, k);
    for (int a = 0; a < 10; ++a)
    {
      const unsigned int g = a < 4 ? mesh.zone_gridpoint[z][a] : mesh.zone_edge_gridpoint[z][a - 4];
      mass[g] += m[a];
      stiff[g] += k[a];
    }
  }
  Eigen::MatrixXd K(n, n);
  const double dt = 1e-8;
  Tet10Scratch s;
  s.resize(nz);
  for (unsigned int j = 0; j < n; ++j)
  {
    std::vector<double> v(n, 0.0), f(n, 0.0), stress(24 * nz, 0.0);
    v[j] = 1.0;
    tet10_strain_increments(mesh, 0, nz, mesh.position.data(), v.data(), dt, stress.data(), s);
    StressBatch b;
    b.size = 4 * nz;
    b.strain_increment = s.strain_increment.data();
    b.stress = stress.data();
    apply_zone_model(rock, b);
    tet10_nodal_forces(mesh, 0, nz, stress.data(), s, f.data());
    for (unsigned int i = 0; i < n; ++i)
      K(i, j) = -f[i] / dt;
  }
  std::fprintf(stderr, "asymmetry %g\n", (K - K.transpose()).norm() / K.norm());
  std::printf("kernel stiffness symmetric: %s\n",
              (K - K.transpose()).norm() / K.norm() < 1e-6 ? "to 1e-6 (the finite step)" : "NO");
  double worst = 0.0;
  Eigen::VectorXd msq(n);
  for (unsigned int i = 0; i < n; ++i)
  {
    double row = 0.0;
    for (unsigned int j = 0; j < n; ++j)
      row += std::abs(K(i, j));
    worst = std::max(worst, row / stiff[i / 3]);
    msq[i] = 1.0 / std::sqrt(stiff[i / 3] / 4.0); // density-scaled mass, dt = 1
  }
  std::printf("largest kernel row sum over its node's bound: %.6f (at most 1)\n", worst);
  Eigen::MatrixXd A = msq.asDiagonal() * (0.5 * (K + K.transpose())) * msq.asDiagonal();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(A);
  std::printf("largest eigenvalue of M^-1 K times dt^2 / 4 with density-scaled masses: %.4f "
              "(at most 1)\n",
              es.eigenvalues().maxCoeff() / 4.0);
  for (unsigned int i = 0; i < n; ++i)
    msq[i] = 1.0 / std::sqrt(mass[i / 3]);
  Eigen::MatrixXd B = msq.asDiagonal() * (0.5 * (K + K.transpose())) * msq.asDiagonal();
  es.compute(B);
  double dtmin = 1e300;
  for (unsigned int g = 0; g < ng; ++g)
    dtmin = std::min(dtmin, 2 * std::sqrt(mass[g] / stiff[g]));
  std::printf("true masses: critical step 2 / omega_max %.4g s, step of the bound %.4g s (ratio "
              "%.4f, at most 1)\n",
              2 / std::sqrt(es.eigenvalues().maxCoeff()), dtmin,
              dtmin / (2 / std::sqrt(es.eigenvalues().maxCoeff())));
}
