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
#include <springlab/simulation.hpp>
#include <springlab/softbody/exercises.hpp>

namespace springlab::softbody {

// ---- The soft body system built from the exercises --------------------------------------

enum class ContactMethod { Penalty, Projection };

// A rigid obstacle: a plane (center = a point on it, axis = unit normal), a sphere (center,
// radius) or an axis-aligned box (center, axis = half extents). A movable one follows the
// user's drag; its velocity comes from the drag.
struct Obstacle {
  ShapeType type = ShapeType::Plane;
  Vec3 center = Vec3::Zero();  // m
  Vec3 axis = Vec3::UnitY();   // plane normal, or box half extents (m)
  double radius = 0.0;         // m, sphere
  bool movable = false;
  Vec3 velocity = Vec3::Zero();  // m/s, while the user drags it
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

  std::string kind() const override { return "soft body"; }
  std::vector<Shape> shapes() const override;
  void moveShape(int index, const Vec3& center) override;
  std::optional<double> groundHeight() const override;
  Bounds reach() const override;
  std::vector<Observable> observables() const override;
  std::vector<Parameter> parameters() override;
  void parametersChanged() override;
  double maxAngularFrequency() const override;

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

 private:
  Penetration penetration(const Vec3& x, const Obstacle& o) const;
  std::optional<int> floorIndex() const;  // the first horizontal plane facing up
  std::vector<int> drawnObstacles() const;  // obstacles shapes() lists, in order

  SoftBodyParameters p_;
  double restVolume_ = 0.0;      // m^3, of the rest shape
  double restPressure_ = 0.0;    // Pa, the target gas over the rest volume: the panel's slider
  double gravityY_ = 0.0;        // m/s^2, the panel's slider
  std::vector<Obstacle> initialObstacles_;
  std::vector<bool> moved_;      // [obstacles] the user moved it during this step
  double lastDt_ = 0.0;          // s
};

// Registers the "softbody" scene kind.
void registerLab(Registry& registry);

}  // namespace springlab::softbody
