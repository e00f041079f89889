#pragma once
// Lab 3: the pressure soft body, given code. The SoftBody system, its scene reader and the
// registration of the lab's scene kind, built on the exercises of
// springlab/softbody/exercises.hpp; the framework compiles this once and links it with the
// student's exercises (labs/03_softbody/) or the reference (solutions/03_softbody/).
#include <optional>
#include <string>
#include <vector>

#include <springlab/registry.hpp>
#include <springlab/scene_reader.hpp>
#include <springlab/scene_shapes.hpp>
#include <springlab/simulation.hpp>
#include <springlab/softbody/exercises.hpp>

namespace springlab::softbody {

// ---- The soft body system built from the exercises --------------------------------------

enum class ContactMethod { Penalty, Projection };

// A rigid obstacle: a plane (center = a point on it, normal), a sphere (center, radius) or
// an axis-aligned box (center, halfExtents). A movable one follows the user's drag; its
// velocity comes from the drag.
struct Obstacle {
  ShapeType type = ShapeType::Plane;
  Vec3 center = Vec3::Zero();       // m: a point on the plane, the sphere's or the box's centre
  Vec3 normal = Vec3::UnitY();      // plane: unit normal, pointing to the free side
  Vec3 halfExtents = Vec3::Zero();  // box: half its edge lengths along x, y and z (m)
  double radius = 0.0;              // sphere: radius (m)
  bool movable = false;
  Vec3 velocity = Vec3::Zero();     // m/s, while the user drags it
};

// Everything a soft body scene sets (keys and units in README's scene reference).
struct SoftBodyParameters {
  SurfaceMesh mesh;                    // rest shape, already placed at the scene's centre
  Vec3 velocity = Vec3::Zero();        // m/s, initial velocity of every mass
  double totalMass = 1.0;              // kg, spread equally over the vertices
  double springConstant = 100.0;       // N/m, edge springs
  double springFriction = 1.0;         // N s/m
  bool oppositeSprings = false;        // extra springs to the farthest vertex
  bool secondRingSprings = false;      // extra springs across each edge
  double extraSpringConstant = 0.0;    // N/m
  double extraSpringFriction = 0.0;    // N s/m
  double gas = 0.0;                    // J, target nRT
  double inflationTime = 0.0;          // s of simulated time to pump the gas in
  double airFriction = 0.0;            // N s/m per mass
  ContactMethod contactMethod = ContactMethod::Penalty;
  ContactMaterial contact;
  std::vector<Obstacle> obstacles;
  Vec3 wind = Vec3::Zero();            // m/s
  double windDrag = 0.0;               // N s/m^3 (3D), N s/m^2 (2D)
  Vec3 gravitation = Vec3::Zero();     // m/s^2
};

// Read the "softbody" section of a scene; mesh files are found relative to the scene file.
SoftBodyParameters readSoftBodyParameters(SceneReader& section, const SceneSettings& settings);

class SoftBody final : public Simulation {
 public:
  SoftBody(int dimension, SoftBodyParameters parameters);

  // Physics.
  double angularFrequencyBound() const override;
  // The terms of accumulateForces, in the order of ForceTerm (the blow-up check names one).
  enum ForceTerm { kSprings, kGravityAndAir, kPressure, kWind, kContact };
  std::vector<std::string> forceTermNames() const override;
  // The wind works on the body, and the pump until the gas is in.
  bool suppliesEnergy() const override {
    return (p_.windDrag > 0.0 && p_.wind.squaredNorm() > 0.0) || (p_.gas > 0.0 && state.time < p_.inflationTime);
  }
  // The wind's power v . F over every mass; nothing while the pump inflates (its work is not
  // a force's).
  std::optional<double> sourcePower(const State& s) const override;

  // Front end.
  std::string kind() const override { return "soft body"; }
  std::vector<Shape> shapes() const override;
  void moveShape(int index, const Vec3& center) override;
  std::optional<double> groundHeight() const override;
  Bounds reach() const override;
  std::vector<Observable> observables() const override;

  const SoftBodyParameters& model() const { return p_; }
  std::vector<Obstacle>& obstacles() { return p_.obstacles; }
  double restVolume() const { return restVolume_; }
  double volume(const State& s) const;  // m^3 (m^2 in 2D)
  double gas() const;                   // J, the nRT pumped in by the current state's time
  double gas(double time) const;        // J, the nRT pumped in by `time` (s)
  double pressure(const State& s) const;  // Pa (N/m in 2D)

 protected:
  void accumulateForces(const State& s, std::vector<Vec3>& f) override;
  double otherPotentialEnergy(const State& s) const override;
  void afterStep(double dt) override;
  void onReset() override;
  std::any saveLabData() const override;
  void restoreLabData(const std::any& data) override;
  std::vector<Parameter> declareParameters() override;

 private:
  Penetration penetration(const Vec3& x, const Obstacle& o) const;
  std::optional<GroundPlane> floor() const;  // the first plane facing straight up
  std::vector<int> drawnObstacles() const;  // obstacles shapes() lists, in order

  SoftBodyParameters p_;
  double restVolume_ = 0.0;      // m^3, of the rest shape
  std::vector<Obstacle> initialObstacles_;
  std::vector<ColliderDrag> drags_;  // [obstacles] where the user holds each one
  mutable std::vector<Vec3> sourceForces_;  // [n] scratch for sourcePower (a step allocates nothing)
};

// Registers the "softbody" scene kind.
void registerLab(Registry& registry);

}  // namespace springlab::softbody
