// The energy account of 10-node and hexahedral zones: the scene of
// soft_beside_stiff.prm (a soft deformable slab on a stiff deformable
// block on a fixed floor) with each element, elastic and Mohr-Coulomb.
// 10-node zones count each Gauss point with a quarter of the zone's
// volume, hexahedral zones each overlay with half: a wrong weight leaves
// the zone elastic energy (about a third of the largest term) or the
// plastic stress work off by a factor, far beyond the tolerance.

#include "stability.h"

int main(int argc, char** argv)
{
  talus::ParallelEnvironment env(argc, argv);
  for (const talus::ZoneElement element :
       {talus::ZoneElement::tet10, talus::ZoneElement::hex_mixed})
    for (const talus::ZoneModel model : {talus::ZoneModel::elastic, talus::ZoneModel::mohr_coulomb})
    {
      std::printf("%s zones, %s:\n",
                  element == talus::ZoneElement::tet10 ? "10-node" : "hexahedral",
                  model == talus::ZoneModel::elastic ? "elastic" : "Mohr-Coulomb");
      StabilityRun r("soft_beside_stiff.prm",
                     [&](talus::Scene& scene)
                     {
                       talus::ZoneMaterial& m = scene.deformable.material;
                       m.element = element;
                       m.model = model;
                       m.cohesion = 2e4;      // Pa: the soft slab yields as it lands
                       m.friction_angle = 20; // degrees
                     });
      r.run(3000);
      r.report(2e-2);
    }
}
