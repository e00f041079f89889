#pragma once
// The base of every lab's system, after the handout's Simulation class:
//   operate(dt) = init() (zero forces), solve() (add up forces), simulate(dt) (integrate).
// The model (masses, springs, gravity) stays constant during a run; the data (state, force)
// changes every step. Every lab derives from it and fills in accumulateForces().
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "springlab/diagnostics.hpp"
#include "springlab/force_jacobian.hpp"
#include "springlab/integrator.hpp"
#include "springlab/mass.hpp"
#include "springlab/not_implemented.hpp"
#include "springlab/math.hpp"
#include "springlab/parameter.hpp"
#include "springlab/phase_profile.hpp"
#include "springlab/shape.hpp"
#include "springlab/spring.hpp"
#include "springlab/state.hpp"

namespace springlab {

// Counters an integrator's cost is measured in.
struct Stats {
  long steps = 0;             // integrator steps taken
  long forceEvaluations = 0;  // calls of evaluateForces
  long solverIterations = 0;  // linear solver iterations (implicit methods)
};

// A triangle of mass indices, counter-clockwise seen from outside (cloth, soft bodies).
struct Triangle {
  int a, b, c;
};

class Simulation {
 public:
  explicit Simulation(int dimension);
  virtual ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  // ---- model: constant during a run -------------------------------------------------
  int dimension;                 // 2 (planar, z = 0) or 3
  std::vector<Mass> masses;      // [n]
  std::vector<Spring> springs;   // [s] indices into masses
  std::vector<Triangle> triangles;  // [t] surface for drawing and wind (may be empty)
  Vec3 gravitation = Vec3::Zero();  // m/s^2

  // ---- data: changes every step -----------------------------------------------------
  State state;                   // positions [n], velocities [n], time
  std::vector<Vec3> force;       // [n] N, forces of the last solve()
  Stats stats;
  PhaseProfile profile;          // where the steps' time goes, when enabled (sim --profile, benchmarks)

  int numOfMasses() const { return static_cast<int>(masses.size()); }

  // ---- the handout's rhythm ----------------------------------------------------------
  void init();                // zero every force
  void solve();               // add up the forces at the current state into `force`
  void simulate(double dt);   // advance one step with the current integrator
  void operate(double dt);    // one step: the integrator calls init() and solve() itself

  // ---- what integrators use ----------------------------------------------------------
  // Forces at an arbitrary state (not necessarily the current one); counts one evaluation.
  void evaluateForces(const State& s, std::vector<Vec3>& f);
  // 1/m, or 0 for a mass moved only by the scene (pinned or grabbed by the user).
  // Inline: integrators call it for every mass in every step.
  double inverseMass(int i) const {
    if (grabbed_ && *grabbed_ == i) return 0.0;
    return masses[static_cast<std::size_t>(i)].inverseMass();
  }
  // Add the force Jacobians dF/dx and dF/dv at state s into J (implicit integrators call it
  // after J.clear()). Returns false when the scene cannot linearise its forces (the default);
  // forceJacobian() then throws, naming the scene.
  virtual bool addForceJacobian(const State& s, ForceJacobian& J) { (void)s; (void)J; return false; }
  // J = the force Jacobians at s; throws std::invalid_argument naming `who` (an integrator)
  // when the scene does not provide them.
  void forceJacobian(const State& s, ForceJacobian& J, std::string_view who);

  // ---- integrator and run control ----------------------------------------------------
  void setIntegrator(std::unique_ptr<Integrator> integrator);
  Integrator& integrator() const { return *integrator_; }
  // Restore the initial state (model edits stay), forget integrator history.
  void reset();
  // The state reset() returns to (stability estimates use it after a blow-up).
  const State& initialState() const { return initialState_; }
  // Turn the blow-up check off for studies that want to watch a method fail.
  void setBlowUpCheck(bool enabled) { blowUpCheckEnabled_ = enabled; }

  // ---- diagnostics --------------------------------------------------------------------
  Energies energies() const;
  Vec3 momentum() const;
  // Estimate of the highest angular frequency (rad/s); labs add their own stiffnesses.
  virtual double maxAngularFrequency() const;

  // ---- interaction (viewer) ----------------------------------------------------------
  void grab(int index, const Vec3& target);  // mass follows target until release()
  void release();
  std::optional<int> grabbed() const { return grabbed_; }
  void togglePinned(int index);
  // Velocity of whatever the scene lets the user drive (the rope's fixed end).
  virtual void setControlVelocity(const Vec3& velocity) { (void)velocity; }
  // Parameters the viewer may edit; parametersChanged() is called after an edit.
  virtual std::vector<Parameter> parameters() { return {}; }
  virtual void parametersChanged() {}
  // Short name of the lab's system for the HUD ("rope").
  virtual std::string kind() const = 0;

  // ---- what the viewer shows besides masses, springs and triangles -------------------
  // Colliders and markers to draw, in the scene's current state.
  virtual std::vector<Shape> shapes() const { return {}; }
  // The user drags shapes()[index] (a movable one) to `center`; called once per substep
  // with the drag spread evenly over a frame, so the lab may derive the shape's velocity.
  virtual void moveShape(int index, const Vec3& center) { (void)index; (void)center; }
  // Height of a horizontal ground y = h, when the scene has one (the viewer draws it there).
  virtual std::optional<double> groundHeight() const { return std::nullopt; }
  // The region the camera frames at the start: by default the masses' bounding box.
  virtual Bounds reach() const;
  // Named quantities of the current state (volume, pressure, sag) for the HUD and studies.
  virtual std::vector<Observable> observables() const { return {}; }

 protected:
  // Add every force acting at state s into f (f arrives zeroed, size n).
  virtual void accumulateForces(const State& s, std::vector<Vec3>& f) = 0;
  // Energy of forces a lab adds beyond springs and gravity (ground repulsion, pressure).
  virtual double otherPotentialEnergy(const State& s) const { (void)s; return 0.0; }
  // Called after each integrator step: kinematic masses, collision projection.
  virtual void afterStep(double dt) { (void)dt; }
  // Called by reset() after the initial state is back: restore the lab's own data.
  virtual void onReset() {}
  // Remember the current state as the one reset() returns to; call at the end of building.
  void markInitialState();
  // The user put energy in through the lab's own controls (a dragged collider, a pressure
  // slider): the blow-up check takes the new energy as part of the scene's scale.
  void admitUserEnergy() { blowUpCheck_.admitUserEnergy(*this); }

 private:
  std::unique_ptr<Integrator> integrator_;
  State initialState_;
  BlowUpCheck blowUpCheck_;
  bool blowUpCheckEnabled_ = true;
  std::optional<int> grabbed_;
  Vec3 grabTarget_ = Vec3::Zero();
};

}  // namespace springlab
