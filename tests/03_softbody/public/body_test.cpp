// Whole-body behaviour: a ball on the floor with and without gas, the user's sphere, the wind
// (exercises 3.7 to 3.9 together with the forces of 3.1 to 3.5).
#include <gtest/gtest.h>

#include <cmath>

#include "seeded.hpp"
#include <springlab/softbody/softbody.hpp>
#include "softbody_fixtures.hpp"

namespace springlab::softbody {
namespace {

using springlab::testing::floorAt;
using springlab::testing::quietBody;

// A 1 kg ball of radius 0.5 m (162 masses) just above a floor, under gravity.
SoftBodyParameters ballAboveTheFloor(double nRT, ContactMethod method) {
  SoftBodyParameters p = quietBody(icosphere(0.5, 2), 1.0, 100.0, 1.0);
  for (Vec3& v : p.mesh.vertices) v += Vec3(0, 0.55, 0);
  p.gas = nRT;
  p.inflationTime = 0.1;  // s: 200 steps of 0.5 ms
  p.gravitation = Vec3(0, -9.81, 0);
  p.airFriction = 0.005;
  p.contactMethod = method;
  p.contact = {2000.0, 5.0, 0.5, 0.0};
  p.obstacles.push_back(floorAt(0.0));
  return p;
}

double run(SoftBody& body, double seconds, double dt) {
  const int steps = static_cast<int>(std::lround(seconds / dt));
  for (int i = 0; i < steps; ++i) body.operate(dt);
  return body.volume(body.state) / body.restVolume();
}

// ---- 3.7 ---------------------------------------------------------------------------------

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

// ---- 3.8 ---------------------------------------------------------------------------------

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

// ---- 3.9 ---------------------------------------------------------------------------------

TEST(Wind, NoForceWhenTheFaceMovesWithTheAir) {
  const SurfaceMesh m = icosphere(1.0, 1);
  const std::vector<Vec3> vel(m.vertices.size(), Vec3(3, -1, 2));
  std::vector<Vec3> f(m.vertices.size(), Vec3::Zero());
  addWindForces(m.vertices, vel, m.triangles, {}, Vec3(3, -1, 2), 1.2, f);
  for (const Vec3& x : f) ASSERT_LT(x.norm(), 1e-12) << "a body moving with the wind feels no wind";
}

TEST(Wind, PushesAlongTheNormalInProportionToArea) {
  // One triangle of area 2 in the plane z = 0, facing +z; wind (1, 2, -3) relative to it.
  const std::vector<Vec3> pos = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0)};
  const std::vector<Vec3> vel(3, Vec3::Zero());
  std::vector<Vec3> f(3, Vec3::Zero());
  addWindForces(pos, vel, {{0, 1, 2}}, {}, Vec3(1, 2, -3), 0.5, f);
  for (const Vec3& x : f) {
    EXPECT_LT((x - Vec3(0, 0, 0.5 * 2.0 * -3.0 / 3.0)).norm(), 1e-12)
        << "each corner gets a third of drag A ((w - v) . n) n";
  }
  // A 2D segment of length 2 along x: normal -y (to its right), wind (0, -1, 0).
  std::vector<Vec3> g(2, Vec3::Zero());
  addWindForces({Vec3(0, 0, 0), Vec3(2, 0, 0)}, {Vec3::Zero(), Vec3::Zero()}, {}, {{0, 1}}, Vec3(0, -1, 0), 1.0, g);
  EXPECT_LT((g[0] - Vec3(0, -1, 0)).norm(), 1e-12) << "in 2D each end gets half of drag L ((w - v) . n) n";
}

TEST(Wind, BlowsTheBallDownwind) {
  SoftBodyParameters p = quietBody(icosphere(0.5, 2), 1.0, 1000.0, 0.5);
  p.gas = 100.0;
  p.wind = Vec3(5, 0, 0);
  p.windDrag = 1.0;
  SoftBody ball(3, p);
  run(ball, 0.5, 5e-4);
  const Vec3 momentum = ball.momentum();
  EXPECT_GT(momentum.x(), 0.1) << "the wind must push the ball along it";
  EXPECT_LT(std::abs(momentum.y()) + std::abs(momentum.z()), 0.02 * momentum.x())
      << "a round ball must be pushed only along the wind";
}

}  // namespace
}  // namespace springlab::softbody
