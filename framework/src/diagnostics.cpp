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
  for (const Spring& s : sim.springs) {
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
  for (const Spring& s : sim.springs) extent += s.springLength;
  for (const Mass& m : sim.masses) totalMass += m.m;
  energyScale_ = std::abs(e.kinetic) + std::abs(e.elastic) + std::abs(e.other) +
                 totalMass * (sim.gravitation.norm() * extent + 1.0);
}

void BlowUpCheck::admitUserEnergy(const Simulation& sim) {
  const double before = energyScale_;
  arm(sim);
  energyScale_ = std::max(before, energyScale_);
}

void BlowUpCheck::check(Simulation& sim, double dt) const {
  // Non-finite state: name the first mass that went bad.
  std::string why;
  for (int i = 0; i < sim.numOfMasses() && why.empty(); ++i) {
    if (!sim.state.pos[i].allFinite() || !sim.state.vel[i].allFinite()) {
      why = "mass " + std::to_string(i) + " has a non-finite position or velocity";
    }
  }
  // Runaway energy: kinetic plus potential energy (springs and the lab's own: ground, gas)
  // far beyond anything the scene can hold. The lab's potentials count because a source
  // such as a gas pays for the elastic energy it stores with its own (-nRT ln V falls).
  if (why.empty()) {
    const Energies e = sim.energies();
    const double grown = e.kinetic + e.elastic + e.other;
    if (!(grown <= kRunawayFactor * energyScale_)) {
      std::ostringstream os;
      os << "kinetic + elastic + other potential energy reached " << grown << " J, over " << kRunawayFactor
         << " times the scene's energy scale of " << energyScale_ << " J";
      why = os.str();
    }
  }
  if (why.empty()) return;

  // Name the likely cause: dt against the integrator's stability limit, with w_max from the
  // linearised scene at its initial state (Lanczos); Gershgorin's bound when that finds nothing.
  const Integrator& integrator = sim.integrator();
  double wMax = lanczosEstimate(sim, sim.initialState()).maxAngularFrequency;
  if (!(wMax > 0.0) || !std::isfinite(wMax)) wMax = sim.angularFrequencyBound();
  const double safeDt = predictedStableDt(integrator, wMax);
  std::ostringstream msg;
  msg << "simulation blew up at t = " << sim.state.time << " s (step " << sim.stats.steps << "): " << why
      << ". ";
  if (integrator.stabilityConstant() <= 0.0) {
    msg << "Likely cause: " << integrator.name()
        << " gains energy at every dt on undamped springs (w_max = " << wMax
        << " rad/s); use symplectic_euler or a Verlet method, or a much smaller dt with damping.";
  } else {
    msg << "Likely cause: dt = " << dt << " s is too large for " << integrator.name()
        << ": the stiffest mode has w_max ~ " << wMax << " rad/s, so dt must stay below about "
        << integrator.stabilityConstant() << " / w_max = " << safeDt << " s.";
    if (dt <= safeDt) msg << " dt is below that limit: look for a force that grows without bound.";
  }
  throw BlowUp(msg.str());
}

}  // namespace springlab
