#pragma once
// The harmonic oscillator x'' = -w^2 x, marched from x = 1, v = 0 by one integrator step: the
// exact answers (energy, phase, order of convergence) the step tests of exercises 1.4 to 1.6
// compare with.
#include <cmath>
#include <functional>
#include <vector>

#include <springlab/rope/rope.hpp>

namespace springlab::testing {

using rope::PhasePoint;

constexpr double kOmega = 2.0;  // rad/s

inline Vec3 spring(const Vec3& x) { return -kOmega * kOmega * x; }

// Oscillator energy per unit mass.
inline double energy(const PhasePoint& s) { return 0.5 * (s.vel.squaredNorm() + kOmega * kOmega * s.pos.squaredNorm()); }

// March the oscillator from x = 1, v = 0 for `steps` steps with one method.
using Method = std::function<PhasePoint(const PhasePoint&, const Vec3& previousPos, bool first, double dt)>;

inline PhasePoint run(const Method& method, double dt, int steps, std::vector<double>* energies = nullptr) {
  PhasePoint s{Vec3(1, 0, 0), Vec3::Zero()};
  Vec3 previous = s.pos;
  for (int n = 0; n < steps; ++n) {
    const PhasePoint next = method(s, previous, n == 0, dt);
    previous = s.pos;
    s = next;
    if (energies) energies->push_back(energy(s));
  }
  return s;
}

// Observed order from the position error at t = 1 s with dt and dt/2.
inline double observedOrder(const Method& method) {
  const double exact = std::cos(kOmega * 1.0);
  const double e1 = std::abs(run(method, 0.01, 100).pos.x() - exact);
  const double e2 = std::abs(run(method, 0.005, 200).pos.x() - exact);
  return std::log2(e1 / e2);
}

}  // namespace springlab::testing
