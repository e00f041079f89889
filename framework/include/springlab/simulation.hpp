#pragma once
// The base of every lab's system, after the handout's Simulation class. One step is
// simulate(dt): the integrator asks for the forces (evaluateForces, which zeroes them and calls
// the lab's accumulateForces) as often as its method needs (once for symplectic Euler, four
// times for RK4) and moves the state, then the lab's afterStep makes its corrections
// (kinematic masses, colliders) and the blow-up check looks at the result.
// What it holds:
//   - the model (masses, springs, gravity, and a lab's own settings): written while a lab
//     builds its scene, then only through editModel (pinning, the panel's sliders, a study's
//     scaling), so whatever a lab derives from it is derived again there;
//   - the data (state, forces, counters): changes every step;
//   - what the viewer, the `sim` command and the studies ask of a scene besides its physics
//     (name, shapes, sliders, observables, the region to frame): "nothing to show" defaults
//     that labs override.
#include <any>
#include <functional>
#include <map>
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
#include "springlab/solver_settings.hpp"
#include "springlab/spring.hpp"
#include "springlab/state.hpp"

namespace springlab {

// Counters an integrator's cost is measured in.
struct Stats {
  long steps = 0;             // integrator steps taken
  long forceEvaluations = 0;  // calls of evaluateForces
  long solverIterations = 0;  // linear solver iterations (implicit methods); XPBD sweeps and
                              // projective dynamics' local/global iterations count here too
  long constraintProjections = 0;  // XPBD: one constraint projected once
  long backSubstitutions = 0;      // projective dynamics: solves with the prefactored matrix
  long factorizations = 0;         // projective dynamics: sparse Cholesky factorisations
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

  // ======== physics ====================================================================

  // ---- model: written while a lab builds its scene, then only through editModel() ------
  int dimension;                 // 2 (planar, z = 0) or 3
  std::vector<Mass> masses;      // [n]
  std::vector<Triangle> triangles;  // [t] surface for drawing and wind (may be empty)
  Vec3 gravitation = Vec3::Zero();  // m/s^2
  // The scene's "integrator_options": option values by method name, then option name. Each
  // integrator set on this simulation receives its own (setIntegrator), so a study that
  // switches methods keeps the scene's XPBD iterations.
  std::map<std::string, std::map<std::string, int>> integratorOptions;

  // ---- data: changes every step -----------------------------------------------------
  State state;                   // positions [n], velocities [n], time
  std::vector<Vec3> force;       // [n] N, the forces solve() or a step's integrator last wrote
  Stats stats;
  SolverSettings solver;         // how hard implicit integrators solve (scene's "solver")
  PhaseProfile profile;          // where the steps' time goes, when enabled (sim --profile, benchmarks)

  int numOfMasses() const { return static_cast<int>(masses.size()); }
  // [s] the springs, indices into masses. Read-only: change them inside editModel, with
  // editSprings().
  const std::vector<Spring>& springs() const { return springs_; }

  // ---- the handout's names for a step ------------------------------------------------
  void init();                // force = 0 for every mass
  void solve();               // force = the forces at the current state (evaluateForces)
  void simulate(double dt);   // one step: the integrator (forces included), then afterStep
  void operate(double dt);    // the handout's whole step: simulate(dt)

  // ---- editing the model between steps -------------------------------------------------
  // The one way to change the model once the scene is built (masses, springs, gravity, and
  // a lab's own settings such as wind or gas): runs edit(*this), then forgets the
  // integrator's history (Verlet's previous positions belong to the old model) and re-arms
  // the blow-up check with the edited model's energy (an edit never counts as a blow-up).
  // The state stays; the edit may change velocities (a newly pinned mass stops). Then the
  // lab derives again what it keeps from the model (onModelEdited).
  void editModel(const std::function<void(Simulation&)>& edit);
  // The springs, to change: inside editModel's edit, or while a lab builds its scene (before
  // markInitialState). Anywhere else it throws std::logic_error.
  std::vector<Spring>& editSprings();
  // Pin a free mass or free a pinned one (a model edit; the mass stops).
  void togglePinned(int index);

  // ---- what integrators use ----------------------------------------------------------
  // Forces at an arbitrary state (not necessarily the current one); counts one evaluation.
  void evaluateForces(const State& s, std::vector<Vec3>& f);
  // A constant force per mass added to every evaluation (empty: none). The stability
  // instrument's: it holds a state that is not a rest in place, so that a step is linearised
  // there as at a rest (step_stability.cpp). Not part of the scene's energies.
  void setHoldingLoad(std::vector<Vec3> load) { holdingLoad_ = std::move(load); }
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
  // Put `integrator` in place (as setIntegrator) and hand back the one that ran, options and
  // all, to be put back later: stepStableDt settles the scene with symplectic Euler first.
  std::unique_ptr<Integrator> exchangeIntegrator(std::unique_ptr<Integrator> integrator);
  // Restore the initial state (model edits stay), forget integrator history.
  void reset();
  // The state reset() returns to (stability estimates use it after a blow-up).
  const State& initialState() const { return initialState_; }
  // Everything reset() puts back, as the run has it now: the state and forces, the counters,
  // the sources' and corrections' work, the user's hand, the lab's own data (saveLabData) and
  // the blow-up check's watch. A computation that resets and steps the scene in the middle of
  // a run (the blow-up check's stability limit) saves the run first and resumes it after, so
  // that the run goes on where it was: without the lab's data the rope's moving fixed end
  // jumped back to where it started. Only the integrator's history is not kept (resumeRun
  // restarts it, as reset does).
  struct SavedRun {
    State state;
    std::vector<Vec3> force;
    Stats stats;
    std::optional<int> grabbed;
    Vec3 grabTarget = Vec3::Zero();
    double sourceWork = 0.0, correctionWork = 0.0;
    bool lastStepWorkKnown = true;
    std::optional<std::pair<long, double>> sourcePowerAfter;
    std::optional<Energies> stepEnd;
    std::any labData;
    BlowUpCheck blowUpCheck;
  };
  SavedRun saveRun() const;
  void resumeRun(const SavedRun& saved);
  // Turn the blow-up check off for studies that want to watch a method fail.
  void setBlowUpCheck(bool enabled) { blowUpCheckEnabled_ = enabled; }
  bool blowUpCheckEnabled() const { return blowUpCheckEnabled_; }
  // J, the energy scale the blow-up check measured when it was last armed (reset, edits).
  double blowUpEnergyScale() const { return blowUpCheck_.energyScale(); }
  // The integrator's energy swing on this scene for the passivity detector
  // (BlowUpCheck::setEnergySwing; studies measure it at half the stability limit).
  void setEnergySwing(double total, double own) { blowUpCheck_.setEnergySwing(total, own); }
  // The largest step reversal a run at half the limit sustained (BlowUpCheck::setReversalSwing).
  void setReversalSwing(double speed) { blowUpCheck_.setReversalSwing(speed); }
  // What that run held along its time (BlowUpCheck::setReversalProfile).
  void setReversalProfile(ReversalProfile held) { blowUpCheck_.setReversalProfile(std::move(held)); }
  // Whether a blow-up's message names the likely cause from the step's exact limit
  // (BlowUpCheck::setExplainCause; studies' trials turn it off, they need only the verdict).
  void setBlowUpExplanation(bool explain) { blowUpCheck_.setExplainCause(explain); }
  // The stability limit of this scene's step (stepStableDt) when someone already computed it
  // (the viewer's worker, on a copy): the blow-up check then uses it instead of computing it
  // again, which on a 80-mass rope takes seconds. Forgotten when the integrator or the model
  // changes.
  void setKnownStepLimit(std::optional<double> dt) { knownStepLimit_ = dt; }
  std::optional<double> knownStepLimit() const { return knownStepLimit_; }

  // ---- diagnostics --------------------------------------------------------------------
  Energies energies() const;
  Vec3 momentum() const;
  // Upper bound (rad/s) on the highest angular frequency the scene's integrator must
  // resolve, without evaluating a force: by default the springs' Gershgorin bound
  // (springGershgorinBound); labs add the stiffness of their other forces (ground, gas,
  // contacts). lanczosEstimate (springlab/frequency_estimate.hpp) gives an estimate instead.
  virtual double angularFrequencyBound() const;
  // Whether the scene itself puts energy in at the current state (wind, a pump still
  // inflating): the blow-up check's passivity test then counts the source's work
  // (sourcePower) or, where the scene cannot say it, lets the energy rise. Moving pinned
  // masses and the user's drags are seen without it. Default: a passive scene.
  virtual bool suppliesEnergy() const { return false; }
  // The power (W) the scene's energy sources deliver at state s: the work rate v . f of the
  // forces that put energy in (the wind's, over every mass). Nothing when the scene cannot
  // say (a pump still inflating); 0 for a scene that supplies none. With it the blow-up check
  // holds a windy scene to passivity too: its total energy less the sources' work
  // (sourceWork) may not rise. Without it (the wind's work unknown) a flag under symplectic
  // Euler at ten times its limit ran at 6000 J with springs 14 times their length, unreported.
  virtual std::optional<double> sourcePower(const State& s) const {
    (void)s;
    return suppliesEnergy() ? std::nullopt : std::optional<double>(0.0);
  }
  // J, the work of the energy sources since the last reset (the trapezoid rule on their power
  // at each step's two ends), and whether the last step's was known (sourcePower said).
  double sourceWork() const { return sourceWork_; }
  bool lastStepWorkKnown() const { return lastStepWorkKnown_; }
  // J, the energy the lab's corrections after each step (afterStep: contacts that project
  // masses out, stretch limiting, a moving anchor) added since the last reset; negative where
  // they took energy out. Counted while the blow-up check runs (or trackCorrectionWork). An
  // instability the corrections cap is seen in it: past its limit a free corner of a cloth
  // lying on a slope jitters at 9 m/s, held by the stretch limit, while the total energy falls.
  double correctionWork() const { return correctionWork_; }
  // energies() at the end of the last step, kept when counting the corrections computed them
  // (the blow-up check's, right after the step; the state must not have changed since).
  Energies stepEndEnergies() const { return stepEnd_ ? *stepEnd_ : energies(); }
  void trackCorrectionWork(bool on) { trackCorrections_ = on; }
  // The total energy less the sources' and the corrections' work: what the step itself (the
  // integrator and the forces) made, which may not rise in a stable run (J).
  double energyBalance() const { return energies().total() - sourceWork_ - correctionWork_; }

  // ---- force terms, for the blow-up check's diagnosis -----------------------------------
  // The lab's force terms by name, indexed as its accumulateForces tests them with
  // forceTermOn(k) (e.g. "spring forces (exercise 1.1, springDamperForce)", "ground contact
  // ..."). When the forces go non-finite, the blow-up check turns each term off in turn and
  // names the one without which the force is finite. Empty (the default): it can only take
  // the springs and gravity away.
  virtual std::vector<std::string> forceTermNames() const { return {}; }
  // Leave term k out of the forces (-1: none); diagnostics only, restored at once.
  void muteForceTerm(int k) { mutedForceTerm_ = k; }

  // ---- the user's hand on a mass (viewer) ------------------------------------------------
  void grab(int index, const Vec3& target);  // mass follows target until release()
  void release();
  std::optional<int> grabbed() const { return grabbed_; }

  // ======== front end: what the viewer, `sim` and the studies show ========================
  // Nothing here is called inside a step; none of it changes the model except through
  // editModel. The defaults are a scene with nothing to show.
  // Short name of the lab's system for the HUD and error messages ("rope").
  virtual std::string kind() const = 0;
  // The sliders of declareParameters(), each set() made a model edit (editModel); the
  // Parameters refer to this simulation and live no longer than it.
  std::vector<Parameter> parameters();
  // Named quantities of the current state (volume, pressure, sag) for the HUD and studies.
  virtual std::vector<Observable> observables() const { return {}; }
  // Colliders and markers to draw, in the scene's current state.
  virtual std::vector<Shape> shapes() const { return {}; }
  // The user drags shapes()[index] (a movable one) to `center`; called once per substep
  // with the drag spread evenly over a frame, so the lab may derive the shape's velocity
  // (springlab/scene_shapes.hpp: ColliderDrag).
  virtual void moveShape(int index, const Vec3& center) { (void)index; (void)center; }
  // Velocity of whatever the scene lets the user drive (the rope's fixed end).
  virtual void setControlVelocity(const Vec3& velocity) { (void)velocity; }
  // Height of a horizontal ground y = h, when the scene has one (the viewer draws it there).
  virtual std::optional<double> groundHeight() const { return std::nullopt; }
  // The region the camera frames at the start; by default the masses' bounding box.
  virtual Bounds reach() const;

 protected:
  // ======== physics, for labs ============================================================
  // Add every force acting at state s into f (f arrives zeroed, size n).
  virtual void accumulateForces(const State& s, std::vector<Vec3>& f) = 0;
  // Energy of forces a lab adds beyond springs and gravity (ground repulsion, pressure).
  virtual double otherPotentialEnergy(const State& s) const { (void)s; return 0.0; }
  // Called after each integrator step: kinematic masses, dragged colliders, collision projection.
  virtual void afterStep(double dt) { (void)dt; }
  // Called by reset() after the initial state is back: restore the lab's own data.
  virtual void onReset() {}
  // The lab's own data that onReset restores and a step may change (the rope's moving
  // connection point, the colliders the user drags), for saveRun; restoreLabData puts back
  // what saveLabData returned. Default: a lab with no data of its own.
  virtual std::any saveLabData() const { return {}; }
  virtual void restoreLabData(const std::any& data) { (void)data; }
  // Called by editModel() after the edit, and by markInitialState() once the scene is built:
  // derive again what the lab keeps from the model (the cloth's fast spring pass).
  virtual void onModelEdited() {}
  // Whether accumulateForces adds force term k of forceTermNames() (false only while the
  // blow-up check's diagnosis leaves it out).
  bool forceTermOn(int k) const { return k != mutedForceTerm_; }
  // Remember the current state as the one reset() returns to; call at the end of building
  // (it ends the building: springs change only inside editModel from then on).
  void markInitialState();
  // The user put energy in through the lab's own controls (a dragged collider): the
  // blow-up check takes the new energy as part of the scene's scale.
  void admitUserEnergy() { blowUpCheck_.admitUserEnergy(*this); }

  // ======== front end, for labs ==========================================================
  // The sliders of the scene: get() reads the model, set() writes it (parameters() makes
  // each set() a model edit, so set() itself only assigns).
  virtual std::vector<Parameter> declareParameters() { return {}; }

 private:
  // The blow-up diagnosis takes the springs away for one evaluation (swapSprings).
  friend class BlowUpCheck;
  // Exchange the springs with `other` and let the lab derive again what it keeps.
  void swapSprings(std::vector<Spring>& other);

  std::vector<Spring> springs_;
  bool building_ = true;  // editSprings() allowed: the lab builds its scene, or editModel runs
  std::unique_ptr<Integrator> integrator_;
  State initialState_;
  BlowUpCheck blowUpCheck_;
  bool blowUpCheckEnabled_ = true;
  std::optional<double> knownStepLimit_;  // s, setKnownStepLimit
  std::vector<Vec3> holdingLoad_;          // N per mass, setHoldingLoad
  double sourceWork_ = 0.0;                // J, sourceWork()
  bool lastStepWorkKnown_ = true;
  double correctionWork_ = 0.0;            // J, correctionWork()
  bool trackCorrections_ = false;          // trackCorrectionWork
  State integrated_;                       // the integrator's result, before afterStep (kept buffers)
  std::optional<Energies> stepEnd_;        // stepEndEnergies, when this step computed them
  // The sources' power at the end of the last step, and that step's count: the next step's
  // start, unless the state was set by hand since.
  std::optional<std::pair<long, double>> sourcePowerAfter_;
  int mutedForceTerm_ = -1;  // index into forceTermNames(), -1: every term acts
  std::optional<int> grabbed_;
  Vec3 grabTarget_ = Vec3::Zero();
};

}  // namespace springlab
