// Exercises 3.6 to 3.8: obstacles, and the two ways a contact pushes the body out.
#include <gtest/gtest.h>

#include <cmath>

#include "seeded.hpp"
#include <springlab/softbody/softbody.hpp>
#include "softbody_fixtures.hpp"

namespace springlab::softbody {
namespace {


// ---- 3.6 ---------------------------------------------------------------------------------

TEST(Penetration, PlaneGivesDepthAlongItsNormal) {
  const Vec3 point(0, 1, 0), n = Vec3(1, 1, 0).normalized();
  const auto below = planePenetration(point - 0.3 * n + Vec3(0, 0, 5), point, n);
  ASSERT_TRUE(below.touching) << "a point behind the plane touches it";
  EXPECT_NEAR(below.depth, 0.3, 1e-12) << "the depth is the distance behind the plane";
  EXPECT_LT((below.normal - n).norm(), 1e-12) << "the way out of a plane is its normal";
  EXPECT_FALSE(planePenetration(point + 0.3 * n, point, n).touching) << "a point in front does not touch";
}

TEST(Penetration, SphereGivesDepthAlongTheRadius) {
  const Vec3 c(1, 2, 3);
  const auto inside = spherePenetration(c + Vec3(0, 0, -0.4), c, 1.0);
  ASSERT_TRUE(inside.touching) << "a point inside the sphere touches it";
  EXPECT_NEAR(inside.depth, 0.6, 1e-12) << "the depth is the radius minus the distance from the centre";
  EXPECT_LT((inside.normal - Vec3(0, 0, -1)).norm(), 1e-12) << "out of a sphere along the radius";
  EXPECT_FALSE(spherePenetration(c + Vec3(1.01, 0, 0), c, 1.0).touching) << "a point outside does not touch";
  const auto centre = spherePenetration(c, c, 1.0);
  EXPECT_TRUE(centre.touching && centre.normal.allFinite() && std::abs(centre.normal.norm() - 1.0) < 1e-12)
      << "the very centre must still give a unit way out (not NaN)";
}

TEST(Penetration, BoxLeavesThroughTheNearestFace) {
  const Vec3 c(0, 0, 0), h(1.0, 0.5, 2.0);
  const auto p = boxPenetration(Vec3(0.2, -0.4, 0.5), c, h);
  ASSERT_TRUE(p.touching) << "a point inside the box touches it";
  EXPECT_NEAR(p.depth, 0.1, 1e-12) << "the nearest face is the bottom (y = -0.5), 0.1 away";
  EXPECT_LT((p.normal - Vec3(0, -1, 0)).norm(), 1e-12) << "out through the bottom face";
  const auto side = boxPenetration(Vec3(0.9, 0.0, 0.0), c, h);
  EXPECT_LT((side.normal - Vec3(1, 0, 0)).norm(), 1e-12) << "out through the +x face";
  EXPECT_FALSE(boxPenetration(Vec3(0.0, 0.6, 0.0), c, h).touching) << "a point outside does not touch";
}

// ---- 3.7 ---------------------------------------------------------------------------------

const ContactMaterial kMaterial{2000.0, 5.0, 0.5, 0.0};

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

// ---- 3.8 ---------------------------------------------------------------------------------

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
