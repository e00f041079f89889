// Exercise 1.5, position Verlet step (labs/01_rope/position_verlet.cpp): its public tests.
#include <gtest/gtest.h>

#include <cmath>

#include <springlab/rope/rope.hpp>
#include "rope_oscillator.hpp"
#include "seeded.hpp"

namespace springlab::rope {
namespace {

using PositionVerlet = springlab::testing::Seeded;
using springlab::testing::kOmega;
using springlab::testing::Method;
using springlab::testing::observedOrder;
using springlab::testing::run;
using springlab::testing::spring;

const Method positionVerlet = [](const PhasePoint& s, const Vec3& previous, bool first, double dt) {
  return first ? positionVerletFirstStep(s, spring(s.pos), dt) : positionVerletStep(s.pos, previous, spring(s.pos), dt);
};

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

}  // namespace
}  // namespace springlab::rope
