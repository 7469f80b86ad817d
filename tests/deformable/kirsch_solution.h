#pragma once

// Kirsch's solution for a circular hole of radius a in a plane-strain
// plate under far-field stresses Sx = -K p, Sy = -p, and the measures the
// Kirsch tests take of a zone solution against it (wall displacement, hoop
// stress of the zones near the axes, a least-squares fit to the wall).
// Shared by kirsch_01 (structured mesh) and kirsch_02 (the mesher's).

#include <talus/solver/deformable_solver.h>
#include <talus/zone/implicit_elastic.h>
#include <talus/zone/tet_mesh.h>
#include <talus/zone/zone_material.h>

#include <Eigen/Dense>

#include <cmath>
#include <memory>
#include <vector>

using namespace talus;

namespace
{
const double a = 1.0, p = 1e5, K = 0.5, E = 1e10, nu = 0.25;
const double G = E / (2.0 * (1.0 + nu));
const double Sx = -K * p, Sy = -p, Sz = nu * (Sx + Sy); // far field, Pa, tension positive
const double eps = 1e-9, big = 1e3;
double L = 40.0;      // m, half-width of the outer square
double target = 1e-6; // unbalanced-force ratio of the static runs

/// Kirsch's stresses at (r, theta): radial, hoop, shear (Pa).
void kirsch(double r, double theta, double& srr, double& stt, double& srt)
{
  const double m = 0.5 * (Sx + Sy), d = 0.5 * (Sx - Sy), rho = a * a / (r * r);
  srr = m * (1.0 - rho) + d * (1.0 - 4.0 * rho + 3.0 * rho * rho) * std::cos(2.0 * theta);
  stt = m * (1.0 + rho) - d * (1.0 + 3.0 * rho * rho) * std::cos(2.0 * theta);
  srt = -d * (1.0 + 2.0 * rho - 3.0 * rho * rho) * std::sin(2.0 * theta);
}

double kirsch_wall_ur(double theta)
{
  return -(p * a / (4.0 * G)) * ((1.0 + K) - (1.0 - K) * (3.0 - 4.0 * nu) * std::cos(2.0 * theta));
}

Vec3 point(const TetMesh& m, unsigned int g)
{
  return Vec3(m.position[3 * g], m.position[3 * g + 1], m.position[3 * g + 2]);
}

/// Zone stresses (6 per zone) of a displacement field in small strain:
/// the far-field stress plus eq. 59 applied to the zone's constant strain.
std::vector<double> small_strain_stress(const TetMesh& m, const std::vector<double>& u,
                                        const ZoneMaterial& rock)
{
  std::vector<double> stress(6 * m.n_zones());
  const double lambda = rock.bulk_modulus - 2.0 * rock.shear_modulus / 3.0;
  for (unsigned int z = 0; z < m.n_zones(); ++z)
  {
    const auto& t = m.zone_gridpoint[z];
    Eigen::Matrix3d edges, du;
    for (int k = 0; k < 3; ++k)
    {
      edges.col(k) = point(m, t[k + 1]) - point(m, t[0]);
      for (int d = 0; d < 3; ++d)
        du(d, k) = u[3 * t[k + 1] + d] - u[3 * t[0] + d];
    }
    const Eigen::Matrix3d grad = du * edges.inverse(); // du_i/dx_j
    const Eigen::Matrix3d e = 0.5 * (grad + grad.transpose());
    const Eigen::Matrix3d s =
        lambda * e.trace() * Eigen::Matrix3d::Identity() + 2.0 * rock.shear_modulus * e;
    double* out = &stress[6 * z];
    out[0] = Sx + s(0, 0);
    out[1] = Sy + s(1, 1);
    out[2] = Sz + s(2, 2);
    out[3] = s(0, 1);
    out[4] = s(1, 2);
    out[5] = s(2, 0);
  }
  return stress;
}

/// Mean radial displacement of the wall gridpoints on the x axis (theta =
/// 0) or on the y axis (theta = 90 degrees): u_x or u_y there.
double wall_ur(const TetMesh& m, const std::vector<double>& u, bool y_axis)
{
  double sum = 0.0;
  unsigned int n = 0;
  for (unsigned int g = 0; g < m.n_gridpoints(); ++g)
  {
    const Vec3 x = point(m, g);
    if (std::abs(x[y_axis ? 1 : 0] - a) < eps && std::abs(x[y_axis ? 0 : 1]) < eps)
    {
      sum += u[3 * g + (y_axis ? 1 : 0)];
      ++n;
    }
  }
  return sum / n;
}

struct ZoneHoop
{
  double r, angle_from_axis, computed, kirsch;
};

/// Mean hoop stress, computed and Kirsch's, of the points of the first
/// ring (r below a ring_ratio) and the first sector (dtheta) next to the
/// axis; n is their number.
struct WallMean
{
  double computed = 0.0, kirsch = 0.0;
  unsigned int n = 0;
};
inline WallMean wall_mean(const std::vector<ZoneHoop>& zones, double ring_ratio, double dtheta)
{
  WallMean m;
  for (const ZoneHoop& z : zones)
    if (z.r < a * ring_ratio && z.angle_from_axis < dtheta)
    {
      m.computed += z.computed;
      m.kirsch += z.kirsch;
      ++m.n;
    }
  m.computed /= m.n;
  m.kirsch /= m.n;
  return m;
}

/// Hoop stress of the stress points (at `where`, their stresses 6 each
/// in `stress`) that lie within `rings` rings of the wall and `sectors`
/// sectors of the x axis (or the y axis).
std::vector<ZoneHoop> hoop_near_axis(const std::vector<Vec3>& where,
                                     const std::vector<double>& stress, double ring_ratio,
                                     double dtheta, int rings, int sectors, bool y_axis)
{
  std::vector<ZoneHoop> out;
  for (std::size_t z = 0; z < where.size(); ++z)
  {
    const Vec3& c = where[z];
    const double r = std::hypot(c[0], c[1]), theta = std::atan2(c[1], c[0]);
    const double from_axis = y_axis ? 0.5 * M_PI - theta : theta;
    if (r > a * std::pow(ring_ratio, rings) || from_axis > sectors * dtheta)
      continue;
    const double* s = &stress[6 * z];
    const double cs = std::cos(theta), sn = std::sin(theta);
    const double stt = s[0] * sn * sn + s[1] * cs * cs - 2.0 * s[3] * sn * cs;
    double srr, kstt, srt;
    kirsch(r, theta, srr, kstt, srt);
    out.push_back({r, from_axis, stt, kstt});
  }
  return out;
}

/// The centroids of the zones (of their four corners).
std::vector<Vec3> zone_centroids(const TetMesh& m)
{
  std::vector<Vec3> out(m.n_zones());
  for (unsigned int z = 0; z < m.n_zones(); ++z)
  {
    Vec3 c = Vec3::Zero();
    for (unsigned int g : m.zone_gridpoint[z])
      c += 0.25 * point(m, g);
    out[z] = c;
  }
  return out;
}

/// Hoop stress of the zones (one stress each) whose centroid lies within
/// `rings` rings of the wall and `sectors` sectors of the x axis (or the y
/// axis).
std::vector<ZoneHoop> hoop_near_axis(const TetMesh& m, const std::vector<double>& stress,
                                     double ring_ratio, double dtheta, int rings, int sectors,
                                     bool y_axis)
{
  return hoop_near_axis(zone_centroids(m), stress, ring_ratio, dtheta, rings, sectors, y_axis);
}

/// Wall value of a least-squares fit to the zone values (from `computed`,
/// or from Kirsch at the same centroids: the bias of the fit itself) of
///   s = c0 + c1 q + c2 q^2 + phi^2 (c3 + c4 q),  q = a^2/r^2 - 1,
/// phi the angle from the axis: along an axis an elastic perturbation of
/// the far field around a circular hole is a polynomial in a^2/r^2 (of
/// degree two for Kirsch), and the hoop stress is even in phi by symmetry.
double wall_fit(const std::vector<ZoneHoop>& zones, bool use_kirsch)
{
  Eigen::MatrixXd A(zones.size(), 5);
  Eigen::VectorXd b(zones.size());
  for (std::size_t k = 0; k < zones.size(); ++k)
  {
    const double q = a * a / (zones[k].r * zones[k].r) - 1.0,
                 phi2 = std::pow(zones[k].angle_from_axis, 2);
    A.row(k) << 1.0, q, q * q, phi2, phi2 * q;
    b[k] = use_kirsch ? zones[k].kirsch : zones[k].computed;
  }
  return A.colPivHouseholderQr().solve(b)[0];
}
/// The explicit static solver of the Kirsch problem on `mesh`, zones of
/// `rock`: no gravity, adaptive global damping, every zone at the far-field
/// stress, the far-field tractions on the outer square (K p on x = L, p on
/// y = L), and the boundary conditions `rollers`.
inline std::unique_ptr<DeformableSolver> kirsch_solver(const TetMesh& mesh, const ZoneMaterial& rock,
                                                       std::vector<GridpointCondition> rollers)
{
  SolverSettings settings;
  settings.gravity = Vec3::Zero();
  settings.damping = Damping::adaptive_global;
  const FacePressure right{Box{Vec3(L - eps, -big, -big), Vec3(L + eps, big, big)}, K * p};
  const FacePressure top{Box{Vec3(-big, L - eps, -big), Vec3(big, L + eps, big)}, p};
  InitialStress initial;
  initial.base[0] = Sx;
  initial.base[1] = Sy;
  initial.base[2] = Sz;
  return std::make_unique<DeformableSolver>(mesh, std::vector<ZoneMaterial>{rock},
                                            std::vector<unsigned int>(mesh.n_zones(), 0),
                                            settings, std::move(rollers),
                                            std::vector<FacePressure>{right, top}, &initial);
}

} // namespace

/// The implicit reference on a mesh of the slab (thickness t): loads are
/// the unbalanced nodal forces of the initial stress state (f_n = sigma0
/// A_n / 3 for each zone, A_n the outward area normal of the face opposite
/// node n), which cancel inside and on the loaded square sides except for
/// the outer tractions added here, leaving the excavation loads on the
/// hole; rollers on the symmetry planes and both faces of the slab.
inline ImplicitElasticProblem kirsch_implicit_problem(const TetMesh& mesh, const ZoneMaterial& rock,
                                                      double t)
{
  ImplicitElasticProblem problem;
  problem.mesh = &mesh;
  problem.zone_bulk.assign(mesh.n_zones(), rock.bulk_modulus);
  problem.zone_shear.assign(mesh.n_zones(), rock.shear_modulus);
  problem.fixed.assign(mesh.n_gridpoints(), 0);
  problem.nodal_force.assign(3 * mesh.n_gridpoints(), 0.0);
  problem.tolerance = 1e-12;
  for (unsigned int g = 0; g < mesh.n_gridpoints(); ++g)
  {
    const Vec3 x = point(mesh, g);
    problem.fixed[g] = (std::abs(x[0]) < eps ? 1 : 0) | (std::abs(x[1]) < eps ? 2 : 0) |
                       (std::abs(x[2]) < eps || std::abs(x[2] - t) < eps ? 4 : 0);
  }
  static const int opposite[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  for (const auto& z : mesh.zone_gridpoint)
    for (int n = 0; n < 4; ++n)
    {
      const Vec3 p0 = point(mesh, z[opposite[n][0]]);
      Vec3 area =
          0.5 * (point(mesh, z[opposite[n][1]]) - p0).cross(point(mesh, z[opposite[n][2]]) - p0);
      if (area.dot(p0 - point(mesh, z[n])) < 0.0)
        area = -area;
      const Vec3 f = Vec3(Sx * area[0], Sy * area[1], Sz * area[2]) / 3.0;
      for (int d = 0; d < 3; ++d)
        problem.nodal_force[3 * z[n] + d] += f[d];
    }
  for (const auto& face : mesh.face_gridpoint)
  {
    const Vec3 p0 = point(mesh, face[0]);
    const Vec3 c = (p0 + point(mesh, face[1]) + point(mesh, face[2])) / 3.0;
    const double pressure = std::abs(c[0] - L) < eps ? K * p : std::abs(c[1] - L) < eps ? p : 0.0;
    const Vec3 area = 0.5 * (point(mesh, face[1]) - p0).cross(point(mesh, face[2]) - p0);
    for (unsigned int g : face)
      for (int d = 0; d < 3; ++d)
        problem.nodal_force[3 * g + d] -= pressure * area[d] / 3.0;
  }
  return problem;
}
