// Physics facts every integrator of the course must show (physics.md section 4), checked by
// name through the registry: the framework's methods and the labs' reference exercises
// alike. An integrator a lab adds joins each table with one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <ostream>
#include <string>
#include <vector>

#include <springlab/frequency_estimate.hpp>
#include <springlab/studies/run.hpp>
#include <springlab/studies/stability.hpp>

#include "study_registry.hpp"

namespace springlab {
namespace {

using testing::allLabs;
using testing::shippedScene;

// ---- a smooth problem: a short undamped chain swinging down under gravity, no contact -------
SceneDocument swingingChain() {
  SceneDocument d = shippedScene("rope_2d.json");
  for (const char* s : {"rope.masses=4", "rope.spring_constant=200", "rope.spring_friction=0", "rope.air_friction=0",
                        "rope.ground.height=-100", "rope.ground.repulsion=0", "rope.ground.friction=0",
                        "rope.ground.absorption=0"}) {
    d.set(s);
  }
  return d;
}

// Largest position error of any mass at t = 0.4 s against RK4 at a tiny step.
double chainError(const std::string& integrator, double dt) {
  static const studies::RunResult reference =
      studies::runScene(allLabs(), {swingingChain(), "rk4", 0.4 / 40000, 40000, 1});
  const long steps = std::lround(0.4 / dt);
  const studies::RunResult run = studies::runScene(allLabs(), {swingingChain(), integrator, dt, steps, 1});
  EXPECT_TRUE(run.stable) << run.failure;
  return studies::positionErrors(run, reference).back();
}

struct OrderCase {
  std::string integrator;
  int order;
  double dt;  // s: small enough for the asymptotic regime, large enough to stay above round-off
};

void PrintTo(const OrderCase& c, std::ostream* os) { *os << c.integrator; }

class ConvergenceOrder : public ::testing::TestWithParam<OrderCase> {};

TEST_P(ConvergenceOrder, HalvingDtDividesTheErrorBy2ToTheOrder) {
  const OrderCase& c = GetParam();
  const double measured = std::log2(chainError(c.integrator, c.dt) / chainError(c.integrator, c.dt / 2));
  EXPECT_NEAR(measured, c.order, 0.15) << c.integrator << " must converge at order " << c.order
                                       << " on a smooth problem; halving dt from " << c.dt << " s gives order "
                                       << measured;
}

INSTANTIATE_TEST_SUITE_P(Integrators, ConvergenceOrder,
                         ::testing::Values(OrderCase{"explicit_euler", 1, 1e-4}, OrderCase{"symplectic_euler", 1, 1e-4},
                                           OrderCase{"position_verlet", 2, 1e-3}, OrderCase{"velocity_verlet", 2, 1e-3},
                                           OrderCase{"midpoint", 2, 1e-3}, OrderCase{"rk4", 4, 4e-3}),
                         [](const auto& p) { return p.param.integrator; });

// ---- the single oscillator: one mass on one spring (k = 100 N/m, m = 1 kg, w = 10 rad/s) ----
// A long rest length keeps the spring linear until the blow-up check fires (with 1 m the
// mass would swing through the fixed end first, where the force is no longer linear); the
// ground moves out of the way.
SceneDocument linearOscillator(double springFriction = 0.0) {
  SceneDocument d = shippedScene("mass_on_spring.json");
  d.set("rope.rest_length=100");
  d.set("rope.ground.height=-1000");
  d.set("rope.spring_friction=" + std::to_string(springFriction));
  return d;
}

// A trial the chart cannot afford (more than maxSteps steps) measures nothing: the bisection
// reports NaN, not 0, which the chart would draw as "no stable dt" (explicit Euler on the ball,
// predicted 0.05 ms: 303 s of trial need 5.9 million steps, over the 4 million allowed). With
// room for the trials the same bracket finds the limit.
TEST(CriticalDt, ATrialTooLongToRunIsNotMeasuredRatherThanUnstable) {
  const double theory = 2.0 / 10.0;  // symplectic Euler on w = 10 rad/s
  const double duration = studies::defaultStabilityDuration(10.0);  // 188 s: 940 steps at the limit
  const studies::CriticalDt cramped =
      studies::criticalDt(allLabs(), linearOscillator(), "symplectic_euler", duration, theory, 0.002, 500);
  EXPECT_TRUE(std::isnan(cramped.measured)) << "measured " << cramped.measured << " s with room for no trial";
  // The first trial fails (20 % past the limit) and the halved one needs 1880 steps: still
  // not measured, though the limit is known to lie below the first guess.
  const studies::CriticalDt halved =
      studies::criticalDt(allLabs(), linearOscillator(), "symplectic_euler", duration, 1.2 * theory, 0.002, 1000);
  EXPECT_TRUE(std::isnan(halved.measured)) << "measured " << halved.measured << " s";
  const studies::CriticalDt roomy =
      studies::criticalDt(allLabs(), linearOscillator(), "symplectic_euler", duration, 1.2 * theory, 0.002, 100000);
  EXPECT_NEAR(roomy.measured / theory, 1.0, 0.02) << "measured " << roomy.measured << " s";
}

class CriticalDtOnTheOscillator : public ::testing::TestWithParam<std::string> {};

TEST_P(CriticalDtOnTheOscillator, IsWithin2PercentOfTheory) {
  const std::string name = GetParam();
  const double c = studies::stabilityConstant(allLabs(), name);
  const double theory = c / 10.0;
  const studies::CriticalDt m =
      studies::criticalDt(allLabs(), linearOscillator(), name, studies::defaultStabilityDuration(10.0), theory, 0.002);
  EXPECT_NEAR(m.measured / theory, 1.0, 0.02) << name << ": measured critical dt " << m.measured
                                              << " s, theory c / w = " << theory << " s";
}

INSTANTIATE_TEST_SUITE_P(Integrators, CriticalDtOnTheOscillator,
                         ::testing::Values("symplectic_euler", "position_verlet", "velocity_verlet", "rk4"));

// Energy of the oscillation about the equilibrium (total energy minus that of the mass at rest
// at y = -(L0 + m g / k)): exactly the modal energy of the linear system.
struct OscillatorRun {
  LoadedScene scene;
  double equilibriumEnergy;
  double oscillation() const { return scene.sim->energies().total() - equilibriumEnergy; }
};

OscillatorRun oscillatorWith(const std::string& integrator, double springFriction = 0.0) {
  OscillatorRun run{allLabs().loadScene(linearOscillator(springFriction)), 0.0};
  Simulation& sim = *run.scene.sim;
  sim.setIntegrator(allLabs().makeIntegrator(integrator));
  sim.setBlowUpCheck(false);
  const State start = sim.state;
  sim.state.pos[1].y() = -(100.0 + 9.81 / 100.0);
  run.equilibriumEnergy = sim.energies().total();
  sim.state = start;
  return run;
}

TEST(ExplicitEuler, UnstableAtEveryDtWithoutDamping) {
  // The oscillation's energy grows by exactly 1 + (w dt)^2 per step, however small dt is.
  for (double y : {1e-3, 1e-2, 1e-1, 1.0}) {
    OscillatorRun run = oscillatorWith("explicit_euler");
    const double e0 = run.oscillation();
    // Enough steps to see the gain, few enough to stay in the spring's linear range.
    const int steps = static_cast<int>(std::min(100000.0, 5.0 / std::log1p(y * y)));
    for (int n = 0; n < steps; ++n) run.scene.sim->operate(y / 10.0);
    const double growth = std::log(run.oscillation() / e0);
    EXPECT_GT(growth, 0.0) << "explicit Euler must gain energy at w dt = " << y;
    EXPECT_NEAR(growth / (steps * std::log1p(y * y)), 1.0, 0.01) << "gain per step must be 1 + (w dt)^2 at w dt = " << y;
  }
}

TEST(ExplicitEuler, StableBelow2ZetaOverWWithDamping) {
  // z = kd / (2 sqrt(k m)) = 0.1 with kd = 2 N s/m: stable while w dt < 2 z = 0.2.
  for (double factor : {0.9, 1.1}) {
    OscillatorRun run = oscillatorWith("explicit_euler", 2.0);
    const double e0 = run.oscillation();
    for (int n = 0; n < 3000; ++n) run.scene.sim->operate(factor * 0.02);
    if (factor < 1.0) {
      EXPECT_LT(run.oscillation(), 1e-3 * e0) << "explicit Euler must be stable at 0.9 x 2 z / w";
    } else {
      EXPECT_GT(run.oscillation(), 1e3 * e0) << "explicit Euler must be unstable at 1.1 x 2 z / w";
    }
  }
}

// ---- energy over 10^5 steps ------------------------------------------------------------------
enum class Energy { Bounded, Grows, Decays };
struct EnergyCase {
  std::string integrator;
  double wdt;
  Energy expected;
};

void PrintTo(const EnergyCase& c, std::ostream* os) { *os << c.integrator << " at w dt = " << c.wdt; }

class EnergyOver1e5Steps : public ::testing::TestWithParam<EnergyCase> {};

TEST_P(EnergyOver1e5Steps, BehavesAsTheMethodPredicts) {
  const EnergyCase& c = GetParam();
  OscillatorRun run = oscillatorWith(c.integrator);
  const double e0 = run.oscillation();
  double lo = 1.0, hi = 1.0;
  for (int n = 0; n < 100000; ++n) {
    run.scene.sim->operate(c.wdt / 10.0);
    const double r = run.oscillation() / e0;
    lo = std::min(lo, r);
    hi = std::max(hi, r);
  }
  const double last = run.oscillation() / e0;
  switch (c.expected) {
    case Energy::Bounded:
      EXPECT_GT(lo, 1.0 - c.wdt) << c.integrator << ": energy fell out of its band";
      EXPECT_LT(hi, 1.0 + c.wdt) << c.integrator << ": energy rose out of its band";
      break;
    case Energy::Grows:
      EXPECT_GT(last, 2.0) << c.integrator << " must gain energy on an undamped oscillator";
      break;
    case Energy::Decays:
      EXPECT_LT(last, 0.5) << c.integrator << " must lose energy on an undamped oscillator";
      break;
  }
}

INSTANTIATE_TEST_SUITE_P(Integrators, EnergyOver1e5Steps,
                         ::testing::Values(EnergyCase{"symplectic_euler", 0.2, Energy::Bounded},
                                           EnergyCase{"position_verlet", 0.2, Energy::Bounded},
                                           EnergyCase{"velocity_verlet", 0.2, Energy::Bounded},
                                           EnergyCase{"explicit_euler", 0.01, Energy::Grows},
                                           EnergyCase{"midpoint", 0.1, Energy::Grows},
                                           EnergyCase{"rk4", 0.5, Energy::Decays},
                                           // stable far beyond every explicit limit, losing energy
                                           // like implicit Euler (physics.md section 6)
                                           EnergyCase{"xpbd", 5.0, Energy::Decays},
                                           EnergyCase{"projective_dynamics", 5.0, Energy::Decays}),
                         [](const auto& p) { return p.param.integrator; });

// ---- a contact that reverses the velocity: an elastic bounce -----------------------------------
// A small flat net dropped onto a floor that reflects it (absorption 2, no friction, no air, no
// stretch limit, no wind drag): it falls, bounces and rises back to the height it fell from, its
// springs never stretched. The floor sets the velocity after the step (projection, exercise 2.5);
// a method with history must take that velocity as the state's, not its own record of the last
// positions: position Verlet's wrapper did not, and its net stayed on the floor.
SceneDocument bouncingNet() {
  SceneDocument d = shippedScene("net_sphere_drop.json");
  for (const char* s : {"net.resolution=4", "net.origin=[-0.6,0.5,-0.6]", "net.air_friction=0",
                        "net.stretch_limit.enabled=false", "net.colliders.spheres=[]",
                        R"(net.colliders.planes=[{"point":[0,0,0],"normal":[0,1,0]}])", "net.colliders.absorption=2",
                        "net.colliders.friction=0", "net.wind.drag=0"}) {
    d.set(s);
  }
  return d;
}

class ElasticBounce : public ::testing::TestWithParam<std::string> {};

TEST_P(ElasticBounce, ANetDroppedOnAnElasticFloorRisesBackToItsHeight) {
  // 0.9 s at 1 ms: the fall from 0.5 m takes 0.32 s, the rise as long.
  const studies::RunResult run = studies::runScene(allLabs(), {bouncingNet(), GetParam(), 1e-3, 1, 900});
  ASSERT_TRUE(run.stable) << run.failure;
  std::vector<double> height;  // the net's mean height per step
  for (const std::vector<Vec3>& frame : run.positions) {
    double sum = 0.0;
    for (const Vec3& x : frame) sum += x.y();
    height.push_back(sum / static_cast<double>(frame.size()));
  }
  // Heights above the lowest point (where the floor, held a contact offset out, stops the net).
  const auto lowest = std::min_element(height.begin(), height.end());
  const double fell = height.front() - *lowest;
  const double rose = *std::max_element(lowest, height.end()) - *lowest;
  EXPECT_GT(fell, 0.3) << "the net must reach the floor";
  EXPECT_NEAR(rose / fell, 1.0, 0.02) << GetParam() << ": fell " << fell << " m, rose " << rose << " m";
}

INSTANTIATE_TEST_SUITE_P(Integrators, ElasticBounce,
                         ::testing::Values("explicit_euler", "symplectic_euler", "position_verlet", "velocity_verlet",
                                           "midpoint", "rk4"),
                         [](const auto& p) { return p.param; });

// The corrections' work (Simulation::correctionWork), which the blow-up check takes off the total
// energy: on an inelastic floor (absorption 1) it is minus the kinetic energy of the fall, M g h,
// which the floor's projection takes; on an elastic one (absorption 2) it is nothing. What is
// left, the step's own energy balance, keeps the start's in both.
TEST(CorrectionWork, IsMinusTheKineticEnergyAnInelasticFloorTakes) {
  for (const double absorption : {1.0, 2.0}) {
    SceneDocument net = bouncingNet();
    net.set("net.colliders.absorption=" + std::to_string(absorption));
    LoadedScene loaded = allLabs().loadScene(net);
    Simulation& sim = *loaded.sim;
    sim.setIntegrator(allLabs().makeIntegrator("symplectic_euler"));
    double mass = 0.0, top = 0.0;
    for (int i = 0; i < sim.numOfMasses(); ++i) {
      mass += sim.masses[i].m;
      top += sim.masses[i].m * sim.state.pos[i].y();
    }
    top /= mass;
    const double start = sim.energyBalance();
    double lowest = top;  // the net's lowest mean height: where the floor, a contact offset out, stops it
    for (int k = 0; k < 400; ++k) {  // 0.4 s: the fall takes 0.29 s
      sim.operate(1e-3);
      double y = 0.0;
      for (int i = 0; i < sim.numOfMasses(); ++i) y += sim.masses[i].m * sim.state.pos[i].y();
      lowest = std::min(lowest, y / mass);
    }
    const double fall = mass * 9.81 * (top - lowest);
    if (absorption == 1.0) {
      EXPECT_NEAR(sim.correctionWork() / -fall, 1.0, 0.01) << "the floor takes the fall's " << fall << " J";
    } else {
      EXPECT_NEAR(sim.correctionWork() / fall, 0.0, 0.01) << "an elastic floor takes nothing of " << fall << " J";
    }
    EXPECT_NEAR((sim.energyBalance() - start) / fall, 0.0, 0.01) << "absorption " << absorption;
  }
}

// ---- the 80-mass rope ------------------------------------------------------------------------
TEST(ClassicRope, SymplecticEulerCriticalDtIsWithin15PercentOf2OverWmax) {
  const SceneDocument rope = shippedScene("rope.json");
  const double w = studies::sceneLanczosEstimate(allLabs(), rope);
  EXPECT_NEAR(w, 2.0 * std::sqrt(10000 / 0.05), 0.02 * w) << "an 80-mass chain's w_max is close to 2 sqrt(k/m)";
  const studies::CriticalDt m =
      studies::criticalDt(allLabs(), rope, "symplectic_euler", studies::defaultStabilityDuration(w), 2.0 / w, 0.01);
  EXPECT_NEAR(m.measured / (2.0 / w), 1.0, 0.15) << "measured " << m.measured << " s, predicted 2 / w_max = " << 2.0 / w;
}

// ---- a 32 x 32 cloth (Lab 2) -----------------------------------------------------------------
// The hanging cloth with nothing but springs and gravity acting: no stretch limiting (a
// position correction that hides instability) and no damping (with kd, light cloth is limited
// by kd / m, which the stiffness-only w_max does not see). CG solves to 1e-10: the scene's
// own 1e-3 is enough for its drape, but these tests measure the integrator, and a CG error of
// 1e-3 of each step's dv would show up as the integrator's (order 0.79 instead of 1).
SceneDocument undampedCloth(int resolution) {
  SceneDocument d = shippedScene("net_hanging.json");
  for (const std::string& s : {"net.resolution=" + std::to_string(resolution), std::string("solver.tolerance=1e-10"),
                               std::string("net.stretch_limit.enabled=false"),
                               std::string("net.springs.structural.damping=0"), std::string("net.springs.shear.damping=0"),
                               std::string("net.springs.bend.damping=0"), std::string("net.air_friction=0")}) {
    d.set(s);
  }
  return d;
}

TEST(HangingCloth, SymplecticEulerCriticalDtIsWithin15PercentOf2OverWmax) {
  const SceneDocument cloth = undampedCloth(32);
  const double w = studies::sceneLanczosEstimate(allLabs(), cloth);
  const studies::CriticalDt m =
      studies::criticalDt(allLabs(), cloth, "symplectic_euler", studies::defaultStabilityDuration(w), 2.0 / w, 0.01);
  EXPECT_NEAR(m.measured / (2.0 / w), 1.0, 0.15) << "measured " << m.measured << " s, predicted 2 / w_max = " << 2.0 / w;
}

TEST(HangingCloth, ImplicitEulerIsStableAt100OverWmax) {
  const SceneDocument cloth = undampedCloth(8);
  const double w = studies::sceneLanczosEstimate(allLabs(), cloth);
  const studies::RunResult run = studies::runScene(allLabs(), {cloth, "implicit_euler", 100.0 / w, 20, 1});
  EXPECT_TRUE(run.stable) << "implicit Euler must be unconditionally stable; at dt = 100 / w_max: " << run.failure;
}

// Implicit Euler needs force Jacobians, which the rope does not provide: its order is measured
// on a small undamped cloth swinging down (no contact within 0.2 s).
TEST(HangingCloth, ImplicitEulerConvergesAtFirstOrder) {
  const SceneDocument cloth = undampedCloth(4);
  const double t = 0.2;
  const studies::RunResult reference = studies::runScene(allLabs(), {cloth, "rk4", t / 20000, 20000, 1});
  auto error = [&](double dt) {
    const studies::RunResult run = studies::runScene(allLabs(), {cloth, "implicit_euler", dt, std::lround(t / dt), 1});
    EXPECT_TRUE(run.stable) << run.failure;
    return studies::positionErrors(run, reference).back();
  };
  const double dt = 2.5e-4;
  const double measured = std::log2(error(dt) / error(dt / 2));
  EXPECT_NEAR(measured, 1.0, 0.15) << "implicit Euler must converge at order 1; halving dt from " << dt
                                   << " s gives order " << measured;
}

// Implicit Euler damps every mode it cannot resolve: an undamped cloth released from rest swings
// down and comes to rest, which no energy-conserving method would let it do.
TEST(HangingCloth, ImplicitEulerDecaysTheSwingOfAnUndampedCloth) {
  LoadedScene loaded = allLabs().loadScene(undampedCloth(6));
  Simulation& sim = *loaded.sim;
  sim.setIntegrator(allLabs().makeIntegrator("implicit_euler"));
  double largest = 0.0;
  for (int n = 0; n < 3000; ++n) {
    sim.operate(1.0 / 60.0);
    largest = std::max(largest, sim.energies().kinetic);
  }
  const double last = sim.energies().kinetic;
  EXPECT_GT(largest, 0.0);
  EXPECT_LT(last, 1e-3 * largest) << "implicit Euler must damp the swing of an undamped cloth away over 50 s";
}

}  // namespace
}  // namespace springlab
