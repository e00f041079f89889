#include "springlab/diagnostics.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "springlab/calm_run.hpp"
#include "springlab/simulation.hpp"
#include "springlab/step_stability.hpp"

namespace springlab {

double springGershgorinBound(const Simulation& sim) {
  // Row sums of M^-1 K for the springs (Gershgorin): each spring adds k to both ends' rows
  // twice (diagonal and off-diagonal), so a free mass with springs k_j has |row| = 2 sum k_j.
  std::vector<double> rowSum(sim.masses.size(), 0.0);
  for (const Spring& s : sim.springs()) {
    rowSum[s.mass1] += 2.0 * s.springConstant;
    rowSum[s.mass2] += 2.0 * s.springConstant;
  }
  double w2 = 0.0;
  for (int i = 0; i < sim.numOfMasses(); ++i) {
    if (!sim.masses[i].pinned) w2 = std::max(w2, rowSum[i] / sim.masses[i].m);
  }
  return std::sqrt(w2);
}

void BlowUpCheck::arm(const Simulation& sim) {
  // Energy the scene holds now plus what gravity can add over the scene's extent, plus
  // 1 J per kg so that a scene at rest without gravity still has a finite scale.
  const Energies e = sim.energies();
  double extent = 0.0;
  double totalMass = 0.0;
  if (!sim.state.pos.empty()) {
    Vec3 lo = sim.state.pos[0], hi = sim.state.pos[0];
    for (const Vec3& p : sim.state.pos) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    extent = (hi - lo).norm();
  }
  for (const Spring& s : sim.springs()) extent += s.springLength;
  for (const Mass& m : sim.masses) totalMass += m.m;
  energyScale_ = std::abs(e.kinetic) + std::abs(e.elastic) + std::abs(e.other) +
                 totalMass * (sim.gravitation.norm() * extent + 1.0);
  speedScale_ = totalMass > 0.0 ? std::sqrt(2.0 * energyScale_ / totalMass) : 0.0;
  reversal_.restart();
  undampedMass_ = -1;
  totalCeiling_ = e.total() - sim.sourceWork();
  passiveCeiling_ = totalCeiling_ - sim.correctionWork();
  restartClimb(totalCeiling_);
  last_ = sim.state;
  lastStep_ = sim.stats.steps;
  armedStep_ = sim.stats.steps;
  armedBalance_ = passiveCeiling_;
  armedCorrections_ = sim.correctionWork();
}

double StepReversal::record(const std::vector<Vec3>& velocities) {
  double largest = 0.0;
  if (count_ >= 2 && last_.size() == velocities.size() && before_.size() == velocities.size()) {
    for (std::size_t i = 0; i < velocities.size(); ++i) {
      const double reversal = 0.25 * (velocities[i] - 2.0 * last_[i] + before_[i]).norm();
      if (reversal > largest) {
        largest = reversal;
        lastMass_ = static_cast<int>(i);
      }
    }
    recent_[static_cast<std::size_t>((count_ - 2) % kWindow)] = largest;
  }
  ++count_;
  std::swap(before_, last_);
  last_ = velocities;  // reuses the storage of the velocities two steps back
  if (count_ < kWindow + 2) return 0.0;
  // Held, not dying out: a damped mode just inside its limit turns back every step too, for
  // hundreds of steps while it decays, so the newer half of the window must reach as high as the
  // older half.
  double older = 0.0, newer = 0.0;
  for (int k = 0; k < kWindow; ++k) {
    const double value = recent_[static_cast<std::size_t>((count_ - 2 + k) % kWindow)];  // oldest first
    double& half = k < kWindow / 2 ? older : newer;
    half = std::max(half, value);
  }
  if (newer < older) return 0.0;
  return smallestInWindow();
}

double StepReversal::smallestInWindow() const {
  return count_ < kWindow + 2 ? 0.0 : *std::min_element(recent_.begin(), recent_.end());
}

namespace {
// The largest of per-bin values within ReversalProfile::kReach bins of time t.
double largestNear(const std::vector<double>& values, double binTime, double t) {
  if (values.empty() || !(binTime > 0.0)) return 0.0;
  const long last = static_cast<long>(values.size()) - 1;
  const long bin = std::min(static_cast<long>(std::max(t, 0.0) / binTime), last);
  double largest = 0.0;
  for (long j = std::max(0L, bin - ReversalProfile::kReach); j <= std::min(last, bin + ReversalProfile::kReach); ++j) {
    largest = std::max(largest, values[static_cast<std::size_t>(j)]);
  }
  return largest;
}
}  // namespace

double ReversalProfile::kineticNear(double t) const { return largestNear(kinetic, binTime, t); }

double ReversalProfile::near(double t) const { return largestNear(held, binTime, t); }

void BlowUpCheck::restartClimb(double energy) {
  low_ = energy;
  recentCount_ = 0;
  recentNext_ = 0;
  fastSwing_ = 0.0;
}

double BlowUpCheck::climbAllowance() const {
  return std::max({passivityAllowance(), kFastSwingMargin * fastSwing_, kClimbFraction * (totalCeiling_ - low_)});
}

bool BlowUpCheck::turningMassIsDamped(Simulation& sim) {
  // The forces on the mass with its velocity and with it at rest, the other masses as they
  // are: the difference is its dampers' (springs', air's, a contact's, the wind's drag).
  const int i = reversal_.lastMass();
  if (i < 0 || i >= sim.numOfMasses() || i == undampedMass_) return false;
  const Stats stats = sim.stats;
  std::vector<Vec3> moving, still;
  sim.evaluateForces(sim.state, moving);
  State atRest = sim.state;
  atRest.vel[static_cast<std::size_t>(i)].setZero();
  sim.evaluateForces(atRest, still);
  sim.stats = stats;
  const Vec3& v = sim.state.vel[static_cast<std::size_t>(i)];
  const Vec3 damping = moving[static_cast<std::size_t>(i)] - still[static_cast<std::size_t>(i)];
  // The power the dampers take out of its motion, against round-off of the forces.
  const bool damped = -damping.dot(v) > 1e-9 * moving[static_cast<std::size_t>(i)].norm() * v.norm();
  if (!damped) undampedMass_ = i;  // asked again every step it holds: answer from here on
  return damped;
}

double BlowUpCheck::passivityAllowance(bool own) const {
  const double swing = own ? ownSwing_ : energySwing_;
  if (swing < 0.0) return kPassivityFraction * energyScale_;
  return std::max(kSwingMargin * swing, kSwingFloor * energyScale_);
}

bool BlowUpCheck::changedSinceLastCheck(const Simulation& sim) const {
  return sim.state.pos != last_.pos || sim.state.vel != last_.vel;
}

void BlowUpCheck::admitUserEnergy(const Simulation& sim) {
  const double before = energyScale_;
  const double ceiling = passiveCeiling_, totalCeiling = totalCeiling_;
  arm(sim);
  energyScale_ = std::max(before, energyScale_);
  passiveCeiling_ = std::max(ceiling, passiveCeiling_);
  totalCeiling_ = std::max(totalCeiling, totalCeiling_);
}

namespace {

bool finite(const Vec3& v) { return v.allFinite(); }

std::string show(const Vec3& v) {
  std::ostringstream os;
  os << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
  return os.str();
}

// The first mass whose force is non-finite, or -1.
int firstNonFinite(const std::vector<Vec3>& f) {
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (!finite(f[i])) return static_cast<int>(i);
  }
  return -1;
}

}  // namespace

std::string BlowUpCheck::blameForces(Simulation& sim) {
  if (last_.pos.size() != sim.masses.size() || last_.vel.size() != sim.masses.size()) return {};
  // Diagnostic evaluations: they must not count in the run's statistics or profile.
  const Stats stats = sim.stats;
  std::vector<Vec3> f;
  auto forcesAtLast = [&]() -> bool {
    try {
      sim.evaluateForces(last_, f);
      return true;
    } catch (const std::exception&) {
      return false;
    }
  };
  const bool evaluated = forcesAtLast();
  const int bad = evaluated ? firstNonFinite(f) : -1;
  if (bad < 0) {
    sim.stats = stats;
    return {};
  }
  const Vec3 badForce = f[static_cast<std::size_t>(bad)];

  // Which of the lab's own terms: leave each out in turn, and name the first without which
  // mass `bad` is finite.
  const std::vector<std::string> terms = sim.forceTermNames();
  int culprit = -1;
  for (int k = 0; k < static_cast<int>(terms.size()) && culprit < 0; ++k) {
    sim.muteForceTerm(k);
    if (forcesAtLast() && finite(f[static_cast<std::size_t>(bad)])) culprit = k;
  }
  sim.muteForceTerm(-1);

  // Which term: take the springs away (k = 0 would not do: 0 times a 0/0 direction is still
  // NaN), then gravity too, and see whether mass `bad` turns finite. Both come back below
  // (swapSprings lets the lab derive again what it keeps from the springs).
  std::vector<Spring> springs;
  sim.swapSprings(springs);
  const Vec3 gravity = sim.gravitation;
  const bool withoutSprings = forcesAtLast() && finite(f[static_cast<std::size_t>(bad)]);
  sim.gravitation = Vec3::Zero();
  const bool withoutGravity = !withoutSprings && forcesAtLast() && finite(f[static_cast<std::size_t>(bad)]);
  sim.swapSprings(springs);
  sim.gravitation = gravity;
  sim.stats = stats;

  std::ostringstream os;
  os << "the forces went non-finite before the state did: at the last finite state (t = " << last_.time
     << " s, step " << lastStep_ << ") the force on mass " << bad << " is " << show(badForce) << " N";
  if (culprit >= 0) {
    os << ", from the " << sim.kind() << "'s " << terms[static_cast<std::size_t>(culprit)]
       << " (it is finite with that term left out)";
  } else if (withoutSprings) {
    os << ", from the spring forces (it is finite without the springs)";
  }
  if (withoutSprings) {
    // What the framework can see: a spring at that mass with coincident ends or bad parameters.
    for (std::size_t j = 0; j < sim.springs().size(); ++j) {
      const Spring& s = sim.springs()[j];
      if (s.mass1 != bad && s.mass2 != bad) continue;
      const double length = (last_.pos[static_cast<std::size_t>(s.mass1)] - last_.pos[static_cast<std::size_t>(s.mass2)]).norm();
      if (length == 0.0) {
        os << "; spring " << j << " (masses " << s.mass1 << "-" << s.mass2
           << ") has both ends at one point: its direction is 0/0";
        break;
      }
      if (!std::isfinite(s.springConstant) || !std::isfinite(s.springLength) || !std::isfinite(s.frictionConstant)) {
        os << "; spring " << j << " (masses " << s.mass1 << "-" << s.mass2 << ") has a non-finite k, L0 or kd";
        break;
      }
    }
  } else if (culprit >= 0) {
    // Named above.
  } else if (withoutGravity) {
    os << ", from gravity (it is finite without gravity: check the mass m = " << sim.masses[static_cast<std::size_t>(bad)].m
       << " kg and g)";
  } else if (!terms.empty()) {
    os << ", from more than one of the " << sim.kind()
       << "'s force terms (it stays non-finite whichever one is left out)";
  } else {
    os << ", from the " << sim.kind()
       << "'s own forces (it stays non-finite without the springs and gravity: ground, air, wind, "
          "pressure or contact terms)";
  }
  os << ". dt is not the cause: look for a division by zero, a normalised zero vector or a value never "
        "initialised in that force";
  return os.str();
}

namespace {

// Did a mass the scene moves (pinned, grabbed) move since the last check? Then the scene did
// work on the rest: the rope's fixed end carried by the user's keys.
bool anchorsMoved(const Simulation& sim, const State& last) {
  if (last.pos.size() != sim.state.pos.size()) return false;
  for (int i = 0; i < sim.numOfMasses(); ++i) {
    if (sim.inverseMass(i) != 0.0) continue;
    if (sim.state.pos[i] != last.pos[i] || sim.state.vel[i] != Vec3::Zero()) return true;
  }
  return false;
}

// Where the scene settles. One already computed (the viewer's, on a copy of the scene) is
// taken as it is.
double exactLimit(Simulation& sim) {
  if (const std::optional<double> known = sim.knownStepLimit()) return *known;
  return limitLeavingTheRun(sim, {});
}

}  // namespace

bool BlowUpCheck::beyondLimitOrMeasured(Simulation& sim, double dt) {
  if (energySwing_ >= 0.0) return true;
  return beyondLimit(sim, dt);
}

bool BlowUpCheck::beyondLimit(Simulation& sim, double dt) {
  if (dt != limitDt_) {
    // Computed before anything is written: the computation puts this check's members back.
    const double limit = exactLimit(sim);
    limitDt_ = dt;
    limit_ = limit;
    beyondLimit_ = !(dt <= limit_);  // NaN (not computable) counts as beyond
  }
  return beyondLimit_;
}

void BlowUpCheck::check(Simulation& sim, double dt) {
  // Detector 1, a non-finite state: name the first mass that went bad.
  std::string why;
  if (const int bad = firstNonFiniteMass(sim.state); bad >= 0) {
    why = "mass " + std::to_string(bad) + " has a non-finite position or velocity";
  }
  bool finiteState = why.empty();
  // Detector 2, runaway energy: kinetic plus potential energy (springs and the lab's own:
  // ground, gas) far beyond anything the scene can hold. The lab's potentials count because a
  // source such as a gas pays for the elastic energy it stores with its own (-nRT ln V falls).
  if (why.empty()) {
    const Energies e = sim.stepEndEnergies();
    const double grown = e.kinetic + e.elastic + e.other;
    // Passivity's energy: the total less what the sources whose work is counted put in (the
    // wind's), so that a windy scene is held to it as well, and less what the corrections
    // after the step added or took (contacts, stretch limiting), so that an instability they
    // cap is held to it too: what is left is the step's own.
    // (The climb holds the total less the sources' work alone, see totalCeiling_.)
    const double lessWork = e.total() - sim.sourceWork();
    const double balance = lessWork - sim.correctionWork();
    // The messages' words for it, written only when a detector fires (a step allocates nothing).
    const bool counted = sim.sourceWork() != 0.0 || sim.suppliesEnergy();
    auto lessSources = [&](std::ostream& os, bool corrections) -> std::ostream& {
      if (counted) os << " less the work of the scene's energy sources (" << sim.sourceWork() << " J, the wind's)";
      if (corrections && sim.correctionWork() != 0.0) {
        os << (counted ? " and" : " less") << " that of its corrections after each step (" << sim.correctionWork()
           << " J: contacts, stretch limiting, moving anchors)";
      }
      return os;
    };
    const char* noInput = counted ? " in a scene that puts energy in only through them (no pump, moving anchor or drag)"
                                  : " in a scene that puts no energy in (no wind, pump, moving anchor or drag)";
    if (!std::isfinite(grown)) {
      // A non-finite energy of a finite state is a non-finite value, not a growth: the forces'
      // story below, not dt's.
      std::ostringstream os;
      os << "kinetic + elastic + other potential energy is " << grown << " J (kinetic " << e.kinetic << ", elastic "
         << e.elastic << ", other " << e.other << ")";
      why = os.str();
      finiteState = false;
    } else if (!(grown <= kRunawayFactor * energyScale_)) {
      std::ostringstream os;
      os << "runaway energy: kinetic + elastic + other potential energy reached " << grown << " J, over "
         << kRunawayFactor << " times the scene's energy scale of " << energyScale_ << " J";
      why = os.str();
    } else if ((sim.suppliesEnergy() && !sim.lastStepWorkKnown()) || anchorsMoved(sim, last_)) {
      // Energy comes in by an amount the scene cannot say (a pump, a moving anchor): the
      // ceiling follows it up, and a climb counts from here. A source whose work the scene
      // counts (the wind's, Simulation::sourcePower) is taken off the total energy instead,
      // and the detectors below hold the rest to passivity.
      passiveCeiling_ = std::max(passiveCeiling_, balance);
      totalCeiling_ = std::max(totalCeiling_, lessWork);
      restartClimb(lessWork);
    } else if (!sim.integrator().restsAtStaticEquilibrium() && energySwing_ < 0.0) {
      // A method that rests away from the springs' equilibrium (XPBD from zero multipliers,
      // projective dynamics): the scene's spring energy is not its own, and it rests calmly
      // holding more of it (the 8 x 8 fabric under XPBD at 50 ms: +0.008 J above its flat
      // start, at rest). Without a measured swing neither passivity nor the climb applies;
      // with one (a chart's trials) passivity does, since the swing run at half the limit
      // holds that offset too (the rope under XPBD at 1.18 times its limit of 34 ms swings
      // between 40 and 1700 J above its start, under the runaway factor's 16000 J).
    } else if ((balance > passiveCeiling_ + passivityAllowance(true) || lessWork > totalCeiling_ + passivityAllowance()) &&
               beyondLimitOrMeasured(sim, dt)) {
      // Detector 3, passivity: nothing puts energy in, yet the energy rose above its ceiling by
      // more than the integrator's own oscillation. Either energy: the step's own (less the
      // corrections' work; one block sweep on the hanging cloth gains 10 J a step that the
      // stretch limit takes out) or the total (a mass the step throws far below, which the
      // tethers pull back, reads as the corrections' work, and the step's own balance falls by
      // all of it: 833 J on the trampoline under velocity Verlet at 1.03 times its limit).
      const bool own = balance > passiveCeiling_ + passivityAllowance(true);
      const double energy = own ? balance : lessWork, ceiling = own ? passiveCeiling_ : totalCeiling_;
      std::ostringstream os;
      os << "passivity: the total energy";
      lessSources(os, own) << " rose to " << energy << " J, " << energy - ceiling
         << " J above the most the scene held while energy came in (" << ceiling
         << " J)," << noInput << "; the integrator's own energy oscillation is allowed "
         << passivityAllowance(own) << " J ("
         << (energySwing_ >= 0.0 ? "64 times its swing at half the stability limit"
                                 : "half the energy scale, no swing was measured, and dt is past the step's limit")
         << ")";
      why = os.str();
    } else if (sim.integrator().restsAtStaticEquilibrium()) {
      // Detector 4, a climb back from the low (see kClimbFraction): the fast swing first
      // takes this step's energy in, so that a jump within the window is a swing, not a climb.
      const double now = lessWork;
      if (recentCount_ > 0) {
        double windowLow = now;
        for (int k = 0; k < recentCount_; ++k) windowLow = std::min(windowLow, recent_[static_cast<std::size_t>(k)]);
        fastSwing_ = std::max(fastSwing_, now - windowLow);
      }
      recent_[static_cast<std::size_t>(recentNext_)] = now;
      recentNext_ = (recentNext_ + 1) % kFastWindow;
      recentCount_ = std::min(recentCount_ + 1, kFastWindow);
      low_ = std::min(low_, now);
      if (now - low_ > climbAllowance() && beyondLimitOrMeasured(sim, dt)) {
        std::ostringstream os;
        os << "passivity: the total energy";
        lessSources(os, false) << " climbed back to " << now << " J, " << now - low_
           << " J above its lowest since energy last came in (" << low_ << " J)," << noInput
           << ": a stable step's energy swings but does not win back what the scene lost (allowed "
           << climbAllowance() << " J, the largest of the integrator's own oscillation " << passivityAllowance()
           << " J, twice its largest rise within " << kFastWindow << " steps " << kFastSwingMargin * fastSwing_
           << " J, and " << 100.0 * kClimbFraction << " % of the " << totalCeiling_ - low_ << " J the scene lost)";
        why = os.str();
      }
    }
  }
  // Detector 5, a capped instability: motion that reverses every step, held (see
  // StepReversal). Steps that do not follow each other (a reset, a state set by hand) start
  // the window again. It counts only past the step's limit; without a swing run (the viewer,
  // `sim`) it holds the floor alone.
  if (why.empty() && sim.integrator().restsAtStaticEquilibrium()) {
    if (lastStep_ + 1 != sim.stats.steps) reversal_.restart();
    const double held = reversal_.record(sim.state.vel);
    // The allowance: against the swing run at the same time where it recorded a profile, else
    // against its largest, else the floor alone.
    const bool profiled = !profile_.held.empty() && reversalSwing_ >= 0.0 && std::isfinite(reversalSwing_);
    const double floor = (profiled ? kProfileFloor : kReversalFloor) * speedScale_;
    const double allowed = profiled                ? std::max(kReversalMargin * profile_.near(sim.state.time), floor)
                           : reversalSwing_ >= 0.0 ? std::max(kReversalMargin * reversalSwing_, floor)
                                                   : floor;
    // Only past the step's limit, swing run or not: a contact with friction chatters at every
    // dt, given time (the cloth on the slope under velocity Verlet reverses by 2.5e-3 m/s a
    // step from 9 s at half the limit, from 5 s at 0.8 times, from 4.1 s at 0.97 times: as much
    // as the capped instability at 1.03 times), and what tells the two apart is whether the
    // step itself is past its limit.
    if (held > allowed && beyondLimit(sim, dt) && turningMassIsDamped(sim)) {
      std::ostringstream os;
      os << "a capped instability: mass " << reversal_.lastMass() << "'s velocity (and others') turned back every step for "
         << StepReversal::kWindow << " steps, by at least " << held << " m/s a step, where a stable step damps such motion "
         << "(allowed " << allowed << " m/s: ";
      if (profiled) {
        os << kReversalMargin << " times what the scene held at half the stability limit near t = " << sim.state.time
           << " s, " << profile_.near(sim.state.time) << " m/s";
      } else if (reversalSwing_ >= 0.0) {
        os << kReversalMargin << " times what the scene held at half the stability limit, " << reversalSwing_ << " m/s";
      } else {
        os << "a thousandth of the speed its energy scale stands for; no swing was measured";
      }
      os << "; dt is past the step's limit); something in the scene that is not linear (a contact, the stretch limit, the wind's drag) keeps it from growing, so the energy does not show it";
      why = os.str();
    }
  }
  // Detector 6, held motion: kinetic energy the swing run had damped away at the same time,
  // kept (its mean over a window, so a mode's exchange with its springs does not hide it). Past
  // the step's limit only, as detector 5, and only against a swing run's profile; off with
  // detector 5 (an infinite reversal swing).
  if (why.empty() && sim.integrator().restsAtStaticEquilibrium() && !profile_.kinetic.empty() &&
      std::isfinite(reversalSwing_)) {
    if (lastStep_ + 1 != sim.stats.steps) kineticCount_ = 0;
    double kinetic = 0.0;
    for (int i = 0; i < sim.numOfMasses(); ++i) kinetic += 0.5 * sim.masses[i].m * sim.state.vel[i].squaredNorm();
    kinetics_[static_cast<std::size_t>(kineticCount_ % StepReversal::kWindow)] = kinetic;
    ++kineticCount_;
    if (kineticCount_ >= StepReversal::kWindow) {
      double mean = 0.0;
      for (double k : kinetics_) mean += k;
      mean /= StepReversal::kWindow;
      const double swing = profile_.kineticNear(sim.state.time);
      const double allowed = std::max(kMotionMargin * swing, kMotionFloor * energyScale_);
      if (mean > allowed && beyondLimit(sim, dt)) {
        std::ostringstream os;
        os << "held motion: the masses kept " << mean << " J of kinetic energy on average over the last "
           << StepReversal::kWindow << " steps, where the run at half the stability limit held at most " << swing
           << " J near t = " << sim.state.time << " s (allowed " << allowed << " J: " << kMotionMargin
           << " times that, and at least " << kMotionFloor
           << " of the energy scale; dt is past the step's limit); a mode past its limit grows until a contact or "
              "the springs' nonlinearity holds it, so the energy does not show it";
        why = os.str();
      }
    }
  }
  if (why.empty()) {
    last_.time = sim.state.time;
    last_.pos = sim.state.pos;  // copies reuse the vectors' storage
    last_.vel = sim.state.vel;
    lastStep_ = sim.stats.steps;
    return;
  }

  std::ostringstream msg;
  msg << "simulation blew up at t = " << sim.state.time << " s (step " << sim.stats.steps << "): " << why << ". ";
  const Integrator& integrator = sim.integrator();
  if (!finiteState) {
    // A non-finite state: did the forces go first? Then dt is not to blame.
    const std::string forces = blameForces(sim);
    if (!forces.empty()) {
      msg << "Likely cause: " << forces << ".";
      throw BlowUp(msg.str());
    }
    // Finite forces at a state of ordinary energy, non-finite state one step later: the
    // step itself (or a force at one of its inner stages) made it, not an instability that grows.
    double lastEnergy = 0.0;
    for (std::size_t i = 0; i < last_.vel.size() && i < sim.masses.size(); ++i) {
      lastEnergy += 0.5 * sim.masses[i].m * last_.vel[i].squaredNorm();
    }
    if (last_.pos.size() == sim.masses.size() && lastEnergy <= kRunawayFactor * energyScale_ && lastStep_ + 1 >= sim.stats.steps) {
      msg << "The forces at the last finite state (t = " << last_.time << " s, step " << lastStep_
          << ") are finite, and one step of " << integrator.name()
          << " made the state non-finite: look at the integrator's update (a division by zero, a value never "
             "initialised) or at the forces at its inner stages; a dt that is too large makes energy grow over many "
             "steps first, so dt is not the likely cause.";
      throw BlowUp(msg.str());
    }
  }

  // Name the likely cause: dt against the exact limit of the step that runs (computed once
  // per dt: the passivity detector may have needed it already). A study's trial leaves it out.
  if (!explainCause_) {
    msg << "The likely cause is not computed here (a study's trial; `springlab sim` with this dt names it).";
    throw BlowUp(msg.str());
  }
  const std::string name = integrator.name();
  const double limit = dt == limitDt_ ? limit_ : exactLimit(sim);
  if (std::isnan(limit)) {
    msg << "The stability limit of " << name << " on this scene could not be computed (where it settles, its step is "
        << "not smooth: a contact switching on or off exactly there); try a smaller dt.";
  } else if (std::isinf(limit)) {
    msg << "Likely cause: not dt: " << name << " is stable at every dt on this scene linearised where it settles. Look "
        << "for a force that grows without bound, a contact or a constraint that adds energy.";
  } else if (limit == 0.0) {
    msg << "Likely cause: " << name << " has no stable dt on this scene (the linearised step grows at every dt: "
        << "an undamped mode); damp the springs or use symplectic_euler, a Verlet method or an implicit one.";
  } else if (dt > limit) {
    msg << "Likely cause: dt = " << dt << " s is too large: the linearised step of " << name
        << " on this scene (dampers, air, contacts and pressure included) is stable only below dt = " << limit
        << " s.";
  } else {
    // Below the limit where the scene settles, the run may still have passed through a state
    // stiffer than its rest (the dropped ball's squash on the floor, whose contact damper
    // lowers symplectic Euler's limit from 1.78 to 1.43 ms). The limit where it was stopped
    // says whether dt was the cause there, but that state may be the blow-up's own (the
    // trampoline in the wind under explicit Euler at 0.8 times its limit: 0.094 ms there), so
    // where it is past dt or not smooth, a run from the scene's start at half dt tells (when
    // this run is that run and replaying it costs at most kCalmWork). Neither is computed where
    // the first limit came from elsewhere (the viewer's worker): it would hold the caller's
    // thread (seconds on the 80-mass rope).
    const State& stopped = finiteState ? sim.state : last_;
    const bool computable = !sim.knownStepLimit() && stopped.pos.size() == sim.masses.size();
    const double here = computable ? stepLimitAt(sim, stopped) : NAN;
    const double replayWork = 2.0 * static_cast<double>(sim.stats.steps) * sim.numOfMasses();
    const CalmRun calm = computable && !(dt <= here) && armedStep_ == 0 && replayWork <= kCalmWork
                             ? calmRun(sim, dt, kCalmMargin, 0.0, stopped.time, kCalmSamples, kCalmLimits)
                             : CalmRun{};
    msg << "dt = " << dt << " s is below the stability limit of " << name << " on this scene linearised where it settles ("
        << limit << " s)";
    if (std::isfinite(calm.limit)) {
      msg << ", but not below " << kCalmMargin << " times its limit in a state a run from the start at half this dt "
          << "passes through (t = " << calm.time << " s: " << calm.limit << " s). Likely cause: dt, in a state "
          << "stiffer than the rest (a contact, a squash, a stretched configuration): try a dt below "
          << kCalmMargin * calm.limit << " s.";
    } else if (calm.states > 0 && calm.cleared == calm.states) {
      // What put the energy in, for the user to look at: the step's own or the corrections'.
      msg << " and " << kCalmMargin << " times its limit at every state of a run from the start at half this dt ("
          << calm.states << " linearised); where this run was stopped (t = " << stopped.time << " s) ";
      if (std::isfinite(here)) {
        msg << "the state is the blow-up's own (its limit " << here << " s).";
      } else {
        msg << "its step is not smooth.";
      }
      msg << " So the step is not the likely cause: look for a force that grows without bound, a contact or a "
          << "constraint that adds energy (since the start the corrections after each step put in "
          << sim.correctionWork() - armedCorrections_ << " J, and the step's own energy changed by "
          << sim.energyBalance() - armedBalance_ << " J).";
    } else if (std::isfinite(here) && dt > here) {
      msg << ", but not below its limit where the run was stopped (t = " << stopped.time << " s: " << here
          << " s). Likely cause: dt, in a state stiffer than the rest (a contact, a squash, a stretched "
          << "configuration): try a dt below " << here << " s.";
    } else {
      if (std::isfinite(here)) msg << " and where the run was stopped (t = " << stopped.time << " s: " << here << " s)";
      if (!computable) msg << " (its limit where the run was stopped is not computed here: `springlab sim` with this dt names it)";
      msg << ", so the step is not the likely cause: look for a force that grows without bound, a contact or a "
          << "constraint that adds energy.";
    }
  }
  throw BlowUp(msg.str());
}

}  // namespace springlab
