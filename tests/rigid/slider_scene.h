#pragma once

// The slider on an incline that the factor-of-safety tests share: a block
// 1 m along the slope, 2 m across, 0.2 m thick (0.4 m^3, rho 2650) on a
// fixed base 11 m long, on the horizontal 'Joint 1' at z = 1, with gravity
// tilted by the slope angle a: g = 9.81 (sin a, 0, -cos a). Its upslope and
// downslope faces are parallel to gravity (two excavations of normal
// (cos a, 0, sin a)), so that its centroid lies over the centre of its base
// and the normal stress on the base is uniform.

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

/// Writes `file`: the slider's model, groups and gravity (the 'Solver'
/// subsection holds `solver_entries` too), then `sections` (joint
/// properties and materials, stages, output) as given.
inline void write_slider_scene(const std::string& file, double slope_degrees,
                               const std::string& solver_entries, const std::string& sections)
{
  const double a = slope_degrees * M_PI / 180.0, g = 9.81;
  char text[2000];
  std::snprintf(text, sizeof text, R"(
subsection Model
  set Brick min = -1, 0, 0
  set Brick max = 10, 2, 1.2
  set Default group = base
end
subsection Material
  set Density = 2650
end
subsection Joint 1
  set Dip = 0
  set Origin = 0, 0, 1
end
subsection Excavation 1
  set Shape = polyhedron
  set Planes = 0, 0, 1, 0, 0, -1; 0, 0, 1, %.17g, 0, %.17g
end
subsection Excavation 2
  set Shape = polyhedron
  set Planes = 0, 0, 1, 0, 0, -1; 1, 0, 1, %.17g, 0, %.17g
end
subsection Group 1
  set Name = slider
  set Corner min = -1, 0, 1
  set Corner max = 1, 2, 2
end
subsection Solver
  set Gravity = %.17g, 0, %.17g
  set Fixed groups = base
%s
end
)",
                std::cos(a), std::sin(a), -std::cos(a), -std::sin(a), g * std::sin(a),
                -g * std::cos(a), solver_entries.c_str());
  std::ofstream(file) << text << sections;
}
