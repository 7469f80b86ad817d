// Verification of the zone models (apply_zone_model) on single zones, SI
// units, tension positive, against closed forms:
// - elasticity (eq. 59): uniaxial strain and pure shear;
// - Mohr-Coulomb: single-plane shear return (on the surface, intermediate
//   principal stress, principal directions, flow direction for psi = 0 and
//   psi = phi, plastic volume change), a plastic flow path with psi > 0,
//   the edge s1 = s2, the tension cut-off (one and two principal stresses,
//   the cap at c / tan(phi)), the shear-tension corner from both sides;
// - a drained triaxial test (confining -p, axial strain in small steps) up
//   to and along the peak s1 = -p N_phi - 2c sqrt(N_phi), with its
//   dilatancy; the state flags along the way;
// - random trial stresses: every returned stress admissible and stable.

#include <talus/zone/zone_models.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "../tests.h"

using talus::StressBatch;
using talus::ZoneMaterial;
using talus::ZoneModel;

namespace
{

const double deg = M_PI / 180.0;

/// One zone: stress and strain increment (xx, yy, zz, xy, yz, zx; tensor
/// shear components), flags and plastic volume change.
struct Zone
{
  double stress[6] = {0, 0, 0, 0, 0, 0};
  double strain_increment[6] = {0, 0, 0, 0, 0, 0};
  unsigned char state = 0;
  double plastic_volumetric = -1.0; // the model must overwrite it
};

void step(const ZoneMaterial& material, Zone& zone)
{
  StressBatch batch;
  batch.size = 1;
  batch.strain_increment = zone.strain_increment;
  batch.stress = zone.stress;
  batch.state = &zone.state;
  batch.plastic_volumetric = &zone.plastic_volumetric;
  talus::apply_zone_model(material, batch);
}

Eigen::Matrix3d to_matrix(const double* t)
{
  Eigen::Matrix3d m;
  m << t[0], t[3], t[5], t[3], t[1], t[4], t[5], t[4], t[2];
  return m;
}

void from_matrix(const Eigen::Matrix3d& m, double* t)
{
  t[0] = m(0, 0);
  t[1] = m(1, 1);
  t[2] = m(2, 2);
  t[3] = m(0, 1);
  t[4] = m(1, 2);
  t[5] = m(2, 0);
}

/// A rotation that puts the principal axes well off the coordinate axes.
Eigen::Matrix3d rotation()
{
  return (Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(-0.4, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(1.1, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

/// Tensor R diag(p) R^T.
void rotated(const double* principal, double* t)
{
  const Eigen::Matrix3d r = rotation();
  from_matrix(r * Eigen::Vector3d(principal[0], principal[1], principal[2]).asDiagonal() *
                  r.transpose(),
              t);
}

struct Principal
{
  Eigen::Vector3d values; // ascending: s1 <= s2 <= s3
  Eigen::Matrix3d axes;   // columns
};

Principal principal(const double* t)
{
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> e(to_matrix(t));
  return {e.eigenvalues(), e.eigenvectors()};
}

struct MohrCoulomb
{
  ZoneMaterial material;
  double alpha1, alpha2, n_phi, n_psi, k_shear, sigma_t;

  MohrCoulomb(double psi_degrees, double tensile_strength = 0.5e6)
  {
    material.model = ZoneModel::mohr_coulomb;
    material.bulk_modulus = 2e9;
    material.shear_modulus = 1e9;
    material.cohesion = 1e6;
    material.friction_angle = 30.0;
    material.dilation_angle = psi_degrees;
    material.tensile_strength = tensile_strength;
    const double k = material.bulk_modulus, g = material.shear_modulus;
    alpha1 = k + 4.0 * g / 3.0;
    alpha2 = k - 2.0 * g / 3.0;
    const double sp = std::sin(30.0 * deg), ss = std::sin(psi_degrees * deg);
    n_phi = (1 + sp) / (1 - sp);
    n_psi = (1 + ss) / (1 - ss);
    k_shear = 2.0 * material.cohesion * std::sqrt(n_phi);
    sigma_t = std::min(tensile_strength, material.cohesion / std::tan(30.0 * deg));
  }
  double f_shear(const Eigen::Vector3d& s) const { return s[0] - n_phi * s[2] + k_shear; }
  /// Plastic strain increment de - C (stress - stress_before).
  Eigen::Matrix3d plastic_strain(const double* before, const Zone& z) const
  {
    const Eigen::Matrix3d ds = to_matrix(z.stress) - to_matrix(before);
    const double mean = ds.trace() / 3.0;
    const Eigen::Matrix3d elastic =
        (ds - mean * Eigen::Matrix3d::Identity()) / (2.0 * material.shear_modulus) +
        mean / (3.0 * material.bulk_modulus) * Eigen::Matrix3d::Identity();
    return to_matrix(z.strain_increment) - elastic;
  }
};

/// Cosine of the angle between two tensors (Frobenius product).
double cosine(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b)
{
  return (a.array() * b.array()).sum() / (a.norm() * b.norm());
}

/// Largest |cosine| mismatch of the principal directions of a and b.
double direction_mismatch(const Principal& a, const Principal& b)
{
  double worst = 0.0;
  for (int i = 0; i < 3; ++i)
    worst = std::max(worst, 1.0 - std::abs(a.axes.col(i).dot(b.axes.col(i))));
  return worst;
}

void elastic_checks()
{
  ZoneMaterial m;
  m.bulk_modulus = 2e9;
  m.shear_modulus = 1e9;
  const double k = m.bulk_modulus, g = m.shear_modulus, e = 1e-4;
  Zone z;
  z.strain_increment[0] = e;
  step(m, z);
  std::printf("elastic, uniaxial strain e = 1e-4:\n");
  talus_test::check("  sigma_xx = (K + 4G/3) e (Pa)", z.stress[0], (k + 4 * g / 3) * e, 1e-14);
  talus_test::check("  sigma_yy = (K - 2G/3) e (Pa)", z.stress[1], (k - 2 * g / 3) * e, 1e-14);
  talus_test::check("  sigma_zz = (K - 2G/3) e (Pa)", z.stress[2], (k - 2 * g / 3) * e, 1e-14);
  Zone shear;
  shear.stress[0] = -3e6; // an initial stress stays: the law is incremental
  shear.strain_increment[3] = e;
  step(m, shear);
  std::printf("elastic, pure shear e_xy = 1e-4 from sigma_xx = -3 MPa:\n");
  talus_test::check("  sigma_xy = 2G e (Pa)", shear.stress[3], 2 * g * e, 1e-14);
  talus_test::check("  sigma_xx unchanged (Pa)", shear.stress[0], -3e6, 1e-14);
  talus_test::check("  sigma_yy + sigma_zz (Pa)", shear.stress[1] + shear.stress[2], 0.0, 1e-14);

  // Mohr-Coulomb inside its surface is the same elastic law.
  MohrCoulomb mc(0.0);
  Zone a, b;
  const double p0[3] = {-8e6, -6e6, -5e6};
  rotated(p0, a.stress);
  rotated(p0, b.stress);
  const double de[6] = {-1e-4, 2e-5, 3e-5, 4e-5, -2e-5, 1e-5};
  std::copy(de, de + 6, a.strain_increment);
  std::copy(de, de + 6, b.strain_increment);
  step(m, a);
  step(mc.material, b);
  double difference = 0.0;
  for (int c = 0; c < 6; ++c)
    difference = std::max(difference, std::abs(a.stress[c] - b.stress[c]) / 8e6);
  std::printf("Mohr-Coulomb inside the surface:\n");
  talus_test::check("  stress minus elastic stress / 8 MPa", difference, 0.0, 1e-14);
  talus_test::check("  state flags", b.state, talus::zone_elastic, 0.0);
  talus_test::check("  plastic volume change", b.plastic_volumetric, 0.0, 0.0);
}

/// Trial beyond the main shear plane, s2 well inside: the single-plane
/// return of FLAC3D-type codes in closed form,
///   lambda = f_s / (a1 - a2 N_psi - (a2 - a1 N_psi) N_phi),
///   s1 -= lambda (a1 - a2 N_psi), s2 -= lambda a2 (1 - N_psi),
///   s3 -= lambda (a2 - a1 N_psi).
void shear_checks(double psi)
{
  const MohrCoulomb mc(psi);
  const double trial[3] = {-30e6, -12e6, -5e6};
  Zone z;
  rotated(trial, z.stress);
  double before[6];
  std::copy(z.stress, z.stress + 6, before);
  step(mc.material, z);
  const Principal t = principal(before), r = principal(z.stress);
  const double a1 = mc.alpha1, a2 = mc.alpha2, nf = mc.n_phi, ns = mc.n_psi;
  const double lambda = mc.f_shear(t.values) / (a1 - a2 * ns - (a2 - a1 * ns) * nf);
  std::printf("shear return, psi = %g deg, trial (-30, -12, -5) MPa:\n", psi);
  talus_test::check("  f_s / c after return", mc.f_shear(r.values) / 1e6, 0.0, 1e-12);
  talus_test::check("  s1 (Pa)", r.values[0], t.values[0] - lambda * (a1 - a2 * ns), 1e-12);
  talus_test::check("  s2 (Pa)", r.values[1], t.values[1] - lambda * a2 * (1 - ns), 1e-12);
  talus_test::check("  s3 (Pa)", r.values[2], t.values[2] - lambda * (a2 - a1 * ns), 1e-12);
  talus_test::check("  1 - |cos| of principal axes, trial vs returned", direction_mismatch(t, r),
                    0.0, 1e-12);
  // Flow: the plastic strain must be parallel to the gradient of
  // g = s1 - N_psi s3, i.e. to -(v1 v1^T) + N_psi v3 v3^T, and have nothing
  // along the intermediate direction.
  const Eigen::Matrix3d ep = mc.plastic_strain(before, z);
  const Eigen::Vector3d v1 = t.axes.col(0), v2 = t.axes.col(1), v3 = t.axes.col(2);
  const Eigen::Matrix3d potential_gradient = -v1 * v1.transpose() + ns * v3 * v3.transpose();
  talus_test::check("  cosine(plastic strain, potential gradient)", cosine(ep, potential_gradient),
                    1.0, 1e-12);
  if (psi == 30.0)
  {
    const Eigen::Matrix3d yield_normal = -v1 * v1.transpose() + nf * v3 * v3.transpose();
    talus_test::check("  associated: cosine(plastic strain, yield surface normal)",
                      cosine(ep, yield_normal), 1.0, 1e-12);
  }
  talus_test::check("  plastic strain along v2 / |plastic strain|", v2.dot(ep * v2) / ep.norm(),
                    0.0, 1e-12);
  const double volumetric = lambda * (1 - ns); // tr(lambda (1, 0, -N_psi))
  talus_test::check("  plastic volume change (model)", z.plastic_volumetric, volumetric, 1e-12);
  talus_test::check("  plastic volume change (trace of de - C ds)", ep.trace(), volumetric, 1e-9);
  talus_test::check("  state flags = shear_now | shear_past", z.state,
                    talus::shear_now | talus::shear_past, 0.0);
}

/// On the surface, a strain increment mu (-1, 0, N_psi) along the principal
/// axes is purely plastic: the stress stays and the volume grows by
/// mu (N_psi - 1) (dilation).
void plastic_flow_check()
{
  const double psi = 10.0;
  const MohrCoulomb mc(psi);
  const double s3 = -5e6, s1 = mc.n_phi * s3 - mc.k_shear;
  const double on_surface[3] = {s1, -12e6, s3};
  const double mu = 1e-4, flow[3] = {-mu, 0.0, mu * mc.n_psi};
  Zone z;
  rotated(on_surface, z.stress);
  rotated(flow, z.strain_increment);
  double before[6];
  std::copy(z.stress, z.stress + 6, before);
  step(mc.material, z);
  double change = 0.0;
  for (int c = 0; c < 6; ++c)
    change = std::max(change, std::abs(z.stress[c] - before[c]) / std::abs(s1));
  std::printf("plastic flow along (-1, 0, N_psi), psi = 10 deg, on the surface:\n");
  talus_test::check("  stress change / |s1|", change, 0.0, 1e-12);
  talus_test::check("  plastic volume change = mu (N_psi - 1) > 0", z.plastic_volumetric,
                    mu * (mc.n_psi - 1), 1e-10);
}

/// Trial with s2 near s1: a single-plane return would carry s1 above s2,
/// so the stress must end on the edge s1 = s2 of the pyramid.
void edge_check()
{
  const MohrCoulomb mc(0.0);
  const double trial[3] = {-30e6, -29e6, -5e6};
  Zone z;
  rotated(trial, z.stress);
  double before[6];
  std::copy(z.stress, z.stress + 6, before);
  step(mc.material, z);
  const Principal r = principal(z.stress);
  const Eigen::Vector3d s2_as_s1(r.values[1], r.values[1], r.values[2]);
  std::printf("edge return, psi = 0, trial (-30, -29, -5) MPa:\n");
  talus_test::check("  (s2 - s1) / c", (r.values[1] - r.values[0]) / 1e6, 0.0, 1e-12);
  talus_test::check("  f_s(s1, s3) / c", mc.f_shear(r.values) / 1e6, 0.0, 1e-12);
  talus_test::check("  f_s(s2, s3) / c", mc.f_shear(s2_as_s1) / 1e6, 0.0, 1e-12);
  talus_test::check("  plastic volume change (psi = 0)", z.plastic_volumetric, 0.0, 1e-15);
  talus_test::check("  trace of de - C ds", mc.plastic_strain(before, z).trace(), 0.0, 1e-15);
}

void print_principal_check(const MohrCoulomb& mc, const char* what, const double* trial,
                           const double* expected, unsigned char expected_state)
{
  Zone z;
  rotated(trial, z.stress);
  step(mc.material, z);
  const Principal r = principal(z.stress);
  std::printf("%s, trial (%g, %g, %g) MPa:\n", what, trial[0] / 1e6, trial[1] / 1e6,
              trial[2] / 1e6);
  const char* names[3] = {"  s1 (Pa)", "  s2 (Pa)", "  s3 (Pa)"};
  for (int i = 0; i < 3; ++i)
    if (!std::isnan(expected[i]))
      talus_test::check(names[i], r.values[i], expected[i], 1e-12);
  talus_test::check("  f_s >= 0: min(f_s, 0) / c", std::min(mc.f_shear(r.values), 0.0) / 1e6, 0.0,
                    1e-12);
  talus_test::check("  state flags", z.state, expected_state, 0.0);
}

void tension_checks()
{
  const MohrCoulomb mc(0.0);
  const unsigned char tension = talus::tension_now | talus::tension_past;
  const unsigned char both = tension | talus::shear_now | talus::shear_past;
  // s3 alone beyond sigma_t: lambda = (s3 - sigma_t) / a1 pulls s1 and s2
  // by lambda a2.
  {
    const double trial[3] = {0.0, 0.3e6, 1.0e6};
    const double shift = (trial[2] - mc.sigma_t) * mc.alpha2 / mc.alpha1;
    const double expected[3] = {trial[0] - shift, trial[1] - shift, mc.sigma_t};
    print_principal_check(mc, "tension cut-off sigma_t = 0.5 MPa", trial, expected, tension);
  }
  // s2 and s3 beyond: both end on sigma_t.
  {
    const double trial[3] = {0.3e6, 1.0e6, 1.1e6};
    const double expected[3] = {NAN, mc.sigma_t, mc.sigma_t};
    print_principal_check(mc, "tension cut-off, s2 and s3 beyond", trial, expected, tension);
  }
  // Tensile strength above c / tan(phi): capped at the apex of the cone
  // (where all planes meet; a return there is reported as tensile).
  {
    const MohrCoulomb capped(0.0, 5e6);
    const double apex = capped.material.cohesion / std::tan(30.0 * deg);
    const double trial[3] = {2.9e6, 3.0e6, 3.1e6};
    const double expected[3] = {apex, apex, apex};
    print_principal_check(capped, "sigma_t = 5 MPa capped at c / tan(phi)", trial, expected,
                          tension);
  }
  // The corner P = (sigma_p, sigma_t), sigma_p = sigma_t N_phi - 2c
  // sqrt(N_phi), reached from the tension side of the bisector h ...
  const double sigma_p = mc.sigma_t * mc.n_phi - mc.k_shear;
  const double corner[3] = {sigma_p, NAN, mc.sigma_t};
  {
    const double trial[3] = {-2e6, -1e6, 3e6};
    print_principal_check(mc, "corner from the tension side (h > 0)", trial, corner, both);
  }
  // ... and from the shear side: h <= 0 starts with the shear return, whose
  // s3 stays above sigma_t.
  {
    const double trial[3] = {sigma_p - 0.5e6, 0.0, mc.sigma_t + 1e6};
    print_principal_check(mc, "corner from the shear side (h < 0)", trial, corner, both);
  }
}

/// Drained triaxial compression: lateral stresses held at -p (their
/// strains found by iteration each step), axial strain -1e-5 per step.
void triaxial_check()
{
  const double psi = 10.0, p = 5e6, axial_step = -1e-5;
  const MohrCoulomb mc(psi);
  const ZoneMaterial& m = mc.material;
  const double peak = -p * mc.n_phi - mc.k_shear;
  const double young = m.young();
  Zone z;
  z.stress[0] = z.stress[1] = z.stress[2] = -p;
  double lateral[2] = {0.0, 0.0};
  double axial_strain = 0.0, largest_deviation = 0.0, dilatancy = 0.0, volumetric = 0.0;
  int first_yield = -1;
  const auto load = [&](double axial)
  {
    Zone trial;
    for (int it = 0; it < 200; ++it)
    {
      trial = z;
      trial.strain_increment[0] = lateral[0];
      trial.strain_increment[1] = lateral[1];
      trial.strain_increment[2] = axial;
      step(m, trial);
      const double rx = trial.stress[0] + p, ry = trial.stress[1] + p;
      if (std::max(std::abs(rx), std::abs(ry)) < 1e-14 * p)
        break;
      // Elastic lateral stiffness [[a1 a2] [a2 a1]]: converges since the
      // plastic tangent is softer.
      const double det = mc.alpha1 * mc.alpha1 - mc.alpha2 * mc.alpha2;
      lateral[0] -= (mc.alpha1 * rx - mc.alpha2 * ry) / det;
      lateral[1] -= (mc.alpha1 * ry - mc.alpha2 * rx) / det;
    }
    z = trial;
  };
  std::printf("triaxial compression, p = 5 MPa, psi = 10 deg, 1000 steps of -1e-5:\n");
  for (int n = 0; n < 1000; ++n)
  {
    load(axial_step);
    axial_strain += axial_step;
    if (n == 99)
    {
      talus_test::check("  elastic, step 100: s_axial + p = E eps_axial (Pa)", z.stress[2] + p,
                        young * axial_strain, 1e-12);
      talus_test::check("  elastic, step 100: state flags", z.state, talus::zone_elastic, 0.0);
    }
    if (first_yield < 0 && (z.state & talus::shear_now))
      first_yield = n;
    if (first_yield >= 0)
      largest_deviation = std::max(largest_deviation, std::abs(z.stress[2] - peak) / -peak);
    volumetric = lateral[0] + lateral[1] + axial_step;
    dilatancy = volumetric / axial_step;
  }
  // Elastic up to (peak + p) / E, then perfectly plastic.
  const int expected_first_yield = int(std::floor((peak + p) / young / axial_step));
  talus_test::check("  first yielding step", first_yield, expected_first_yield, 0.0);
  talus_test::check("  s_axial at the end (Pa)", z.stress[2], peak, 1e-9);
  talus_test::check("  largest |s_axial - peak| / |peak| after yield", largest_deviation, 0.0,
                    1e-9);
  talus_test::check("  s_lateral at the end (Pa)", 0.5 * (z.stress[0] + z.stress[1]), -p, 1e-12);
  talus_test::check("  dilatancy de_v / de_axial at peak = 1 - N_psi", dilatancy, 1 - mc.n_psi,
                    1e-9);
  talus_test::check("  plastic volume change = total at peak (dilation > 0)", z.plastic_volumetric,
                    volumetric, 1e-9);
  talus_test::check("  state flags at peak", z.state, talus::shear_now | talus::shear_past, 0.0);
  load(-axial_step); // unloading: elastic, the past flag stays
  talus_test::check("  state flags after unloading", z.state, talus::shear_past, 0.0);
  talus_test::check("  plastic volume change after unloading", z.plastic_volumetric, 0.0, 0.0);
}

/// Random trials (principal values in [-30, 5] MPa, random axes, psi of 0,
/// 10 and 30 degrees): every returned stress must be admissible, keep its
/// principal axes, and stay put under a zero strain increment.
void random_checks()
{
  std::mt19937 random(12345);
  std::uniform_real_distribution<double> value(-30e6, 5e6), angle(-M_PI, M_PI);
  int inadmissible = 0, turned = 0, unstable = 0;
  const int n = 3000;
  for (int i = 0; i < n; ++i)
  {
    const MohrCoulomb mc(i % 3 == 0 ? 0.0 : (i % 3 == 1 ? 10.0 : 30.0));
    const Eigen::Matrix3d r = (Eigen::AngleAxisd(angle(random), Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(angle(random), Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(angle(random), Eigen::Vector3d::UnitX()))
                                  .toRotationMatrix();
    Eigen::Vector3d p(value(random), value(random), value(random));
    Zone z;
    from_matrix(r * p.asDiagonal() * r.transpose(), z.stress);
    const Principal t = principal(z.stress);
    step(mc.material, z);
    const Principal s = principal(z.stress);
    const double tolerance = 1e-12 * 30e6;
    if (mc.f_shear(s.values) < -tolerance || s.values[2] > mc.sigma_t + tolerance)
      ++inadmissible;
    // Axes only mean something where the principal values are distinct.
    const double gap = std::min(s.values[1] - s.values[0], s.values[2] - s.values[1]);
    if (gap > 1e3 && direction_mismatch(t, s) > 1e-9)
      ++turned;
    Zone again = z;
    step(mc.material, again);
    for (int c = 0; c < 6; ++c)
      if (std::abs(again.stress[c] - z.stress[c]) > tolerance)
      {
        ++unstable;
        break;
      }
  }
  std::printf("random trials (%d):\n", n);
  talus_test::check("  returned stresses outside the surfaces", inadmissible, 0, 0.0);
  talus_test::check("  returned stresses with turned principal axes", turned, 0, 0.0);
  talus_test::check("  returned stresses moved by a zero increment", unstable, 0, 0.0);
}

} // namespace

int main()
{
  elastic_checks();
  shear_checks(0.0);
  shear_checks(10.0);
  shear_checks(30.0);
  plastic_flow_check();
  edge_check();
  tension_checks();
  triaxial_check();
  random_checks();
}
