#pragma once

// The scene of the zone benchmarks: an elastic 10 m cube (rho = 2650
// kg/m^3, E = 10 GPa, nu = 0.25) in statics under gravity, its base held,
// starting from the gravitational stress sigma_zz = -rho g (H - z); and its
// Mohr-Coulomb variant (c = 40 kPa, phi = 30, psi = 0, sigma_t = 10 kPa:
// the uniaxial strength 2 c sqrt(N_phi) = 139 kPa is reached about halfway
// down).

#include <talus/solver/deformable_solver.h>

struct GravityCube
{
  double side = 10.0;      ///< m
  double density = 2650.0; ///< kg/m^3
  double g = 9.81;         ///< m/s^2
  talus::ZoneMaterial elastic, plastic;
  talus::SolverSettings settings;
  talus::GridpointCondition base;
  talus::InitialStress initial;

  GravityCube()
  {
    elastic.density = density;
    elastic.set_young_poisson(1e10, 0.25);
    plastic = elastic;
    plastic.model = talus::ZoneModel::mohr_coulomb;
    plastic.cohesion = 4e4;
    plastic.friction_angle = 30.0;
    plastic.dilation_angle = 0.0;
    plastic.tensile_strength = 1e4;
    settings.dynamic = false;
    settings.gravity = talus::Vec3(0, 0, -g);
    base.region = talus::Box{talus::Vec3(-1, -1, -1e-9), talus::Vec3(side + 1, side + 1, 1e-9)};
    initial.base[2] = -density * g * side;
    initial.gradient[2] = density * g;
  }
};
