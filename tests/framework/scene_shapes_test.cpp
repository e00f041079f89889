// The helpers labs share for their colliders and markers: the ground among the planes, the
// wind's arrow, and a dragged collider's velocity.
#include <gtest/gtest.h>

#include <optional>
#include <vector>

#include <springlab/scene_shapes.hpp>

namespace springlab {
namespace {

// A collider of a made-up lab: a plane, or something else.
struct Collider {
  bool plane = true;
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitY();
};

std::optional<PlaneGeometry> planeOf(const Collider& c) {
  if (!c.plane) return std::nullopt;
  return PlaneGeometry{c.point, c.normal};
}

TEST(GroundPlane, IsTheFirstPlaneFacingStraightUp) {
  const std::vector<Collider> colliders{
      {true, Vec3(0, 5, 0), Vec3(0, 1, 1).normalized()},  // a slope
      {false, Vec3(0, 7, 0), Vec3::UnitY()},              // a sphere: never the ground
      {true, Vec3(0, 3, 0), -Vec3::UnitY()},              // a ceiling
      {true, Vec3(1, -2, 4), Vec3::UnitY()},              // the ground
      {true, Vec3(0, -9, 0), Vec3::UnitY()},              // a second floor further down
  };
  const std::optional<GroundPlane> g = findGroundPlane(colliders, planeOf);
  ASSERT_TRUE(g) << "a plane facing +y is the ground";
  EXPECT_EQ(g->index, 3) << "the ground is the first upward plane, counted among all colliders";
  EXPECT_EQ(g->height, -2.0) << "the ground lies at the height of its point";
}

TEST(GroundPlane, SlopesAndCeilingsAreNoGround) {
  const std::vector<Collider> colliders{{true, Vec3::Zero(), Vec3(1e-3, 1, 0).normalized()},
                                        {true, Vec3::Zero(), -Vec3::UnitY()}};
  EXPECT_FALSE(findGroundPlane(colliders, planeOf)) << "a plane tilted by 1 mrad or facing down is not the ground";
}

TEST(ColliderDrag, VelocityIsDisplacementOverTheStep) {
  ColliderDrag drag;
  Vec3 center(1, 2, 3), velocity = Vec3::Zero();
  const double dt = 0.01;
  drag.holdAt(Vec3(1.5, 2, 2));
  drag.finishStep(center, velocity, dt);
  EXPECT_EQ(center, Vec3(1.5, 2, 2)) << "the collider ends the step where the user holds it";
  EXPECT_TRUE(velocity.isApprox(Vec3(50, 0, -100))) << "velocity = (new - old) / dt, got " << velocity.transpose();
}

TEST(ColliderDrag, ColliderLetGoStandsStill) {
  ColliderDrag drag;
  Vec3 center = Vec3::Zero(), velocity = Vec3::Zero();
  drag.holdAt(Vec3(1, 0, 0));
  drag.finishStep(center, velocity, 0.1);
  drag.finishStep(center, velocity, 0.1);  // not held during this step
  EXPECT_EQ(center, Vec3(1, 0, 0)) << "a collider no longer held stays where it was left";
  EXPECT_EQ(velocity, Vec3::Zero()) << "a collider no longer held stands still";
}

TEST(WindArrow, PointsDownwindAboveTheBody) {
  const Bounds body{Vec3(-1, 0, -1), Vec3(1, 2, 1)};
  const std::optional<Shape> arrow = windArrow(body, Vec3(3, 0, 4), 0.1);
  ASSERT_TRUE(arrow);
  EXPECT_EQ(arrow->type, ShapeType::Arrow);
  EXPECT_TRUE(arrow->arrow.normalized().isApprox(Vec3(0.6, 0, 0.8))) << "the arrow points along the wind";
  EXPECT_NEAR(arrow->arrow.norm(), 0.1 * (body.hi - body.lo).norm(), 1e-12) << "a tenth of the body's size";
  const Vec3 middle = arrow->center + 0.5 * arrow->arrow;
  EXPECT_GT(middle.y(), body.hi.y()) << "the arrow floats above the body";
  EXPECT_NEAR(middle.x(), 0.0, 1e-12);
  EXPECT_NEAR(middle.z(), 0.0, 1e-12);
}

TEST(WindArrow, NoWindNoArrow) {
  const Bounds body{Vec3::Zero(), Vec3::Ones()};
  EXPECT_FALSE(windArrow(body, Vec3::Zero(), 0.5));
  EXPECT_FALSE(windArrow(body, Vec3::UnitX(), 0.0));
}

}  // namespace
}  // namespace springlab
