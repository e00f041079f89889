// Exercises 1.7 and 1.8, and the rope as a whole: statics, oscillation, conservation.
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
using FixedEnd = springlab::testing::Seeded;
using HangingRope = springlab::testing::Seeded;
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

TEST_F(FixedEnd, MovesWithTheConnectionVelocity) {
  const PhasePoint c{vec3(-1, 1) + Vec3(0, 5, 0), vec3(-1, 1)};
  const double dt = uniform(0.001, 0.05);
  const PhasePoint next = moveConnection(c, dt, -10.0);
  EXPECT_LT((next.pos - (c.pos + c.vel * dt)).norm(), 1e-12) << "the connection point moves by v dt " << seedText();
  EXPECT_LT((next.vel - c.vel).norm(), 1e-12) << "above the ground the connection keeps its velocity " << seedText();
}

TEST_F(FixedEnd, StopsAtTheGround) {
  const double ground = uniform(-2, 0);
  const PhasePoint c{Vec3(0.3, ground + 0.01, -0.2), Vec3(1, -5, 0.5)};
  const PhasePoint next = moveConnection(c, 0.1, ground);
  EXPECT_NEAR(next.pos.y(), ground, 1e-12) << "the connection point must stop at the ground height " << seedText();
  EXPECT_EQ(next.vel.y(), 0.0) << "at the ground the connection point loses its downward velocity";
  EXPECT_NEAR(next.pos.x(), 0.4, 1e-12) << "the ground stops only the vertical motion";
}

TEST_F(FixedEnd, RopeFollowsTheConnectionPoint) {
  RopeParameters p = quietRope(10, 0.05, 1000, 0.1, 0.5);
  Rope rope(3, p);
  const Vec3 v = vec3(-1, 1);
  rope.setControlVelocity(v);
  for (int n = 0; n < 100; ++n) rope.operate(0.001);
  EXPECT_LT((rope.state.pos[0] - (p.ropeConnectionPos + v * 0.1)).norm(), 1e-9)
      << "after 0.1 s the fixed end must be where the moving connection point is " << seedText();
  EXPECT_LT((rope.state.vel[0] - v).norm(), 1e-9) << "the fixed end must move with the connection point";
}

TEST_F(HangingRope, EachSpringCarriesTheWeightBelowIt) {
  // A rope hanging straight down settles where spring i holds the weight of the masses below.
  const int n = integer(5, 10);
  RopeParameters p = quietRope(n, 0.1, 200, 0.1, 2.0);
  p.direction = Vec3(0, -1, 0);
  p.gravitation = Vec3(0, -9.81, 0);
  p.airFrictionConstant = 0.3;
  Rope rope(3, p);
  for (int step = 0; step < 30000; ++step) rope.operate(0.001);
  for (int i = 0; i + 1 < n; ++i) {
    const double stretch = (rope.state.pos[i] - rope.state.pos[i + 1]).norm() - p.springLength;
    const double expected = (n - 1 - i) * p.mass * 9.81 / p.springConstant;
    EXPECT_NEAR(stretch, expected, 0.01 * expected + 1e-6)
        << "at rest, spring " << i << " must stretch by (weight of the " << n - 1 - i << " masses below) / k "
        << seedText();
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

TEST_F(RopeDynamics, InternalForcesConserveMomentum) {
  // Without gravity, air and ground, forces are spring forces only: they sum to zero.
  RopeParameters p = quietRope(integer(3, 30), 0.05, uniform(10, 1e4), 0.1, uniform(0, 1));
  Rope rope(3, p);
  for (int i = 0; i < rope.numOfMasses(); ++i) {
    rope.state.pos[i] += vec3(-0.05, 0.05);
    rope.state.vel[i] = vec3(-1, 1);
  }
  rope.init();
  rope.solve();
  Vec3 total = Vec3::Zero();
  double scale = 0;
  for (const Vec3& f : rope.force) {
    total += f;
    scale += f.norm();
  }
  EXPECT_LT(total.norm(), 1e-9 * std::max(1.0, scale))
      << "the rope's internal forces must sum to zero (momentum is conserved) " << seedText();
}

TEST_F(RopeDynamics, SymplecticEulerKeepsEnergyBoundedAndExplicitEulerGainsIt) {
  // An undamped mass on a spring at w dt = 0.2: energy oscillates within about +-w dt/2 with
  // symplectic Euler, and grows by (1 + (w dt)^2) per step with explicit Euler.
  auto energyAfter = [](const std::string& method) {
    Registry registry = springlab::testing::ropeRegistry();
    RopeParameters p = quietRope(2, 1.0, 100.0, 1.0, 0.0);
    Rope rope(3, p);
    rope.setIntegrator(registry.makeIntegrator(method));
    rope.setBlowUpCheck(false);
    rope.state.pos[1].x() += 0.1;
    const double e0 = rope.energies().total();
    double worst = 1.0;
    for (int n = 0; n < 2000; ++n) {
      rope.operate(0.02);
      worst = std::max(worst, rope.energies().total() / e0);
    }
    return std::pair{rope.energies().total() / e0, worst};  // final and largest E / E0
  };
  EXPECT_LT(energyAfter("symplectic_euler").second, 1.15)
      << "symplectic Euler's energy must stay bounded on an undamped spring";
  EXPECT_GT(energyAfter("explicit_euler").first, 1.0e6)
      << "explicit Euler must gain energy on an undamped spring (factor 1.04 per step)";
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
