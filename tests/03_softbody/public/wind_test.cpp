// Exercise 3.9, wind on the faces (labs/03_softbody/wind.cpp): its public tests.
#include <gtest/gtest.h>

#include <cmath>

#include "seeded.hpp"
#include <springlab/softbody/softbody.hpp>
#include "softbody_fixtures.hpp"

namespace springlab::softbody {
namespace {

using springlab::testing::quietBody;
using springlab::testing::run;

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
