// Exercise 3.7, contact by a penalty spring (labs/03_softbody/penalty_contact.cpp): its public tests.
#include <gtest/gtest.h>

#include <cmath>

#include "seeded.hpp"
#include <springlab/softbody/softbody.hpp>
#include "softbody_fixtures.hpp"

namespace springlab::softbody {
namespace {

using springlab::testing::kMaterial;
using springlab::testing::ballAboveTheFloor;
using springlab::testing::run;

TEST(BallOnTheFloor, CollapsesWithoutPressure) {
  // Springs along a surface resist stretching, not folding: without gas the ball folds flat.
  SoftBody ball(3, ballAboveTheFloor(0.0, ContactMethod::Penalty));
  const double ratio = run(ball, 3.0, 5e-4);
  EXPECT_LT(ratio, 0.5) << "a ball without gas keeps " << 100 * ratio
                        << " % of its volume on the floor; springs alone cannot hold a shape up";
}

TEST(BallOnTheFloor, KeepsNinetyPercentOfItsVolumeWithPressure) {
  SoftBody ball(3, ballAboveTheFloor(30.0, ContactMethod::Penalty));
  const double ratio = run(ball, 3.0, 5e-4);
  EXPECT_GE(ratio, 0.9) << "a ball with gas (nRT = 30 J, P = 60 Pa at rest volume) keeps only " << 100 * ratio
                        << " % of its rest volume on the floor";
  double lowest = INFINITY, speed = 0.0;
  for (size_t i = 0; i < ball.state.pos.size(); ++i) {
    lowest = std::min(lowest, ball.state.pos[i].y());
    speed = std::max(speed, ball.state.vel[i].norm());
  }
  EXPECT_GT(lowest, -0.02) << "the floor's penalty spring must hold the ball up (lowest point " << lowest << " m)";
  EXPECT_LT(speed, 0.2) << "after 3 s the ball should be at rest on the floor";
}

TEST(PenaltyContact, PushesOutInProportionToDepth) {
  const Penetration p{true, 0.01, Vec3::UnitY()};
  const Vec3 f = penaltyContactForce(p, Vec3::Zero(), kMaterial);
  EXPECT_LT((f - Vec3(0, 20.0, 0)).norm(), 1e-12) << "at rest the contact is a spring: k depth along the normal";
  const Vec3 f2 = penaltyContactForce({true, 0.02, Vec3::UnitY()}, Vec3::Zero(), kMaterial);
  EXPECT_NEAR(f2.y(), 2 * f.y(), 1e-12) << "twice as deep, twice the push";
  EXPECT_EQ(penaltyContactForce({}, Vec3(1, -1, 0), kMaterial).norm(), 0.0) << "no contact, no force";
  // Moving in is resisted by the damping.
  EXPECT_NEAR(penaltyContactForce(p, Vec3(0, -1, 0), kMaterial).y(), 20.0 + 5.0, 1e-12)
      << "moving into the obstacle must be damped: k depth - damping (v . n)";
}

TEST(PenaltyContact, NeverPulls) {
  // Leaving fast: damping would pull the point back in; a contact only pushes.
  const Vec3 f = penaltyContactForce({true, 0.001, Vec3::UnitY()}, Vec3(0.3, 10.0, 0), kMaterial);
  EXPECT_GE(f.y(), 0.0) << "a contact must never pull a point into the obstacle";
  EXPECT_NEAR(f.norm(), 0.0, 1e-12) << "with no normal force there is no friction either";
}

TEST(PenaltyContact, FrictionIsCappedByCoulomb) {
  const Penetration p{true, 0.01, Vec3::UnitY()};  // normal force 20 N at rest
  const Vec3 slow = penaltyContactForce(p, Vec3(0.1, 0, 0), kMaterial);
  EXPECT_NEAR(slow.x(), -0.5, 1e-12) << "slow sliding: viscous friction -damping v_t";
  const Vec3 fast = penaltyContactForce(p, Vec3(0, 0, -30.0), kMaterial);
  EXPECT_NEAR(fast.z(), 0.5 * 20.0, 1e-12) << "fast sliding: friction is capped at mu times the normal force";
  EXPECT_NEAR(fast.y(), 20.0, 1e-12) << "friction must not change the normal force";
}

}  // namespace
}  // namespace springlab::softbody
