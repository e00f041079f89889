#include "springlab/energy_source.hpp"

#include <cmath>
#include <sstream>

#include "springlab/simulation.hpp"

namespace springlab {

namespace {

// sum_i v_i . f_i
double power(const std::vector<Vec3>& f, const std::vector<Vec3>& v) {
  double p = 0.0;
  for (std::size_t i = 0; i < f.size() && i < v.size(); ++i) p += f[i].dot(v[i]);
  return p;
}

// sum_i |f_i| |v_i|: the scale the power's change is measured against.
double powerScale(const std::vector<Vec3>& f, const std::vector<Vec3>& v) {
  double s = 0.0;
  for (std::size_t i = 0; i < f.size() && i < v.size(); ++i) s += f[i].norm() * v[i].norm();
  return s;
}

}  // namespace

std::optional<std::string> energySourceWarning(Simulation& sim) {
  const std::vector<std::string> terms = sim.forceTermNames();
  const State& now = sim.state;
  double speed = 0.0;
  for (const Vec3& v : now.vel) speed = std::max(speed, v.norm());
  if (terms.empty() || !(speed > 0.0) || !std::isfinite(speed)) return std::nullopt;

  // Only a scene that holds more energy than it started with can have a source: a force that
  // releases what it stored (a contact spring pushing a ball back out) passes the test below
  // for a moment, and says nothing then.
  const double energyNow = sim.energies().total();
  const State saved = sim.state;
  sim.state = sim.initialState();
  const double energyAtStart = sim.energies().total();
  sim.state = saved;
  if (!(energyNow > energyAtStart)) return std::nullopt;

  // The state with every velocity doubled (positions and time the same).
  State faster = now;
  for (Vec3& v : faster.vel) v *= 2.0;
  const Stats stats = sim.stats;
  std::vector<Vec3> all, allFast, without, withoutFast;
  std::optional<std::string> warning;
  try {
    sim.evaluateForces(now, all);
    sim.evaluateForces(faster, allFast);
    const double scale = powerScale(all, now.vel) + powerScale(allFast, now.vel);
    for (int k = 0; k < static_cast<int>(terms.size()) && !warning; ++k) {
      sim.muteForceTerm(k);
      sim.evaluateForces(now, without);
      sim.evaluateForces(faster, withoutFast);
      sim.muteForceTerm(-1);
      // The term's force is the total minus the total without it; its change when the
      // velocities double, dotted with the velocities: <= 0 for anything passive.
      const double gain = (power(allFast, now.vel) - power(withoutFast, now.vel)) -
                          (power(all, now.vel) - power(without, now.vel));
      if (gain > 1e-6 * scale) {
        std::ostringstream os;
        os << "the " << sim.kind() << "'s " << terms[static_cast<std::size_t>(k)]
           << " pushes the masses along their own velocity: it feeds energy into the scene at every step, at any dt"
           << " (kinetic energy now " << sim.energies().kinetic
           << " J); a passive force only takes energy out as things move faster: check its sign";
        warning = os.str();
      }
    }
  } catch (const std::exception&) {
    // A force that cannot be evaluated here says nothing about energy; the run's own
    // messages report it.
    warning.reset();
  }
  sim.muteForceTerm(-1);
  sim.stats = stats;
  return warning;
}

}  // namespace springlab
