// Exercises 1.4 to 1.6: the integrator steps, on problems with exact answers: free fall
// (constant acceleration) and the harmonic oscillator x'' = -w^2 x.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include <springlab/rope/rope.hpp>
#include "seeded.hpp"

namespace springlab::rope {
namespace {

using ExplicitEuler = springlab::testing::Seeded;
using PositionVerlet = springlab::testing::Seeded;
using VelocityVerlet = springlab::testing::Seeded;

constexpr double kOmega = 2.0;  // rad/s

Vec3 spring(const Vec3& x) { return -kOmega * kOmega * x; }

// Oscillator energy per unit mass.
double energy(const PhasePoint& s) { return 0.5 * (s.vel.squaredNorm() + kOmega * kOmega * s.pos.squaredNorm()); }

// March the oscillator from x = 1, v = 0 for `steps` steps with one method.
using Method = std::function<PhasePoint(const PhasePoint&, const Vec3& previousPos, bool first, double dt)>;

PhasePoint run(const Method& method, double dt, int steps, std::vector<double>* energies = nullptr) {
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

const Method explicitEuler = [](const PhasePoint& s, const Vec3&, bool, double dt) {
  return explicitEulerStep(s, spring(s.pos), dt);
};
const Method positionVerlet = [](const PhasePoint& s, const Vec3& previous, bool first, double dt) {
  return first ? positionVerletFirstStep(s, spring(s.pos), dt) : positionVerletStep(s.pos, previous, spring(s.pos), dt);
};
const Method velocityVerlet = [](const PhasePoint& s, const Vec3&, bool, double dt) {
  const Vec3 x = velocityVerletPosition(s, spring(s.pos), dt);
  return PhasePoint{x, velocityVerletVelocity(s.vel, spring(s.pos), spring(x), dt)};
};

// Observed order from the position error at t = 1 s with dt and dt/2.
double observedOrder(const Method& method) {
  const double exact = std::cos(kOmega * 1.0);
  const double e1 = std::abs(run(method, 0.01, 100).pos.x() - exact);
  const double e2 = std::abs(run(method, 0.005, 200).pos.x() - exact);
  return std::log2(e1 / e2);
}

TEST_F(ExplicitEuler, UpdatesFromTheOldState) {
  const PhasePoint s{vec3(-1, 1), vec3(-1, 1)};
  const Vec3 a = vec3(-10, 10);
  const double dt = uniform(0.001, 0.1);
  const PhasePoint next = explicitEulerStep(s, a, dt);
  EXPECT_LT((next.pos - (s.pos + s.vel * dt)).norm(), 1e-12)
      << "explicit Euler moves the position with the OLD velocity (the new one makes it symplectic Euler) "
      << seedText();
  EXPECT_LT((next.vel - (s.vel + a * dt)).norm(), 1e-12) << "explicit Euler: v' = v + a dt " << seedText();
}

TEST_F(ExplicitEuler, OscillatorEnergyGrowsBy1PlusWdtSquaredEachStep) {
  const double dt = uniform(0.01, 0.2);
  std::vector<double> e;
  run(explicitEuler, dt, 50, &e);
  const double gain = 1.0 + kOmega * kOmega * dt * dt;
  EXPECT_NEAR(e.back() / 0.5 / (kOmega * kOmega), std::pow(gain, 50), 1e-9 * std::pow(gain, 50))
      << "on an undamped oscillator explicit Euler multiplies the energy by exactly 1 + (w dt)^2 per step "
      << seedText();
}

TEST_F(ExplicitEuler, ConvergesAtFirstOrder) {
  EXPECT_NEAR(observedOrder(explicitEuler), 1.0, 0.15) << "halving dt must halve explicit Euler's error";
}

TEST_F(PositionVerlet, FirstStepIsATaylorStep) {
  const PhasePoint s{vec3(-1, 1), vec3(-1, 1)};
  const Vec3 a = vec3(-10, 10);
  const double dt = uniform(0.001, 0.1);
  const PhasePoint next = positionVerletFirstStep(s, a, dt);
  EXPECT_LT((next.pos - (s.pos + s.vel * dt + 0.5 * a * dt * dt)).norm(), 1e-12)
      << "the first Verlet step has no previous position: x1 = x0 + v0 dt + a dt^2 / 2 " << seedText();
  EXPECT_LT((next.vel - (next.pos - s.pos) / dt).norm(), 1e-9)
      << "Verlet's velocity is estimated from the positions: (x1 - x0) / dt " << seedText();
}

TEST_F(PositionVerlet, IsExactForConstantAcceleration) {
  const PhasePoint start{vec3(-1, 1), vec3(-1, 1)};
  const Vec3 g = vec3(-10, 10);
  const double dt = uniform(0.001, 0.05);
  PhasePoint s = positionVerletFirstStep(start, g, dt);
  Vec3 previous = start.pos;
  for (int n = 1; n < 100; ++n) {
    const PhasePoint next = positionVerletStep(s.pos, previous, g, dt);
    previous = s.pos;
    s = next;
  }
  const double t = 100 * dt;
  EXPECT_LT((s.pos - (start.pos + start.vel * t + 0.5 * g * t * t)).norm(), 1e-9)
      << "position Verlet must follow a free fall x0 + v0 t + g t^2 / 2 exactly " << seedText();
}

TEST_F(PositionVerlet, OscillatorEnergyStaysBounded) {
  std::vector<double> e;
  run(positionVerlet, 0.5 / kOmega, 20000, &e);  // w dt = 0.5, 1600 periods
  const double e0 = 0.5 * kOmega * kOmega;
  for (double en : e) ASSERT_LT(std::abs(en - e0), 0.3 * e0) << "position Verlet's energy must stay bounded (it drifted)";
}

TEST_F(PositionVerlet, ConvergesAtSecondOrder) {
  EXPECT_NEAR(observedOrder(positionVerlet), 2.0, 0.15) << "halving dt must quarter position Verlet's error";
}

TEST_F(VelocityVerlet, IsExactForConstantAcceleration) {
  PhasePoint s{vec3(-1, 1), vec3(-1, 1)};
  const PhasePoint start = s;
  const Vec3 g = vec3(-10, 10);
  const double dt = uniform(0.001, 0.05);
  for (int n = 0; n < 100; ++n) s = PhasePoint{velocityVerletPosition(s, g, dt), velocityVerletVelocity(s.vel, g, g, dt)};
  const double t = 100 * dt;
  EXPECT_LT((s.pos - (start.pos + start.vel * t + 0.5 * g * t * t)).norm(), 1e-9)
      << "velocity Verlet must follow a free fall x0 + v0 t + g t^2 / 2 exactly " << seedText();
  EXPECT_LT((s.vel - (start.vel + g * t)).norm(), 1e-9) << "velocity Verlet: v = v0 + g t in free fall " << seedText();
}

TEST_F(VelocityVerlet, OscillatorEnergyStaysBounded) {
  std::vector<double> e;
  run(velocityVerlet, 1.0 / kOmega, 20000, &e);  // w dt = 1: half the stability limit 2
  const double e0 = 0.5 * kOmega * kOmega;
  for (double en : e) ASSERT_LT(std::abs(en - e0), 0.5 * e0) << "velocity Verlet's energy must stay bounded (it drifted)";
}

TEST_F(VelocityVerlet, ConvergesAtSecondOrder) {
  EXPECT_NEAR(observedOrder(velocityVerlet), 2.0, 0.15) << "halving dt must quarter velocity Verlet's error";
}

}  // namespace
}  // namespace springlab::rope
