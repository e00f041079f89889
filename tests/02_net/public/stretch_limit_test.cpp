// Exercise 2.6: stretch limiting after each step.
#include <gtest/gtest.h>

#include <springlab/net/net.hpp>
#include "net_fixtures.hpp"
#include "seeded.hpp"

namespace springlab::net {
namespace {

using StretchLimit = springlab::testing::Seeded;
using springlab::testing::quietNet;

TEST_F(StretchLimit, NoSpringAboveTheLimit) {
  NetParameters p = quietNet(integer(4, 10));
  p.pins = {Pin::Corner00, Pin::Corner10};
  NetLayout net = buildNet(p);
  std::vector<double> w(net.masses.size());
  for (std::size_t i = 0; i < w.size(); ++i) w[i] = net.masses[i].pinned ? 0.0 : 1.0 / uniform(0.05, 0.5);
  for (std::size_t i = 0; i < w.size(); ++i) {
    if (w[i] > 0.0) net.pos[i] += vec3(-0.4, 0.4) / p.resolution;
  }
  const double limit = uniform(0.05, 0.2);
  const int passes = limitStretch(net.pos, net.vel, net.springs, w, limit, 0.01, 5000);
  EXPECT_LT(passes, 5000) << "the passes should stop once every spring is within the limit " << seedText();
  for (const Spring& s : net.springs) {
    const double l = (net.pos[s.mass1] - net.pos[s.mass2]).norm();
    ASSERT_LE(l, (1.0 + limit) * s.springLength * (1.0 + 1e-6))
        << "spring " << s.mass1 << "-" << s.mass2 << " is stretched by " << 100.0 * (l / s.springLength - 1.0)
        << " %, above the limit of " << 100.0 * limit << " % " << seedText();
  }
}

TEST_F(StretchLimit, PinnedMassesDoNotMove) {
  NetParameters p = quietNet(integer(3, 8));
  p.pins = {Pin::EdgeV0};
  NetLayout net = buildNet(p);
  std::vector<double> w(net.masses.size());
  for (std::size_t i = 0; i < w.size(); ++i) w[i] = net.masses[i].pinned ? 0.0 : 10.0;
  for (std::size_t i = 0; i < w.size(); ++i) {
    if (w[i] > 0.0) net.pos[i] *= uniform(1.2, 1.6);
  }
  const std::vector<Vec3> before = net.pos;
  limitStretch(net.pos, net.vel, net.springs, w, 0.1, 0.01, 100);
  for (std::size_t i = 0; i < w.size(); ++i) {
    if (w[i] == 0.0) {
      EXPECT_EQ(net.pos[i], before[i]) << "pinned mass " << i << " moved " << seedText();
      EXPECT_EQ(net.vel[i], Vec3::Zero()) << "pinned mass " << i << " got a velocity " << seedText();
    }
  }
}

TEST_F(StretchLimit, KeepsMomentumAndLeavesShortSpringsAlone) {
  // One spring stretched beyond the limit between masses m1 and m2.
  const double m1 = uniform(0.1, 2), m2 = uniform(0.1, 2), L0 = uniform(0.1, 1), dt = uniform(0.001, 0.02);
  const Vec3 dir = vec3(-1, 1).normalized();
  std::vector<Vec3> pos{Vec3::Zero(), uniform(1.3, 2.0) * L0 * dir}, vel{vec3(-1, 1), vec3(-1, 1)};
  const std::vector<Spring> springs{Spring{0, 1, 100.0, L0, 0.0, SpringKind::Structural}};
  const std::vector<double> w{1 / m1, 1 / m2};
  const Vec3 centre = (m1 * pos[0] + m2 * pos[1]) / (m1 + m2), momentum = m1 * vel[0] + m2 * vel[1];
  limitStretch(pos, vel, springs, w, 0.1, dt, 10);
  EXPECT_NEAR((pos[1] - pos[0]).norm(), 1.1 * L0, 1e-9) << "shortened to exactly 110 % of its rest length " << seedText();
  EXPECT_LT(((m1 * pos[0] + m2 * pos[1]) / (m1 + m2) - centre).norm(), 1e-12)
      << "moves in proportion to the inverse masses keep the centre of mass " << seedText();
  EXPECT_LT((m1 * vel[0] + m2 * vel[1] - momentum).norm(), 1e-9) << "and the momentum " << seedText();

  // Within the limit nothing moves.
  std::vector<Vec3> shortPos{Vec3::Zero(), uniform(0.5, 1.09) * L0 * dir}, shortVel{Vec3::Zero(), Vec3::Zero()};
  const std::vector<Vec3> keep = shortPos;
  limitStretch(shortPos, shortVel, springs, w, 0.1, dt, 10);
  EXPECT_EQ(shortPos, keep) << "springs within the limit (or compressed) are left alone " << seedText();
}

}  // namespace
}  // namespace springlab::net
