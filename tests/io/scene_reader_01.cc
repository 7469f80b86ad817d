// read_scene: defaults, numbered subsections in file order, the parameters
// as used, and a missing file refused with its name.

#include <talus/base/exceptions.h>
#include <talus/scene/scene.h>

#include <fstream>
#include <iostream>

int main()
{
  using namespace talus;
  {
    std::ofstream prm("scene.prm");
    prm << "subsection Joint set 2\n  set Dip = 45\n  set Spacing = 0.5\nend\n"
        << "subsection Joint set 1\n  set Dip direction = 270\nend\n"
        << "subsection Group 1\n  set Name = left\nend\n"
        << "subsection Output\n  set Directory = out_scene\nend\n";
  }
  const Scene s = read_scene("scene.prm");
  std::cout << "brick " << s.brick.lo.transpose() << " to " << s.brick.hi.transpose() << '\n'
            << "density " << s.density << '\n'
            << "joint sets " << s.joint_sets.size() << " (numbered order): set 1 dip direction "
            << s.joint_sets[0].dip_direction << ", set 2 dip " << s.joint_sets[1].dip
            << " spacing " << s.joint_sets[1].spacing << '\n'
            << "groups " << s.groups.size() << " first " << s.groups[0].name << '\n'
            << "output " << s.output.directory << '/' << s.output.base_name << '\n';
  std::cout << "---- used parameters\n" << s.used_parameters;
  try
  {
    read_scene("no_such_scene.prm");
  }
  catch (const InputError& e)
  {
    std::cout << "refused: " << e.what() << '\n';
  }
}
