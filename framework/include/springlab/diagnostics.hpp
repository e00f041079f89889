#pragma once
// Diagnostics every system provides: energies, momentum, the largest angular frequency and
// the blow-up check that stops a run with a message naming the likely cause.
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "springlab/math.hpp"
#include "springlab/state.hpp"

namespace springlab {

class Simulation;

struct Energies {
  double kinetic = 0.0;        // J, sum 1/2 m |v|^2
  double gravitational = 0.0;  // J, sum -m g . x
  double elastic = 0.0;        // J, sum 1/2 k (l - L0)^2 over springs
  double other = 0.0;          // J, potentials a lab adds (ground repulsion, pressure)
  double total() const { return kinetic + gravitational + elastic + other; }
};

// Upper bound on the highest angular frequency of the springs (rad/s), by Gershgorin's
// theorem on M^-1 K: w_max^2 <= max_i 2 sum_{springs at i} k / m_i. It is exact for a
// uniform chain, w_max = 2 sqrt(k/m), and never underestimates.
double springGershgorinBound(const Simulation& sim);

// Raised when a run blew up; what() says when, why it is likely, and the safe dt.
class BlowUp : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// How much of the masses' motion turns back every step, held over a window of steps: the
// measure of detector 5 (a capped instability, see BlowUpCheck). Per step it takes the largest
// quarter second difference of a mass's velocity over three steps, |v_k - 2 v_k-1 + v_k-2| / 4:
// a motion that reverses each step with amplitude A gives A, a smooth one |d3x/dt3| dt^2 / 4. A
// stable step damps the fast modes whose motion reverses (their eigenvalues lie inside the unit
// circle), an impact excites them once; only a step past its limit keeps them going, when a
// contact or the stretch limit caps their growth (measured on the shipped scenes under
// symplectic Euler: at 0.97 times the limit at most 0.06 m/s, 34 times what the same scene holds
// at half the limit; at 1.03 times 0.6 to 35 m/s).
class StepReversal {
 public:
  static constexpr int kWindow = 64;
  // Takes the velocities after a step and returns the smallest reversal over the last kWindow
  // steps (m/s), or 0 while it dies out (the newer half of the window stays below the older
  // half's largest) and until that many steps were recorded.
  double record(const std::vector<Vec3>& velocities);
  // Forgets the steps recorded (a state not made by the step: reset, a drag).
  void restart() { count_ = 0; }
  // The smallest reversal over the last kWindow steps, dying out or not (0 until that many):
  // what a stable run's profile records (ReversalProfile).
  double smallestInWindow() const;
  // The mass whose reversal was largest in the last step recorded.
  int lastMass() const { return lastMass_; }

 private:
  std::vector<Vec3> last_, before_;  // the velocities one and two steps back
  std::array<double, kWindow> recent_{};
  int count_ = 0;
  int lastMass_ = -1;
};

// The step reversal a stable run (at half the limit) held along its simulated time: per bin of
// StepReversal::kWindow steps, the largest smallest-in-window. Detector 5 holds a run to it at
// the same time: the reversal a stable scene sustains dies out over seconds (the cloth settling
// on the slope: 2e-4 m/s at 1 s, 2e-7 at 4 s), a capped instability's stays (5e-3 m/s at 1.03
// times the limit), so its largest over the whole run lets the latter through.
// It also keeps the largest kinetic energy per bin, which detector 6 holds a run to.
struct ReversalProfile {
  double binTime = 0.0;         // s
  std::vector<double> held;     // m/s, one per bin from t = 0
  std::vector<double> kinetic;  // J, the largest kinetic energy in each bin
  // The largest within kReach bins of time t; past the end, of the last kReach bins.
  double near(double t) const;
  double kineticNear(double t) const;  // the same for the kinetic energy
  static constexpr long kReach = 2;
};

// Watches a run, with six detectors: a non-finite state; kinetic plus elastic plus other
// potential energy (otherPotentialEnergy: ground, gas) grown far beyond the energy the scene
// could ever hold (its initial energy plus the work gravity can do: the runaway factor); and
// passivity: a scene that puts no energy in (no wind, pump, moving pinned mass or user drag)
// cannot gain energy, so a total energy (gravity included) above the highest it had while
// energy came in, by more than the integrator's own energy oscillation, is a blow-up. A
// source whose work the scene counts (the wind's: Simulation::sourcePower, sourceWork) is
// taken off the total, so a windy scene is held to passivity as well; the pump's and a moving
// anchor's are not counted, and the ceiling follows them up. Past
// the stability limit a nonlinear scene often saturates instead of overflowing (springs flip,
// the state turns to noise at a bounded energy): passivity catches that. And the climb:
// passivity counted from the lowest energy since energy last came in, for an instability that
// saturates after the scene has lost most of its start (kClimbFraction). The climb is for
// methods that rest at the scene's static equilibrium (Integrator::restsAtStaticEquilibrium);
// the others (XPBD, projective dynamics) are held to passivity only where a swing run measured
// the energy they rest holding (setEnergySwing), and otherwise by the first two detectors.
// And a capped instability (StepReversal): a mode past its limit
// that a one-sided contact or the stretch limit holds down (a corner of cloth jittering at
// 4 m/s on the slope, a ball resting on a penalty floor jittering at 3 m/s) loses to them
// what the step puts in, and no energy detector sees it.
//
// The oscillation allowed: a stable step's true energy swings about a conserved (modified)
// one. On a mode at a fraction r = dt / limit of its limit symplectic Euler's energy swings
// by a factor up to (1 + r) / (1 - r) of the mode's energy (a Verlet method's 1 / (1 - r^2),
// the damped methods' less): 2 / (1 - r) - 1 = 3 at r = 1/2, 65 at r = 0.97. So the swing
// measured in a run at half the limit (setEnergySwing), times kSwingMargin = 64
// (twice the ratio 65 / 3 between the two dts, rounded up), bounds the swing of any stable
// run up to 0.97 of the limit; the energy a saturated instability gains, a good part of the
// scene's own, is far above it. Without a measured swing (the viewer) the allowance is
// kPassivityFraction of the energy scale, and only a run past the step's limit is stopped.
class BlowUpCheck {
 public:
  // Energy growth factor over the scene's energy scale that counts as a runaway.
  static constexpr double kRunawayFactor = 100.0;
  // The message's calm run (a run stopped below the limit where the scene settles and past the
  // one where it was stopped is run again from its start at half its dt): linearised at this
  // many evenly spaced times (the trampoline's catch dips below 0.8 of the rest's limit for
  // 6 ms of its first 62), and only where replaying it takes at most this many mass-steps
  // (masses times steps: 2e7 is some 10 s of stepping; a longer run keeps the limit where it
  // was stopped).
  static constexpr int kCalmSamples = 32;
  static constexpr double kCalmWork = 2e7;
  // Of those times, the limit itself is computed at most at this many (a radius past 1, or a
  // step that is not smooth there); the others are cleared by one spectral radius each.
  static constexpr int kCalmLimits = 8;
  // A run at dt passes near the calm run's states, not through them: dt counts as past a
  // state's limit from this fraction of it (the self-colliding cloth under the midpoint rule
  // blows up at 0.99 times the 0.4725 ms its calm run linearises to after the landing, and
  // lasts at 0.97 times; the targets' own 3 %).
  static constexpr double kCalmMargin = 0.97;
  // Rise of a passive scene's total energy, in energy scales, that counts as a blow-up when
  // no swing was measured.
  static constexpr double kPassivityFraction = 0.5;
  // The measured swing is allowed this many times over (see above), and never less than
  // kSwingFloor of the energy scale (round-off of a scene whose energy does not move). The
  // floor is far above round-off (about 1e-13 of the scale) and far below what a user sees:
  // the scale counts gravity's work over every spring's length (543 J on the 32 x 32 cloth,
  // which holds about 1 J), and at 1e-4 of it (0.054 J) symplectic Euler at 1.07 times its
  // limit there passed while gaining 0.014 J from nothing in its first 0.04 s.
  static constexpr double kSwingMargin = 64.0;
  static constexpr double kSwingFloor = 1e-7;
  // Detector 4, a climb: a passive scene that has lost energy cannot win it back. An
  // instability that saturates after the scene has dissipated most of its start (the rope
  // under the midpoint rule just past its limit: falls from 0 to -47.6 J, then climbs back by
  // 5 to 9 J and swings there) never reaches the ceiling above, so the climb counts from the
  // lowest energy since energy last came in. A stable step's energy still moves: fast (its
  // own oscillation near the limit: 88.7 J in one step, 180 J within 64, on the instantly
  // inflated ball at 0.97 times its limit) and slowly (the midpoint rule on the resting ball
  // wanders 0.07 J about its low over minutes). So a climb counts only past kFastSwingMargin times the largest
  // rise within kFastWindow steps seen so far, and past kClimbFraction of what the scene lost
  // from its ceiling to its low (measured margins: at 0.97 times the limit every shipped scene,
  // the damped chain and the inflated ball stay below half of that; the rope's midpoint rule at
  // 1.03 times climbs 5 times past it).
  // Detector 5: motion that reverses every step, sustained over StepReversal::kWindow steps,
  // by more than kReversalMargin times the most the scene sustained at half the limit
  // (setReversalSwing) and kReversalFloor of the speed the energy scale stands for
  // (sqrt(2 scale / mass): 33 m/s on the 32 x 32 cloth); with the swing run's profile
  // (setReversalProfile), by kReversalMargin times what it held at the same time and
  // kProfileFloor of that speed; without a swing run, by more than kReversalFloor. Only while
  // dt is past the step's limit: below it the reversal is a contact's chatter, not the step's.
  // Detector 6, held motion: with the swing run's profile, past the step's limit, a mean
  // kinetic energy over StepReversal::kWindow steps above kMotionMargin times the most the swing
  // run held near the same time and kMotionFloor of the energy scale. Explicit Euler's capped
  // instability does not turn back every step: past its limit a mode at its own frequency grows
  // (gamma / w^2 < dt) until a contact holds it. The cube resting on its floor at 1.04 times
  // the limit: a corner keeps moving at up to 3.3 m/s for minutes, 0.2 J above the rest, while
  // at 0.9 times the cube comes to rest (1e-28 J); its reversal, 1.4e-4 m/s, stays below
  // detector 5's floor.
  static constexpr double kMotionMargin = 64.0;
  static constexpr double kMotionFloor = 1e-7;
  static constexpr double kReversalMargin = 64.0;
  static constexpr double kReversalFloor = 1e-3;
  static constexpr double kProfileFloor = 1e-5;
  static constexpr int kFastWindow = 64;
  static constexpr double kFastSwingMargin = 2.0;
  static constexpr double kClimbFraction = 0.02;

  void arm(const Simulation& sim);  // measure the energy scale of the scene as it starts
  // The user put energy in (dragged, pinned): never count that as a blow-up.
  void admitUserEnergy(const Simulation& sim);
  // Whether the state differs from the one the last check passed (or arm() saw): set by hand
  // between steps.
  bool changedSinceLastCheck(const Simulation& sim) const;
  // Throws BlowUp naming the detector that fired and the likely cause. A non-finite state:
  // the forces are evaluated again at the last finite state the check saw; when one is
  // non-finite there, the message names the first such mass and the term that makes it
  // non-finite (the lab's forceTermNames(), each left out in turn; else springs, gravity, or
  // the lab's own forces), and does not blame dt. Otherwise it gives the exact stability
  // limit of the step that runs (stepStableDt, where the scene settles: a state blown up by
  // then says nothing about the scene's stiffness) and compares dt with it; when dt is below
  // it, also the limit linearised where the run was stopped (a squash, a contact the rest does
  // not have), which may still be below dt, and where it is (or that step is not smooth) the
  // stiffest state a calm run from the start at half dt passes through (kCalmSamples). Computing the
  // limit resets the lab's own data (a dragged collider returns); the state and the counters
  // are put back as the blow-up left them. Remembers the state as the last finite one when
  // it passes.
  void check(Simulation& sim, double dt);

  double energyScale() const { return energyScale_; }
  // The integrator's own energy swing on this scene (J: the largest rise of the total energy
  // less the sources' work above its lowest so far in a run at half the stability limit), and
  // the same for the step's own energy (less the corrections' work too); negative: not measured.
  void setEnergySwing(double total, double own) {
    energySwing_ = total;
    ownSwing_ = own;
  }
  // The largest reversal (m/s, StepReversal) a run at half the stability limit sustained;
  // negative: not measured (detector 5 then holds its floor alone, past the step's limit);
  // infinite: detectors 5 and 6 off.
  void setReversalSwing(double speed) { reversalSwing_ = speed; }
  // The reversal that run held along its time (ReversalProfile): detector 5 then holds a run
  // to it at the same time instead of to its largest. Empty: not measured.
  void setReversalProfile(ReversalProfile profile) { profile_ = std::move(profile); }
  // Whether the message computes the exact limit of the step to name the likely cause (on by
  // default). A study's trials need only the verdict: the limit costs up to seconds per
  // blow-up (an 80-mass rope: 10 s), and a chart meets dozens of them.
  void setExplainCause(bool explain) { explainCause_ = explain; }
  // The rise of a passive scene's total energy (less the sources' work; own: the step's own
  // energy) above its ceiling that counts as a blow-up (J).
  double passivityAllowance(bool own = false) const;

 private:
  // The message's "why it blew up" part for a non-finite state: the forces' story when they
  // went non-finite first, else empty (the step made the state non-finite from finite forces).
  std::string blameForces(Simulation& sim);

  double energyScale_ = 0.0;  // J
  // J, the highest energy the scene reached while energy came in, of the two that passivity
  // holds: the step's own (the total, gravity included, less the sources' and the corrections'
  // work) and the total less the sources' work; a passive scene may rise above neither by more
  // than passivityAllowance(own) / passivityAllowance().
  double passiveCeiling_ = 0.0;
  // The climb holds the latter only: at a rest the corrections hold (the trampoline against its
  // tethers in the wind) the step's own balance drifts by O(dt) per second, the sources' work
  // estimated at the step's ends missing what the corrections take out (9 mJ/s under velocity
  // Verlet at 0.8 of its limit), and a climb counted from its low would read that as a blow-up.
  double totalCeiling_ = 0.0;
  double energySwing_ = -1.0;  // J, setEnergySwing; negative: not measured
  double ownSwing_ = -1.0;     // J, the step's own energy's
  // Whether dampers act on the mass whose motion turned back most in the last step: only then
  // does a stable step damp that motion (an undamped mode at 0.97 of its limit turns back every
  // step for ever, the mass on its undamped spring at 0.17 m/s). Two force evaluations, only
  // when detector 5 is about to fire.
  bool turningMassIsDamped(Simulation& sim);
  int undampedMass_ = -1;  // the last mass turningMassIsDamped found undamped
  double reversalSwing_ = -1.0;  // m/s, setReversalSwing
  ReversalProfile profile_;      // setReversalProfile
  double speedScale_ = 0.0;      // m/s, sqrt(2 energy scale / total mass)
  StepReversal reversal_;
  // Detector 6: the kinetic energies of the last StepReversal::kWindow steps (a ring).
  std::array<double, StepReversal::kWindow> kinetics_{};
  long kineticCount_ = 0;
  // Without a measured swing the allowance cannot know how far a stable step's energy swings
  // near its limit (symplectic Euler's (1 + r) / (1 - r) has no bound as r -> 1), so a rise
  // counts only when dt is past the limit of the linearised step (computed once per dt).
  bool beyondLimitOrMeasured(Simulation& sim, double dt);
  bool beyondLimit(Simulation& sim, double dt);  // dt past that limit, measured swing or not
  double limitDt_ = -1.0;    // s, the dt beyondLimit_ was computed for
  bool beyondLimit_ = true;
  double limit_ = NAN;       // s, the exact limit computed at limitDt_ (reused by the message)
  bool explainCause_ = true;
  // The climb (detector 4): the lowest total energy since energy last came in, the energies of
  // the last kFastWindow checks (a ring) and the largest rise within such a window so far.
  double low_ = 0.0;       // J
  std::array<double, kFastWindow> recent_{};
  int recentCount_ = 0;
  int recentNext_ = 0;
  double fastSwing_ = 0.0;  // J
  void restartClimb(double energy);
  // The climb's allowance now: the larger of the passivity allowance, the fast swings' and the
  // fraction of what the scene lost.
  double climbAllowance() const;
  // The state at the last check that passed (or at arm()): where the forces are evaluated
  // again when the state turns non-finite.
  State last_;
  long lastStep_ = 0;
  // When the check was armed: the step (0: the run is the scene's from its start, which the
  // message may run again), the step's own energy balance (Simulation::energyBalance) and the
  // corrections' work, so that the message can say what each put in since.
  long armedStep_ = 0;
  double armedBalance_ = 0.0;
  double armedCorrections_ = 0.0;
};

}  // namespace springlab
