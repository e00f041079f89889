// Exercises 3.4 and 3.5: the gas, its pressure force, pumping it in and its energy.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "seeded.hpp"
#include <springlab/softbody/softbody.hpp>
#include "softbody_fixtures.hpp"

namespace springlab::softbody {
namespace {

using springlab::testing::quietBody;

class Pressure : public springlab::testing::Seeded {};

TEST_F(Pressure, TimesVolumeIsNRT) {
  for (int t = 0; t < 100; ++t) {
    const double nRT = uniform(0.1, 1e4), v = uniform(1e-3, 10);
    ASSERT_NEAR(gasPressure(nRT, v) * v, nRT, 1e-9 * nRT) << "Boyle's law: P V = nRT " << seedText();
  }
  EXPECT_EQ(gasPressure(100.0, 0.0), 0.0) << "a body without volume holds no pressure (and no infinity)";
  EXPECT_EQ(gasPressure(100.0, -1.0), 0.0) << "a body turned inside out holds no pressure";
}

TEST_F(Pressure, ForceAndTorqueSumToZeroOnAClosedBody) {
  // Pressure is internal: a closed body cannot push itself along or spin itself up.
  std::mt19937_64 rng(static_cast<unsigned>(integer(0, 1 << 30)));
  for (int t = 0; t < 20; ++t) {
    const SurfaceMesh m = springlab::testing::lumpySphere(integer(0, 2), uniform(0.2, 2), 0.3, vec3(-5, 5), rng);
    std::vector<Vec3> f(m.vertices.size(), Vec3::Zero());
    const double P = uniform(1, 1000);
    addPressureForces(m.vertices, m.triangles, {}, P, f);
    Vec3 total = Vec3::Zero(), torque = Vec3::Zero();
    double size = 0.0;
    for (size_t i = 0; i < f.size(); ++i) {
      total += f[i];
      torque += m.vertices[i].cross(f[i]);
      size += f[i].norm();
    }
    ASSERT_GT(size, 0.0) << "pressure exerts no force at all " << seedText();
    ASSERT_LT(total.norm(), 1e-9 * size) << "the pressure forces on a closed body do not sum to zero: it would "
                                            "propel itself " << seedText();
    ASSERT_LT(torque.norm(), 1e-8 * size * (1 + m.vertices[0].norm()))
        << "the pressure forces on a closed body have a net torque: it would spin itself up " << seedText();
  }
  // The 2D ring too.
  SurfaceMesh ring = ringMesh(integer(3, 40), uniform(0.5, 3));
  for (Vec3& v : ring.vertices) v += Vec3(uniform(-1, 1), uniform(-1, 1), 0.0) * 0.1;
  std::vector<Vec3> f(ring.vertices.size(), Vec3::Zero());
  addPressureForces(ring.vertices, {}, ring.segments, 10.0, f);
  Vec3 total = Vec3::Zero();
  for (const Vec3& x : f) total += x;
  EXPECT_LT(total.norm(), 1e-9) << "the pressure forces on a closed 2D loop do not sum to zero " << seedText();
}

TEST_F(Pressure, PushesASphereOutwardWithPTimesItsArea) {
  // On a sphere every force points out along the radius; their sizes add up to P times the
  // surface area (sum of face areas).
  const SurfaceMesh m = icosphere(1.5, 2);
  const double P = uniform(10, 100);
  std::vector<Vec3> f(m.vertices.size(), Vec3::Zero());
  addPressureForces(m.vertices, m.triangles, {}, P, f);
  double area = 0.0, radial = 0.0;
  for (const Triangle& t : m.triangles) {
    area += 0.5 * (m.vertices[t.b] - m.vertices[t.a]).cross(m.vertices[t.c] - m.vertices[t.a]).norm();
  }
  for (size_t i = 0; i < f.size(); ++i) {
    const Vec3 out = m.vertices[i].normalized();
    ASSERT_GT(f[i].dot(out), 0.0) << "pressure must push vertex " << i << " outward " << seedText();
    radial += f[i].dot(out);
  }
  EXPECT_NEAR(radial, P * area, 0.02 * P * area) << "the outward forces must add up to P times the area";
}

// Radius of a regular n-gon ring of rest radius r0 at which spring tension balances the gas:
// 2 k (l - l0) sin(pi/n) = P l cos(pi/n), l = 2 r sin(pi/n), P = nRT / ((n/2) r^2 sin(2 pi/n)).
double ringEquilibriumRadius(int n, double r0, double k, double nRT) {
  const double s = std::sin(std::numbers::pi / n), c = std::cos(std::numbers::pi / n);
  auto imbalance = [&](double r) {
    const double l = 2 * r * s, l0 = 2 * r0 * s;
    const double P = nRT / (0.5 * n * r * r * std::sin(2 * std::numbers::pi / n));
    return 2 * k * (l - l0) * s - P * l * c;
  };
  double lo = r0, hi = 10 * r0;  // inward pull grows with r, pressure falls: one root
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (imbalance(mid) < 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(RingEquilibrium, RadiusMatchesTheBalanceOfTensionAndPressure) {
  // The chapter's ring (17 points, radius 30, k = 400, kd = 15, m = 4 each) in zero gravity,
  // pumped up over 2 s (200 steps) and left to settle.
  const int n = 17;
  const double r0 = 30.0, k = 400.0, nRT = 2.0e5;
  SoftBodyParameters p = quietBody(ringMesh(n, r0), 4.0 * n, k, 15.0);
  p.gas = nRT;
  p.inflationTime = 2.0;
  SoftBody ring(2, p);
  for (int step = 0; step < 4000; ++step) ring.operate(0.01);

  Vec3 centroid = Vec3::Zero();
  for (const Vec3& x : ring.state.pos) centroid += x / n;
  double meanRadius = 0.0, spread = 0.0;
  for (const Vec3& x : ring.state.pos) meanRadius += (x - centroid).norm() / n;
  for (const Vec3& x : ring.state.pos) spread = std::max(spread, std::abs((x - centroid).norm() - meanRadius));
  const double expected = ringEquilibriumRadius(n, r0, k, nRT);
  ASSERT_GT(expected, 1.1 * r0) << "test setup: the gas should stretch the ring noticeably";
  EXPECT_NEAR(meanRadius, expected, 1e-3 * expected)
      << "the ring settles where spring tension balances pressure, radius " << expected << " (rest radius " << r0
      << ")";
  EXPECT_LT(spread, 1e-3 * expected) << "the inflated ring should be round";
  for (const Vec3& x : ring.state.pos) EXPECT_EQ(x.z(), 0.0) << "a 2D ring must stay exactly in its plane";
}

}  // namespace
}  // namespace springlab::softbody
