#pragma once
// Small soft bodies for tests, built in code so each test states the physics it sets up.
#include <cmath>
#include <random>

#include <springlab/mesh.hpp>
#include <springlab/registry.hpp>

#include <springlab/softbody/softbody.hpp>

#include "matches_reference.hpp"  // MatchesReference below

namespace springlab::testing {

// A body of the given rest shape with no gravity, air, wind, gas or obstacles unless the
// test asks for them.
inline softbody::SoftBodyParameters quietBody(SurfaceMesh mesh, double totalMass, double k, double kd) {
  softbody::SoftBodyParameters p;
  p.mesh = std::move(mesh);
  p.totalMass = totalMass;
  p.springConstant = k;
  p.springFriction = kd;
  p.gas = 0.0;
  p.inflationTime = 0.0;
  p.contact = {1000.0, 5.0, 0.0, 0.0};
  return p;
}

// The contact tests' material: stiffness 2000 N/m, damping 5 N s/m, friction 0.5, no bounce.
inline const softbody::ContactMaterial kMaterial{2000.0, 5.0, 0.5, 0.0};

// A horizontal floor y = height facing up.
inline softbody::Obstacle floorAt(double height) {
  softbody::Obstacle o;
  o.type = ShapeType::Plane;
  o.center = Vec3(0.0, height, 0.0);
  o.normal = Vec3::UnitY();
  return o;
}

// An icosphere with every vertex moved radially by up to `jitter` of the radius: a closed,
// outward-wound surface that is no longer symmetric.
template <class Rng>
SurfaceMesh lumpySphere(int subdivisions, double radius, double jitter, const Vec3& center, Rng& rng) {
  SurfaceMesh m = icosphere(radius, subdivisions);
  std::uniform_real_distribution<double> u(1.0 - jitter, 1.0 + jitter);
  for (Vec3& v : m.vertices) v = center + v * u(rng);
  return m;
}

// Random velocities for every vertex of a mesh.
template <class Rng>
std::vector<Vec3> randomVelocities(size_t n, double speed, Rng& rng) {
  std::uniform_real_distribution<double> u(-speed, speed);
  std::vector<Vec3> v(n);
  for (Vec3& x : v) x = Vec3(u(rng), u(rng), u(rng));
  return v;
}

// A 1 kg ball of radius 0.5 m (162 masses) just above a floor, under gravity.
inline softbody::SoftBodyParameters ballAboveTheFloor(double nRT, softbody::ContactMethod method) {
  softbody::SoftBodyParameters p = quietBody(icosphere(0.5, 2), 1.0, 100.0, 1.0);
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

// Run the body for `seconds` with steps of dt; its volume then, over its rest volume.
inline double run(softbody::SoftBody& body, double seconds, double dt) {
  const int steps = static_cast<int>(std::lround(seconds / dt));
  for (int i = 0; i < steps; ++i) body.operate(dt);
  return body.volume(body.state) / body.restVolume();
}

// A registry with the framework's integrators and this lab's scene kind.
inline Registry softbodyRegistry() {
  Registry r;
  registerFramework(r);
  softbody::registerLab(r);
  return r;
}

}  // namespace springlab::testing

// ---- the fixture of the hidden suite MatchesReference (every tests/03_softbody/hidden/*.cpp) -----
// One class for the whole suite (see matches_reference.hpp): a new hidden file uses it by name.
namespace springlab::softbody {

class MatchesReference : public springlab::testing::MatchesReferenceFixture<500> {
 protected:
  std::mt19937_64 rng() { return std::mt19937_64(static_cast<unsigned>(integer(0, 1 << 30))); }

  // A random closed body: a lumpy icosphere (3D) or a lumpy ring (2D) somewhere in space.
  SurfaceMesh randomBody(bool planar) {
    if (planar) {
      SurfaceMesh ring = ringMesh(integer(3, 60), uniform(0.2, 3.0));
      const Vec3 c(uniform(-3, 3), uniform(-3, 3), 0.0);
      for (Vec3& v : ring.vertices) v = c + v * uniform(0.7, 1.3);
      return ring;
    }
    auto r = rng();
    return springlab::testing::lumpySphere(integer(0, 2), uniform(0.2, 2.0), 0.3, vec3(-3, 3), r);
  }
  std::vector<Vec3> randomVectors(size_t n, double size) {
    std::vector<Vec3> v(n);
    for (Vec3& x : v) x = vec3(-size, size);
    return v;
  }
};

}  // namespace springlab::softbody
