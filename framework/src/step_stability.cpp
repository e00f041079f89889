#include "springlab/step_stability.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <random>

#include <Eigen/Eigenvalues>

#include "springlab/frequency_estimate.hpp"
#include "springlab/symplectic_euler.hpp"

namespace springlab {

namespace {

// One free coordinate: mass i, axis c.
struct Dof {
  int mass;
  int axis;
};

// The coordinates that can move at the initial state, positions then velocities.
std::vector<Dof> freeCoordinates(const Simulation& sim) {
  std::vector<Dof> dofs;
  for (int i = 0; i < sim.numOfMasses(); ++i) {
    if (sim.inverseMass(i) == 0.0) continue;
    for (int c = 0; c < sim.dimension; ++c) dofs.push_back({i, c});
  }
  return dofs;
}

// Typical length of the scene: the springs' mean rest length, else the extent of the masses.
double typicalLength(const Simulation& sim) {
  double sum = 0.0;
  for (const Spring& s : sim.springs()) sum += s.springLength;
  if (!sim.springs().empty() && sum > 0.0) return sum / static_cast<double>(sim.springs().size());
  const Bounds b = sim.Simulation::reach();
  const double extent = (b.hi - b.lo).norm();
  return extent > 0.0 ? extent : 1.0;
}

Eigen::VectorXd randomDirection(int size, unsigned seed);
template <class Apply>
Eigen::MatrixXd topEigenvectors(const Apply& apply, int n, int k, unsigned seed, bool distinctOnly);
template <class ApplyK, class ApplyC>
Eigen::MatrixXd stiffestForTheirDamping(const ApplyK& applyK, const ApplyC& applyC, const Eigen::VectorXd& stiffest,
                                        int n, int k);

// ritzRadius's orthonormalising factor B of X (X B orthonormal), kept while X stays the same.
struct RitzBasis {
  Eigen::MatrixXd X, B;
};

// Runs the scene from its initial state, or from it moved by a perturbation, and records
// the free coordinates after each step, made dimensionless: positions over the typical
// length, velocities over that length times w_max. The blow-up check is off meanwhile, and
// the simulation is left reset.
class LinearisedRuns {
 public:
  LinearisedRuns(Simulation& sim, const StepStabilityOptions& o)
      : sim_(sim), dofs_(freeCoordinates(sim)), solverSettings_(sim.solver), cancelled_(o.cancelled) {
    // An implicit step's linear solve stops at a residual relative to the whole right-hand
    // side: an error of that size, not proportional to the perturbation, would swamp the
    // finite differences. The linearised step is the step with its system solved exactly (a
    // solver error that does not grow is not an instability), so the runs here solve tightly.
    sim_.solver.tolerance = std::min(sim_.solver.tolerance, 1e-12);
    // Twelve decades are hundreds of block-Jacobi iterations on all but the smallest systems,
    // and each run starts the solver afresh (Integrator::reset), so the "auto" choice would
    // spend every run's first step finding that out: the runs take smoothed aggregation.
    if (sim_.solver.preconditioner == "auto") sim_.solver.preconditioner = "smoothed_aggregation";
    sim_.reset();
    length_ = typicalLength(sim_);
    frequency_ = stiffestFrequency(sim_.initialState());
    // Where to linearise: the state the scene settles to, not the state it starts in. A
    // damped scene spends all but its first moments near its rest state, and a run blows up
    // there or not at all: a start far from rest (the mass on its spring released stretched,
    // the rope released straight) stiffens or softens the springs for a few steps only, and
    // growth over a few steps is a transient, not an instability (the mass on its spring:
    // RK4's limit at its start is 0.077 s, the runs' and the closed form's at rest 0.283 s).
    // Scenes that never settle (wind, a moving anchor) are linearised where the settling
    // budget leaves them, a state of their ordinary motion.
    if (o.at) {
      base_ = *o.at;
      given_ = true;
    } else if (o.settle) {
      try {
        base_ = settledState(o);
      } catch (const StepStabilityCancelled&) {
        sim_.solver = solverSettings_;  // no destructor runs for a constructor that throws
        throw;
      }
    }
    if (!base_.pos.empty()) frequency_ = std::max(frequency_, stiffestFrequency(base_));
    // An implicit method that rests at the force equilibrium is linearised at the settled state
    // as at a rest: a constant load cancels the force left there (the settled state is where
    // the first swing turned). Away from rest a linear solve's step has a term that grows with
    // dt (its matrix's change times its solution, which carries the residual force; at large
    // dt the step is a Newton step towards the equilibrium): on the 32 x 32 hanging cloth it
    // made implicit Euler's limit 47.6 ms, where its runs at 160 ms settle to the same drape and
    // its step at a plain run's rest is stable at every dt. A constant force has no Jacobian:
    // nothing else of the step changes (the per-particle blocks' limits move by up to 4 %, the
    // trampoline's 3.18 -> 3.31 ms, and on the slope in strong wind 11.8 ms -> none). Explicit
    // methods are left as they were (their limits were checked against runs from this state).
    if (!base_.pos.empty() && !given_ && sim_.integrator().restsAtStaticEquilibrium() &&
        !std::isfinite(sim_.integrator().stabilityConstant())) {
      std::vector<Vec3> residual;
      sim_.evaluateForces(base_, residual);
      for (int i = 0; i < sim_.numOfMasses(); ++i) {
        if (sim_.inverseMass(i) != 0.0) residual[static_cast<std::size_t>(i)] *= -1.0;
        else residual[static_cast<std::size_t>(i)].setZero();
      }
      sim_.setHoldingLoad(std::move(residual));
    }
    // Finite-difference steps relative to the state's own scale: a perturbation below the
    // round-off of the coordinates (a scene far from the origin, a large velocity) would
    // measure round-off, so it is at least sqrt(machine epsilon) times the largest of them.
    double position = 0.0, velocity = 0.0;
    const State& at = base_.pos.empty() ? sim_.initialState() : base_;
    for (const Dof& d : dofs_) {
      position = std::max(position, std::abs(at.pos[d.mass][d.axis]));
      velocity = std::max(velocity, std::abs(at.vel[d.mass][d.axis]));
    }
    epsilon_ = o.relativePerturbation;
    const double roundOff = std::sqrt(std::numeric_limits<double>::epsilon());
    positionStep_ = std::max(epsilon_ * length_, roundOff * position);
    velocityStep_ = std::max(epsilon_ * length_ * frequency_, roundOff * velocity);
    restore();
  }

  // The state the runs start from (the method's rest at the dt probed, else the settled
  // state), with the integrator's history forgotten.
  void restore() {
    sim_.reset();
    const State& from = own_.pos.empty() ? base_ : own_;
    if (from.pos.empty()) return;
    sim_.state.pos = from.pos;
    sim_.state.vel = from.vel;
    sim_.state.time = from.time;
  }

  // Kinetic damping, one step of it: when the kinetic energy has passed a peak (fell below
  // `last`), every velocity is set to zero and the integrator's history forgotten. Returns the
  // kinetic energy to compare the next step's with.
  double dampAtPeak(double now, double last) {
    if (now >= last) return now;
    for (Vec3& v : sim_.state.vel) v.setZero();
    sim_.integrator().reset();
    return 0.0;
  }

  // Where the method itself rests at dt. A method that solves the springs approximately
  // (XPBD or projective dynamics with a fixed number of iterations, each step started from
  // the inertial prediction) does not rest at the force equilibrium the settling found but
  // lower, at a place that depends on dt (the 8 x 8 fabric: XPBD at 20 ms hangs at 8 %
  // strain, not 2.6 %). Its step linearised at the force equilibrium is a map at a point it
  // moves away from, with a radius of 1.37 there although the cloth comes to rest; at its own
  // rest the radius is below 1.
  //
  // So, for a method that says it rests elsewhere (Integrator::restsAtStaticEquilibrium),
  // the settling goes on with its own step at dt (kinetic damping, as settledState) until a
  // step leaves the state in place (it moves no coordinate by the finite differences'
  // perturbation) or the budget runs out. Where that settling grows or turns non-finite, the
  // runs start from the settled state (an instability is the linearisation's to find).
  void settleAt(double dt, const StepStabilityOptions& o) {
    if (dt == ownDt_) return;
    ownDt_ = dt;
    own_ = State{};
    if (given_ || base_.pos.empty() || sim_.integrator().restsAtStaticEquilibrium()) return;
    const Stats stats = sim_.stats;
    const bool checked = sim_.blowUpCheckEnabled();
    sim_.setBlowUpCheck(false);
    // How far a step moves a state, in units of the finite differences' perturbation.
    auto motion = [&](const State& before) {
      double moved = 0.0;
      for (const Dof& d : dofs_) {
        moved = std::max({moved, std::abs(sim_.state.pos[d.mass][d.axis] - before.pos[d.mass][d.axis]) / positionStep_,
                          std::abs(sim_.state.vel[d.mass][d.axis] - before.vel[d.mass][d.axis]) / velocityStep_});
      }
      return moved;
    };
    restore();
    const double start = sim_.energies().total();
    const double scale = sim_.blowUpEnergyScale();
    const long budget = std::clamp<long>(o.settleEvaluations / std::max<long>(1, static_cast<long>(dofs_.size())),
                                         100, o.settleSteps);
    double kinetic = 0.0;
    bool stopped = false;
    for (long k = 0; k < budget; ++k) {
      if (k % 64 == 0 && isCancelled()) {
        stopped = true;
        break;
      }
      const State before = sim_.state;
      try {
        sim_.operate(dt);
      } catch (const std::exception&) {
        own_ = State{};
        break;
      }
      ++steps_;
      if (motion(before) < 1.0) {
        if (k > 0) own_ = before;  // the method's rest (k = 0: the settled state is it)
        break;
      }
      const Energies e = sim_.energies();
      if (!std::isfinite(e.total()) || e.total() > start + scale) {
        own_ = State{};
        break;
      }
      kinetic = dampAtPeak(e.kinetic, kinetic);
      if (k + 1 == budget) own_ = sim_.state;  // the budget's end: where its settling got to
    }
    if (!own_.pos.empty()) {
      for (Vec3& v : own_.vel) v.setZero();
    }
    sim_.setBlowUpCheck(checked);
    sim_.reset();
    sim_.stats = stats;
    if (stopped) throw StepStabilityCancelled();
  }

  // The finite differences' perturbation times f (the smoothness check: 1 / 16, then 16).
  void scalePerturbation(double f) {
    positionStep_ *= f;
    velocityStep_ *= f;
  }

  // The masses a contact holds one-sidedly at the state, for the modal directions (the dense
  // probe finds its own, per coordinate): one step at dt along a pseudo-random direction and
  // along its negative. A smooth step answers the two with opposite differences; a mass resting
  // on a projected collider does not (a push inwards is projected away and kicks its velocity by
  // the push over dt, a pull outwards moves freely: explicit Euler's first step from rest leaves
  // such a mass exactly on the surface, where the perturbation's sign decides its contact). Every
  // coordinate of such a mass, position and velocity, is held from then on: the modal
  // directions leave it where it is, as the contact does. Returns how many masses were held.
  int findHeldMasses(double dt) {
    const int n = static_cast<int>(dofs_.size());
    const Eigen::VectorXd u = randomDirection(size(), 2026);
    Eigen::MatrixXd base, plus, minus;
    runInto(dt, 0, {}, base);
    runInto(dt, 0, u, plus);
    runInto(dt, 0, -u, minus);
    held.assign(static_cast<std::size_t>(size()), 0);
    if (base.cols() < 1 || plus.cols() < 1 || minus.cols() < 1) return 0;
    const Eigen::VectorXd up = plus.col(0) - base.col(0), down = minus.col(0) - base.col(0);
    // A coordinate's two differences, position and velocity alike, in the recorded units:
    // one-sided where their sum is a tenth of the larger and the larger stands out of round-off
    // (a millionth of the largest difference anywhere).
    const double floor = 1e-6 * std::max(up.cwiseAbs().maxCoeff(), down.cwiseAbs().maxCoeff());
    std::vector<char> mass(static_cast<std::size_t>(sim_.numOfMasses()), 0);
    for (int r = 0; r < size(); ++r) {
      const double larger = std::max(std::abs(up[r]), std::abs(down[r]));
      if (larger > floor && std::abs(up[r] + down[r]) > 0.1 * larger) mass[static_cast<std::size_t>(dofs_[r % n].mass)] = 1;
    }
    for (int j = 0; j < n; ++j) {
      const char h = mass[static_cast<std::size_t>(dofs_[j].mass)];
      held[static_cast<std::size_t>(j)] = held[static_cast<std::size_t>(n + j)] = h;
    }
    const int count = static_cast<int>(std::count(mass.begin(), mass.end(), 1));
    if (count == 0) held.clear();
    return count;
  }

  ~LinearisedRuns() {
    sim_.setHoldingLoad({});
    sim_.solver = solverSettings_;
    sim_.reset();
  }
  LinearisedRuns(const LinearisedRuns&) = delete;
  LinearisedRuns& operator=(const LinearisedRuns&) = delete;

  int size() const { return 2 * static_cast<int>(dofs_.size()); }
  bool isCancelled() const { return cancelled_ && cancelled_(); }
  double maxAngularFrequency() const { return frequency_; }
  int steps() const { return steps_; }
  // Whether the runs start where a free body that fell has come to rest on what it hit (its
  // impact's ringing damped away, settledState), contacts pressed by its weight.
  bool restsAfterImpact() const { return afterImpact_; }

  // Snapshots [size x (count + 1)] after 1 .. count + 1 steps at dt, starting from the
  // initial state plus epsilon times `direction` (dimensionless, largest entry 1; empty: none).
  // Stops early (fewer columns) when the state turns non-finite.
  Eigen::MatrixXd run(double dt, int count, const Eigen::VectorXd& direction) {
    Eigen::MatrixXd out;
    runInto(dt, count, direction, out);
    return out;
  }

  // run() into `out`, whose storage is kept from one run to the next (the 64 x 64 cloth's
  // snapshots are 0.4 MB: a fresh allocation per run cost page faults, a tenth of its time).
  void runInto(double dt, int count, const Eigen::VectorXd& direction, Eigen::MatrixXd& out) {
    restoreMoved(direction);
    runFromCurrentInto(dt, count, out);
  }

  // restore(), then the state moved by epsilon times `direction` (empty: not moved).
  void restoreMoved(const Eigen::VectorXd& direction) {
    restore();
    if (direction.size() != size()) return;
    State& s = sim_.state;
    const int n = static_cast<int>(dofs_.size());
    for (int j = 0; j < n; ++j) {
      s.pos[dofs_[j].mass][dofs_[j].axis] += positionStep_ * direction[j];
      s.vel[dofs_[j].mass][dofs_[j].axis] += velocityStep_ * direction[n + j];
    }
  }

  // Steps from the current state (the integrator's history forgotten), as run() records them.
  Eigen::MatrixXd runFromCurrent(double dt, int count = 0) {
    Eigen::MatrixXd out;
    runFromCurrentInto(dt, count, out);
    return out;
  }
  void runFromCurrentInto(double dt, int count, Eigen::MatrixXd& out) {
    if (isCancelled()) throw StepStabilityCancelled();
    sim_.integrator().reset();
    const bool checked = sim_.blowUpCheckEnabled();
    sim_.setBlowUpCheck(false);
    out.resize(size(), count + 1);
    int columns = 0;
    try {
      for (int k = 0; k <= count; ++k) {
        sim_.operate(dt);
        ++steps_;
        if (!recordState(out, k)) break;
        columns = k + 1;
      }
    } catch (...) {
      sim_.setBlowUpCheck(checked);
      sim_.reset();
      throw;
    }
    // The simulation is left where the run ended (the next run restores its start, the
    // destructor resets it): a reset per run re-arms the blow-up check, an energy sum over
    // every mass, 4 % of the 64 x 64 cloth's prediction.
    sim_.setBlowUpCheck(checked);
    if (columns < count + 1) out.conservativeResize(Eigen::NoChange, columns);
  }

  // The current state into column c of `out`, in the recorded (dimensionless) coordinates:
  // positions over the typical length, velocities over that length times w_max. False when a
  // coordinate is not finite.
  bool recordState(Eigen::MatrixXd& out, Eigen::Index c) const {
    const State& s = sim_.state;
    const int n = static_cast<int>(dofs_.size());
    bool finite = true;
    for (int j = 0; j < n; ++j) {
      out(j, c) = s.pos[dofs_[j].mass][dofs_[j].axis] / length_;
      out(n + j, c) = s.vel[dofs_[j].mass][dofs_[j].axis] / (length_ * frequency_);
      finite = finite && std::isfinite(out(j, c)) && std::isfinite(out(n + j, c));
    }
    return finite;
  }

  // A long run from the start state (plus epsilon times `direction`, as run()), recorded
  // every `stride` steps: column c is the state after (c + 1) stride steps. Stops early
  // (fewer columns) when the state turns non-finite or the step throws.
  Eigen::MatrixXd sampledRun(double dt, long steps, long stride, const Eigen::VectorXd& direction) {
    restoreMoved(direction);
    sim_.integrator().reset();
    const bool checked = sim_.blowUpCheckEnabled();
    sim_.setBlowUpCheck(false);
    Eigen::MatrixXd out(size(), steps / stride);
    long columns = 0;
    try {
      for (long k = 1; k <= steps && columns < out.cols(); ++k) {
        if (k % 256 == 0 && isCancelled()) throw StepStabilityCancelled();
        sim_.operate(dt);
        ++steps_;
        if (k % stride != 0) continue;
        if (!recordState(out, columns)) break;
        ++columns;
      }
    } catch (const StepStabilityCancelled&) {
      sim_.setBlowUpCheck(checked);
      sim_.reset();
      throw;
    } catch (const std::exception&) {
      // A step that throws (a lab's own blow-up check) ends the run where it got to.
    }
    sim_.setBlowUpCheck(checked);
    out.conservativeResize(Eigen::NoChange, columns);
    return out;
  }

  // The perturbations in the recorded (dimensionless) coordinates: positions over the typical
  // length, velocities over that length times w_max.
  Eigen::VectorXd perturbationScale() const {
    const Eigen::Index n = static_cast<Eigen::Index>(dofs_.size());
    Eigen::VectorXd scale(2 * n);
    scale.head(n).setConstant(positionStep_ / length_);
    scale.tail(n).setConstant(velocityStep_ / (length_ * frequency_));
    return scale;
  }

  // The largest angular frequency at a state: Lanczos on the forces' Jacobian there, else the
  // lab's bound; 1 rad/s when neither finds one.
  double stiffestFrequency(const State& at) {
    const Stats stats = sim_.stats;
    double w = 0.0;
    try {
      w = lanczosEstimate(sim_, at).maxAngularFrequency;
    } catch (const std::exception&) {
      w = 0.0;
    }
    sim_.stats = stats;
    if (!(w > 0.0) || !std::isfinite(w)) w = sim_.angularFrequencyBound();
    return w > 0.0 && std::isfinite(w) ? w : 1.0;
  }

  // Dynamic relaxation with kinetic damping: symplectic Euler (the framework's own, with the
  // lab's after-step corrections) at a quarter of its undamped limit, every velocity set to
  // zero whenever the kinetic energy passes a peak, until the first such peak once no pump
  // inflates and no fallen body is still ringing from its impact (see below), or the budget
  // of force evaluations runs out (the 64 x 64 cloth gets about a hundred steps: its
  // springs' local tension, which sets the stiffest modes, forms within those). The step
  // halves and the settling starts again if the energy grows (damping or contacts stiffer
  // than w_max says); the start state is kept if it never settles stably.
  State settledState(const StepStabilityOptions& o) {
    const Stats stats = sim_.stats;
    const bool checked = sim_.blowUpCheckEnabled();
    sim_.setBlowUpCheck(false);
    std::unique_ptr<Integrator> own = sim_.exchangeIntegrator(std::make_unique<SymplecticEuler>());
    const long budget = std::clamp<long>(o.settleEvaluations / std::max<long>(1, static_cast<long>(dofs_.size())),
                                         100, o.settleSteps);
    State settled;
    bool stopped = false;
    bool freeBody = true;
    for (int i = 0; i < sim_.numOfMasses(); ++i) freeBody = freeBody && sim_.inverseMass(i) != 0.0;
    for (double dt = 0.5 / frequency_, tries = 0; tries < 4 && settled.pos.empty() && !stopped; dt *= 0.5, ++tries) {
      sim_.reset();
      double fallEnergy = 0.0;  // the largest kinetic energy an impact stopped (J)
      bool ringing = false;     // an impact's peaks have not yet fallen to a millionth of it
      // What pulls a free body at its start (gravity): where nothing does, it cannot fly. The
      // springs and the gas cancel in it up to round-off, which is not a pull (a scale of the
      // scene's accelerations: its length times w_max^2).
      Vec3 startPull = freeBody ? commonAcceleration() : Vec3::Zero();
      if (startPull.norm() <= 1e-9 * length_ * frequency_ * frequency_) startPull.setZero();
      double start = sim_.energies().total();
      // Growth: a passive scene under kinetic damping only loses energy, up to symplectic
      // Euler's own swing, so a rise of a hundredth of its energy scale is the step growing (the
      // 64 x 64 cloth: 0.5 / w_max is 2.9 times its damped limit, and it gained 17 J in 100
      // steps, below the scale of 1098 J that counted before). A scene that supplies energy
      // (wind, a pump) may rise by the whole scale.
      const double scale = sim_.blowUpEnergyScale() * (sim_.suppliesEnergy() ? 1.0 : 0.01);
      double kinetic = 0.0;
      bool grew = false;
      // The budget is not spent while a pump still inflates: up to four budgets more, the
      // settling waits for it (the squeezed ball, 1926 coordinates: its budget of 207 steps of
      // 0.8 ms ended at 0.166 s, before the pump's 0.2 s, and the limit was the half-inflated
      // ball's, 2.772 ms under the midpoint rule, where the inflated ball's is 2.364 ms and its
      // rest breaks at 0.97 times the first).
      // Nor while a free body is still in flight or has not yet hit what it falls on, nor while
      // it rings from its impact: up to nine budgets more (the ball dropped from 1 m, 642
      // masses: its budget of 207 steps of 0.8 ms ended at 0.17 s, in the air, 0.3 s before it
      // lands; symplectic Euler's limit there is 1.78 ms, at its rest on the floor 1.47 ms, the
      // floor's damper included, as at a plain run's rest after 12 s).
      bool pumping = false;
      bool flying = false;
      bool flew = false;
      auto falling = [&] { return flying || ringing || (flew && fallEnergy == 0.0); };
      for (long k = 0; k < budget || (pumping && k < 5 * budget) || (falling() && k < 10 * budget); ++k) {
        if (k % 64 == 0 && isCancelled()) {
          stopped = true;
          break;
        }
        try {
          sim_.simulate(dt);
        } catch (const std::exception&) {
          grew = true;
          break;
        }
        const Energies e = sim_.energies();
        // A pump still inflating puts in energy the scene cannot count (the cube's gas, 41 J
        // over an energy scale of 12 J): the start follows it up, as the blow-up check's
        // ceiling does.
        pumping = sim_.suppliesEnergy() && !sim_.sourcePower(sim_.state);
        if (pumping) start = std::max(start, e.total());
        if (!std::isfinite(e.total()) || e.total() > start + scale) {
          grew = true;
          break;
        }
        // A free body (no mass pinned) that falls reaches its first peak where it hits what it
        // falls on: a peak of its common motion (more than half of the kinetic energy in the
        // centre of mass's), not of the springs' swing. Its state there is the impact's, squashed
        // for a moment by the fall and left at once; the body lives at rest on what it hit. So
        // after an impact the settling goes on until the peaks have fallen to a millionth of the
        // fall's. The cube (26 masses, pumped round over 0.3 s while it drops): linearised at
        // its impact, the Verlets' limits were 2.7 and 1.6 ms, RK4's 3.8 ms, the midpoint rule's
        // 4.7 ms, where the runs fail at 13.7, 13.6, 22.9 and 7.4 ms; at its rest on the floor
        // (0.86 s later) they are 13.9, 13.9, 22.9 and 7.4 ms.
        const bool peak = e.kinetic < kinetic;
        // In flight until the first impact: still speeding up along its common motion (the air's
        // drag slows the gain, only what it hits turns it), or not yet moving where it is pulled.
        if (fallEnergy == 0.0 && startPull.squaredNorm() > 0.0) {
          const Vec3 a = commonAcceleration();
          const Vec3 v = commonVelocity();
          flying = a.dot(v) > 0.0 || (v.norm() * frequency_ < 1e-3 * a.norm() && a.dot(startPull) > 0.0);
          flew = flew || flying;
        } else {
          flying = false;
        }
        // An impact: a peak where the common motion carries most of the kinetic energy, or the
        // first peak after a flight ended (the ball without gas: its bottom stops on the floor,
        // its top falls on, and the common motion's share is below half at the peak).
        const bool impact =
            peak && freeBody && (bulkKinetic() > 0.5 * e.kinetic || (flew && !flying && fallEnergy == 0.0));
        if (impact) fallEnergy = std::max(fallEnergy, kinetic);
        const bool fallDamped = !peak || fallEnergy == 0.0 || kinetic < 1e-6 * fallEnergy;
        if (peak && fallEnergy > 0.0) ringing = !fallDamped;
        // In flight a peak is the springs' swing (a fall's own kinetic energy only grows): it
        // is damped away, the fall's common velocity kept.
        const Vec3 keep = flying && peak && !impact ? commonVelocity() : Vec3::Zero();
        kinetic = dampAtPeak(e.kinetic, kinetic);
        if (keep.squaredNorm() > 0.0) {
          for (int i = 0; i < sim_.numOfMasses(); ++i) sim_.state.vel[static_cast<std::size_t>(i)] = keep;
          kinetic = sim_.energies().kinetic;
        }
        // Stop at the first peak of the kinetic energy after ten steps (its velocities just set
        // to zero), or at the budget: the first swing has turned and the springs' tension has
        // formed. Settling on to full rest (no mass moving a billionth of the typical length
        // in a step) moved the limits by up to 2 % (the inflated ball: 4.28 -> 4.22 ms, where
        // the runs fail at 4.41 ms) and costs the whole budget on a cloth.
        // Not while a pump still inflates (energy comes in that the scene cannot count): the
        // gas is not yet what the runs live with, and a face it starts to push out is unstable
        // physics, at any dt. Nor just after an impact, nor at one (above).
        double fastest = 0.0;
        for (const Dof& d : dofs_) fastest = std::max(fastest, std::abs(sim_.state.vel[d.mass][d.axis]));
        if (k > 10 && fastest * dt < 1e-9 * length_ && kinetic == 0.0 && !pumping && !impact && fallDamped && !flying)
          break;
      }
      if (!grew && !stopped) {
        settled = sim_.state;
        afterImpact_ = fallEnergy > 0.0;
      }
    }
    sim_.exchangeIntegrator(std::move(own));
    sim_.setBlowUpCheck(checked);
    sim_.reset();
    sim_.stats = stats;
    if (stopped) throw StepStabilityCancelled();
    if (!settled.pos.empty()) {
      // The settled state at rest: only the free masses' motion is relaxed away.
      for (Vec3& v : settled.vel) v.setZero();
    }
    return settled;
  }

  // The free masses' common velocity, their momentum over their mass (m/s).
  Vec3 commonVelocity() const {
    Vec3 momentum = Vec3::Zero();
    double mass = 0.0;
    for (int i = 0; i < sim_.numOfMasses(); ++i) {
      if (sim_.inverseMass(i) == 0.0) continue;
      momentum += sim_.masses[i].m * sim_.state.vel[i];
      mass += sim_.masses[i].m;
    }
    return mass > 0.0 ? Vec3(momentum / mass) : Vec3::Zero();
  }

  // The free masses' common acceleration at the current state, their net force over their mass
  // (m/s^2): the springs' and the gas's forces cancel in it, gravity, drag and contacts do not.
  Vec3 commonAcceleration() {
    std::vector<Vec3>& f = forceScratch_;
    f.assign(static_cast<std::size_t>(sim_.numOfMasses()), Vec3::Zero());
    sim_.evaluateForces(sim_.state, f);
    Vec3 force = Vec3::Zero();
    double mass = 0.0;
    for (int i = 0; i < sim_.numOfMasses(); ++i) {
      if (sim_.inverseMass(i) == 0.0) continue;
      force += f[static_cast<std::size_t>(i)];
      mass += sim_.masses[i].m;
    }
    return mass > 0.0 ? Vec3(force / mass) : Vec3::Zero();
  }

  // The kinetic energy of the free masses' common motion, 1/2 M |v_cm|^2 (J).
  double bulkKinetic() const {
    double mass = 0.0;
    for (int i = 0; i < sim_.numOfMasses(); ++i) {
      if (sim_.inverseMass(i) != 0.0) mass += sim_.masses[i].m;
    }
    return 0.5 * mass * commonVelocity().squaredNorm();
  }


  // Whether the integrator keeps no history between steps: two steps from the state land
  // where one step, a reset and a step from its result land. Then the map is probed one step
  // from the state itself (the Jacobian there, even when the scene moves); otherwise by the
  // second step of two (d_2 = J d_1 after the history has formed). The state is perturbed
  // first: at rest in equilibrium nothing moves, and every method would look history-free.
  bool historyFree(double dt) {
    if (historyFree_) return *historyFree_;
    const Eigen::VectorXd nudge = randomDirection(size(), 2026);
    const Eigen::MatrixXd twoSteps = run(dt, 1, nudge);
    const Eigen::MatrixXd oneStep = run(dt, 0, nudge);
    bool same = twoSteps.cols() == 2 && oneStep.cols() == 1;
    if (same) {
      restore();
      State& s = sim_.state;
      const int n = static_cast<int>(dofs_.size());
      for (int j = 0; j < n; ++j) {
        s.pos[dofs_[j].mass][dofs_[j].axis] = oneStep(j, 0) * length_;
        s.vel[dofs_[j].mass][dofs_[j].axis] = oneStep(n + j, 0) * length_ * frequency_;
      }
      s.time += dt;
      const Eigen::MatrixXd again = runFromCurrent(dt);
      same = again.cols() == 1 && (again.col(0) - twoSteps.col(1)).cwiseAbs().maxCoeff() <=
                                      1e-12 * std::max(1.0, twoSteps.col(1).cwiseAbs().maxCoeff());
    }
    historyFree_ = same;
    return same;
  }

  // modalDirections(count), computed once.
  const Eigen::MatrixXd& directions(int count) {
    if (directions_.cols() == 0) directions_ = modalDirections(count);
    return directions_;
  }

  // Directions (orthonormal columns, dimensionless state coordinates) that hold the modes
  // which set a limit: the `count` stiffest modes of M^-1 K, the `count` most damped of
  // M^-1 C and the count / 2 (or count) stiffest for their damping (largest w^2 / gamma) at the state
  // (K = -dF/dx, C = -dF/dv by central differences of the forces), each as a displacement
  // and as a velocity. For a linear scene with proportional
  // damping these are invariant under the step, and the Ritz values on them are the modes'
  // exact eigenvalues; otherwise they are the modes most likely to fail first.
  Eigen::MatrixXd modalDirections(int count) {
    restore();
    const int n = static_cast<int>(dofs_.size());
    const State at = sim_.state;
    const Stats stats = sim_.stats;
    std::vector<Vec3> plus, minus;
    // B u = M^-1/2 A M^-1/2 u with A d = -(F(moved by +h d) - F(moved by -h d)) / 2h, moving
    // positions (A = K) or velocities (A = C).
    auto mass = [&](int j) { return 1.0 / sim_.inverseMass(dofs_[j].mass); };
    auto symmetric = [&](bool velocities) {
      return [&, velocities](const Eigen::VectorXd& u) {
        Eigen::VectorXd d(n);
        for (int j = 0; j < n; ++j) d[j] = u[j] / std::sqrt(mass(j));
        Eigen::VectorXd out = Eigen::VectorXd::Zero(n);
        const double largest = d.cwiseAbs().maxCoeff();
        if (largest == 0.0) return out;
        const double h = (velocities ? velocityStep_ : positionStep_) / largest;
        State up = at, down = at;
        for (int j = 0; j < n; ++j) {
          Vec3& a = velocities ? up.vel[dofs_[j].mass] : up.pos[dofs_[j].mass];
          Vec3& b = velocities ? down.vel[dofs_[j].mass] : down.pos[dofs_[j].mass];
          a[dofs_[j].axis] += h * d[j];
          b[dofs_[j].axis] -= h * d[j];
        }
        sim_.evaluateForces(up, plus);
        sim_.evaluateForces(down, minus);
        for (int j = 0; j < n; ++j) {
          const int i = dofs_[j].mass, c = dofs_[j].axis;
          out[j] = -(plus[i][c] - minus[i][c]) / (2.0 * h) / std::sqrt(mass(j));
        }
        return out;
      };
    };
    const auto applyK = symmetric(false);
    const auto applyC = symmetric(true);
    const Eigen::MatrixXd stiff = topEigenvectors(applyK, n, count, 2024, false);
    const Eigen::MatrixXd damped = topEigenvectors(applyC, n, count, 2025, true);
    const Eigen::MatrixXd light = stiffestForTheirDamping(
        applyK, applyC, stiff.cols() > 0 ? Eigen::VectorXd(stiff.col(0)) : Eigen::VectorXd(), n, std::max(1, count / 2));
    sim_.stats = stats;

    // Mode shapes x = M^-1/2 psi, as displacements and as velocities.
    Eigen::MatrixXd U = Eigen::MatrixXd::Zero(size(), 2 * (stiff.cols() + damped.cols() + light.cols()));
    int column = 0;
    for (const Eigen::MatrixXd* modes : {&stiff, &damped, &light}) {
      for (Eigen::Index c = 0; c < modes->cols(); ++c) {
        Eigen::VectorXd shape(n);
        for (int j = 0; j < n; ++j) shape[j] = (*modes)(j, c) / std::sqrt(mass(j));
        U.col(column++).head(n) = shape;
        U.col(column++).tail(n) = shape;
      }
    }
    // Orthonormal (Gram-Schmidt, twice), without the directions the two sets share.
    Eigen::Index kept = 0;
    for (Eigen::Index c = 0; c < U.cols(); ++c) {
      Eigen::VectorXd v = U.col(c);
      const double before = v.norm();
      for (int pass = 0; pass < 2; ++pass) v -= U.leftCols(kept) * (U.leftCols(kept).transpose() * v);
      if (v.norm() > 1e-8 * before) U.col(kept++) = v.normalized();
    }
    return U.leftCols(std::max<Eigen::Index>(1, kept));
  }

 private:
  Simulation& sim_;
  std::vector<Dof> dofs_;
  double length_ = 1.0;     // m
  double frequency_ = 1.0;  // rad/s
  double epsilon_ = 1e-6;
  double positionStep_ = 1e-6;  // m, the finite differences' perturbation of a position
  double velocityStep_ = 1e-6;  // m/s, of a velocity
  SolverSettings solverSettings_;  // the scene's own, put back when the runs end
  std::function<bool()> cancelled_;  // StepStabilityOptions::cancelled
  State base_;              // where the map is linearised: the settled state (empty: the initial one)
  bool given_ = false;      // base_ is StepStabilityOptions::at: linearised there, as it is
  State own_;               // the method's own rest at ownDt_ where it is not base_ (empty: base_)
  double ownDt_ = -1.0;     // s, the dt own_ was settled for
  int steps_ = 0;
  bool afterImpact_ = false;  // the settling stopped where a fallen body came to rest on what it hit
                              // (never with StepStabilityOptions::at: no settling then)
  Eigen::MatrixXd directions_;  // [size x ...] modalDirections
  std::optional<bool> historyFree_;
  std::vector<Vec3> forceScratch_;  // commonAcceleration's forces

 public:
  // The coordinates a contact holds at the settled state (found once, by radiusOf's first
  // dense probe; empty until then).
  std::vector<char> held;
  // radiusOf's matrices, kept from one radius to the next.
  struct Scratch {
    Eigen::MatrixXd base, moved, opposite, X, Y;
    Eigen::VectorXd u;
    RitzBasis basis;  // X's Gram factor, while X stays the same
  } scratch;
};

// The largest |eigenvalue| of the map that takes the columns of X to those of Y, on X's
// range (Rayleigh-Ritz): with the Gram matrix G = X^T X = W L W^T, the map in the
// orthonormal basis X W L^-1/2 is L^-1/2 W^T (X^T Y) W L^-1/2. Directions with
// sqrt(L) below 1e-7 of the largest are dropped: there the differences are round-off (a mode
// the step all but removes, whose eigenvalue is near 0 and cannot be the largest).
//
// `basis`, when given, keeps X and its B from the last call: a step without history is probed
// by the perturbations themselves, the same X at every dt, and its Gram matrix (a product of
// the 64 x 64 cloth's 24576 x 40 X with itself, 6 % of RK4's prediction there) is formed once.
double ritzRadius(const Eigen::Ref<const Eigen::MatrixXd>& X, const Eigen::Ref<const Eigen::MatrixXd>& Y,
                  RitzBasis* basis = nullptr) {
  if (X.cols() == 0) return 0.0;
  // A square X of full rank (the whole Jacobian, no coordinate held): the map is Y X^-1,
  // whose eigenvalues are those of X^-1 Y; one QR instead of the Gram matrix's eigenvectors
  // (a third of the 80-mass rope's prediction).
  if (X.rows() == X.cols()) {
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(X);
    qr.setThreshold(1e-7);
    if (qr.rank() == X.cols()) {
      const Eigen::EigenSolver<Eigen::MatrixXd> eig(qr.solve(Y), false);
      return eig.eigenvalues().cwiseAbs().maxCoeff();
    }
  }
  const Eigen::MatrixXd H = X.transpose() * Y;
  if (!basis || basis->X.rows() != X.rows() || basis->X.cols() != X.cols() || basis->X != X) {
    const Eigen::MatrixXd G = X.transpose() * X;
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> gram(G);
    const Eigen::VectorXd& l = gram.eigenvalues();  // ascending
    const double largest = l[l.size() - 1];
    if (!(largest > 0.0)) return 0.0;
    Eigen::Index first = 0;
    while (first < l.size() && !(l[first] > 1e-14 * largest)) ++first;
    const Eigen::Index rank = l.size() - first;
    Eigen::MatrixXd B = gram.eigenvectors().rightCols(rank) * l.tail(rank).cwiseSqrt().cwiseInverse().asDiagonal();
    if (!basis) {
      const Eigen::MatrixXd A = B.transpose() * H * B;
      const Eigen::EigenSolver<Eigen::MatrixXd> eig(A, false);
      return eig.eigenvalues().cwiseAbs().maxCoeff();
    }
    basis->X = X;
    basis->B = std::move(B);
  }
  const Eigen::MatrixXd& B = basis->B;
  const Eigen::MatrixXd A = B.transpose() * H * B;
  const Eigen::EigenSolver<Eigen::MatrixXd> eig(A, false);
  return eig.eigenvalues().cwiseAbs().maxCoeff();
}

// ritzRadius for X whose columns lie along coordinate axes: column l is x_l times axis
// axes[l] (the whole Jacobian of a step without history, one coordinate per run). The
// orthonormal basis is those axes, so the map there is A(k, l) = Y(axes[k], l) / x_l: no
// Gram matrix, no QR, only the eigenvalues.
double axisRitzRadius(const std::vector<Eigen::Index>& axes, const Eigen::Ref<const Eigen::VectorXd>& x,
                      const Eigen::Ref<const Eigen::MatrixXd>& Y) {
  const Eigen::Index m = static_cast<Eigen::Index>(axes.size());
  if (m == 0) return 0.0;
  Eigen::MatrixXd A(m, m);
  for (Eigen::Index l = 0; l < m; ++l) {
    for (Eigen::Index k = 0; k < m; ++k) A(k, l) = Y(axes[static_cast<std::size_t>(k)], l) / x[l];
  }
  const Eigen::EigenSolver<Eigen::MatrixXd> eig(A, false);
  return eig.eigenvalues().cwiseAbs().maxCoeff();
}

// The k modes stiffest for their damping (`stiffest`: the stiffest mode's vector): the largest
// ratios mu = u^T K u / u^T C u (K, C
// mass-normalised, applied by `applyK`, `applyC`; for proportional damping mu = w^2 / gamma
// of a mode). Neither the stiffest nor the most damped modes: explicit Euler fails first on
// the largest mu (its limit on a mode is gamma / w^2), the midpoint rule nearly so, and a
// scene whose spring dampers leave some motion to the air alone (the ball's and the rope's
// sideways motion, damped by air a thousand times less) has them at moderate frequencies:
// the coarse ball's explicit Euler limit is 0.32 ms with every direction, 1.95 ms with the
// stiffest and most damped modes only.
//
// With no inverse of C: mu_0 = the ratio of the stiffest mode, and the top eigenvectors of
// K - mu_0 C are the modes whose ratio exceeds mu_0 the most (one Lanczos run). Where they
// reach a ratio mu_1 well above mu_0, a second run on K - mu_1 C (one step of Dinkelbach's
// iteration, which converges to the largest ratio) finds the modes past mu_1, and both sets
// are kept. Why the second: the first run's top is set by K (the stiffest modes dominate
// K - mu_0 C), and a mode of moderate frequency that only the air and the floor's damper
// damp ranks below them. The ball resting on its floor (642 masses; the whole Jacobian of
// its step, 3852 coordinates, as the oracle): explicit Euler 0.054 ms on the wobble at
// 209 rad/s (damping ratio 0.006), the midpoint rule 1.75 ms; one run predicted 0.94 and
// 2.71 ms, two runs 0.058 and 1.78 ms. Repeating further narrowed the vectors onto a cluster
// of nearly equal ratios (on the inflated ball the limit on them alone fell from 2.5 % to 9 %
// below every direction's): the union of two runs, not the last run, is kept.
template <class ApplyK, class ApplyC>
Eigen::MatrixXd stiffestForTheirDamping(const ApplyK& applyK, const ApplyC& applyC, const Eigen::VectorXd& stiffest,
                                        int n, int k) {
  if (stiffest.size() == 0 || n == 0) return Eigen::MatrixXd(n, 0);
  const double kk = stiffest.dot(applyK(stiffest));
  const double cc = stiffest.dot(applyC(stiffest));
  // The stiffest mode undamped: its ratio is infinite, and explicit Euler fails on it first.
  if (!(cc > 1e-12 * std::abs(kk))) return Eigen::MatrixXd(n, 0);
  const auto pastRatio = [&](double mu) {
    return topEigenvectors(
        [&](const Eigen::VectorXd& u) {
          Eigen::VectorXd out = applyK(u);
          out -= mu * applyC(u);
          return out;
        },
        n, k, 2026, false);
  };
  const double mu0 = kk / cc;
  const Eigen::MatrixXd first = pastRatio(mu0);
  // The largest ratio the first run found.
  double mu1 = mu0;
  for (Eigen::Index c = 0; c < first.cols(); ++c) {
    const Eigen::VectorXd u = first.col(c);
    const double uc = u.dot(applyC(u));
    if (uc > 0.0) mu1 = std::max(mu1, u.dot(applyK(u)) / uc);
  }
  // Within half again of mu_0 the first run's modes already are the ones past it (every
  // cloth and rope here, the cube, the pillow): no second run.
  if (!(mu1 > 1.5 * mu0)) return first;
  const Eigen::MatrixXd second = pastRatio(mu1);
  Eigen::MatrixXd both(n, first.cols() + second.cols());
  both << first, second;
  return both;
}

// A fixed pseudo-random direction (the same on every run), largest entry 1.
Eigen::VectorXd randomDirection(int size, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::VectorXd u(size);
  for (int j = 0; j < size; ++j) u[j] = uniform(random);
  return u / u.cwiseAbs().maxCoeff();
}

// The k eigenvectors of largest eigenvalue of a symmetric operator of size n, by Lanczos
// with full reorthogonalisation from a fixed pseudo-random start (columns, unit length).
// 40 steps (3 k for k over 13): 60 moved no shipped scene's limit by more than 0.15 % (the
// 16 x 16 cloth's RK4 0.28 %) and cost 11-13 % of the whole limit on the 64 x 64 cloth (RK4
// 0.98 against 0.88 s: each step is two or four force evaluations and a reorthogonalisation).
template <class Apply>
Eigen::MatrixXd topEigenvectors(const Apply& apply, int n, int k, unsigned seed, bool distinctOnly) {
  const int steps = std::min(n, std::max(3 * k, 40));
  Eigen::MatrixXd basis(n, steps);
  basis.col(0) = randomDirection(n, seed).normalized();
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(steps, steps);
  int m = steps;
  for (int j = 0; j < steps; ++j) {
    Eigen::VectorXd w = apply(Eigen::VectorXd(basis.col(j)));
    T(j, j) = basis.col(j).dot(w);
    for (int pass = 0; pass < 2; ++pass) w -= basis.leftCols(j + 1) * (basis.leftCols(j + 1).transpose() * w);
    const double b = w.norm();
    if (j + 1 == steps || b <= 1e-12 * std::max(std::abs(T(j, j)), 1e-300)) {
      m = j + 1;
      break;
    }
    T(j, j + 1) = T(j + 1, j) = b;
    basis.col(j + 1) = w / b;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(T.topLeftCorner(m, m));
  // distinctOnly: only eigenvalues well above the smallest. Damping that is the same on
  // every mass (air friction alone) has no preferred vectors, and arbitrary ones would spoil
  // the subspace the stiffness picked.
  const Eigen::VectorXd& values = eig.eigenvalues();  // ascending
  int kept = 0;
  while (kept < std::min(k, m) && (!distinctOnly || values[m - 1 - kept] > 1.5 * std::max(values[0], 0.0))) ++kept;
  return basis.leftCols(m) * eig.eigenvectors().rightCols(kept);
}

StepSpectrum radiusOf(LinearisedRuns& runs, double dt, const StepStabilityOptions& o) {
  StepSpectrum out;
  const int before = runs.steps();
  const int n = runs.size();
  if (n == 0) return out;
  // Every coordinate (a small system: the whole Jacobian) or the modal directions; for each,
  // its run against the unperturbed one.
  runs.settleAt(dt, o);
  Eigen::MatrixXd identity;
  if (n <= o.denseBelow) identity.setIdentity(n, n);
  const Eigen::MatrixXd& U = n <= o.denseBelow ? identity : runs.directions(o.modes);
  const bool oneStep = runs.historyFree(dt);
  // Buffers kept between radii (runs.scratch): no allocation per run.
  LinearisedRuns::Scratch& b = runs.scratch;
  runs.runInto(dt, oneStep ? 0 : 1, {}, b.base);
  const Eigen::MatrixXd& base = b.base;
  const Eigen::VectorXd scale = runs.perturbationScale();
  // The first dense probe takes both sides of every coordinate. Where the two disagree the
  // step is not differentiable there: a mass resting on a collider, whose push inwards is
  // projected away (and kicks its velocity by the push over dt) while a pull outwards moves
  // freely. That coordinate is held by its contact, not an oscillator of the step: it is left
  // out of the Rayleigh-Ritz subspace from then on (the contacts of the settled state do not
  // depend on dt). The modal directions, spread over many masses, are probed on one side.
  const bool dense = n <= o.denseBelow;
  const bool findHeld = dense && runs.held.empty();
  if (findHeld) runs.held.assign(static_cast<std::size_t>(n), 0);
  const int last = oneStep ? 0 : 1;
  Eigen::MatrixXd& X = b.X;
  Eigen::MatrixXd& Y = b.Y;
  X.resize(n, U.cols());
  Y.resize(n, U.cols());
  Eigen::Index kept = 0;
  // The whole Jacobian of a step without history: each X column lies along its coordinate.
  const bool alongAxes = dense && oneStep;
  std::vector<Eigen::Index> axes;
  Eigen::VectorXd axisLength(U.cols());
  for (Eigen::Index j = 0; j < U.cols(); ++j) {
    if (dense && !findHeld && runs.held[static_cast<std::size_t>(j)]) continue;
    b.u = U.col(j);
    // A modal direction leaves the coordinates its contacts hold where they are (findHeldMasses).
    if (!dense && !runs.held.empty()) {
      for (int i = 0; i < n; ++i)
        if (runs.held[static_cast<std::size_t>(i)]) b.u[i] = 0.0;
    }
    const double largest = b.u.cwiseAbs().maxCoeff();
    if (!(largest > 0.0)) continue;
    b.u /= largest;
    const Eigen::VectorXd& u = b.u;
    runs.runInto(dt, last, u, b.moved);
    if (findHeld) runs.runInto(dt, last, -u, b.opposite);
    const Eigen::MatrixXd& moved = b.moved;
    const Eigen::MatrixXd& opposite = findHeld ? b.opposite : base;
    if (moved.cols() < base.cols() || opposite.cols() < base.cols() || base.cols() < last + 1) {
      out.radius = INFINITY;
      out.steps = runs.steps() - before;
      return out;
    }
    Y.col(kept) = moved.col(last) - base.col(last);
    const auto y = Y.col(kept);
    if (findHeld) {
      const Eigen::VectorXd back = opposite.col(last) - base.col(last);
      if ((y + back).norm() > 0.1 * std::max(y.norm(), back.norm())) {
        runs.held[static_cast<std::size_t>(j)] = 1;  // one-sided: a contact
        continue;
      }
    }
    if (oneStep) {
      X.col(kept) = u.cwiseProduct(scale);
    } else {
      X.col(kept) = moved.col(0) - base.col(0);
    }
    if (alongAxes) {
      axes.push_back(j);
      axisLength[kept] = X(j, kept);
    }
    ++kept;
  }
  out.radius = alongAxes ? axisRitzRadius(axes, axisLength.head(kept), Y.leftCols(kept))
                         : ritzRadius(X.leftCols(kept), Y.leftCols(kept), oneStep ? &b.basis : nullptr);
  out.steps = runs.steps() - before;
  return out;
}

// The radius at dt as the limit sees it. A step that is not smooth at the state: a contact
// whose response switches exactly there (a mass resting on a projected obstacle: explicit
// Euler's first step from rest leaves it on the surface, and a perturbation into the obstacle
// turns the contact's absorption on). Its finite differences measure a jump over the
// perturbation, not a derivative (the radius grows as dt / perturbation: 388 at 0.1 ms on the
// ball under the user's sphere), and the growth read from them swallowed every dt
// ("unlimited"). A smooth step gives the same radius for a perturbation 16 times smaller (to
// about 1e-3); only a radius past 1 is asked (a stable one decides nothing). Where it is not
// smooth and a fallen body has come to rest on what it hit (a cloth dropped on a sphere;
// LinearisedRuns::restsAfterImpact), the modal directions hold the masses its contacts hold
// one-sidedly (findHeldMasses) and are asked again. Still not smooth, or not such a rest (the
// thesis cloth's settling stops where its hem has just landed, velocities set to zero: holding
// its contacts there, or settling it to rest, gave limits 1.3 to 4 times off its runs' either
// way): not smooth, no linearised radius there.
struct SmoothRadius {
  StepSpectrum spectrum;
  bool smooth = true;
  int evaluations = 0;  // radii computed
};
SmoothRadius smoothRadiusOf(LinearisedRuns& runs, double dt, const StepStabilityOptions& o) {
  SmoothRadius out;
  const int before = runs.steps();
  out.spectrum = radiusOf(runs, dt, o);
  out.evaluations = 1;
  auto smooth = [&](double coarse) {
    runs.scalePerturbation(1.0 / 16.0);
    const double fine = radiusOf(runs, dt, o).radius;
    runs.scalePerturbation(16.0);
    ++out.evaluations;
    return std::abs(fine - coarse) <= 1e-3 * coarse;
  };
  double& r = out.spectrum.radius;
  if (std::isfinite(r) && r > 1.0 + o.radiusSlack && !smooth(r)) {
    const bool dense = runs.size() <= o.denseBelow;
    if (o.holdRestingContacts && !dense && runs.restsAfterImpact() && runs.held.empty() &&
        runs.findHeldMasses(dt) > 0) {
      r = radiusOf(runs, dt, o).radius;
      ++out.evaluations;
    }
    out.smooth = !dense && !runs.held.empty() && std::isfinite(r) && (r <= 1.0 + o.radiusSlack || smooth(r));
  }
  out.spectrum.steps = runs.steps() - before;
  return out;
}

}  // namespace

StepSpectrum stepSpectralRadius(Simulation& sim, double dt, const StepStabilityOptions& options) {
  LinearisedRuns runs(sim, options);
  if (!options.holdRestingContacts) {
    StepSpectrum out = radiusOf(runs, dt, options);
    out.restsAfterImpact = runs.restsAfterImpact();
    return out;
  }
  // The limit's own linearisation: a fallen body's resting contacts held, NaN where not smooth.
  SmoothRadius r = smoothRadiusOf(runs, dt, options);
  if (!r.smooth) r.spectrum.radius = NAN;
  r.spectrum.restsAfterImpact = runs.restsAfterImpact();
  return r.spectrum;
}

StepGrowth stepPerturbationGrowth(Simulation& sim, double dt, long steps, const StepStabilityOptions& o,
                                  unsigned seed, int directions) {
  LinearisedRuns runs(sim, o);
  StepGrowth out;
  if (runs.size() == 0 || steps <= 0 || directions <= 0) return out;
  runs.settleAt(dt, o);
  // Recorded about 256 times over the run: the growth is read where the runs are compared.
  const long stride = std::max(1L, steps / 256);
  const long samples = steps / stride;
  const Eigen::MatrixXd reference = runs.sampledRun(dt, steps, stride, {});
  // The difference is read in the velocities: a disturbance along a free direction (a mass
  // that nothing holds sideways, a body on a floor without friction) moves it by its velocity
  // over the damping's time, a drift that grows the positions' difference without bound (117
  // times on the chain, whose air alone holds it sideways) and is no instability. A growing
  // mode grows in the velocities as in the positions; the scaling makes a disturbance of a
  // stiff mode's position and of its velocity alike (velocities over length x w_max).
  const int n = runs.size() / 2;
  const double size = runs.perturbationScale().cwiseAbs().maxCoeff();
  // One disturbed run per direction (seeds seed, seed + 1, ...), each against the same
  // reference; a run that ended early (not finite, or a step threw) grows without bound.
  for (int d = 0; d < directions; ++d) {
    const Eigen::MatrixXd moved =
        runs.sampledRun(dt, steps, stride, randomDirection(runs.size(), seed + static_cast<unsigned>(d)));
    const long both = std::min(reference.cols(), moved.cols());
    double growth = 0.0;
    for (long c = 0; c < both; ++c)
      growth = std::max(growth, (moved.col(c).tail(n) - reference.col(c).tail(n)).cwiseAbs().maxCoeff() / size);
    out.growths.push_back(both == samples ? growth : INFINITY);
  }
  // The median: a direction that happens to hold little of the growing mode (1 in 100 on the
  // wind ball) or much of a slow one cannot decide alone.
  std::vector<double> sorted = out.growths;
  std::nth_element(sorted.begin(), sorted.begin() + directions / 2, sorted.end());
  out.growth = sorted[static_cast<std::size_t>(directions / 2)];
  out.finite = std::isfinite(out.growth);
  out.steps = runs.steps();
  return out;
}

StepStabilityLimit stepStabilityLimit(Simulation& sim, double firstGuess, const StepStabilityOptions& o) {
  LinearisedRuns runs(sim, o);
  StepStabilityLimit out;
  // The physics' own growth rate g at the settled state: a scene may rest at an unstable
  // equilibrium (the 8 x 8 cloth draped over its movable sphere grows at about 15 /s), and
  // any step that follows the physics then grows by 1 + g dt. Numerical instability is growth
  // beyond that. The radius near dt = 0 is 1 + g dt + a dt^2 (a: the method's own error, the
  // whole of explicit Euler's 1 + w^2 dt^2 / 2), so two small probes h and h/2 separate them:
  // g = (4 (r(h/2) - 1) - (r(h) - 1)) / h. For a scene at a stable rest g is 0. A step may
  // grow by up to 1 + 2 g dt: the margin takes the method's own error on the growing mode
  // (symplectic Euler's r - 1 is 15.2 dt to 15.3 dt there), and costs little, since past the
  // limit the radius climbs steeply (3.8 at twice symplectic Euler's limit on that cloth).
  // The probes are small (1/32 of the first guess): the method's next error term, h^3 in
  // r - 1, leaks into g as h^2, and at 1/8 explicit Euler's own 1 + y^2 / 2 - y^4 / 8 on an
  // undamped spring read as g = 0.015 /s, whose allowance 2 g dt hid its growth up to a
  // "limit" of 0.6 ms where it has none.
  const double h = firstGuess / 32.0;
  // A step that is not smooth at the state (smoothRadiusOf): the limit is not computable
  // there, NaN; where a fallen body rests on what it hit, its contacts are held first.
  const SmoothRadius atH = smoothRadiusOf(runs, h, o);
  out.evaluations += atH.evaluations;
  const double rh = atH.spectrum.radius;
  double growth = 0.0;
  if (!atH.smooth) {
    out.dt = NAN;
    out.steps = runs.steps();
    return out;
  }
  // A radius at h within the slack leaves no growth to measure (g h at most the slack): the
  // second probe is skipped (a radius of the 64 x 64 cloth costs 0.04-0.07 s).
  if (std::isfinite(rh) && rh > 1.0 + o.radiusSlack) {
    const double rh2 = radiusOf(runs, 0.5 * h, o).radius;
    ++out.evaluations;
    if (std::isfinite(rh2)) growth = std::max(0.0, (4.0 * (rh2 - 1.0) - (rh - 1.0)) / h);
  }
  // How far the radius exceeds what is allowed at dt, in log (<= 0: stable). Past the limit
  // the radius grows about geometrically with dt, so in log dt this is nearly straight near
  // its root and a secant finds it in a few steps; an infinite radius (a run went
  // non-finite) is +inf.
  std::vector<std::pair<double, double>> probes;  // (dt, r - 1 - 2 g dt) of each radius below
  auto excess = [&](double dt) {
    ++out.evaluations;
    const double r = radiusOf(runs, dt, o).radius;
    probes.emplace_back(dt, r - 1.0 - 2.0 * growth * dt);
    return std::log(std::max(r, 1e-300)) - std::log(1.0 + o.radiusSlack + 2.0 * growth * dt);
  };

  // The two unstable points nearest the limit (log dt, finite excess): a line through them,
  // extrapolated to excess 0, is where the failing mode's radius crosses 1. The stable side
  // cannot say that: below the limit the radius is another mode's, the slowest damped one,
  // nearly flat in dt (0.96-0.97 on the 64 x 64 cloth from a sixth of RK4's limit up to it),
  // and a secant through a stable point lands next to that point (RK4 took 12 radii there).
  struct Point {
    double x, g;
  };
  std::optional<Point> nearest, next;
  auto noteUnstable = [&](double x, double g) {
    if (!std::isfinite(g)) return;
    if (!nearest || x < nearest->x) {
      next = nearest;
      nearest = Point{x, g};
    } else if (!next || x < next->x) {
      next = Point{x, g};
    }
  };
  auto extrapolated = [&]() -> std::optional<double> {
    if (!nearest || !next || !(next->g > nearest->g)) return std::nullopt;
    return nearest->x - nearest->g * (next->x - nearest->x) / (next->g - nearest->g);
  };
  const double tau = std::log1p(o.tolerance);  // the final bracket's width in log dt

  // Bracket: grow while stable, halve while unstable. The growth factor doubles with each
  // stable probe (2, 4, 8, ...): a method whose limit lies far above 2 / w_max (implicit Euler
  // on the 32 x 32 cloth: 65 times, six doublings of a radius of about 80 implicit solves each)
  // or that has none (XPBD: stable past 1000 times, ten doublings) gets there in three or
  // four probes, and the wider bracket costs a probe or two more (16 radii in all -> 14).
  double lo = 0.0, hi = 0.0, glo = 0.0, ghi = 0.0;
  bool lastStable = false;  // the last probe's verdict
  double first = excess(firstGuess);
  // A stable first guess counts only when half of it is stable too: the radius need not rise
  // with dt. Position Verlet's on the trampoline (the Ritz estimate, pinned edges, stretch
  // limit, wind) is 1.6 at 0.4 ms, 5.3 at 1 ms and 0.93 at the first guess 2.2 ms; growing
  // from there, its "limit" was 4.6 ms where symplectic Euler's, the same map, is 0.31 ms.
  // Where half is unstable, the limit is looked for below it.
  double unstableStart = firstGuess;
  if (first <= 0.0) {
    const double half = excess(0.5 * firstGuess);
    if (half > 0.0) {
      unstableStart = 0.5 * firstGuess;
      first = half;
    }
  }
  if (first <= 0.0) {
    lo = firstGuess;
    glo = first;
    lastStable = true;
    double factor = 2.0;
    while (hi == 0.0) {
      if (lo >= o.largestFactor * firstGuess) {
        out.dt = INFINITY;
        out.steps = runs.steps();
        return out;
      }
      const double g = excess(factor * lo);
      if (g <= 0.0) {
        lo *= factor;
        glo = g;
        factor *= 2.0;
      } else {
        hi = factor * lo;
        ghi = g;
        lastStable = false;
        noteUnstable(std::log(hi), g);
      }
    }
  } else {
    hi = unstableStart;
    ghi = first;
    noteUnstable(std::log(hi), first);
    while (lo == 0.0) {
      if (hi <= o.smallestFactor * firstGuess) {
        out.dt = 0.0;
        out.steps = runs.steps();
        return out;
      }
      const double g = excess(0.5 * hi);
      if (g <= 0.0) {
        lo = 0.5 * hi;
        glo = g;
        lastStable = true;
      } else {
        hi *= 0.5;
        ghi = g;
        noteUnstable(std::log(hi), g);
      }
    }
  }

  // Narrow the bracket to the tolerance. Where the line through the unstable points crosses
  // inside the bracket, the next probe is that crossing set 0.45 of the tolerance to the side
  // the last probe was not on: a good estimate closes the bracket in two probes (RK4 on the
  // 64 x 64 cloth: 4 radii after the bracket, where a secant took 12). A radius that bends
  // past the limit (symplectic Euler's: the damped pair meets, then one eigenvalue leaves
  // through -1, steeply at first) puts the line's crossing low; once a probe just above it
  // is still stable, the line is not trusted again. Otherwise an Illinois secant (an end
  // kept twice in a row counts half), which does well where the stable side rises towards
  // the limit (symplectic Euler's failing mode is the largest below its limit too); the
  // geometric midpoint where neither has anything to go on, or when two probes did not halve
  // the bracket, so that it never takes many more than bisection's 9. Every probe lies at
  // least a quarter of the tolerance inside the bracket.
  int lastKept = 0;  // Illinois: +1 the last step moved lo, -1 it moved hi
  bool trustLine = true;
  double reference = std::log(hi / lo);  // the width two probes are to halve
  int sinceReference = 0;
  while (hi / lo > 1.0 + o.tolerance) {
    const double a = std::log(lo), b = std::log(hi);
    double x = 0.5 * (a + b);
    const std::optional<double> p = trustLine ? extrapolated() : std::nullopt;
    bool fromLine = false;
    if (sinceReference >= 2 && b - a > 0.5 * reference) {
      reference = b - a;  // the midpoint
      sinceReference = 0;
    } else if (p && *p > a + tau && *p < b - tau) {
      x = *p + (lastStable ? 0.45 : -0.45) * tau;
      fromLine = true;
    } else if (std::isfinite(ghi) && ghi > glo) {
      x = a - glo * (b - a) / (ghi - glo);
    }
    x = std::clamp(x, a + 0.25 * tau, b - 0.25 * tau);
    const double mid = std::exp(x);
    const double g = excess(mid);
    ++sinceReference;
    if (g <= 0.0) {
      if (fromLine && lastStable) trustLine = false;  // the line's crossing was low
      lo = mid;
      glo = g;
      if (lastKept == 1) ghi *= 0.5;
      lastKept = 1;
      lastStable = true;
    } else {
      hi = mid;
      ghi = g;
      if (lastKept == -1) glo *= 0.5;
      lastKept = -1;
      lastStable = false;
      noteUnstable(x, g);
    }
    if (std::log(hi / lo) <= 0.5 * reference) {
      reference = std::log(hi / lo);
      sinceReference = 0;
    }
  }
  // Unstable at every dt, the slack alone setting a "limit": a radius above 1 by a power of
  // dt on an undamped mode (explicit Euler's 1 + w^2 dt^2 / 2, the midpoint rule's
  // 1 + w^4 dt^4 / 8) meets 1 + slack at some small dt and exceeds 1 below it too. Below a
  // genuine limit the excess is negative (damping) or zero up to the finite differences'
  // noise (a symplectic method's undamped modes, about 1e-8). So at half the limit found an
  // excess still above slack / 32 (explicit Euler there: slack / 4, the midpoint rule
  // slack / 16) says no dt is stable. Only a limit far below the first guess (2 / w_max) is
  // asked: that is where such a "limit" lands.
  // A probe already taken between half the limit and the limit, within slack / 32 of 1,
  // answers it (no such power law passes there): RK4 on the 64 x 64 cloth has one at 0.997.
  const bool answered = std::any_of(probes.begin(), probes.end(), [&](const std::pair<double, double>& p) {
    return p.first >= 0.5 * lo && p.first <= lo && p.second <= o.radiusSlack / 32.0;
  });
  if (lo < 0.25 * firstGuess && !answered) {
    ++out.evaluations;
    const double half = 0.5 * lo;
    const double r = radiusOf(runs, half, o).radius;
    if (r - 1.0 - 2.0 * growth * half > o.radiusSlack / 32.0) lo = 0.0;
  }
  out.dt = lo;
  out.steps = runs.steps();
  return out;
}

double stepStableDt(Simulation& sim, const StepStabilityOptions& options) {
  sim.reset();
  double w = 0.0;
  try {
    w = lanczosEstimate(sim, sim.initialState()).maxAngularFrequency;
  } catch (const std::exception&) {
    w = 0.0;
  }
  if (!(w > 0.0) || !std::isfinite(w)) w = sim.angularFrequencyBound();
  const double guess = w > 0.0 && std::isfinite(w) ? 2.0 / w : 1e-3;
  return stepStabilityLimit(sim, guess, options).dt;
}

}  // namespace springlab
