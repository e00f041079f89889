// Exercise 1.6, velocity Verlet step (labs/01_rope/velocity_verlet.cpp): its public tests.
#include <gtest/gtest.h>

#include <cmath>

#include <springlab/rope/rope.hpp>
#include "rope_oscillator.hpp"
#include "seeded.hpp"

namespace springlab::rope {
namespace {

using VelocityVerlet = springlab::testing::Seeded;
using springlab::testing::kOmega;
using springlab::testing::Method;
using springlab::testing::observedOrder;
using springlab::testing::run;
using springlab::testing::spring;

const Method velocityVerlet = [](const PhasePoint& s, const Vec3&, bool, double dt) {
  const Vec3 x = velocityVerletPosition(s, spring(s.pos), dt);
  return PhasePoint{x, velocityVerletVelocity(s.vel, spring(s.pos), spring(x), dt)};
};

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
