#pragma once
// Lab 2: the elastic net, given code. The Net system, its scene reader and the registration
// of the lab's scene kind and integrators, built on the exercises of springlab/net/exercises.hpp;
// the framework compiles this once and links it with the student's exercises (labs/02_net/)
// or the reference (solutions/02_net/).
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <springlab/integrator.hpp>
#include <springlab/net/exercises.hpp>
#include <springlab/net/tethers.hpp>
#include <springlab/registry.hpp>
#include <springlab/scene_reader.hpp>
#include <springlab/scene_shapes.hpp>
#include <springlab/simulation.hpp>

namespace springlab::net {

// Read a scene's "net" section; errors name the file and the key.
NetParameters readNetParameters(SceneReader& section, const SceneSettings& settings);


// The framework's fast spring pass (src/fast_spring_forces.hpp), which Net asks first.
class FastSpringForces;

// ---- The net system, calling the exercises ----------------------------------------------
class Net final : public Simulation {
 public:
  Net(int dimension, const NetParameters& parameters);
  ~Net() override;

  NetParameters settings;  // the scene's settings: model, edited through editModel (the panel)

  // Physics.
  bool addForceJacobian(const State& s, ForceJacobian& J) override;
  // The terms of accumulateForces, in the order of ForceTerm (the blow-up check names one).
  enum ForceTerm { kSprings, kGravityAndAir, kWind };
  std::vector<std::string> forceTermNames() const override;
  // A wind of nonzero speed (or strength) works on the cloth; a still air only drags.
  bool suppliesEnergy() const override { return settings.wind.strength > 0.0; }
  // The wind's power v . F over every mass (its whole force: the push and the drag).
  std::optional<double> sourcePower(const State& s) const override;

  // Front end.
  std::string kind() const override { return "net"; }
  std::vector<Shape> shapes() const override;
  void moveShape(int index, const Vec3& center) override;
  std::optional<double> groundHeight() const override;
  Bounds reach() const override;
  std::vector<Observable> observables() const override;

  int columns() const { return columns_; }
  int rows() const { return rows_; }
  const std::vector<SphereCollider>& spheres() const { return spheres_; }
  // Move a sphere to `center` at the next step (what the viewer's drag does).
  void moveSphere(int sphere, const Vec3& center);

 protected:
  void accumulateForces(const State& s, std::vector<Vec3>& f) override;
  void afterStep(double dt) override;
  void onReset() override;
  std::any saveLabData() const override;
  void restoreLabData(const std::any& data) override;
  void onModelEdited() override;
  std::vector<Parameter> declareParameters() override;

 private:
  // The wind's arrow above the cloth, when there is wind.
  std::optional<Shape> windArrow() const;
  // The first plane of settings.planes facing straight up: the ground the viewer draws.
  std::optional<GroundPlane> ground() const;

  int columns_ = 0;
  int rows_ = 0;
  std::vector<SphereCollider> spheres_;            // current colliders
  std::vector<ColliderDrag> drags_;                // [spheres] where the user holds each one
  std::unique_ptr<FastSpringForces> fastSprings_;  // the springs' forces and Jacobians, faster
  std::vector<Vec3> normals_;                      // [n] scratch for the wind
  std::vector<double> areas_;                      // [n] m^2
  mutable std::vector<Vec3> sourceNormals_;        // [n] scratch for sourcePower (a step allocates nothing)
  mutable std::vector<double> sourceAreas_;        // [n] m^2
  std::vector<double> inverseMass_;                // [n] scratch for stretch limiting
  Tethers tethers_;                                // stretch limit: distances from the pins
  Vec3 pinnedCentre_ = Vec3::Zero();               // m, centre of the pinned masses at the start
};

// Registers the "net" scene kind and the implicit integrators "implicit_euler" and
// "implicit_euler_blocks" (which run on any scene that provides its force Jacobians).
void registerLab(Registry& registry);

}  // namespace springlab::net
