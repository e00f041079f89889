// Exercise 3.6, where a point touches an obstacle (labs/03_softbody/penetration.cpp): its public tests.
#include <gtest/gtest.h>

#include <cmath>

#include "seeded.hpp"
#include <springlab/softbody/softbody.hpp>

namespace springlab::softbody {
namespace {

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

}  // namespace
}  // namespace springlab::softbody
