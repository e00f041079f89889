#include <springlab/net/net.hpp>

#include <cmath>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

namespace springlab::net {

void registerIntegrators(Registry& registry);  // integrators.cpp

namespace {
// Masses of a net with `resolution` masses along its width (rows follow the aspect ratio).
double netMasses(const nlohmann::json& net, int resolution) {
  const double aspect = net.at("height").get<double>() / net.at("width").get<double>();
  const double rows = std::round(aspect * (resolution - 1)) + 1.0;
  return rows * resolution;
}

// Resolution studies keep the same cloth: a net given by areal density already keeps its
// mass; one given per particle spreads the same total mass over the new masses.
void rescaleNet(nlohmann::json& net, int resolution) {
  if (resolution < 2) throw std::invalid_argument("a net needs a resolution of at least 2, got " + std::to_string(resolution));
  if (net.contains("particle_mass")) {
    const double total = net["particle_mass"].get<double>() * netMasses(net, net.at("resolution").get<int>());
    net["particle_mass"] = total / netMasses(net, resolution);
  }
  net["resolution"] = resolution;
}
}  // namespace

void registerLab(Registry& registry) {
  registerIntegrators(registry);
  registry.addScene("net", [](SceneReader& section, const SceneSettings& settings) {
    const NetParameters p = readNetParameters(section, settings);
    return std::make_unique<Net>(settings.dimension, p);
  },
  ResolutionRule{"resolution", rescaleNet});
}

}  // namespace springlab::net
