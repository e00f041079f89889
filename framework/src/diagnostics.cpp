#include "springlab/diagnostics.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "springlab/frequency_estimate.hpp"
#include "springlab/simulation.hpp"

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

double predictedStableDt(const Integrator& integrator, double maxAngularFrequency) {
  if (maxAngularFrequency <= 0.0) return INFINITY;
  return integrator.stabilityConstant() / maxAngularFrequency;
}

double explicitEulerDampedStableDt(double beta, double maxAngularFrequency) {
  if (!(beta > 0.0)) return 0.0;
  if (!(maxAngularFrequency > 0.0)) return INFINITY;
  // Every underdamped mode allows dt < 2 zeta / w = beta; an overdamped stiffest mode less.
  const double zeta = 0.5 * beta * maxAngularFrequency;
  if (zeta <= 1.0) return beta;
  return 2.0 / (maxAngularFrequency * (zeta + std::sqrt(zeta * zeta - 1.0)));
}

double springDampingRatio(const Simulation& sim) {
  double beta = INFINITY;
  for (const Spring& s : sim.springs()) {
    if (s.springConstant > 0.0) beta = std::min(beta, s.frictionConstant / s.springConstant);
  }
  return std::isfinite(beta) ? beta : 0.0;
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
  last_ = sim.state;
  lastStep_ = sim.stats.steps;
}

void BlowUpCheck::admitUserEnergy(const Simulation& sim) {
  const double before = energyScale_;
  arm(sim);
  energyScale_ = std::max(before, energyScale_);
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

void BlowUpCheck::check(Simulation& sim, double dt) {
  // Non-finite state: name the first mass that went bad.
  std::string why;
  for (int i = 0; i < sim.numOfMasses() && why.empty(); ++i) {
    if (!sim.state.pos[i].allFinite() || !sim.state.vel[i].allFinite()) {
      why = "mass " + std::to_string(i) + " has a non-finite position or velocity";
    }
  }
  bool runaway = false;
  // Runaway energy: kinetic plus potential energy (springs and the lab's own: ground, gas)
  // far beyond anything the scene can hold. The lab's potentials count because a source
  // such as a gas pays for the elastic energy it stores with its own (-nRT ln V falls).
  if (why.empty()) {
    const Energies e = sim.energies();
    const double grown = e.kinetic + e.elastic + e.other;
    if (!std::isfinite(grown)) {
      // A non-finite energy of a finite state is a non-finite value, not a growth: the forces'
      // story below, not dt's.
      std::ostringstream os;
      os << "kinetic + elastic + other potential energy is " << grown << " J (kinetic " << e.kinetic << ", elastic "
         << e.elastic << ", other " << e.other << ")";
      why = os.str();
    } else if (!(grown <= kRunawayFactor * energyScale_)) {
      std::ostringstream os;
      os << "kinetic + elastic + other potential energy reached " << grown << " J, over " << kRunawayFactor
         << " times the scene's energy scale of " << energyScale_ << " J";
      why = os.str();
      runaway = true;
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
  if (!runaway) {
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

  // Name the likely cause: dt against the integrator's stability limit, with w_max from the
  // linearised scene at its initial state (Lanczos); Gershgorin's bound when that finds nothing.
  double wMax = 0.0;
  try {
    wMax = lanczosEstimate(sim, sim.initialState()).maxAngularFrequency;
  } catch (const std::exception&) {
    wMax = 0.0;
  }
  if (!(wMax > 0.0) || !std::isfinite(wMax)) wMax = sim.angularFrequencyBound();
  const double beta = springDampingRatio(sim);
  if (integrator.stabilityConstant() <= 0.0 && integrator.name() == "explicit_euler" && beta > 0.0) {
    // Explicit Euler is stable only through damping: its damped limit, not the undamped rule.
    const double safeDt = explicitEulerDampedStableDt(beta, wMax);
    msg << "Likely cause: dt = " << dt << " s is too large for explicit_euler, which is stable only through "
        << "damping: with the springs' kd/k = " << beta << " s and w_max ~ " << wMax
        << " rad/s, dt must stay below about ";
    if (0.5 * beta * wMax <= 1.0) {
      msg << "kd/k = " << safeDt << " s.";
    } else {
      msg << "2 / (w_max (zeta + sqrt(zeta^2 - 1))) = " << safeDt << " s (the stiffest mode is overdamped, zeta = "
          << 0.5 * beta * wMax << ").";
    }
    if (dt <= safeDt) msg << " dt is below that limit: look for a force that grows without bound.";
  } else if (integrator.stabilityConstant() <= 0.0) {
    msg << "Likely cause: " << integrator.name()
        << " gains energy at every dt on undamped springs (w_max = " << wMax
        << " rad/s); use symplectic_euler or a Verlet method, or damp the springs (explicit Euler is then stable "
           "below dt = kd/k).";
  } else {
    const double safeDt = predictedStableDt(integrator, wMax);
    msg << "Likely cause: dt = " << dt << " s is too large for " << integrator.name()
        << ": the stiffest mode has w_max ~ " << wMax << " rad/s, so dt must stay below about "
        << integrator.stabilityConstant() << " / w_max = " << safeDt << " s.";
    if (dt <= safeDt) msg << " dt is below that limit: look for a force that grows without bound.";
  }
  throw BlowUp(msg.str());
}

}  // namespace springlab
