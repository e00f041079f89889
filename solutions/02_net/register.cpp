#include "net.hpp"

namespace springlab::net {

void registerIntegrators(Registry& registry);  // integrators.cpp

void registerLab(Registry& registry) {
  registerIntegrators(registry);
  registry.addScene("net", [](SceneReader& section, const SceneSettings& settings) {
    const NetParameters p = readNetParameters(section, settings);
    return std::make_unique<Net>(settings.dimension, p);
  });
}

}  // namespace springlab::net
