#pragma once
// The handout's RopeSimulation: a chain of masses joined by damped springs, one end fixed
// to a connection point the user can move, gravity, air friction and a ground. This base
// class holds the rope's parameters and state; Lab 1 derives from it and writes the forces,
// the construction and the fixed end (labs/01_rope/).
#include <string>
#include <vector>

#include "springlab/registry.hpp"
#include "springlab/scene_reader.hpp"
#include "springlab/simulation.hpp"

namespace springlab {

// The ground: a horizontal plane y = height that pushes back on masses below it.
struct Ground {
  double height = -1.5;     // m, y of the ground plane
  double repulsion = 100;   // N/m, pushes up in proportion to the depth below the ground
  double friction = 0.2;    // N s/m, slows horizontal motion of masses below the ground
  double absorption = 2.0;  // N s/m, slows downward motion of masses below the ground
};

// Everything a rope scene sets (units as in README's scene reference).
struct RopeParameters {
  int numOfMasses = 80;               // masses in the chain, >= 2
  double mass = 0.05;                 // kg, each mass
  double springConstant = 10000.0;    // N/m
  double springLength = 0.05;         // m, rest length of each spring
  double springFrictionConstant = 0.2;  // N s/m, damping along each spring
  Vec3 ropeConnectionPos = Vec3::Zero();  // m, where the fixed end starts
  Vec3 ropeConnectionVel = Vec3::Zero();  // m/s, how the fixed end moves at the start
  Vec3 direction = Vec3::UnitX();     // unit vector from the fixed end along the rope at rest
  Vec3 gravitation = Vec3(0.0, -9.81, 0.0);  // m/s^2
  double airFrictionConstant = 0.02;  // N s/m
  Ground ground;
};

// Read the "rope" section of a scene file (keys and units in README's scene reference).
RopeParameters readRopeParameters(SceneReader& section, const Vec3& gravity, int dimension);

// The rope's resolution rule (Registry::addScene): "masses" changes the number of masses while
// the physical rope stays the same: its length, its free mass, its stretch under load (k L0),
// its material damping (kd L0), and drag and ground contact per kilogram.
ResolutionRule ropeResolutionRule();

class RopeSimulation : public Simulation {
 public:
  RopeSimulation(int dimension, const RopeParameters& parameters);

  // The handout's members.
  Vec3 ropeConnectionPos;             // m
  Vec3 ropeConnectionVel;             // m/s, set by the user's keys
  double springConstant;              // N/m, every spring's k (the panel sets both)
  double springFrictionConstant;      // N s/m
  double airFrictionConstant;         // N s/m
  Ground ground;

  std::string kind() const override { return "rope"; }
  void setControlVelocity(const Vec3& velocity) override;
  double angularFrequencyBound() const override;
  std::optional<double> groundHeight() const override { return ground.height; }
  // Where the rope is and swings: its masses, and the circle its free-hanging part (down to
  // the ground) sweeps around the connection point, cut at the ground.
  Bounds reach() const override;
  // "sag": how far the lowest mass hangs below the connection point (m);
  // "tip_y": the height of the free end (m).
  std::vector<Observable> observables() const override;

 protected:
  // Energy stored in the ground's repulsion, 1/2 k depth^2 per mass below the ground.
  double otherPotentialEnergy(const State& s) const override;
  // The fixed end returns to where the scene put it.
  void onReset() override;
  std::any saveLabData() const override;
  void restoreLabData(const std::any& data) override;
  // Lab code calls this after filling masses, springs and state, to start the run.
  void finishBuilding();
  std::vector<Parameter> declareParameters() override;

 private:
  Vec3 initialConnectionPos_;
  Vec3 initialConnectionVel_;
};

}  // namespace springlab
