#pragma once
// The catalogue of what a build can run: integrators by name and scene kinds by lab.
// The framework registers its own pieces; each lab adds its pieces with one call
// (see labs/*/register.cpp). Nothing is registered behind the program's back.
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "springlab/integrator.hpp"
#include "springlab/scene_document.hpp"
#include "springlab/scene_reader.hpp"
#include "springlab/solver_settings.hpp"
#include "springlab/simulation.hpp"

namespace springlab {

// Settings every scene file has, whatever its lab (units in README's scene reference).
struct SceneSettings {
  std::string file;         // path the scene was read from
  std::string lab;          // "rope", "net", "softbody": selects the factory and the section
  std::string name;         // title shown in the viewer
  std::string description;  // one sentence
  int dimension = 3;        // 2 or 3
  double dt = 0.0;          // s, integrator step
  int substeps = 1;         // integrator steps per displayed frame
  std::string integrator;   // registered integrator name
  Vec3 gravity = Vec3::Zero();  // m/s^2
  SolverSettings solver;    // optional "solver" section: the implicit integrators' accuracy
};

struct LoadedScene {
  SceneSettings settings;
  std::unique_ptr<Simulation> sim;
};

// How a scene kind changes its resolution (masses per rope, grid size, mesh subdivision)
// while the physical object stays the same: the resolution study and the advisor use it.
// A lab passes one to Registry::addScene. `key` names an integer key of the lab's section;
// `rescale` rewrites the section for a new value. Without `rescale` only the key is set,
// which is right when the section gives the object in physical totals (size, total mass,
// material stiffness) and the lab derives per-mass and per-spring values from them.
struct ResolutionRule {
  std::string key;  // in the lab's section, dots for nested keys: "masses", "mesh.subdivisions"; empty: none
  std::function<void(nlohmann::json& section, int value)> rescale;  // may be empty
};

class Registry {
 public:
  using IntegratorFactory = std::function<std::unique_ptr<Integrator>()>;
  // Builds a simulation from the scene's lab section (e.g. the "rope" object).
  using SceneFactory =
      std::function<std::unique_ptr<Simulation>(SceneReader& section, const SceneSettings&)>;

  void addIntegrator(const std::string& name, IntegratorFactory factory);
  void addScene(const std::string& lab, SceneFactory factory, ResolutionRule resolution = {});

  // Throws std::invalid_argument listing the known names when `name` is unknown.
  std::unique_ptr<Integrator> makeIntegrator(const std::string& name) const;
  std::vector<std::string> integratorNames() const;
  std::vector<std::string> labNames() const;

  // Read and validate a scene file, build its simulation with the scene's integrator.
  // Throws SceneError naming the file and key on any bad input.
  LoadedScene loadScene(const std::string& path) const;
  LoadedScene loadScene(SceneReader& reader) const;
  // A scene document, edited or not (--set, studies).
  LoadedScene loadScene(const SceneDocument& document) const;

  // The scene kind's resolution rule; std::invalid_argument when the lab registered none.
  const ResolutionRule& resolutionRule(const std::string& lab) const;
  // The document's resolution (the value of its lab's resolution key).
  int resolution(const SceneDocument& document) const;
  // The same physical object at another resolution.
  SceneDocument atResolution(const SceneDocument& document, int value) const;
  // Only the settings every scene has, without building the simulation (the viewer shows
  // them even when the lab's code cannot build the scene yet).
  SceneSettings readSceneSettings(const std::string& path) const;

 private:
  SceneSettings readSettings(SceneReader& reader) const;
  // The scene's optional "integrator_options" into sim.integratorOptions; SceneError naming
  // the key for a method or option this build does not know.
  void readIntegratorOptions(SceneReader& reader, Simulation& sim) const;

  std::map<std::string, IntegratorFactory> integrators_;
  std::map<std::string, SceneFactory> scenes_;
  std::map<std::string, ResolutionRule> resolutions_;
};

// Registers the framework's own integrators (symplectic Euler, midpoint, RK4).
void registerFramework(Registry& registry);

}  // namespace springlab
