#include "springlab/registry.hpp"

#include <stdexcept>

#include "springlab/midpoint.hpp"
#include "springlab/rk4.hpp"
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

void Registry::addScene(const std::string& lab, SceneFactory factory, ResolutionRule resolution) {
  scenes_[lab] = std::move(factory);
  if (!resolution.key.empty()) resolutions_[lab] = std::move(resolution);
}

LoadedScene Registry::loadScene(const SceneDocument& document) const {
  SceneReader reader = SceneReader::fromJson(document.json, document.file);
  return loadScene(reader);
}

const ResolutionRule& Registry::resolutionRule(const std::string& lab) const {
  auto it = resolutions_.find(lab);
  if (it == resolutions_.end()) {
    throw std::invalid_argument("the " + lab + " lab registers no resolution key (Registry::addScene's ResolutionRule), so its scenes cannot change resolution");
  }
  return it->second;
}

namespace {
// The lab's section of a document and the lab's name, or SceneError naming the file.
std::string labOf(const SceneDocument& document) {
  const auto it = document.json.find("lab");
  if (it == document.json.end() || !it->is_string()) throw SceneError(document.file + ": lab: missing or not a string");
  const std::string lab = it->get<std::string>();
  if (!document.json.contains(lab) || !document.json[lab].is_object()) {
    throw SceneError(document.file + ": " + lab + ": the lab's section is missing");
  }
  return lab;
}
}  // namespace

int Registry::resolution(const SceneDocument& document) const {
  const std::string lab = labOf(document);
  const ResolutionRule& rule = resolutionRule(lab);
  const nlohmann::json& section = document.json[lab];
  const auto key = dottedKey(rule.key);
  if (!section.contains(key) || !section[key].is_number_integer()) {
    throw SceneError(document.file + ": " + lab + "." + rule.key + ": the resolution key must be an integer");
  }
  return section[key].get<int>();
}

SceneDocument Registry::atResolution(const SceneDocument& document, int value) const {
  const std::string lab = labOf(document);
  const ResolutionRule& rule = resolutionRule(lab);
  SceneDocument out = document;
  if (rule.rescale) {
    rule.rescale(out.json[lab], value);
  } else {
    out.json[lab][dottedKey(rule.key)] = value;
  }
  return out;
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
  // The implicit integrators' accuracy, when the scene chooses it.
  if (reader.has("solver")) {
    SceneReader solver = reader.object("solver");
    if (solver.has("tolerance")) s.solver.tolerance = solver.positive("tolerance");
    if (solver.has("preconditioner")) {
      s.solver.preconditioner = solver.string("preconditioner");
      if (s.solver.preconditioner != "auto" && s.solver.preconditioner != "block_jacobi" &&
          s.solver.preconditioner != "smoothed_aggregation") {
        solver.fail("preconditioner", "must be \"auto\", \"block_jacobi\" or \"smoothed_aggregation\"");
      }
    }
    if (solver.has("block_sweeps")) s.solver.blockSweeps = solver.integer("block_sweeps", 1);
    if (solver.has("block_tolerance")) s.solver.blockTolerance = solver.nonNegative("block_tolerance");
    solver.rejectUnknownKeys();
  }
  return s;
}

void Registry::readIntegratorOptions(SceneReader& reader, Simulation& sim) const {
  // Optional: {"xpbd": {"iterations": 4, "substeps": 2}, ...}, each method's own names, >= 1.
  if (!reader.has("integrator_options")) return;
  SceneReader all = reader.object("integrator_options");
  for (const std::string& method : integratorNames()) {
    if (!all.has(method)) continue;
    SceneReader options = all.object(method);
    for (const std::string& option : makeIntegrator(method)->optionNames()) {
      if (options.has(option)) sim.integratorOptions[method][option] = options.integer(option, 1);
    }
    options.rejectUnknownKeys();
  }
  all.rejectUnknownKeys();
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
  readIntegratorOptions(reader, *loaded.sim);
  reader.rejectUnknownKeys();
  loaded.sim->solver = s.solver;
  loaded.sim->setIntegrator(makeIntegrator(s.integrator));
  return loaded;
}

void registerFramework(Registry& registry) {
  registry.addIntegrator("symplectic_euler", [] { return std::make_unique<SymplecticEuler>(); });
  registry.addIntegrator("midpoint", [] { return std::make_unique<Midpoint>(); });
  registry.addIntegrator("rk4", [] { return std::make_unique<RungeKutta4>(); });
}

}  // namespace springlab
