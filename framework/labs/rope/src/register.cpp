#include <springlab/rope/rope.hpp>

namespace springlab::rope {

void registerIntegrators(Registry& registry);  // integrators.cpp

void registerLab(Registry& registry) {
  registerIntegrators(registry);
  registry.addScene("rope", [](SceneReader& section, const SceneSettings& settings) {
    const RopeParameters p = readRopeParameters(section, settings.gravity, settings.dimension);
    return std::make_unique<Rope>(settings.dimension, p);
  }, ropeResolutionRule());
}

}  // namespace springlab::rope
