// Extreme scene: parameters/stability/rattling_block.prm (see the comment there).
// Contacts made and lost every few steps, faces pressed far deeper than
// the contact tolerance while they turn. Three things close the balance
// here (the first or the third undone leaves 2.2e-1 or 1.1e-2): the region of a rigid
// face turns with the face (the face whole, its far vertices open); rebuilt
// sub-contacts carry shear stress, not force; friction counts the energy a
// shear spring gives up when its strength falls.

#include "stability.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  StabilityRun r("rattling_block.prm");
  r.run();
  r.report(1e-3);
}
