#include "springlab/registry.hpp"

#include <stdexcept>

#include "springlab/symplectic_euler.hpp"

namespace springlab {

namespace {
std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}
}  // namespace

void Registry::addIntegrator(const std::string& name, IntegratorFactory factory) {
  integrators_[name] = std::move(factory);
}

void Registry::addScene(const std::string& lab, SceneFactory factory) {
  scenes_[lab] = std::move(factory);
}

std::unique_ptr<Integrator> Registry::makeIntegrator(const std::string& name) const {
  auto it = integrators_.find(name);
  if (it == integrators_.end()) {
    throw std::invalid_argument("unknown integrator \"" + name + "\"; known: " + joined(integratorNames()));
  }
  return it->second();
}

std::vector<std::string> Registry::integratorNames() const {
  std::vector<std::string> names;
  for (const auto& [name, factory] : integrators_) names.push_back(name);
  return names;
}

std::vector<std::string> Registry::labNames() const {
  std::vector<std::string> names;
  for (const auto& [name, factory] : scenes_) names.push_back(name);
  return names;
}

LoadedScene Registry::loadScene(const std::string& path) const {
  SceneReader reader = SceneReader::fromFile(path);
  return loadScene(reader);
}

SceneSettings Registry::readSceneSettings(const std::string& path) const {
  SceneReader reader = SceneReader::fromFile(path);
  return readSettings(reader);
}

SceneSettings Registry::readSettings(SceneReader& reader) const {
  // Settings shared by every lab.
  SceneSettings s;
  s.file = reader.file();
  s.lab = reader.string("lab");
  s.name = reader.string("name");
  s.description = reader.string("description");
  s.dimension = reader.integer("dimension", 2);
  if (s.dimension != 2 && s.dimension != 3) reader.fail("dimension", "must be 2 or 3");
  s.dt = reader.positive("dt");
  s.substeps = reader.integer("substeps", 1);
  s.integrator = reader.string("integrator");
  if (!integrators_.count(s.integrator)) {
    reader.fail("integrator", "unknown integrator \"" + s.integrator + "\"; known: " + joined(integratorNames()));
  }
  s.gravity = reader.vec3("gravity");
  if (s.dimension == 2 && s.gravity.z() != 0.0) reader.fail("gravity", "must have z = 0 in a 2D scene");
  return s;
}

LoadedScene Registry::loadScene(SceneReader& reader) const {
  const SceneSettings s = readSettings(reader);

  // The lab's own section, named after the lab.
  auto factory = scenes_.find(s.lab);
  if (factory == scenes_.end()) {
    reader.fail("lab", "unknown lab \"" + s.lab + "\"; this build knows: " + joined(labNames()));
  }
  SceneReader section = reader.object(s.lab);
  LoadedScene loaded{s, factory->second(section, s)};
  section.rejectUnknownKeys();
  reader.rejectUnknownKeys();
  loaded.sim->setIntegrator(makeIntegrator(s.integrator));
  return loaded;
}

void registerFramework(Registry& registry) {
  registry.addIntegrator("symplectic_euler", [] { return std::make_unique<SymplecticEuler>(); });
}

}  // namespace springlab
