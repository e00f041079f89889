#include <springlab/softbody/softbody.hpp>

namespace springlab::softbody {

void registerLab(Registry& registry) {
  registry.addScene("softbody", [](SceneReader& section, const SceneSettings& settings) {
    return std::make_unique<SoftBody>(settings.dimension, readSoftBodyParameters(section, settings));
  },
  // Resolution studies refine a generated icosphere; radius and total_mass stay as they are.
  ResolutionRule{"mesh.subdivisions", {}});
}

}  // namespace springlab::softbody
