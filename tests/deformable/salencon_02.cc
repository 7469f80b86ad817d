// Verification: a cylindrical hole (radius a = 1 m) in a Mohr-Coulomb medium
// under a hydrostatic far field p0 = 0.1 MPa (compression), hole unloaded
// (p_i = 0), plane strain, against Salencon (1969). Rock: E = 20 GPa,
// nu = 0.4, c = 17 kPa, phi = 20 degrees, psi = 0, no tension cut-off below
// the apex of the shear surface.
//
// Closed form, compression positive, K_p = (1 + sin phi)/(1 - sin phi),
// C = c cot(phi) (so 2c sqrt(K_p) = (K_p - 1) C). In the plastic ring the
// hoop stress is the major and the radial the minor principal stress,
// sigma_t = K_p sigma_r + 2c sqrt(K_p), and equilibrium
// d sigma_r/dr = (sigma_t - sigma_r)/r = (K_p - 1)(sigma_r + C)/r gives
//   sigma_r = (p_i + C)(r/a)^(K_p - 1) - C.
// Outside R_p the elastic field is sigma_r,t = p0 -/+ (p0 - sigma_re)(R_p/r)^2,
// so sigma_r + sigma_t = 2 p0 and yield at R_p gives
// sigma_re = (2 p0 - 2c sqrt(K_p))/(K_p + 1); equal sigma_r on both sides,
// with (K_p + 1)C - 2c sqrt(K_p) = 2C:
//   R_p = a [ (2/(K_p + 1)) (p0 + C)/(p_i + C) ]^(1/(K_p - 1)).
// Here K_p = 2.040, C = 46.7 kPa, R_p = 2.010 a (psi changes only the
// displacements). The solution needs the out-of-plane stress to stay
// intermediate; then the plastic flow has no z component and u_z = 0 gives
// sigma_z = p0 - nu (2 p0 - sigma_r - sigma_t), between sigma_r and
// sigma_t at the wall when p0 (1 - 2nu) <= (1 - nu) 2c sqrt(K_p); hence
// nu = 0.4 (at nu = 0.25 sigma_z would be the major stress at the wall).
// The test checks this too. The code's stresses are tension positive, the
// printed ones too (closed form negated).
//
// Model: salencon_01's (see salencon_01.cc for the outer radius, the local
// damping and what is checked; the checks and tolerances here are its
// own), with the quarter slab meshed the way blocks are: one
// closed polyhedral body (tests/deformable/hole_body.h) through gmsh
// (zone/convex_block_mesher.h), the hole a polygon of 24 facets in the
// quarter inscribed in the circle, the outer circle one of 32 facets
// (R = 20 a), zones of edge h0 = 0.08 a at the wall growing as h0 r / a up
// to 2 a, the slab 0.25 a thick (u_z held on both faces; plane strain needs
// no resolution across it, so it is thin and the far zones flat). The
// flagged plastic radius counts the hole's polygon area. The rings are
// salencon_01's (12 sectors: 24 rings spaced geometrically), each the
// zones whose centroid falls in it. Zones with nodal mixed discretization
// (eqs. 68-76): with plain 4-node zones an unstructured mesh locks in the
// plastic ring, whose flow keeps the volume (psi = 0): on this mesh
// (argument 5 = 0) 11 of the 13 checks fail, the wall ring's hoop stress
// 5.7 % of p0 off, the rings' radial stress 1.5-2.9 %, the fitted R_p
// 2.1 % short; at h0 = 0.05 a (17,500 zones) still 3.5 % and 4.9 %
// (salencon_01's structured 24-tetrahedra hexahedra do not lock). With
// plain zones sigma_z also leaves the intermediate place in some yielded
// zones; with nodal mixed ones a few (2 to 4 of 2,400) do too, so that
// check is on 99 % of them.
//
// Against salencon_01 (6,912 zones, about 45 s on the loaded machine):
// 6,900 zones, 25,400 steps, about 25 s; errors (salencon_01's in
// brackets): R_p fitted 0.1 % (0.75 %), flagged 0.26 % (0.06 %); ring
// means, over p0, sigma_r 0.8 / 0.26 / 0.38 / 0.32 / 0.44 % (0.4 / 0.5 /
// 0.8 / 1.0 / 0.8 %), sigma_t 1.6 / 0.47 / 0.72 / 0.59 / 0.58 % (0.7 /
// 0.9 / 1.5 / 1.8 / 0.2 %) for the rings at 1, 1.25, 1.5, 1.75 and 3 a.
// The mesher gives the same mesh every time (gmsh's Delaunay volume
// mesher); the output holds verdicts only, as the last digits of a plastic
// path follow the CPU's rounding.
//
// Arguments for a study: h0 / a, facets, thickness / a, h_max / a, zones
// (0 plain, 1 nodal mixed, 2 10-node: then each Gauss point is a stress
// point at its own place, with a quarter of its zone's volume), target
// ratio, damping (0 local, 1 combined, 2 adaptive global). 10-node zones
// do not reach Salencon here: the sudden excavation yields too much
// (points in the ring unload off the yield surface), the flagged R_p
// 8-9 % long and the ring hoop stresses 3.5-15 % of p0 low, at h0 =
// 0.16 a (2,200 zones, 4,300 steps) and at 0.08 a alike, and the same at
// ratio 1e-7; on salencon_01's structured mesh 4 % and up to 8 % (nodal
// mixed zones there: 0.07 % and below 0.9 %). The answer depends on the
// path: with adaptive global damping nodal mixed zones overshoot too
// (R_p 21 % long at h0 = 0.16 a).

#include <talus/base/parallel_environment.h>
#include <talus/solver/deformable_solver.h>
#include <talus/zone/block_mesher.h>
#include <talus/zone/tet10_kernel.h>
#include <talus/zone/tet10_mesh.h>

#include <Eigen/Dense>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "../tests.h"
#include "salencon_solution.h"
#include "hole_body.h"
#include "hole_mesh.h"

using namespace talus;


int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  const Salencon closed;
  std::printf("closed form: K_p %.6g, C %.6g Pa, R_p %.6g m (with the outer radius %g m: %.6g m)\n",
              closed.Kp, closed.C, closed.Rp, R, closed.finite_Rp());

  // The analysis rings of salencon_01 (12 sectors: rings as deep as the
  // sectors are wide, geometrically out to R), so that both tests average
  // over the same regions.
  const double dtheta = 0.5 * M_PI / 12;
  const unsigned int n_r =
      static_cast<unsigned int>(std::lround(std::log(R / a) / std::log(1.0 + dtheta)));
  const double ring_ratio = std::pow(R / a, 1.0 / n_r);
  HoleBody hole;
  hole.a = a;
  hole.R = R;
  hole.h0 = (argc > 1 ? std::atof(argv[1]) : 0.08) * a;
  hole.n_facets = argc > 2 ? std::atoi(argv[2]) : 24;
  hole.n_outer = 32;
  hole.thickness = (argc > 3 ? std::atof(argv[3]) : 0.25) * a;
  hole.h_max = (argc > 4 ? std::atof(argv[4]) : 2.0) * a;
  // Zones: 0 plain, 1 nodal mixed, 2 10-node (4 Gauss points each).
  const int zones = argc > 5 ? std::atoi(argv[5]) : 1;
  const bool nodal_mixed = zones == 1, quadratic = zones == 2;
  const double t = hole.thickness;
  const auto start = std::chrono::steady_clock::now();
  TetMesh mesh = hole.build();
  const MeshReport report = measure_mesh(mesh);
  if (quadratic)
    make_quadratic(mesh);
  std::printf("%u facets, h0 %.2g a, thickness %.2g a: about %s zones\n", hole.n_facets,
              hole.h0 / a, t / a, one_digit(report.zones).c_str());
  std::fprintf(stderr, "%u zones, %u gridpoints, smallest height %.3g m, meshed in %.2f s\n",
               report.zones, report.gridpoints, report.smallest_height,
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());

  ZoneMaterial rock;
  rock.model = ZoneModel::mohr_coulomb;
  rock.set_young_poisson(E, nu);
  rock.friction_angle = phi * 180.0 / M_PI;
  rock.dilation_angle = 0.0;
  rock.cohesion = c;
  rock.tensile_strength = 1e30; // capped at the apex, c cot(phi)
  rock.nodal_mixed = nodal_mixed;
  if (quadratic)
    rock.element = ZoneElement::tet10;
  SolverSettings settings;
  settings.gravity = Vec3::Zero();
  settings.damping = argc > 7 ? Damping(std::atoi(argv[7])) : Damping::local;
  // The outer circle's faces only: beyond 2a, off the symmetry planes and
  // the z faces.
  const FacePressure outer_x{Box{Vec3(2.0 * a, eps, eps), Vec3(big, big, t - eps)}, p0};
  const FacePressure outer_y{Box{Vec3(eps, 2.0 * a, eps), Vec3(big, big, t - eps)}, p0};
  InitialStress initial;
  initial.base[0] = initial.base[1] = initial.base[2] = -p0;
  DeformableSolver solver(mesh, {rock}, std::vector<unsigned int>(mesh.n_zones(), 0), settings,
                          plane_strain_rollers(t, eps, big), {outer_x, outer_y}, &initial);
  const double target = argc > 6 ? std::atof(argv[6]) : 1e-5;
  const unsigned long steps = solver.run_to_ratio(target, 200000);
  std::printf("static run: %s\n",
              solver.unbalanced_ratio() < target ? "reached ratio 1e-5" : "NOT converged");
  std::fprintf(stderr, "static run: %lu steps, %.1f s\n", steps,
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());

  // Per stress point (the zone's centroid for a 4-node zone, each Gauss
  // point of a 10-node zone, with a quarter of its volume): radius, ring,
  // stresses in polar axes, the yield function f = (s1 - K_p s3 + 2c
  // sqrt(K_p)) / p0 (s1 <= s2 <= s3 the principal stresses; 0 on the shear
  // surface, > 0 inside).
  const unsigned int per_zone = solver.stress_points_per_zone();
  const unsigned int nz = mesh.n_zones() * per_zone;
  std::vector<double> radius(nz), s_r(nz), s_t(nz), f(nz);
  std::vector<unsigned int> ring(nz);
  double plastic_volume = 0.0;
  unsigned int n_plastic = 0, n_intermediate = 0;
  for (unsigned int z = 0; z < nz; ++z)
  {
    const auto& g = mesh.zone_gridpoint[z / per_zone];
    Vec3 centre = Vec3::Zero();
    if (quadratic)
    {
      double x[4][3];
      tet10_gauss_points(mesh, z / per_zone, x);
      centre = Vec3(x[z % 4][0], x[z % 4][1], x[z % 4][2]);
    }
    else
      for (unsigned int k : g)
        centre += 0.25 * point(mesh, k);
    radius[z] = centre.head<2>().norm();
    ring[z] = std::min<unsigned int>(n_r - 1,
                                     std::max(0.0, std::log(radius[z] / a) / std::log(ring_ratio)));
    const double theta = std::atan2(centre[1], centre[0]), cs = std::cos(theta),
                 sn = std::sin(theta);
    const double* s = &solver.stress()[6 * z];
    s_r[z] = s[0] * cs * cs + s[1] * sn * sn + 2.0 * s[3] * sn * cs;
    s_t[z] = s[0] * sn * sn + s[1] * cs * cs - 2.0 * s[3] * sn * cs;
    Eigen::Matrix3d tensor;
    tensor << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
    const Eigen::Vector3d principal =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(tensor).eigenvalues();
    f[z] = (principal[0] - closed.Kp * principal[2] + 2.0 * c * std::sqrt(closed.Kp)) / p0;
    if (solver.plastic_state()[z] & shear_past)
    {
      const Vec3 p = point(mesh, g[0]);
      plastic_volume +=
          (point(mesh, g[1]) - p).dot((point(mesh, g[2]) - p).cross(point(mesh, g[3]) - p)) /
          (6.0 * per_zone);
      ++n_plastic;
      n_intermediate += s_t[z] <= s[2] && s[2] <= s_r[z];
    }
  }
  std::fprintf(stderr, "zones that yielded in shear: %u, sigma_z intermediate in %u\n", n_plastic,
               n_intermediate);
  std::printf("zones that yielded in shear: sigma_z between sigma_t and sigma_r in at least 99 %% "
              "of them: %s\n",
              talus_test::verdict(n_intermediate >= 0.99 * n_plastic));

  // Plastic radius 1: the yielded zones' area as a ring a < r < R_f.
  const double r_flag =
      std::sqrt(4.0 * (hole.hole_area() + plastic_volume / t) / M_PI); // the hole a polygon
  talus_test::check_within("plastic radius, area of the zones flagged shear_past (m)", r_flag,
                           closed.Rp, 0.02);
  // Plastic radius 2: where the yield function of the elastic zones (f
  // above 1e-3, out to twice the flagged radius) reaches zero; there
  // f = alpha + beta / r^2 exactly, so fit that.
  {
    std::vector<double> rows_x, rows_f;
    for (unsigned int z = 0; z < nz; ++z)
      if (f[z] > 1e-3 && radius[z] < 2.0 * r_flag)
      {
        rows_x.push_back(1.0 / (radius[z] * radius[z]));
        rows_f.push_back(f[z]);
      }
    Eigen::MatrixXd A(rows_x.size(), 2);
    Eigen::VectorXd b(rows_x.size());
    for (std::size_t k = 0; k < rows_x.size(); ++k)
    {
      A.row(k) << 1.0, rows_x[k];
      b[k] = rows_f[k];
    }
    const Eigen::Vector2d fit = A.colPivHouseholderQr().solve(b);
    std::fprintf(stderr, "%zu elastic zones in the fit\n", rows_x.size());
    talus_test::check_within("plastic radius, root of the yield function fitted over the "
                             "elastic zones within 2 R_f (m)",
                             std::sqrt(-fit[1] / fit[0]), closed.Rp, 0.015);
  }

  // Ring means of the stresses against the closed form at the same
  // centroids: the ring at the wall, rings near 1.25, 1.5 and 1.75 a in the
  // plastic zone, and near 3 a in the elastic zone.
  for (const double r_wanted : {1.0, 1.25, 1.5, 1.75, 3.0})
  {
    const unsigned int k =
        std::min<unsigned int>(n_r - 1, std::log(r_wanted / a) / std::log(ring_ratio));
    double computed_r = 0.0, computed_t = 0.0, exact_r = 0.0, exact_t = 0.0;
    unsigned int n = 0;
    for (unsigned int z = 0; z < nz; ++z)
      if (ring[z] == k)
      {
        double er, et;
        closed.stress(radius[z], er, et);
        computed_r += s_r[z];
        computed_t += s_t[z];
        exact_r += er;
        exact_t += et;
        ++n;
      }
    char name[120];
    std::snprintf(name, sizeof name, "ring %.3f-%.3f m (%s), mean", a * std::pow(ring_ratio, k),
                  a * std::pow(ring_ratio, k + 1), r_wanted < 2.0 ? "plastic" : "elastic");
    check_over_p0(std::string(name) + " sigma_r (Pa)", computed_r / n, exact_r / n, 0.013);
    check_over_p0(std::string(name) + " sigma_t (Pa)", computed_t / n, exact_t / n, 0.024);
  }
}
