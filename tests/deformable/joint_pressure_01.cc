// Water of a joint set's own ('Joint set pressures') on deformable blocks
// (tests/deformable/joint_pressure_cube.prm): a deformable cube on a fixed
// rigid one, the joint between them at p = 5000 Pa. The faces of the zones
// on that joint take p; the others none (no phreatic surface):
//  - in every zone formulation, the cube ends where the same cube ends
//    with the uplift given instead as a 'Boundary N' pressure p on its base
//    (to 1e-6 of the uplift's effect);
//  - the base's closure (W - p A) / kn, W = 25506 N, kn = 1e9 Pa/m (1e-6),
//    with hexahedral zones (the tetrahedra's lumped gravity makes their
//    joint close unevenly).
// The before figure: the scene was refused ("rigid blocks only").

#include <talus/base/parallel_environment.h>

#include <tuple>

#include "../scenes/stage_history.h"
#include "../tests.h"

int main(int argc, char** argv)
{
  ParallelEnvironment env(argc, argv);
  const double W = 2600 * 9.81, p = 5000, kn = 1e9;
  for (const auto& [element, nodal_mixed, name] :
       {std::tuple{ZoneElement::tet4, false, "tet4"}, std::tuple{ZoneElement::tet4, true, "nmd"},
        std::tuple{ZoneElement::tet10, false, "tet10"},
        std::tuple{ZoneElement::hex_mixed, false, "hex-mixed"}})
  {
    Scene scene = read_scene(std::string(SOURCE_DIR) + "/joint_pressure_cube.prm", false);
    scene.deformable.material.element = element;
    scene.deformable.material.nodal_mixed = nodal_mixed;
    scene.output.directory += std::string("_") + name;
    Scene dry = scene;
    dry.solver.water = WaterSpec();
    dry.output.directory += "_dry";
    Scene pressed = dry;
    pressed.face_pressures.push_back(
        FacePressure{Box{Vec3(-0.1, -0.1, 0.99), Vec3(1.1, 1.1, 1.01)}, p, Vec3::Zero()});
    pressed.face_pressure_sections.push_back("Boundary 1");
    pressed.output.directory += "_pressed";
    const int codes = run_quietly(scene) + run_quietly(dry) + run_quietly(pressed);
    std::printf("%s: the three runs end in equilibrium: %s\n", name,
                talus_test::verdict(codes == 0));
    const auto end = [](const Scene& s, const char* point)
    {
      std::vector<std::string> columns;
      const auto rows =
          read_history(s.output.directory + "/" + s.output.base_name + "_history.csv", columns);
      return column(rows.back(), columns, point);
    };
    for (const auto& [point, where] :
         {std::pair{"point 0 uz (m)", "top face"}, std::pair{"point 1 uz (m)", "base"}})
    {
      const double wet = end(scene, point), effect = std::abs(wet - end(dry, point));
      std::fprintf(stderr, "%s %s: joint pressure %.10g, boundary pressure %.10g, dry %.10g\n",
                   name, where, wet, end(pressed, point), end(dry, point));
      std::printf("  %s: %s, the joint's water as a pressure on the base: %s\n", name, where,
                  talus_test::verdict(effect > 0.0 &&
                                      std::abs(wet - end(pressed, point)) <= 1e-6 * effect));
    }
    if (element == ZoneElement::hex_mixed)
      talus_test::check_within("  hex-mixed: the base's closure (W - p A) / kn (m)",
                               end(scene, "point 1 uz (m)"), -(W - p) / kn, 1e-6);
  }
}
