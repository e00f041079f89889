#pragma once
// Small net scenes for tests, built in code so each test states the physics it sets up.
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

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

// ---- the fabric and the drape, shared by Xpbd.* and ProjectiveDynamics.* (issue 17) ---------
namespace springlab::testing {

// The light fabric of scenes/net_hanging.json (0.2 kg/m^2, k = 400/40/2 N/m, 10 % stretch
// limit), r x r, held at two corners, without its colliders.
inline net::NetParameters fabric(int r) {
  net::NetParameters p = quietNet(r);
  p.massModel = net::MassModel::Density;
  p.arealDensity = 0.2;
  p.springs[SpringKind::Structural] = {true, 400.0, 0.3};
  p.springs[SpringKind::Shear] = {true, 40.0, 0.1};
  p.springs[SpringKind::Bend] = {true, 2.0, 0.02};
  p.pins = {net::Pin::Corner00, net::Pin::Corner10};
  p.gravitation = Vec3(0.0, -9.81, 0.0);
  p.airFriction = 0.05;
  p.stretchLimiting = true;
  return p;
}

// A small heavy cloth (the thesis' material) hanging in its own plane from two corners, with
// air friction to bring it to rest.
inline net::NetParameters hangingCloth(int r) {
  net::NetParameters p = thesisCloth();
  p.resolution = r;
  p.airFriction = 2.0;
  return p;
}

// The integrator `name` with integer options set as a scene's "integrator_options" would.
inline std::unique_ptr<Integrator> netIntegrator(const std::string& name,
                                                 const std::vector<std::pair<std::string, int>>& options = {}) {
  std::unique_ptr<Integrator> integrator = netRegistry().makeIntegrator(name);
  for (const auto& [option, value] : options) integrator->setOption(option, value);
  return integrator;
}

// The drape: the height of the lowest mass, m.
inline double lowestPoint(const Simulation& sim) {
  double y = INFINITY;
  for (const Vec3& x : sim.state.pos) y = std::min(y, x.y());
  return y;
}

// The largest net force of the force model on a free mass at sim's positions, at rest,
// relative to that mass's weight.
inline double largestForceOverWeight(Simulation& sim) {
  State still = sim.state;
  for (Vec3& v : still.vel) v.setZero();
  std::vector<Vec3> f;
  sim.evaluateForces(still, f);
  double worst = 0.0;
  for (int i = 0; i < sim.numOfMasses(); ++i) {
    if (sim.inverseMass(i) == 0.0) continue;
    worst = std::max(worst, f[i].norm() / (sim.masses[i].m * sim.gravitation.norm()));
  }
  return worst;
}

}  // namespace springlab::testing
