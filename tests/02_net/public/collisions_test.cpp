// Exercise 2.5: projection out of spheres and planes, and the velocity after a contact.
#include <gtest/gtest.h>

#include <springlab/net/net.hpp>
#include "net_fixtures.hpp"
#include "seeded.hpp"

namespace springlab::net {
namespace {

using Collision = springlab::testing::Seeded;
using ContactVelocity = springlab::testing::Seeded;
using ClothOnSphere = springlab::testing::Seeded;
using springlab::testing::quietNet;

TEST_F(Collision, ProjectionLeavesNoMassInsideASphere) {
  const Vec3 c = vec3(-1, 1);
  const double R = uniform(0.2, 1.0);
  for (int t = 0; t < 200; ++t) {
    const Vec3 x = c + vec3(-1, 1).normalized() * uniform(0.0, 0.999 * R);
    const Contact k = sphereContact(x, c, R);
    ASSERT_TRUE(k.touching) << "a mass inside the sphere touches it " << seedText();
    EXPECT_NEAR((k.pos - c).norm(), R, 1e-12) << "it is moved onto the sphere's surface " << seedText();
    EXPECT_LT((k.normal - (x - c).normalized()).norm(), 1e-9) << "along the outward radius through it " << seedText();
    EXPECT_LT((k.pos - x).cross(k.normal).norm(), 1e-9) << "the shortest way out is along the radius";
  }
  const Contact centre = sphereContact(c, c, R);
  EXPECT_TRUE(centre.touching && std::abs(centre.normal.norm() - 1.0) < 1e-12 && std::abs((centre.pos - c).norm() - R) < 1e-12)
      << "a mass at the very centre still leaves the sphere along a unit normal (+y)";
}

TEST_F(Collision, ProjectionLeavesNoMassBehindAPlane) {
  const Vec3 p = vec3(-1, 1), n = vec3(-1, 1).normalized();
  for (int t = 0; t < 200; ++t) {
    const Vec3 x = p + vec3(-2, 2) - n * uniform(0.01, 1.0);
    if ((x - p).dot(n) >= 0.0) continue;
    const Contact k = planeContact(x, p, n);
    ASSERT_TRUE(k.touching) << "a mass behind the plane touches it " << seedText();
    EXPECT_NEAR((k.pos - p).dot(n), 0.0, 1e-12) << "it is moved onto the plane " << seedText();
    EXPECT_LT((k.pos - x).cross(n).norm(), 1e-12) << "straight along the normal " << seedText();
    EXPECT_LT((k.normal - n).norm(), 1e-12) << "the contact normal is the plane's";
  }
}

TEST_F(Collision, MassesOutsideAreNotTouched) {
  const Vec3 c = vec3(-1, 1), n = vec3(-1, 1).normalized();
  const double R = uniform(0.2, 1.0);
  const Vec3 x = c + vec3(-1, 1).normalized() * uniform(1.001 * R, 3 * R);
  const Contact s = sphereContact(x, c, R);
  EXPECT_FALSE(s.touching) << "outside the sphere there is no contact " << seedText();
  EXPECT_EQ(s.pos, x) << "and the mass stays where it is";
  const Vec3 y = c + n * uniform(0.001, 1.0);
  const Contact q = planeContact(y, c, n);
  EXPECT_FALSE(q.touching) << "in front of the plane there is no contact " << seedText();
  EXPECT_EQ(q.pos, y) << "and the mass stays where it is";
}

TEST_F(ContactVelocity, AbsorptionRemovesApproachingNormalVelocity) {
  const Vec3 n = vec3(-1, 1).normalized();
  const Vec3 tangent = n.cross(vec3(-1, 1)).normalized();
  const double in = uniform(0.1, 3), along = uniform(-2, 2), a = uniform(0, 2);
  const Vec3 v = -in * n + along * tangent;
  const Vec3 after = contactVelocity(v, Vec3::Zero(), n, a, 0.0);
  EXPECT_NEAR(after.dot(n), -(1.0 - a) * in, 1e-12)
      << "absorption " << a << " removes that share of the approaching normal speed (1 stops, 2 bounces) " << seedText();
  EXPECT_NEAR(after.dot(tangent), along, 1e-12) << "without friction the tangential velocity stays " << seedText();
  const Vec3 leaving = in * n + along * tangent;
  EXPECT_EQ(contactVelocity(leaving, Vec3::Zero(), n, a, 0.5), leaving) << "a separating mass keeps its velocity";
}

TEST_F(ContactVelocity, FrictionIsCoulomb) {
  const Vec3 n = Vec3::UnitY(), t = Vec3::UnitX();
  const double in = uniform(0.5, 1.0), mu = uniform(0.1, 0.5);
  // Fast sliding: the tangential speed drops by mu times the removed normal speed.
  const double fast = uniform(2.0, 4.0);
  const Vec3 a = contactVelocity(-in * n + fast * t, Vec3::Zero(), n, 1.0, mu);
  EXPECT_NEAR(a.dot(t), fast - mu * in, 1e-12) << "Coulomb friction: |dv_t| = mu |dv_n| while sliding " << seedText();
  // Slow sliding: friction stops it, never reverses it.
  const Vec3 b = contactVelocity(-in * n + 0.01 * t, Vec3::Zero(), n, 1.0, mu);
  EXPECT_NEAR(b.dot(t), 0.0, 1e-12) << "friction stops a slow slide and never reverses it " << seedText();
}

TEST_F(ContactVelocity, MovingColliderCarriesTheMass) {
  // A collider moving into a mass at rest (along n, and some way across it).
  const Vec3 n = vec3(-1, 1).normalized();
  const Vec3 vc = uniform(0.2, 2.0) * n + n.cross(vec3(-1, 1));
  // A mass at rest hit by the collider takes the collider's normal velocity.
  const Vec3 after = contactVelocity(Vec3::Zero(), vc, n, 1.0, 0.0);
  EXPECT_NEAR(after.dot(n), vc.dot(n), 1e-12)
      << "with absorption 1 the mass leaves with the collider's normal velocity " << seedText();
  EXPECT_NEAR((after - after.dot(n) * n).norm(), 0.0, 1e-12) << "and, without friction, no tangential velocity";
  // Moving with the collider, nothing changes.
  EXPECT_LT((contactVelocity(vc, vc, n, 1.0, 0.3) - vc).norm(), 1e-12) << "no relative motion, no change";

  // In a net: a sphere dragged up (as the viewer's Ctrl + drag does) lifts the cloth at its speed.
  NetParameters p = springlab::testing::quietNet(9, 1.0, 1.0);
  p.origin = Vec3(-0.5, 0.0, -0.5);
  p.spheres = {SphereCollider{Vec3(0, -0.3, 0), 0.29, true, Vec3::Zero()}};
  Net net(3, p);
  const double speed = uniform(0.5, 2.0), dt = 0.002;
  for (int step = 0; step < 100; ++step) {
    net.moveShape(0, net.spheres()[0].center + Vec3(0, speed * dt, 0));
    net.operate(dt);
  }
  const int middle = 4 * 9 + 4;
  EXPECT_NEAR(net.state.vel[middle].y(), speed, 0.05 * speed)
      << "the mass on top of a sphere moving up at " << speed << " m/s must move up with it " << seedText();
  EXPECT_GE((net.state.pos[middle] - net.spheres()[0].center).norm(), 0.29 * (1 - 1e-12)) << "and stay outside it";
}

TEST_F(ClothOnSphere, NoMassEverInsideTheColliders) {
  // A free cloth dropped on a sphere beside a slope: after every step, no mass is inside.
  NetParameters p = quietNet(10, 1.2, 1.2);
  p.origin = Vec3(-0.6, 0.3, -0.6);
  p.gravitation = Vec3(0, -9.81, 0);
  p.massModel = MassModel::Density;
  p.arealDensity = 0.3;
  p.spheres = {SphereCollider{Vec3(uniform(-0.1, 0.1), 0.0, uniform(-0.1, 0.1)), uniform(0.2, 0.3), false, Vec3::Zero()}};
  p.planes = {PlaneCollider{Vec3(0, -0.8, 0), Vec3(0.3, 1, 0).normalized()}};
  p.friction = uniform(0, 0.5);
  Net net(3, p);
  for (int step = 0; step < 300; ++step) {
    net.operate(0.002);
    for (int i = 0; i < net.numOfMasses(); ++i) {
      const Vec3& x = net.state.pos[i];
      ASSERT_GE((x - p.spheres[0].center).norm(), p.spheres[0].radius * (1 - 1e-12))
          << "mass " << i << " is inside the sphere after step " << step << " " << seedText();
      ASSERT_GE((x - p.planes[0].point).dot(p.planes[0].normal), -1e-12)
          << "mass " << i << " is behind the slope after step " << step << " " << seedText();
    }
  }
}

}  // namespace
}  // namespace springlab::net
