#pragma once
// What both implicit integrators of Lab 2 (exercises 2.8 and 2.9) are checked on: one mass on a
// spring, where backward Euler has a closed form; pinned masses; the thesis' cloth at 1/60 s.
// One fixture class (ImplicitCase) for both suites, shared by their two test files.
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <springlab/net/net.hpp>
#include "net_fixtures.hpp"
#include "seeded.hpp"

namespace springlab::testing {

// One free mass on one spring to a pinned mass, moving along the spring.
class OneSpring final : public Simulation {
 public:
  OneSpring(double m, double k, double L0, double kd) : Simulation(3) {
    masses = {Mass{m, true}, Mass{m, false}};
    editSprings() = {Spring{1, 0, k, L0, kd, SpringKind::Structural}};
    state.pos = {Vec3::Zero(), Vec3(L0, 0, 0)};
    state.vel = {Vec3::Zero(), Vec3::Zero()};
    markInitialState();
  }
  std::string kind() const override { return "one spring"; }
  bool addForceJacobian(const State& s, ForceJacobian& J) override {
    const Spring& sp = springs()[0];
    const auto j = net::springJacobian(s.pos[1], s.pos[0], sp.springConstant, sp.springLength, sp.frictionConstant);
    J.pairs.push_back({1, 0, j.dx, j.dv});
    return true;
  }

 protected:
  void accumulateForces(const State& s, std::vector<Vec3>& f) override {
    const Spring& sp = springs()[0];
    f[1] += net::springDamperForce(s.pos[1], s.pos[0], s.vel[1], s.vel[0], sp.springConstant, sp.springLength, sp.frictionConstant);
  }
};

// Checks both implicit integrators share.
class ImplicitCase : public springlab::testing::Seeded {
 protected:
  void checkBackwardEuler(const std::string& method);
  void checkPinnedNeverMove(const std::string& method);
};

// Backward Euler for m x'' = -k (x - L0) - kd x' along the spring, five steps.
inline void ImplicitCase::checkBackwardEuler(const std::string& method) {
  const double m = uniform(0.1, 2), k = uniform(10, 1000), L0 = uniform(0.2, 1), kd = uniform(0, 2);
  const double dt = uniform(0.005, 0.1);
  OneSpring sim(m, k, L0, kd);
  sim.setIntegrator(netRegistry().makeIntegrator(method));
  sim.setBlowUpCheck(false);
  double x = L0 + uniform(0.05, 0.3) * L0, v = uniform(-1, 1);
  sim.state.pos[1].x() = x;
  sim.state.vel[1].x() = v;
  for (int n = 0; n < 5; ++n) {
    sim.operate(dt);
    // (m + dt kd + dt^2 k) dv = dt (F + dt (-k) v)
    const double dv = dt * (-k * (x - L0) - kd * v - dt * k * v) / (m + dt * kd + dt * dt * k);
    v += dv;
    x += dt * v;
    ASSERT_NEAR(sim.state.vel[1].x(), v, 1e-6 * std::max(1.0, std::abs(v)))
        << method << ": one free mass on a spring must follow backward Euler exactly, "
        << "(m + dt kd + dt^2 k) dv = dt (F - dt k v), at step " << n + 1 << " " << seedText();
    ASSERT_NEAR(sim.state.pos[1].x(), x, 1e-6 * std::max(1.0, std::abs(x))) << method << ": x' = x + dt v' " << seedText();
  }
  ASSERT_EQ(sim.state.pos[0], Vec3::Zero()) << method << ": the pinned end never moves";
}

inline void ImplicitCase::checkPinnedNeverMove(const std::string& method) {
  net::NetParameters p = thesisCloth();
  p.resolution = integer(4, 10);
  p.pins = {net::Pin::Corner00, net::Pin::Corner11, net::Pin::EdgeU1};
  net::Net net(3, p);
  net.setIntegrator(netRegistry().makeIntegrator(method));
  const std::vector<Vec3> start = net.state.pos;
  for (int n = 0; n < 60; ++n) {
    net.operate(1.0 / 60.0);
    for (int i = 0; i < net.numOfMasses(); ++i) {
      if (net.masses[i].pinned) {
        ASSERT_EQ(net.state.pos[i], start[i]) << method << ": pinned mass " << i << " moved at step " << n + 1;
        ASSERT_EQ(net.state.vel[i], Vec3::Zero()) << method << ": pinned mass " << i << " has a velocity";
      }
    }
  }
}

// The thesis' cloth for `seconds` at dt = 1/60 s; true when it blew up (BlowUp thrown).
inline bool blowsUp(std::unique_ptr<Integrator> integrator, double seconds, double* lowest = nullptr) {
  net::Net net(3, thesisCloth());
  net.setIntegrator(std::move(integrator));
  try {
    for (int n = 0; n < static_cast<int>(seconds * 60); ++n) net.operate(1.0 / 60.0);
  } catch (const BlowUp&) {
    return true;
  }
  if (lowest) {
    *lowest = INFINITY;
    for (const Vec3& x : net.state.pos) *lowest = std::min(*lowest, x.y());
  }
  return false;
}

}  // namespace springlab::testing
