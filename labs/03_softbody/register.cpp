#include "softbody.hpp"

namespace springlab::softbody {

void registerLab(Registry& registry) {
  registry.addScene("softbody", [](SceneReader& section, const SceneSettings& settings) {
    return std::make_unique<SoftBody>(settings.dimension, readSoftBodyParameters(section, settings));
  });
}

}  // namespace springlab::softbody
