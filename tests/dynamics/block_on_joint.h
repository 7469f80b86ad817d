#pragma once

// The scene of one degree of freedom of the dynamics tests: a block on a
// joint spring.

#include <sstream>
#include <string>

#include "../stability/scene_text.h"

inline constexpr double rho = 2650.0, kn = 1e10, ks = 4e9, v0 = 1e-3;

/// A 1 m cube (group cube, rotation held) on a fixed one (group floor),
/// joined by a bonded joint (kn, ks; cohesion and tensile strength 1e9
/// Pa), no gravity, the cube's initial velocity `velocity` ("x, y, z",
/// m/s), Rayleigh damping `alpha` (1/s) and `beta` (s), 'Mode' `mode`, and
/// `more` lines in 'Solver'.
inline std::string block_on_joint(const char* mode, const char* velocity, double alpha, double beta,
                                  const std::string& more = "")
{
  std::ostringstream s;
  s.precision(17);
  s << "subsection Model\n  set Brick min = 0, 0, 0\n  set Brick max = 1, 1, 2\nend\n"
    << "subsection Material\n  set Density = " << rho << "\nend\n"
    << "subsection Joint 1\n  set Dip = 0\n  set Origin = 0, 0, 1\nend\n"
    << "subsection Group 1\n  set Name = floor\n  set Corner min = 0, 0, 0\n"
    << "  set Corner max = 1, 1, 1\nend\n"
    << "subsection Group 2\n  set Name = cube\n  set Corner min = 0, 0, 1\n"
    << "  set Corner max = 1, 1, 2\nend\n"
    << "subsection Load 1\n  set Group = cube\n  set Hold rotation = true\n"
    << "  set Initial velocity = " << velocity << "\nend\n"
    << "subsection Joint properties\n  set Normal stiffness = " << kn
    << "\n  set Shear stiffness = " << ks
    << "\n  set Cohesion = 1e9\n  set Tensile strength = 1e9\n  set Friction angle = 30\nend\n"
    << "subsection Solver\n  set Mode = " << mode << "\n  set Gravity = 0, 0, 0\n"
    << "  set Fixed groups = floor\n  set Rayleigh alpha = " << alpha
    << "\n  set Rayleigh beta = " << beta << "\n"
    << more << "end\n";
  return s.str();
}
