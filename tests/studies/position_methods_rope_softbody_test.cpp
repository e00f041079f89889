// XPBD and projective dynamics (Lab 2's given loops) on the rope and the soft body: they take a
// scene's springs and treat every other force, the soft body's gas pressure included, as an
// external force taken once per step (see handouts/02_net.md, section 7.c). The physics must hold
// there as on the cloth: momentum kept without external forces, stable at dt = 1/60 s, and a
// rest state where the force model's forces balance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <springlab/diagnostics.hpp>

#include "study_registry.hpp"

namespace springlab {
namespace {

using testing::allLabs;
using testing::shippedScene;

const char* const kMethods[] = {"xpbd", "projective_dynamics"};

LoadedScene withMethod(SceneDocument doc, const std::string& method) {
  LoadedScene scene = allLabs().loadScene(doc);
  scene.sim->setIntegrator(allLabs().makeIntegrator(method));
  return scene;
}

// Options that bring each method to the force model's rest state: XPBD warm-started (its
// fixed point is the equilibrium at any sweep count), projective dynamics iterated (its local
// step uses the directions of the iterate, one iteration ends short by O(h^2 a)).
nlohmann::json converged() {
  return {{"xpbd", {{"iterations", 4}, {"substeps", 4}, {"warm_start", 1}}}, {"projective_dynamics", {{"iterations", 30}}}};
}

// A rope of 20 masses (1 m) hanging from its still connection; air friction brings it to rest.
SceneDocument hangingRope() {
  SceneDocument rope = shippedScene("rope.json");
  rope.set("rope.masses=20");
  rope.set("rope.air_friction=0.5");
  rope.set("rope.ground.height=-100");
  rope.json["integrator_options"] = converged();
  return rope;
}

// The ball of 42 masses (one subdivision) with nothing outside it: no gravity, floor, air or wind.
SceneDocument isolatedBall() {
  SceneDocument ball = shippedScene("softbody_ball.json");
  ball.set("softbody.mesh.subdivisions=1");
  ball.set("gravity=[0, 0, 0]");
  ball.set("softbody.obstacles=[]");
  ball.set("softbody.air_friction=0");
  return ball;
}

// The largest force of the force model on a free mass at the scene's positions, at rest.
double largestRestForce(Simulation& sim) {
  State still = sim.state;
  for (Vec3& v : still.vel) v.setZero();
  std::vector<Vec3> f;
  sim.evaluateForces(still, f);
  double worst = 0.0;
  for (int i = 0; i < sim.numOfMasses(); ++i) {
    if (sim.inverseMass(i) != 0.0) worst = std::max(worst, f[i].norm());
  }
  return worst;
}

void run(Simulation& sim, double dt, int steps) {
  for (int n = 0; n < steps; ++n) sim.operate(dt);
}

TEST(RopePositionMethods, StableAtASixtiethOfASecond) {
  for (const char* method : kMethods) {
    SceneDocument rope = shippedScene("rope.json");  // 80 masses, k = 10^4 N/m: explicit Euler needs dt < 4 ms
    rope.json["integrator_options"] = {{"xpbd", {{"iterations", 10}}}, {"projective_dynamics", {{"iterations", 5}}}};
    LoadedScene scene = withMethod(rope, method);
    try {
      run(*scene.sim, 1.0 / 60.0, 180);
    } catch (const BlowUp& e) {
      FAIL() << method << " must not blow up on the rope at dt = 1/60 s: " << e.what();
    }
    double lowest = INFINITY;
    for (const Vec3& x : scene.sim->state.pos) lowest = std::min(lowest, x.y());
    EXPECT_GT(lowest, -1.6) << method << ": the rope rests on its ground at -1.5 m, not below";
  }
}

TEST(RopePositionMethods, RestWhereTheForceModelBalancesGravity) {
  for (const char* method : kMethods) {
    LoadedScene scene = withMethod(hangingRope(), method);
    run(*scene.sim, 1.0 / 60.0, 900);
    const double weight = 0.05 * 9.81;
    const double residual = largestRestForce(*scene.sim) / weight;
    EXPECT_LT(residual, 0.01) << method << ": at rest a mass of the rope still feels " << 100 * residual
                              << " % of its weight from the force model: the rest state must be its equilibrium";
  }
}

TEST(SoftBodyPositionMethods, StableAtASixtiethOfASecond) {
  for (const char* method : kMethods) {
    SceneDocument ball = shippedScene("softbody_ball.json");
    ball.set("softbody.mesh.subdivisions=2");
    LoadedScene scene = withMethod(ball, method);
    try {
      run(*scene.sim, 1.0 / 60.0, 180);  // drop, bounce on the penalty floor, settle: 3 s
    } catch (const BlowUp& e) {
      FAIL() << method << " must not blow up on the bouncing ball at dt = 1/60 s: " << e.what();
    }
    double lowest = INFINITY;
    for (const Vec3& x : scene.sim->state.pos) lowest = std::min(lowest, x.y());
    EXPECT_GT(lowest, -0.1) << method << ": the ball must stay on its floor (y = 0)";
  }
}

TEST(SoftBodyPositionMethods, ConserveMomentumWithoutExternalForces) {
  for (const char* method : kMethods) {
    LoadedScene scene = withMethod(isolatedBall(), method);
    Simulation& sim = *scene.sim;
    // Every mass its own velocity: the springs and the gas push masses against each other.
    for (int i = 0; i < sim.numOfMasses(); ++i) {
      sim.state.vel[i] = Vec3(std::sin(1.0 + i), std::cos(2.0 * i), std::sin(0.5 * i));
    }
    const Vec3 before = sim.momentum();
    run(sim, 1.0 / 60.0, 60);
    EXPECT_LT((sim.momentum() - before).norm(), 1e-9 * (1.0 + before.norm()))
        << method << " changed the ball's momentum by " << (sim.momentum() - before).norm()
        << " kg m/s: springs and gas pressure are internal forces";
  }
}

TEST(SoftBodyPositionMethods, RestWhereSpringsBalanceTheGas) {
  for (const char* method : kMethods) {
    SceneDocument ball = isolatedBall();
    ball.set("softbody.air_friction=2");
    ball.json["integrator_options"] = converged();
    LoadedScene scene = withMethod(ball, method);
    run(*scene.sim, 1.0 / 60.0, 1800);
    // A vertex's share of the gas force at the rest radius R: p A / n = (nRT / (4/3 pi R^3)) 4 pi R^2 / n.
    const double gasPerVertex = 3.0 * 30.0 / (0.5 * scene.sim->numOfMasses());
    const double residual = largestRestForce(*scene.sim) / gasPerVertex;
    EXPECT_LT(residual, 0.01) << method << ": at rest a vertex still feels " << 100 * residual
                              << " % of its share of the gas force: the rest state must be where springs and gas balance";
  }
}

}  // namespace
}  // namespace springlab
