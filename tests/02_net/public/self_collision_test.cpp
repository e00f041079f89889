// Exercise 2.10 (advanced): close pairs by spatial hashing, and pushing pairs apart.
#include <gtest/gtest.h>

#include <algorithm>

#include <springlab/net/net.hpp>
#include "net_fixtures.hpp"
#include "seeded.hpp"

namespace springlab::net {
namespace {

using SelfCollision = springlab::testing::Seeded;
using springlab::testing::quietNet;

TEST_F(SelfCollision, ClosePairsMatchBruteForce) {
  // Points in a box, some on top of each other and some on cell borders.
  std::vector<Vec3> pos;
  const double d = uniform(0.05, 0.2);
  for (int i = 0; i < 400; ++i) pos.push_back(vec3(-1, 1));
  for (int i = 0; i < 20; ++i) pos.push_back(pos[static_cast<std::size_t>(integer(0, 399))]);
  for (int i = 0; i < 20; ++i) pos.push_back(Vec3(d * integer(-5, 5), d * integer(-5, 5), uniform(-1, 1)));
  std::vector<std::pair<int, int>> want;
  for (int i = 0; i < static_cast<int>(pos.size()); ++i) {
    for (int j = i + 1; j < static_cast<int>(pos.size()); ++j) {
      if ((pos[i] - pos[j]).norm() < d) want.emplace_back(i, j);
    }
  }
  const std::vector<std::pair<int, int>> got = closePairs(pos, d);
  ASSERT_EQ(got.size(), want.size()) << "the spatial hash found " << got.size() << " pairs closer than " << d
                                     << " m; checking every pair finds " << want.size() << " " << seedText();
  EXPECT_EQ(got, want) << "each close pair (i < j) once, sorted by i then j " << seedText();
}

TEST_F(SelfCollision, SeparationKeepsMomentumAndReachesTheThickness) {
  const double m1 = uniform(0.1, 2), m2 = uniform(0.1, 2), h = uniform(0.01, 0.1);
  Vec3 x1 = vec3(-1, 1), x2 = x1 + vec3(-1, 1).normalized() * uniform(0.0, 0.9 * h);
  Vec3 v1 = vec3(-1, 1), v2 = vec3(-1, 1);
  const Vec3 centre = (m1 * x1 + m2 * x2) / (m1 + m2), momentum = m1 * v1 + m2 * v2;
  separatePair(x1, x2, v1, v2, 1 / m1, 1 / m2, h);
  EXPECT_NEAR((x1 - x2).norm(), h, 1e-12) << "the pair is pushed apart to the thickness " << seedText();
  EXPECT_LT(((m1 * x1 + m2 * x2) / (m1 + m2) - centre).norm(), 1e-12) << "the centre of mass stays " << seedText();
  EXPECT_LT((m1 * v1 + m2 * v2 - momentum).norm(), 1e-12) << "momentum is kept " << seedText();
  EXPECT_GE((v1 - v2).dot((x1 - x2).normalized()), -1e-12) << "the pair no longer approaches " << seedText();
}

TEST_F(SelfCollision, FoldedClothKeepsItsThickness) {
  // A cloth falling onto the floor folds onto itself; masses of the two layers stay apart.
  NetParameters p = quietNet(12, 1.0, 1.0);
  p.uAxis = Vec3::UnitX();
  p.vAxis = -Vec3::UnitY();
  p.origin = Vec3(-0.5, 1.05, uniform(-0.05, 0.05));
  p.gravitation = Vec3(0, -9.81, 0);
  p.planes = {PlaneCollider{Vec3::Zero(), Vec3::UnitY()}};
  p.friction = 0.5;
  p.selfCollision = true;
  p.thickness = 0.05;
  Net net(3, p);
  for (int n = 0; n < 500; ++n) net.operate(0.002);
  // No two masses end closer than half the thickness (one pass per step allows some overlap).
  int violations = 0;
  for (int i = 0; i < net.numOfMasses(); ++i) {
    for (int j = i + 1; j < net.numOfMasses(); ++j) {
      if ((net.state.pos[i] - net.state.pos[j]).norm() < 0.5 * p.thickness) ++violations;
    }
  }
  EXPECT_EQ(violations, 0) << "after the cloth folds, pairs of masses are closer than half the thickness "
                           << seedText();
}

}  // namespace
}  // namespace springlab::net
