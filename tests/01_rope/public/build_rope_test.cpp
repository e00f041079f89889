// Exercise 1.7, building the rope (labs/01_rope/build_rope.cpp): its public tests.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <springlab/rope/rope.hpp>
#include "rope_fixtures.hpp"
#include "seeded.hpp"

namespace springlab::rope {
namespace {

using springlab::testing::quietRope;
using BuildRope = springlab::testing::Seeded;
using OneMassOnASpring = springlab::testing::Seeded;
using RopeDynamics = springlab::testing::Seeded;

TEST_F(BuildRope, HasOneSpringPerNeighbourPairAtRestLength) {
  RopeParameters p = quietRope(integer(2, 50), uniform(0.01, 1), uniform(1, 1e4), uniform(0.01, 0.5), uniform(0, 1));
  const RopeLayout r = buildRope(p);
  ASSERT_EQ(r.springs.size(), static_cast<size_t>(p.numOfMasses - 1)) << "a rope of n masses has n - 1 springs " << seedText();
  for (size_t i = 0; i < r.springs.size(); ++i) {
    const Spring& s = r.springs[i];
    EXPECT_EQ(std::abs(s.mass1 - s.mass2), 1) << "spring " << i << " must join neighbouring masses";
    EXPECT_DOUBLE_EQ(s.springConstant, p.springConstant) << "spring " << i << " has the wrong stiffness";
    EXPECT_DOUBLE_EQ(s.springLength, p.springLength) << "spring " << i << " has the wrong rest length";
    EXPECT_DOUBLE_EQ(s.frictionConstant, p.springFrictionConstant) << "spring " << i << " has the wrong damping";
  }
}

TEST_F(BuildRope, FirstMassIsFixedAtTheConnectionPoint) {
  RopeParameters p = quietRope(integer(2, 50), uniform(0.01, 1), 100, 0.1, 0);
  p.ropeConnectionPos = vec3(-2, 2);
  const RopeLayout r = buildRope(p);
  ASSERT_EQ(r.masses.size(), static_cast<size_t>(p.numOfMasses)) << "wrong number of masses " << seedText();
  EXPECT_TRUE(r.masses[0].pinned) << "the first mass is the fixed end: it must be pinned";
  EXPECT_LT((r.pos[0] - p.ropeConnectionPos).norm(), 1e-12) << "the fixed end must start at the connection point";
  for (size_t i = 1; i < r.masses.size(); ++i) {
    EXPECT_FALSE(r.masses[i].pinned) << "only the first mass is fixed; mass " << i << " is pinned";
    EXPECT_DOUBLE_EQ(r.masses[i].m, p.mass) << "mass " << i << " has the wrong mass";
  }
}

TEST_F(BuildRope, MassesLieAlongTheDirectionAtRest) {
  RopeParameters p = quietRope(integer(2, 50), 0.05, 100, uniform(0.01, 0.5), 0);
  p.direction = vec3(-1, 1).normalized();
  const RopeLayout r = buildRope(p);
  ASSERT_EQ(r.pos.size(), static_cast<size_t>(p.numOfMasses));
  ASSERT_EQ(r.vel.size(), static_cast<size_t>(p.numOfMasses));
  for (int i = 0; i < p.numOfMasses; ++i) {
    EXPECT_LT((r.pos[i] - (p.ropeConnectionPos + i * p.springLength * p.direction)).norm(), 1e-12)
        << "mass " << i << " must sit i rest lengths from the connection point along the direction " << seedText();
    EXPECT_EQ(r.vel[i], Vec3::Zero()) << "the rope starts at rest; mass " << i << " moves";
  }
}

TEST_F(OneMassOnASpring, PeriodIs2PiSqrtMOverK) {
  // One free mass on a spring to the fixed end: x(t) = A cos(sqrt(k/m) t).
  constexpr double mMax = 2.0, kMin = 50.0;
  const double m = uniform(0.1, mMax), k = uniform(kMin, 500);
  const double expected = 2 * std::numbers::pi * std::sqrt(m / k);
  RopeParameters p = quietRope(2, m, k, 1.0, 0.0);
  Rope rope(3, p);
  rope.state.pos[1].x() += 0.1;
  const double dt = 1e-4;
  // 10 periods after the first crossing (T/4) take at most 10.25 * 2 pi sqrt(mMax/kMin) = 12.9 s; run
  // 15 longest periods (18.8 s) so a period up to 45 % too long on the slowest draw is still measured.
  constexpr int kPeriods = 10;
  const double longestPeriod = 2 * std::numbers::pi * std::sqrt(mMax / kMin);
  const int maxSteps = static_cast<int>(std::ceil(15 * longestPeriod / dt));
  double previous = 0.1, firstCrossing = -1, lastCrossing = -1;
  int crossings = 0;
  for (int step = 0; step < maxSteps && crossings < kPeriods + 1; ++step) {
    rope.operate(dt);
    const double d = rope.state.pos[1].x() - 1.0;
    if (previous > 0 && d <= 0) {  // downward zero crossing, once per period
      const double t = rope.state.time - dt * d / (d - previous);
      if (crossings == 0) firstCrossing = t;
      lastCrossing = t;
      ++crossings;
    }
    previous = d;
  }
  if (crossings < 2) {
    FAIL() << "the mass on a spring (m = " << m << " kg, k = " << k << " N/m) does not oscillate: "
           << crossings << " downward crossings of its rest position in " << rope.state.time << " s, where "
           << "2 pi sqrt(m/k) = " << expected << " s " << seedText();
  }
  // Too few crossings for 10 periods: measure the period over those seen, so the message gives it.
  const double period = (lastCrossing - firstCrossing) / (crossings - 1);
  EXPECT_GE(crossings, kPeriods + 1) << "the mass on a spring oscillates too slowly: only " << crossings - 1
                                     << " periods of " << period << " s in " << rope.state.time << " s, where 2 pi "
                                     << "sqrt(m/k) = " << expected << " s (m = " << m << " kg, k = " << k << " N/m) "
                                     << seedText();
  EXPECT_NEAR(period, expected, 0.002 * period)
      << "one mass on a spring must oscillate with period 2 pi sqrt(m/k) (m = " << m << " kg, k = " << k
      << " N/m) " << seedText();
}

TEST_F(RopeDynamics, PlanarRopeStaysExactlyInItsPlane) {
  RopeParameters p = quietRope(20, 0.05, 1000, 0.05, 0.2);
  p.gravitation = Vec3(0, -9.81, 0);
  p.airFrictionConstant = 0.02;
  p.ground = Ground{-0.5, 100, 0.2, 2};
  Rope rope(2, p);
  rope.setControlVelocity(Vec3(uniform(-1, 1), uniform(-1, 1), 0));
  for (int n = 0; n < 3000; ++n) rope.operate(0.001);
  for (int i = 0; i < rope.numOfMasses(); ++i) {
    ASSERT_EQ(rope.state.pos[i].z(), 0.0) << "a 2D rope must stay exactly in the plane z = 0 (mass " << i << ")";
  }
}

}  // namespace
}  // namespace springlab::rope
