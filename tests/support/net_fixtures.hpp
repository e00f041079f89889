#pragma once
// Small net scenes for tests, built in code so each test states the physics it sets up.
#include <memory>
#include <string>

#include <springlab/diagnostics.hpp>
#include <springlab/registry.hpp>
#include <springlab/simulation.hpp>

#include <springlab/net/net.hpp>

#include "matches_reference.hpp"  // MatchesReference below

namespace springlab::testing {

// A horizontal w x h cloth in the plane y = 0 (u = x, v = z): no gravity, wind, air,
// colliders or corrections unless the test asks for them.
inline net::NetParameters quietNet(int resolution, double width = 1.0, double height = 1.0) {
  net::NetParameters p;
  p.width = width;
  p.height = height;
  p.resolution = resolution;
  p.origin = Vec3::Zero();
  p.uAxis = Vec3::UnitX();
  p.vAxis = Vec3::UnitZ();
  p.massModel = net::MassModel::Constant;
  p.particleMass = 0.1;
  p.springs[SpringKind::Structural] = {true, 100.0, 0.1};
  p.springs[SpringKind::Shear] = {true, 40.0, 0.1};
  p.springs[SpringKind::Bend] = {true, 10.0, 0.05};
  p.gravitation = Vec3::Zero();
  p.airFriction = 0.0;
  p.wind = net::Wind{net::WindModel::Relative, Vec3::UnitY(), 0.0, 0.0};
  p.absorption = 1.0;
  p.friction = 0.0;
  p.stretchLimiting = false;
  p.maxStretch = 0.1;
  p.selfCollision = false;
  p.thickness = 0.01;
  return p;
}

// The cloth thesis' case: a unit square of 16 x 16 masses of 1 kg, k = 75 / 22 / 8 N/m,
// kd = 0.25 N s/m, hanging in the plane x-y from its two top corners, stepped at 1/60 s.
inline net::NetParameters thesisCloth() {
  net::NetParameters p = quietNet(16);
  p.vAxis = -Vec3::UnitY();
  p.particleMass = 1.0;
  p.springs[SpringKind::Structural] = {true, 75.0, 0.25};
  p.springs[SpringKind::Shear] = {true, 22.0, 0.25};
  p.springs[SpringKind::Bend] = {true, 8.0, 0.25};
  p.pins = {net::Pin::Corner00, net::Pin::Corner10};
  p.gravitation = Vec3(0.0, -9.81, 0.0);
  return p;
}

// A registry with the framework's and this lab's integrators and scene kinds.
inline Registry netRegistry() {
  Registry r;
  registerFramework(r);
  net::registerLab(r);
  return r;
}

// Explicit (forward) Euler for any system: x' = x + v dt, v' = v + F/m dt, both from the
// old state. The course's own is a Lab 1 exercise; this one lets Lab 2 test without it.
class ForwardEuler final : public Integrator {
 public:
  std::string name() const override { return "explicit_euler"; }
  int order() const override { return 1; }
  double stabilityConstant() const override { return 0.0; }
  void step(Simulation& sim, double dt) override {
    sim.evaluateForces(sim.state, sim.force);
    for (int i = 0; i < sim.numOfMasses(); ++i) {
      sim.state.pos[i] += sim.state.vel[i] * dt;
      sim.state.vel[i] += sim.force[i] * (sim.inverseMass(i) * dt);
    }
    sim.state.time += dt;
  }
};

}  // namespace springlab::testing

// ---- the fixture of the hidden suite MatchesReference (every tests/02_net/hidden/*.cpp) -----
// One class for the whole suite (see matches_reference.hpp): a new hidden file uses it by name.
namespace springlab::net {

class MatchesReference : public springlab::testing::MatchesReferenceFixture<300> {
 protected:
  // Random net parameters, the same for the student's and the reference's types.
  NetParameters randomNet() {
    NetParameters p = springlab::testing::quietNet(integer(2, 9), uniform(0.3, 2), uniform(0.3, 2));
    p.origin = vec3(-1, 1);
    const Vec3 u = vec3(-1, 1).normalized();
    p.uAxis = u;
    p.vAxis = u.cross(vec3(-1, 1)).normalized();
    if (integer(0, 1)) {
      p.massModel = MassModel::Density;
      p.arealDensity = uniform(0.1, 2);
    } else {
      p.particleMass = uniform(0.01, 1);
    }
    for (int k = 0; k < 3; ++k) p.springs[k] = {integer(0, 3) > 0, uniform(1, 500), uniform(0, 1)};
    const Pin all[] = {Pin::Corner00, Pin::Corner10, Pin::Corner01, Pin::Corner11,
                       Pin::EdgeU0,   Pin::EdgeU1,   Pin::EdgeV0,   Pin::EdgeV1};
    for (Pin pin : all) {
      if (integer(0, 3) == 0) p.pins.push_back(pin);
    }
    return p;
  }
  // A random net in motion, with gravity and air friction, for the implicit steps.
  std::unique_ptr<Net> movingNet(NetParameters p) {
    p.gravitation = Vec3(0, -9.81, 0);
    p.airFriction = uniform(0, 1);
    auto net = std::make_unique<Net>(3, p);
    for (int i = 0; i < net->numOfMasses(); ++i) {
      if (!net->masses[i].pinned) {
        net->state.pos[i] += vec3(-0.2, 0.2) / p.resolution;
        net->state.vel[i] = vec3(-1, 1);
      }
    }
    return net;
  }
};

}  // namespace springlab::net
