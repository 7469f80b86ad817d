// The contact VTU: array names with underscores as the README lists them
// (normal_force, shear_force, normal_stress, shear_stress,
// shear_displacement, area, state, type, joint_set, joint, contact_id),
// contact types numbered from 1, stresses equal to the forces over the
// areas, and each contact labelled with the joint set or joint whose plane
// it lies on (issue 20, item 10). Three rows of blocks: a horizontal joint
// set (Joint set 1), a vertical one normal to x (Joint set 2) and one
// vertical joint normal to y (Joint 1); the bottom row is fixed.

#include <talus/io/contact_vtu_writer.h>
#include <talus/scene/scene.h>
#include <talus/scene/build_blocks.h>
#include <talus/solver/rigid_solver.h>

#include "../tests.h"

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace
{
/// The values of DataArray `name` of a VTU file written by talus in ASCII.
std::vector<double> data_array(const std::string& text, const std::string& name)
{
  std::vector<double> values;
  const std::size_t at = text.find("Name=\"" + name + "\"");
  if (at == std::string::npos)
    return values;
  const std::size_t start = text.find('>', at) + 1;
  std::istringstream in(text.substr(start, text.find("</DataArray>", start) - start));
  for (double v; in >> v;)
    values.push_back(v);
  return values;
}
} // namespace

int main()
{
  std::ofstream("contact_vtu_01.prm") << "subsection Model\n"
                                         "  set Brick min = 0, 0, 0\n"
                                         "  set Brick max = 2, 1, 3\n"
                                         "end\n"
                                         "subsection Joint set 1\n"
                                         "  set Dip = 0\n"
                                         "  set Spacing = 1\n"
                                         "end\n"
                                         "subsection Joint set 2\n"
                                         "  set Dip = 90\n"
                                         "  set Dip direction = 90\n"
                                         "  set Spacing = 1\n"
                                         "end\n"
                                         "subsection Joint 1\n"
                                         "  set Dip = 90\n"
                                         "  set Origin = 0, 0.5, 0\n"
                                         "end\n"
                                         "subsection Group 1\n"
                                         "  set Name = floor\n"
                                         "  set Corner min = 0, 0, 0\n"
                                         "  set Corner max = 2, 1, 1\n"
                                         "end\n"
                                         "subsection Solver\n"
                                         "  set Mode = dynamic\n"
                                         "  set Steps = 50\n"
                                         "  set Fixed groups = floor\n"
                                         "end\n";
  using namespace talus;
  Scene scene = read_scene("contact_vtu_01.prm", false);
  BuildReport report;
  BlockModel model = build_blocks(scene, report);
  resolve_group_names(scene, model);
  RigidSolver solver(model, scene.density, scene.solver);
  for (int i = 0; i < 50; ++i)
    solver.step();
  write_contacts_vtu("contacts.vtu", solver.contacts(), model, JointNumbers{{1, 2}, {1}},
                     VtuEncoding::ascii);
  std::ifstream in("contacts.vtu");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());

  const unsigned int n = solver.contacts().n_subcontacts();
  std::printf("blocks %u, sub-contacts %u\n", model.n_blocks(), n);
  for (const char* name :
       {"normal", "normal_force", "shear_force", "normal_stress", "shear_stress",
        "shear_displacement", "area", "state", "type", "joint_set", "joint", "contact_id"})
  {
    const std::size_t components =
        std::string(name) == "normal" || std::string(name).rfind("shear", 0) == 0 ? 3 : 1;
    std::printf("array %s: %s\n", name,
                talus_test::verdict(data_array(text, name).size() == components * n));
  }
  const std::vector<double> fn = data_array(text, "normal_force"),
                            sn = data_array(text, "normal_stress"),
                            fs = data_array(text, "shear_force"),
                            ss = data_array(text, "shear_stress"), area = data_array(text, "area"),
                            type = data_array(text, "type"), normal = data_array(text, "normal"),
                            set = data_array(text, "joint_set"), joint = data_array(text, "joint");
  double stress_error = 0.0;
  bool types_from_1 = true;
  // Labels by the plane's orientation: z normal on joint set 1, x normal on
  // joint set 2, y normal on joint 1.
  std::map<std::string, unsigned int> labelled;
  unsigned int wrong_label = 0;
  for (unsigned int i = 0; i < n; ++i)
  {
    stress_error =
        std::max(stress_error, std::abs(sn[i] * area[i] - fn[i]) / (std::abs(fn[i]) + 1));
    for (int d = 0; d < 3; ++d)
      stress_error = std::max(stress_error, std::abs(ss[3 * i + d] * area[i] - fs[3 * i + d]) /
                                                (std::abs(fs[3 * i + d]) + 1));
    types_from_1 &= type[i] >= 1 && type[i] <= 6;
    int axis = 0;
    for (int d = 1; d < 3; ++d)
      if (std::abs(normal[3 * i + d]) > std::abs(normal[3 * i + axis]))
        axis = d;
    // A plane more than 10 degrees from every face (an edge-edge contact
    // across the corner where joints cross) lies on no joint.
    const bool on_a_face = std::abs(normal[3 * i + axis]) > std::cos(10.0 * M_PI / 180.0);
    const int want_set = !on_a_face  ? 0
                         : axis == 2 ? 1
                         : axis == 0 ? 2
                                     : 0,
              want_joint = on_a_face && axis == 1 ? 1 : 0;
    if (set[i] == want_set && joint[i] == want_joint)
      ++labelled[!on_a_face  ? "no joint (across a corner)"
                 : axis == 2 ? "joint set 1"
                 : axis == 0 ? "joint set 2"
                             : "joint 1"];
    else
    {
      ++wrong_label;
      std::fprintf(stderr, "sub-contact %u: type %g normal %g %g %g joint set %g joint %g\n", i,
                   type[i], normal[3 * i], normal[3 * i + 1], normal[3 * i + 2], set[i], joint[i]);
    }
  }
  std::printf("stresses are the forces over the areas: %s\n",
              talus_test::verdict(stress_error < 1e-9));
  std::printf("types from 1 to 6: %s\n", talus_test::verdict(types_from_1));
  for (const auto& [label, count] : labelled)
    std::printf("sub-contacts on %s: %u\n", label.c_str(), count);
  std::printf("sub-contacts with another label: %u\n", wrong_label);
}
