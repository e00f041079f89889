// Exercise 3.8, contact by projection (labs/03_softbody/projection_contact.cpp): its public tests.
#include <gtest/gtest.h>

#include "seeded.hpp"
#include <springlab/softbody/softbody.hpp>
#include "softbody_fixtures.hpp"

namespace springlab::softbody {
namespace {

using springlab::testing::kMaterial;
using springlab::testing::ballAboveTheFloor;
using springlab::testing::run;

TEST(BallOnTheFloor, ProjectionKeepsEveryMassAboveTheFloor) {
  SoftBody ball(3, ballAboveTheFloor(30.0, ContactMethod::Projection));
  for (int i = 0; i < 4000; ++i) {
    ball.operate(5e-4);
    for (const Vec3& x : ball.state.pos) ASSERT_GE(x.y(), -1e-12) << "projection left a mass below the floor";
  }
  EXPECT_GE(ball.volume(ball.state) / ball.restVolume(), 0.9) << "the ball should rest on the floor, round";
}

TEST(UsersSphere, PushesADentIntoTheBall) {
  // The ball rests on the floor; the user's sphere comes down on it from above.
  SoftBodyParameters p = ballAboveTheFloor(30.0, ContactMethod::Projection);
  Obstacle sphere;
  sphere.type = ShapeType::Sphere;
  sphere.center = Vec3(0.1, 1.6, 0.0);
  sphere.radius = 0.3;
  sphere.movable = true;
  p.obstacles.push_back(sphere);
  SoftBody ball(3, p);
  ASSERT_EQ(ball.shapes().size(), 1u) << "the floor is the ground; the sphere is the one shape shown";
  ASSERT_TRUE(ball.shapes()[0].movable) << "the user's sphere must be movable";
  run(ball, 1.5, 5e-4);
  const double restingVolume = ball.volume(ball.state), restingPressure = ball.pressure(ball.state);

  // Down by 0.55 m over 1 s, through moveShape as the viewer calls it once per step.
  Vec3 c = ball.shapes()[0].center;
  for (int i = 0; i < 2000; ++i) {
    c.y() -= 0.55 / 2000;
    ball.moveShape(0, c);
    ball.operate(5e-4);
  }
  EXPECT_LT((ball.shapes()[0].center - c).norm(), 1e-12) << "moveShape must move the sphere";
  for (const Vec3& x : ball.state.pos) {
    ASSERT_GE((x - c).norm(), 0.3 - 1e-9) << "a mass is left inside the user's sphere";
  }
  EXPECT_LT(ball.volume(ball.state), 0.97 * restingVolume) << "the sphere must dent the ball";
  EXPECT_GT(ball.pressure(ball.state), restingPressure) << "squeezed, the gas's pressure must rise";
}

TEST(ProjectionContact, MovesThePointOutOfTheObstacle) {
  const Vec3 c(0, 0, 0);
  const PhasePoint in{Vec3(0.3, 0.4, 0.0) * 0.5, Vec3(1, 1, 0)};  // 0.25 from the centre, leaving
  const Penetration p = spherePenetration(in.pos, c, 1.0);
  const PhasePoint out = projectContact(in, p, Vec3::Zero(), kMaterial);
  EXPECT_NEAR((out.pos - c).norm(), 1.0, 1e-12) << "projection puts the point on the sphere's surface";
  EXPECT_LT((out.vel - in.vel).norm(), 1e-12) << "a point already leaving keeps its velocity";
  const PhasePoint free{Vec3(2, 0, 0), Vec3(-1, 0, 0)};
  const PhasePoint same = projectContact(free, spherePenetration(free.pos, c, 1.0), Vec3::Zero(), kMaterial);
  EXPECT_EQ((same.pos - free.pos).norm() + (same.vel - free.vel).norm(), 0.0) << "a free point is left alone";
}

TEST(ProjectionContact, RestitutionScalesTheBounce) {
  const Penetration p{true, 0.05, Vec3::UnitY()};
  for (double e : {0.0, 0.5, 1.0}) {
    const ContactMaterial m{0.0, 0.0, 0.0, e};
    const PhasePoint out = projectContact({Vec3::Zero(), Vec3(0, -2, 0)}, p, Vec3::Zero(), m);
    EXPECT_NEAR(out.vel.y(), 2.0 * e, 1e-12) << "restitution " << e << ": outgoing normal speed is e times incoming";
    EXPECT_NEAR(out.pos.y(), 0.05, 1e-12);
  }
  // Against an obstacle moving up at 1 m/s, a point at rest is hit: it leaves with the obstacle.
  const PhasePoint hit = projectContact({Vec3::Zero(), Vec3::Zero()}, p, Vec3(0, 1, 0), ContactMaterial{});
  EXPECT_NEAR(hit.vel.y(), 1.0, 1e-12) << "an inelastic contact leaves the point moving with the obstacle";
}

TEST(ProjectionContact, FrictionStopsButNeverReverses) {
  const Penetration p{true, 0.0, Vec3::UnitY()};
  const ContactMaterial m{0.0, 0.0, 0.5, 0.0};
  // Normal change 2 m/s, so friction may take 1 m/s of the 3 m/s sliding.
  const PhasePoint fast = projectContact({Vec3::Zero(), Vec3(3, -2, 0)}, p, Vec3::Zero(), m);
  EXPECT_NEAR(fast.vel.x(), 2.0, 1e-12) << "Coulomb: tangential speed drops by mu times the normal change";
  // Sliding at only 0.4 m/s: friction stops it, and does not push it backwards.
  const PhasePoint slow = projectContact({Vec3::Zero(), Vec3(0.4, -2, 0)}, p, Vec3::Zero(), m);
  EXPECT_NEAR(slow.vel.x(), 0.0, 1e-12) << "friction may stop sliding but never reverse it";
}

}  // namespace
}  // namespace springlab::softbody
