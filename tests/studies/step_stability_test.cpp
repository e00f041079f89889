// The stability limit of the step that runs (springlab/step_stability.hpp) against the closed
// forms of physics.md section 7: on a uniform damped chain every mode q'' = -w^2 q - gamma q'
// is stepped by a 2x2 matrix written out here from each method's update formulas, and the
// chain's limit is the smallest over its modes. The step-map estimate never sees these.
#include <gtest/gtest.h>

#include <algorithm>
#include <ostream>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include <springlab/calm_run.hpp>
#include <springlab/diagnostics.hpp>
#include <springlab/frequency_estimate.hpp>
#include <springlab/step_stability.hpp>
#include <springlab/studies/rest_check.hpp>
#include <springlab/studies/run.hpp>
#include <springlab/studies/stability.hpp>

#include "study_registry.hpp"

namespace springlab {
namespace {

using testing::allLabs;
using testing::shippedScene;

// ---- the closed forms: one mode, one method ---------------------------------------------------
// The step of q'' = -w2 q - g q' as a matrix on (q, q'), from each method's formulas.
Eigen::Matrix2d modeStep(const std::string& method, double w2, double g, double h) {
  Eigen::Matrix2d A;  // the rate matrix: d/dt (q, v) = A (q, v)
  A << 0.0, 1.0, -w2, -g;
  const Eigen::Matrix2d I = Eigen::Matrix2d::Identity();
  const Eigen::Matrix2d hA = h * A;
  if (method == "explicit_euler") return I + hA;
  if (method == "midpoint") return I + hA + hA * hA / 2.0;
  if (method == "rk4") return I + hA + hA * hA / 2.0 + hA * hA * hA / 6.0 + hA * hA * hA * hA / 24.0;
  if (method == "symplectic_euler" || method == "position_verlet") {
    // Kick with the force at the start, drift with the new velocity (position Verlet's
    // x' = 2x - x_prev + h^2 a with v = (x - x_prev) / h is the same map).
    Eigen::Matrix2d S;
    S << 1.0 - h * h * w2, h * (1.0 - h * g), -h * w2, 1.0 - h * g;
    return S;
  }
  if (method == "velocity_verlet") {
    // State (q, v, a) with a kept from the last step: a = -w2 q - g (v - a h / 2), so
    // a = (-w2 q - g v) / (1 - g h / 2). Drift with a half kick, force at the new position
    // and half-kicked velocity, then the second half kick.
    const double d = 1.0 - g * h / 2.0;
    const Eigen::RowVector2d a(-w2 / d, -g / d);             // a as a row acting on (q, v)
    const Eigen::RowVector2d q1 = Eigen::RowVector2d(1.0, h) + h * h / 2.0 * a;
    const Eigen::RowVector2d vHalf = Eigen::RowVector2d(0.0, 1.0) + h / 2.0 * a;
    const Eigen::RowVector2d a1 = -w2 * q1 - g * vHalf;
    Eigen::Matrix2d S;
    S.row(0) = q1;
    S.row(1) = vHalf + h / 2.0 * a1;
    return S;
  }
  ADD_FAILURE() << "no closed form for " << method;
  return I;
}

double modeRadius(const std::string& method, double w2, double g, double h) {
  return Eigen::EigenSolver<Eigen::Matrix2d>(modeStep(method, w2, g, h)).eigenvalues().cwiseAbs().maxCoeff();
}

// The largest h with every mode's radius <= 1, by bisection from a bracket [lo, hi].
double closedFormLimit(const std::string& method, const std::vector<std::pair<double, double>>& modes, double lo,
                       double hi) {
  auto stable = [&](double h) {
    for (const auto& [w2, g] : modes) {
      if (modeRadius(method, w2, g, h) > 1.0 + 1e-12) return false;
    }
    return true;
  };
  if (!stable(lo)) return 0.0;
  if (stable(hi)) return INFINITY;
  for (int k = 0; k < 100; ++k) {
    const double mid = 0.5 * (lo + hi);
    (stable(mid) ? lo : hi) = mid;
  }
  return lo;
}

// ---- a uniform damped chain: N free masses hanging sideways from a fixed end ---------------
// m = 0.05 kg, k = 10000 N/m, L0 = 0.05 m, spring dampers kd along each spring and air a.
// Without gravity the chain rests where it starts, springs at rest length along x, so the
// linearised chain has only its axial modes w_j = 2 sqrt(k/m) sin((2j - 1) pi / (2 (2N + 1)))
// (fixed-free chain) with gamma_j = a / m + (kd / k) w_j^2, and transverse modes with w = 0,
// gamma = a / m. With gravity (fallingChain) it swings down and settles hanging.
constexpr int kChainMasses = 12;
constexpr double kMass = 0.05, kStiffness = 10000.0, kAir = 0.02;

SceneDocument fallingChain(double kd, double air = kAir) {
  SceneDocument d = shippedScene("rope.json");
  for (const std::string& s :
       {"rope.masses=" + std::to_string(kChainMasses + 1), std::string("rope.ground.height=-100"),
        "rope.spring_friction=" + std::to_string(kd), "rope.air_friction=" + std::to_string(air)}) {
    d.set(s);
  }
  return d;
}

SceneDocument dampedChain(double kd) {
  SceneDocument d = fallingChain(kd);
  d.set("gravity=[0, 0, 0]");
  return d;
}

std::vector<std::pair<double, double>> chainModes(double kd) {
  std::vector<std::pair<double, double>> modes{{0.0, kAir / kMass}};
  for (int j = 1; j <= kChainMasses; ++j) {
    const double w = 2.0 * std::sqrt(kStiffness / kMass) *
                     std::sin((2 * j - 1) * std::numbers::pi / (2.0 * (2 * kChainMasses + 1)));
    modes.push_back({w * w, kAir / kMass + kd / kStiffness * w * w});
  }
  return modes;
}

double stepLimit(const SceneDocument& scene, const std::string& integrator, const StepStabilityOptions& o = {}) {
  LoadedScene loaded = allLabs().loadScene(scene);
  loaded.sim->setIntegrator(allLabs().makeIntegrator(integrator));
  return stepStableDt(*loaded.sim, o);
}

const std::vector<std::string> kExplicitMethods{"explicit_euler", "symplectic_euler", "position_verlet",
                                                "velocity_verlet", "midpoint", "rk4"};

// ---- the predicted limit against the closed form, mode by mode -------------------------------
struct ChainCase {
  double kd;  // N s/m: damping ratio of the stiffest mode 0, 0.009, 0.2, 1.5
  std::string integrator;
};

void PrintTo(const ChainCase& c, std::ostream* os) { *os << c.integrator << " kd " << c.kd; }

// The chain's stiffest angular frequency and the case's closed-form limit (chainModes).
double chainMaxFrequency() { return 2.0 * std::sqrt(kStiffness / kMass); }
double chainExactLimit(const ChainCase& c) {
  return closedFormLimit(c.integrator, chainModes(c.kd), 1e-9, 10.0 / chainMaxFrequency());
}

class DampedChainLimit : public ::testing::TestWithParam<ChainCase> {};

TEST_P(DampedChainLimit, IsTheClosedFormOfTheStiffestModeWithin2Percent) {
  const auto [kd, integrator] = GetParam();
  const double exact = chainExactLimit(GetParam());
  // The whole Jacobian (the chain is small) and the modal runs the large scenes use.
  StepStabilityOptions modal;
  modal.denseBelow = 0;
  EXPECT_NEAR(stepLimit(dampedChain(kd), integrator) / exact, 1.0, 0.02) << "closed form " << exact << " s";
  EXPECT_NEAR(stepLimit(dampedChain(kd), integrator, modal) / exact, 1.0, 0.02) << "closed form " << exact << " s";
}

std::vector<ChainCase> chainCases() {
  std::vector<ChainCase> cases;
  for (double kd : {0.0, 0.2, 4.5, 30.0}) {
    for (const std::string& m : kExplicitMethods) {
      // Undamped but for the air, explicit Euler and the midpoint rule have no useful limit:
      // what the estimate finds is the slack of 1e-6 in the spectral radius.
      if (kd == 0.0 && (m == "explicit_euler" || m == "midpoint")) continue;
      cases.push_back({kd, m});
    }
  }
  return cases;
}

std::string chainCaseName(const ::testing::TestParamInfo<ChainCase>& p) {
  return p.param.integrator + "_kd" + std::to_string(static_cast<int>(p.param.kd * 10));
}

INSTANTIATE_TEST_SUITE_P(Methods, DampedChainLimit, ::testing::ValuesIn(chainCases()),
                         chainCaseName);

// ---- the radius at dt, which `sim` asks instead of the limit, against the closed form -----------
// `sim` takes dt as within the limit when the step's spectral radius at dt is within the slack.
// On the chain, damped from none to overdamped (stiffest mode's damping ratio up to 1.5), that
// verdict must agree with the closed-form limit: within at 0.97 times it, past it at 1.03 times.
class DampedChainRadius : public ::testing::TestWithParam<ChainCase> {};

TEST_P(DampedChainRadius, IsWithinOneBelowTheClosedFormLimitAndAboveItPast) {
  const auto [kd, integrator] = GetParam();
  const double exact = chainExactLimit(GetParam());
  LoadedScene loaded = allLabs().loadScene(dampedChain(kd));
  loaded.sim->setIntegrator(allLabs().makeIntegrator(integrator));
  const double slack = StepStabilityOptions{}.radiusSlack;
  EXPECT_LE(stepSpectralRadius(*loaded.sim, 0.97 * exact).radius, 1.0 + slack) << "closed form " << exact << " s";
  EXPECT_GT(stepSpectralRadius(*loaded.sim, 1.03 * exact).radius, 1.0 + slack) << "closed form " << exact << " s";
}

INSTANTIATE_TEST_SUITE_P(Methods, DampedChainRadius, ::testing::ValuesIn(chainCases()),
                         chainCaseName);

// ---- the rest check, the real step's runs, against the closed form ------------------------------
// The rest check (rest_check.hpp) runs the real step twice from the rest, one run disturbed by
// 1e-8 of the scene's size, and says the rest does not hold where the difference grows past
// kRestGrowthLimit. No eigenvalue in it: on the chain at rest, undamped to overdamped, it must
// agree with the closed-form limit by itself, for a trial as long as the chart's.
class DampedChainRest : public ::testing::TestWithParam<ChainCase> {};

TEST_P(DampedChainRest, HoldsBelowTheClosedFormLimitAndBreaksPastIt) {
  const auto [kd, integrator] = GetParam();
  const double exact = chainExactLimit(GetParam());
  const SceneDocument chain = dampedChain(kd);
  const double duration = studies::stabilityTrialDuration(allLabs(), chain, integrator, exact,
                                                          studies::defaultStabilityDuration(chainMaxFrequency()));
  auto growth = [&](double factor) {
    return studies::measureRestGrowth(allLabs(), chain, integrator, 1.0, factor * exact, duration);
  };
  const studies::RestGrowth half = growth(0.5), below = growth(0.97), past = growth(1.03);
  EXPECT_TRUE(studies::restCheckApplies(half)) << "half the limit: " << half.growth;
  EXPECT_FALSE(studies::restBroken(below)) << "0.97 times " << exact << " s: " << below.growth;
  EXPECT_TRUE(studies::restBroken(past)) << "1.03 times " << exact << " s: " << past.growth;
}

INSTANTIATE_TEST_SUITE_P(Methods, DampedChainRest, ::testing::ValuesIn(chainCases()), chainCaseName);

// ---- runs at 0.97 and 1.03 times the prediction -----------------------------------------------
// The chart's trial: at least 300 periods of the stiffest mode, longer when the instability
// just past the limit grows slowly.
// (duration > 0: that trial time, computed by the caller already.)
studies::RunResult trialAt(const SceneDocument& scene, const std::string& integrator, double predicted, double factor,
                           bool watchReversal = true, double duration = 0.0) {
  if (!(duration > 0.0)) {
    const double w = studies::sceneLanczosEstimate(allLabs(), scene);
    duration =
        studies::stabilityTrialDuration(allLabs(), scene, integrator, predicted, studies::defaultStabilityDuration(w));
  }
  const long steps = std::lround(std::ceil(duration / (factor * predicted)));
  studies::RunSpec spec{scene, integrator, factor * predicted, steps, 1};
  spec.keepPositions = false;
  spec.swingDt = 0.5 * predicted;  // as the chart's trials
  spec.watchReversal = watchReversal;
  return studies::runScene(allLabs(), spec);
}

// The chart's options for one method's row, on one thread and quiet.
studies::StabilityOptions chartRow(const std::string& integrator) {
  studies::StabilityOptions o;
  o.integrators = {integrator};
  o.threads = 1;
  o.progress = false;
  return o;
}

// Returns the trial at 1.03 times the limit, whose message a test may read.
studies::RunResult expectStableBelowAndReportedAbove(const SceneDocument& scene, const std::string& integrator) {
  const double predicted = studies::sceneStepStableDt(allLabs(), scene, integrator);
  EXPECT_TRUE(std::isfinite(predicted) && predicted > 0.0) << predicted;
  if (!(std::isfinite(predicted) && predicted > 0.0)) return {};
  const studies::RunResult below = trialAt(scene, integrator, predicted, 0.97);
  EXPECT_TRUE(below.stable) << integrator << " at 0.97 x " << predicted << " s: " << below.failure;
  const studies::RunResult above = trialAt(scene, integrator, predicted, 1.03);
  EXPECT_FALSE(above.stable) << integrator << " at 1.03 x " << predicted << " s must be reported unstable";
  return above;
}

class DampedChainAtTheLimit : public ::testing::TestWithParam<std::string> {};

TEST_P(DampedChainAtTheLimit, SurvivesJustBelowAndIsStoppedJustAbove) {
  // Damping ratio 0.2 in the stiffest mode; the chain falls, swings and settles. Hanging, it
  // has transverse modes (w^2 up to 4 T / (m L0)) that only the air damps: with air 0.02
  // explicit Euler's limit is one of those, (a / m) / w^2 = 25 us, where 1.03 times the limit
  // grows a mode by 3e-7 per step (1e8 steps to see). Air 0.5 puts its limit back on the
  // spring dampers' kd / k, as on the chain without gravity.
  expectStableBelowAndReportedAbove(fallingChain(4.5, 0.5), GetParam());
}

INSTANTIATE_TEST_SUITE_P(Methods, DampedChainAtTheLimit, ::testing::ValuesIn(kExplicitMethods),
                         [](const auto& p) { return p.param; });

TEST(DampedChainAtTheLimit, APassiveChainThatGainsEnergyIsStoppedByPassivity) {
  // Just past symplectic Euler's limit the chain saturates: the springs flip and the total
  // energy stays bounded, far below the runaway threshold; passivity sees it.
  const double predicted = studies::sceneStepStableDt(allLabs(), fallingChain(4.5), "symplectic_euler");
  const studies::RunResult above = trialAt(fallingChain(4.5), "symplectic_euler", predicted, 1.03);
  ASSERT_FALSE(above.stable);
  EXPECT_NE(above.failure.find("passivity"), std::string::npos) << above.failure;
  EXPECT_NE(above.failure.find("is stable only below dt = "), std::string::npos) << above.failure;
  EXPECT_EQ(above.failure.find("below the stability limit"), std::string::npos) << above.failure;
}

// ---- the rope under the midpoint rule: an instability that saturates after the fall ----------
// The rope falls from straight (0 J) and settles to -47.6 J. Just past the midpoint rule's
// limit it climbs back by 5 to 9 J and swings there, never near its start: only the climb
// from its low (BlowUpCheck detector 4) sees it, 10 s into the 58 s trial (the chart measured
// 1.18 times the prediction before). Its masses' motion turns back every step meanwhile, and
// detector 5 sees that first (8.7 s), detector 6 its motion held at 9.4 s: the climb is held
// to it with both off.
TEST(RopeAtTheLimit, TheMidpointRuleClimbsBackFromItsLowAndIsStopped) {
  const SceneDocument rope = shippedScene("rope.json");
  expectStableBelowAndReportedAbove(rope, "midpoint");
  const double predicted = studies::sceneStepStableDt(allLabs(), rope, "midpoint");
  const studies::RunResult above = trialAt(rope, "midpoint", predicted, 1.03, false);
  EXPECT_FALSE(above.stable);
  EXPECT_NE(above.failure.find("climbed back"), std::string::npos) << above.failure;
}

// ---- a start far from rest: the mass on its spring --------------------------------------------
// One undamped mass m on a spring k, released away from where it hangs: it swings about the point where
// it hangs, where the step's limit is c / sqrt(k / m) (the spring's axial mode is the stiffest;
// 2 for symplectic Euler and both Verlets, 2 sqrt(2) for RK4). The linearised step at the
// start has another limit (RK4's was 0.077 s there); the runs follow the one at rest.
TEST(MassOnSpring, TheLimitIsTheOneAtRestNotAtItsStart) {
  const SceneDocument scene = shippedScene("mass_on_spring.json");
  const double w = std::sqrt(scene.json.at("rope").at("spring_constant").get<double>() /
                             scene.json.at("rope").at("mass").get<double>());
  for (const auto& [integrator, c] : std::vector<std::pair<std::string, double>>{
           {"symplectic_euler", 2.0}, {"position_verlet", 2.0}, {"velocity_verlet", 2.0}, {"rk4", 2.0 * std::sqrt(2.0)}}) {
    const double predicted = studies::sceneStepStableDt(allLabs(), scene, integrator);
    EXPECT_NEAR(predicted / (c / w), 1.0, 0.02) << integrator << ": closed form " << c / w << " s";
    expectStableBelowAndReportedAbove(scene, integrator);
  }
}

// ---- a contact: the rope lying on the ground at equilibrium -------------------------------------
// The ground's penalty spring holds each mass at depth m g / k_g, so every contact is active
// at the start; with k_g = 1e5 N/m its vertical modes (w^2 = k_g / m = 2e6 s^-2, damped only
// by the air) are the stiffest, above the chain's 8e5 s^-2.
SceneDocument ropeOnTheGround() {
  SceneDocument d = fallingChain(4.5);
  const double depth = kMass * 9.81 / 1e5;
  for (const std::string& s : {"rope.ground.height=" + std::to_string(depth), std::string("rope.ground.repulsion=1e5"),
                               std::string("rope.ground.friction=0"), std::string("rope.ground.absorption=0")}) {
    d.set(s);
  }
  return d;
}

TEST(RopeOnTheGround, TheActiveContactSetsTheLimitAndTheRunsAgree) {
  std::vector<std::pair<double, double>> modes = chainModes(4.5);
  modes.push_back({1e5 / kMass, kAir / kMass});
  const double exact = closedFormLimit("symplectic_euler", modes, 1e-9, 0.01);
  const double predicted = studies::sceneStepStableDt(allLabs(), ropeOnTheGround(), "symplectic_euler");
  EXPECT_NEAR(predicted / exact, 1.0, 0.02) << "closed form with the ground's spring " << exact << " s";
  EXPECT_LT(predicted, 0.9 * studies::sceneStepStableDt(allLabs(), dampedChain(4.5), "symplectic_euler"))
      << "the contact must lower the limit";
  // Just below the limit the rope rests on the ground. (Just above, the masses hop off the
  // ground and the motion saturates below the blow-up check's thresholds: not tested.)
  const studies::RunResult below = trialAt(ropeOnTheGround(), "symplectic_euler", predicted, 0.97);
  EXPECT_TRUE(below.stable) << below.failure;
}

// ---- pressure: the soft ball with its gas in from the start --------------------------------
// The ball in flight: without gravity it stays where it starts, a metre above its floor (with
// gravity the settling follows it down to its rest on the floor).
SceneDocument inflatedBall(double gas, int subdivisions = 2) {
  SceneDocument d = shippedScene("softbody_ball.json");
  for (const std::string& s : {"softbody.mesh.subdivisions=" + std::to_string(subdivisions), "softbody.gas.nRT=" + std::to_string(gas),
                               std::string("softbody.gas.inflation_time=0"), std::string("gravity=[0,0,0]")}) {
    d.set(s);
  }
  return d;
}

// Explicit Euler's limit on a scene with the whole Jacobian for up to denseBelow coordinates
// (100000: every direction, the oracle) or the modal directions only (0).
double explicitEulerLimit(const SceneDocument& scene, int denseBelow) {
  LoadedScene loaded = allLabs().loadScene(scene);
  loaded.sim->setIntegrator(allLabs().makeIntegrator("explicit_euler"));
  StepStabilityOptions o;
  o.denseBelow = denseBelow;
  return stepStableDt(*loaded.sim, o);
}

TEST(InflatedBall, PressureLowersTheLimitAndTheRunsAgree) {
  const double soft = studies::sceneStepStableDt(allLabs(), inflatedBall(30), "symplectic_euler");
  const double hard = studies::sceneStepStableDt(allLabs(), inflatedBall(1000), "symplectic_euler");
  EXPECT_LT(hard, 0.97 * soft) << "the gas adds stiffness: 30 J " << soft << " s, 1000 J " << hard << " s";
  expectStableBelowAndReportedAbove(inflatedBall(1000), "symplectic_euler");
}

// ---- the ball's wobble: explicit Euler fails where the air alone damps -------------------------
// The surface moving sideways stretches no spring along its length, so only the air damps it
// (0.0002 N s/m per mass: gamma = 0.03 /s on 162 masses), while the gas and the springs'
// tension make it stiff. Explicit Euler's limit on a mode is gamma / w^2: it fails there first,
// neither on the stiffest nor on the most damped modes. The modal directions must hold those
// modes: their limit is near the one of every direction (the dense Jacobian; on the ball as
// shipped, coarsened, where it settles: 0.321 against 0.321 ms, where the stiffest and most
// damped modes alone said 1.95 ms). Damping that is not proportional (spring dampers and air)
// leaves the modes' span not quite invariant under the step, and the Ritz radius on it then
// errs high: a limit a little low, on the safe side (this inflated ball: 0.194 against 0.199 ms).
TEST(InflatedBall, ExplicitEulerFailsFirstOnTheWobbleTheAirAloneDamps) {
  const SceneDocument ball = inflatedBall(30);
  const double everyDirection = explicitEulerLimit(ball, 100000);
  const double modal = explicitEulerLimit(ball, 0);
  ASSERT_TRUE(std::isfinite(everyDirection) && everyDirection > 0.0) << everyDirection;
  EXPECT_GT(modal, 0.95 * everyDirection) << "modal " << modal << " s, every direction " << everyDirection << " s";
  EXPECT_LT(modal, 1.02 * everyDirection) << "modal " << modal << " s, every direction " << everyDirection << " s";
  const double symplectic = studies::sceneStepStableDt(allLabs(), ball, "symplectic_euler");
  EXPECT_LT(modal, 0.5 * symplectic) << "the wobble is soft: symplectic Euler, set by the stiffest modes, goes far higher";
}

// ---- the ball on the floor: the contact's damper lowers the limit where the ball touches ---------
// The limit belongs to a state. In flight (no gravity, gas in from the start) symplectic Euler's
// is 1.78 ms; resting on the floor 1.47 ms: each vertex on the floor has the contact's damper on
// top of its springs' (c / m = 0.5 N s/m x 642 / kg = 321 /s), and symplectic Euler's rule
// w^2 dt^2 + 2 gamma dt < 4 takes every bit of damping off its step. Without that damper the
// floor changes little (its spring, k / m = 3.2e5 /s^2, is softer than the springs' modes).
// The shipped ball, dropped from 1 m, is predicted where it comes to rest: the settling follows
// its flight (0.45 s) and its landing, as a plain run does (the oracle: symplectic Euler at 1 ms
// for 12 s, the ball bouncing to rest; its limit there). It was predicted in the air, where the
// settling's budget ran out (1.78 ms), and a run at 0.97 times that was stopped in its first
// squash. The runs agree with the rest's limit: 0.97 times survives, and the chart's bisection,
// its trials past the limit held to the rest check, measures it.
TEST(BallOnTheFloor, TheContactsDamperLowersTheLimitWhereTheBallTouches) {
  const SceneDocument inFlight = inflatedBall(30, 3);
  SceneDocument onFloor = shippedScene("softbody_ball.json");
  onFloor.set("softbody.center=[0,0.5,0]");
  onFloor.set("softbody.gas.inflation_time=0");
  SceneDocument onFloorUndamped = onFloor;
  onFloorUndamped.set("softbody.contact.damping=0");
  const double flying = studies::sceneStepStableDt(allLabs(), inFlight, "symplectic_euler");
  const double resting = studies::sceneStepStableDt(allLabs(), onFloor, "symplectic_euler");
  const double restingUndamped = studies::sceneStepStableDt(allLabs(), onFloorUndamped, "symplectic_euler");
  EXPECT_LT(resting, 0.92 * flying) << "on the floor " << resting << " s, in flight " << flying << " s";
  EXPECT_NEAR(restingUndamped / flying, 1.0, 0.015) << "the floor without its damper: " << restingUndamped << " s";

  const SceneDocument dropped = shippedScene("softbody_ball.json");
  LoadedScene rested = allLabs().loadScene(dropped);
  while (rested.sim->state.time < 12.0) rested.sim->operate(1e-3);
  ASSERT_LT(rested.sim->energies().kinetic, 0.1) << "the oracle's run has not come to rest";
  LoadedScene probe = allLabs().loadScene(dropped);
  StepStabilityOptions atRest;
  atRest.at = rested.sim->state;
  const double oracle = stepStableDt(*probe.sim, atRest);
  const double predicted = studies::sceneStepStableDt(allLabs(), dropped, "symplectic_euler");
  EXPECT_NEAR(predicted / oracle, 1.0, 0.02) << "predicted " << predicted << " s, at the plain run's rest " << oracle << " s";
  EXPECT_NEAR(predicted / resting, 1.0, 0.02) << "dropped " << predicted << " s, placed on the floor " << resting << " s";
  const studies::RunResult below = trialAt(dropped, "symplectic_euler", predicted, 0.97);
  EXPECT_TRUE(below.stable) << "0.97 x " << predicted << " s: " << below.failure;
  // Past the limit the floor caps the growing mode, and the rest check sees it (the run's own
  // check lets 1.03 times the limit run to the end): the chart measures the limit.
  studies::StabilityOptions o = chartRow("symplectic_euler");
  const studies::CriticalDt m = studies::stability(allLabs(), dropped, o).methods.at(0);
  EXPECT_NEAR(m.measured / m.predicted, 1.0, 0.03) << m.measured << " s measured, " << m.predicted << " s predicted";
}

// ---- the ball on the floor: the wobble only the air and the floor's damper damp -------------------
// On the floor the ball's sideways wobble (the coarse ball: 108 rad/s, damping ratio 0.011: the
// air and the floor's damper on the few masses that touch) is lightly damped, and explicit
// Euler's limit on it, gamma / w^2, is its limit. The modal directions rank the modes by their ratio w^2 / gamma, starting from the
// stiffest mode's: the first Lanczos run's top is set by the stiffness, and on the floor it
// missed the wobble (1.0 ms against 0.21 ms with every direction); the second run, at the largest
// ratio the first found, holds it. The oracle is every direction (the dense Jacobian of the
// step, 972 coordinates). On the scene's ball (642 masses, the whole Jacobian of 3852
// coordinates computed once outside the tests) the two runs give explicit Euler 0.058 ms and the
// midpoint rule 1.78 ms against 0.054 and 1.75 ms; one run gave 0.94 and 2.71 ms.
TEST(BallOnTheFloor, ExplicitEulerFailsFirstOnTheWobbleTheFloorLeavesToTheAir) {
  SceneDocument ball = shippedScene("softbody_ball.json");
  ball.set("softbody.mesh.subdivisions=2");
  const double everyDirection = explicitEulerLimit(ball, 100000);
  const double modal = explicitEulerLimit(ball, 0);
  ASSERT_TRUE(std::isfinite(everyDirection) && everyDirection > 0.0) << everyDirection;
  EXPECT_NEAR(modal / everyDirection, 1.0, 0.08) << "modal " << modal << " s, every direction " << everyDirection << " s";
}

// ---- a dropped body: linearised at its rest on what it fell on, not at its impact ------------------
// The cube (26 masses) is pumped round over 0.3 s while it drops 1 m on to the floor. The first
// peak of its kinetic energy is the impact (4.6 J, nearly all of it the centre of mass's fall),
// where it is squashed for a moment: linearised there (velocities zeroed) the Verlets' limits
// were 2.7 and 1.6 ms, while their runs fail at 13.7 and 13.6 ms. The oracle here is the state
// a plain damped run reaches (symplectic Euler at 1 ms for 4 s, 1e-4 J left moving), not the
// settling's: the prediction is the limit there, and the runs agree with it.
TEST(DroppedCube, IsLinearisedAtItsRestOnTheFloorNotAtItsImpact) {
  const SceneDocument cube = shippedScene("softbody_cube_asc.json");
  LoadedScene rested = allLabs().loadScene(cube);
  while (rested.sim->state.time < 4.0) rested.sim->operate(1e-3);
  ASSERT_LT(rested.sim->energies().kinetic, 1e-3) << "the oracle's run has not come to rest";
  for (const std::string method : {"velocity_verlet", "midpoint"}) {
    LoadedScene probe = allLabs().loadScene(cube);
    probe.sim->setIntegrator(allLabs().makeIntegrator(method));
    StepStabilityOptions atRest;
    atRest.at = rested.sim->state;
    const double oracle = stepStableDt(*probe.sim, atRest);
    const double predicted = studies::sceneStepStableDt(allLabs(), cube, method);
    EXPECT_NEAR(predicted / oracle, 1.0, 0.02) << method << ": predicted " << predicted << " s, at rest " << oracle << " s";
  }
  expectStableBelowAndReportedAbove(cube, "velocity_verlet");
}

// Explicit Euler on the resting cube: past its limit a mode at its own frequency grows until
// the floor holds it (gamma / w^2 < dt), not the every-step reversal of detector 5. At 1.03 times
// the limit a corner keeps moving (0.08 J held where the run at half the limit held 1.3e-3 J
// at 3.4 s, and comes to rest), and the runs between 1.03 and 1.11 times went to the end (the
// chart measured 1.111 times). Detector 6 sees the motion held.
TEST(CappedInstability, ExplicitEulerOnTheRestingCubeIsHeldMotionNotReversal) {
  const studies::RunResult above = expectStableBelowAndReportedAbove(shippedScene("softbody_cube_asc.json"), "explicit_euler");
  EXPECT_NE(above.failure.find("held motion"), std::string::npos) << above.failure;
}

// ---- the hanging cloth: an instability that saturates --------------------------------------------
// The stability chart's 32 x 32 cloth. Just past symplectic Euler's limit its stiff modes grow,
// the springs' nonlinearity stops them within 0.04 s, and the cloth then hangs calmly, having
// gained energy from nothing (0.014 J at 1.07 times the limit). Passivity must see that gain:
// it did not while the allowance's floor was 1e-4 of the energy scale (0.054 J here), and the
// chart's measured limit stood 7.6 % above the prediction.
TEST(ClothAtTheLimit, SurvivesJustBelowAndIsStoppedJustAbove) {
  SceneDocument cloth = shippedScene("net_hanging.json");
  cloth.set("net.resolution=32");
  cloth.set("net.stretch_limit.enabled=false");
  expectStableBelowAndReportedAbove(cloth, "symplectic_euler");
}

// ---- wind: a scene that puts energy in ----------------------------------------------------------
// The flag as shipped (8 m/s relative wind, stretch limiting on). Past symplectic Euler's limit
// its springs flip and the flag turns to noise held together by the stretch limit, at bounded
// energy (63 J at 3 times the limit, 0.13 J when stable). Passivity did not apply while the
// wind blew, and the chart measured no limit at all; it now counts the wind's work
// (Simulation::sourcePower) and holds the rest of the energy to passivity.
TEST(FlagInTheWind, SymplecticEulerPastItsLimitIsStoppedThoughTheWindPutsEnergyIn) {
  const studies::RunResult above = expectStableBelowAndReportedAbove(shippedScene("net_flag.json"), "symplectic_euler");
  EXPECT_NE(above.failure.find("less the work of the scene's energy sources"), std::string::npos) << above.failure;
}

// The wind's work, as the net counts it, against a closed form: the flag unpinned, without
// gravity, in a wind along its normal. Its masses (areal density times a third of the area
// around each) and the wind's force (the same area) give every mass the same acceleration
// (drag / density) (w - v): the flag flies off flat, its springs untouched, at
// v(t) = w (1 - exp(-t drag / density)). The wind's work is then all its kinetic energy.
TEST(FlagInTheWind, TheWindsWorkIsTheKineticEnergyOfAFlagItCarriesOff) {
  SceneDocument flag = shippedScene("net_flag.json");
  for (const char* s : {"net.pinned=[]", "gravity=[0,0,0]", "net.wind.direction=[0,0,1]"}) flag.set(s);
  LoadedScene loaded = allLabs().loadScene(flag);
  Simulation& sim = *loaded.sim;
  sim.setIntegrator(allLabs().makeIntegrator("rk4"));
  const double dt = 2.5e-4;  // below RK4's limit on the flag's springs (0.9 ms): round-off stays put
  for (int k = 0; k < 2000; ++k) sim.operate(dt);
  const auto& net = flag.json.at("net");
  const double density = net.at("areal_density").get<double>(), drag = net.at("wind").at("drag").get<double>();
  const double w = net.at("wind").at("strength").get<double>();
  const double mass = density * net.at("width").get<double>() * net.at("height").get<double>();
  const double v = w * (1.0 - std::exp(-sim.state.time * drag / density));
  const double kinetic = 0.5 * mass * v * v;
  EXPECT_NEAR(sim.energies().kinetic / kinetic, 1.0, 1e-6) << "closed form " << kinetic << " J";
  EXPECT_NEAR(sim.sourceWork() / kinetic, 1.0, 1e-6) << "the wind's work " << sim.sourceWork() << " J";
  EXPECT_NEAR(sim.energyBalance(), 0.0, 1e-6 * kinetic) << "the total energy less the wind's work";
}

// ---- a radius that does not rise with dt: position Verlet on the trampoline --------------------
// Position Verlet and symplectic Euler are one map on positions and velocities (x' = 2 x - x_prev
// + h^2 a with v = (x - x_prev) / h), so their limits agree; symplectic Euler's is probed on its
// own step, position Verlet's through its history (two-step runs), whose Ritz estimate on the
// trampoline (pinned edges, stretch limit, wind) dips below 1 again at the first guess 2 / w_max
// (0.93 at 2.2 ms, 5.3 at 1 ms). Growing the bracket from there found 4.6 ms.
void expectPositionVerletsLimitIsSymplecticEulers(const SceneDocument& scene) {
  const double twin = studies::sceneStepStableDt(allLabs(), scene, "symplectic_euler");
  const double verlet = studies::sceneStepStableDt(allLabs(), scene, "position_verlet");
  EXPECT_NEAR(verlet / twin, 1.0, 0.01) << "symplectic Euler " << twin << " s, position Verlet " << verlet << " s";
}

TEST(TrampolineLimit, PositionVerletAgreesWithSymplecticEulerItsTwin) {
  expectPositionVerletsLimitIsSymplecticEulers(shippedScene("net_trampoline.json"));
}

// ---- velocity Verlet after a correction: the forces where the masses are ----------------------
// A stretch limit, a contact or the user moves masses between steps. Velocity Verlet kept the
// accelerations of the positions before that move for its next step (on the trampoline, whose
// tethers act every step, its runs failed at 0.74 times the prediction). The oracle: the mass on
// its undamped spring moved by hand between two steps is stepped exactly as a fresh velocity
// Verlet steps it from the moved state (without damping the half-kicked velocity its kept
// forces saw does not matter).
TEST(VelocityVerletAfterACorrection, StepsTheMovedStateWithItsOwnForces) {
  const SceneDocument scene = shippedScene("mass_on_spring.json");
  LoadedScene kept = allLabs().loadScene(scene), fresh = allLabs().loadScene(scene);
  kept.sim->setIntegrator(allLabs().makeIntegrator("velocity_verlet"));
  fresh.sim->setIntegrator(allLabs().makeIntegrator("velocity_verlet"));
  const double dt = 0.01;
  kept.sim->operate(dt);
  kept.sim->state.pos[1].y() -= 0.05;  // 5 cm further down: the spring pulls 5 N harder
  fresh.sim->state = kept.sim->state;
  kept.sim->operate(dt);
  fresh.sim->operate(dt);
  EXPECT_NEAR(kept.sim->state.pos[1].y(), fresh.sim->state.pos[1].y(), 1e-12);
  EXPECT_NEAR(kept.sim->state.vel[1].y(), fresh.sim->state.vel[1].y(), 1e-12);
}

// The same fix where it showed: the trampoline's tethers and stretch limit act after every step,
// and velocity Verlet's runs failed at 0.74 times the prediction; now 0.97 / 1.03.
TEST(TrampolineLimit, VelocityVerletSurvivesJustBelowAndIsStoppedJustAbove) {
  expectStableBelowAndReportedAbove(shippedScene("net_trampoline.json"), "velocity_verlet");
}

// ---- a pump: the 2D ring, inflated over its first second ------------------------------------------
// The settling stopped at the first peak of the kinetic energy, 0.3 s into the pump's second,
// where the gas is still rising and every method that takes a trial state (velocity Verlet's
// half kick, the midpoint rule's stage) sees a face it starts to push out: unstable physics at
// any dt. Linearised there, velocity Verlet's limit was 0.051 s and the midpoint rule had none;
// the runs, living with the inflated ring, fail at 0.071 s and 0.092 s. The settling now goes
// on until the pump is done, and past the ring's impact on the floor (2.6 s) to its rest there
// (DroppedCube): velocity Verlet's limit 0.0698 s, the runs' 0.0708 s. The midpoint rule's at
// that rest is 0.0124 s; the ring takes some 400 s to come to rest, and past the limit its
// motion is then held (detector 6), where the energy detectors let it through to 0.0174 s.
TEST(PumpedRing, TheLimitIsTheInflatedRingsNotThePumpsStart) {
  for (const char* integrator : {"velocity_verlet", "midpoint"}) {
    expectStableBelowAndReportedAbove(shippedScene("softbody_ring_2d.json"), integrator);
  }
}

// ---- a capped instability: the cloth dropped on the sphere ----------------------------------------
// Past the limit a light free corner grows until the stretch limit pulls it back; it then
// jitters (25 m/s at 1.03 times symplectic Euler's limit) while the total energy falls, and the
// energy detectors passed it up to 1.09 times the limit (velocity Verlet 1.21). Detector 5
// sees the motion that turns back every step.
TEST(CappedInstability, TheDroppedClothSurvivesJustBelowAndIsStoppedByItsJitterJustAbove) {
  for (const char* integrator : {"symplectic_euler", "velocity_verlet"}) {
    const studies::RunResult above = expectStableBelowAndReportedAbove(shippedScene("net_sphere_drop.json"), integrator);
    EXPECT_NE(above.failure.find("capped instability"), std::string::npos) << integrator << ": " << above.failure;
  }
}

// The midpoint rule on the dropped cloth: past its limit a run may miss its instability by luck
// (the scene's contacts make it chaotic: at 1.09 times the limit one run fails by passivity at
// 0.27 s and a run at a dt 1.5e-9 larger runs to the end), and the bisection, trusting one run,
// measured 1.09 times the prediction. A surviving trial counts only where its twin at a dt one
// part in a million smaller survives too.
TEST(CriticalDt, AStableVerdictDoesNotHangOnRoundOff) {
  const SceneDocument dropped = shippedScene("net_sphere_drop.json");
  const double predicted = studies::sceneStepStableDt(allLabs(), dropped, "midpoint");
  ASSERT_TRUE(std::isfinite(predicted) && predicted > 0.0) << predicted;
  const double w = studies::sceneLanczosEstimate(allLabs(), dropped);
  const double duration =
      studies::stabilityTrialDuration(allLabs(), dropped, "midpoint", predicted, studies::defaultStabilityDuration(w));
  const studies::CriticalDt m =
      studies::criticalDt(allLabs(), dropped, "midpoint", duration, predicted, 0.005, 4000000, 1.0, 0.5 * predicted);
  EXPECT_NEAR(m.measured / predicted, 1.0, 0.05) << "measured " << m.measured << " s, predicted " << predicted << " s";
}

// Velocity Verlet on the slope: past its limit the cloth's corner under the sphere jitters by
// 5e-3 m/s a step for seconds, held by the contact. The run at half the limit reversed by more
// than a 64th of that early on (2e-4 m/s at 1 s, settling), and by 2e-7 m/s at 4 s; held to its
// largest, the jitter went through (the chart measured 1.12 times the limit). Held to the swing
// run at the same time (ReversalProfile), it is stopped, and 0.97 times the limit is not.
TEST(CappedInstability, TheSlopesCornerUnderVelocityVerletIsHeldToTheStableRunAtTheSameTime) {
  const studies::RunResult above =
      expectStableBelowAndReportedAbove(shippedScene("net_sphere_slope_weak_wind.json"), "velocity_verlet");
  EXPECT_NE(above.failure.find("capped instability"), std::string::npos) << above.failure;
  EXPECT_NE(above.failure.find("near t ="), std::string::npos) << above.failure;
}

// The same without a swing run, as `sim` and the viewer run it: the detector holds its floor
// alone and counts only past the step's limit, so 0.97 times the limit runs to the end and 1.03
// times is stopped (the slope's corner from step 215, 0.35 s).
TEST(CappedInstability, WithoutASwingRunTheSlopesCornerIsStoppedJustAboveTheLimitOnly) {
  const SceneDocument slope = shippedScene("net_sphere_slope_weak_wind.json");
  const double predicted = studies::sceneStepStableDt(allLabs(), slope, "symplectic_euler");
  for (const double factor : {0.97, 1.03}) {
    const double dt = factor * predicted;
    studies::RunSpec spec{slope, "symplectic_euler", dt, std::lround(std::ceil(2.0 / dt)), 1};
    spec.keepPositions = false;
    const studies::RunResult run = studies::runScene(allLabs(), spec);
    if (factor < 1.0) {
      EXPECT_TRUE(run.stable) << run.failure;
    } else {
      EXPECT_FALSE(run.stable) << "1.03 x " << predicted << " s must be reported";
      EXPECT_NE(run.failure.find("capped instability"), std::string::npos) << run.failure;
      EXPECT_NE(run.failure.find("no swing was measured"), std::string::npos) << run.failure;
    }
  }
}

// ---- The integrator's own swing: its rise from the low, not from the start ------------------------
// The flag under explicit Euler: the dampers take energy out early on faster than the step swings
// it up, so at half the limit its energy never rises above its start (the swing held to the start
// was 6e-6 J), while at 0.8 times the limit it rose 4.7e-4 J from its low when the stretch limit
// engaged at 0.1 s, gave it back at once and ran calmly to the end; passivity stopped it (the
// chart measured 0.75 times the limit). Held to the rise from the swing run's low (1.3e-4 J), 0.8
// and 0.9 times run to the end. Just below the limit the flag still fails: at 0.97 times its
// flapping passes a state whose own limit is lower (0.966 times the settled one, at 0.5 s), and
// the energy then rises by joules.
TEST(EnergySwing, ADampedFlagIsAllowedItsStepsRiseFromTheLowNotFromTheStart) {
  const SceneDocument flag = shippedScene("net_flag.json");
  const double predicted = studies::sceneStepStableDt(allLabs(), flag, "explicit_euler");
  ASSERT_TRUE(std::isfinite(predicted) && predicted > 0.0) << predicted;
  for (const double factor : {0.8, 0.9}) {
    const studies::RunResult run = trialAt(flag, "explicit_euler", predicted, factor);
    EXPECT_TRUE(run.stable) << factor << " x " << predicted << " s: " << run.failure;
  }
  const studies::RunResult above = trialAt(flag, "explicit_euler", predicted, 1.03);
  EXPECT_FALSE(above.stable) << "1.03 x " << predicted << " s must be reported";
}

// ---- XPBD on the rope: a limit, and passivity where a swing run measured what it rests holding ----
// With a fixed number of iterations XPBD's step has a limit on the rope (34 ms). It rests away
// from the springs' equilibrium, so without a swing run passivity does not hold it; the chart's
// trials measure the swing at half the limit and do. Past the limit the rope's energy swings
// hundreds of joules above its start, under the runaway factor: without passivity the chart
// measured 1.40 times the prediction, with it 1.21.
TEST(XpbdOnTheRope, PastItsLimitIsStoppedByPassivityWhereASwingWasMeasured) {
  const SceneDocument rope = shippedScene("rope.json");
  const double predicted = studies::sceneStepStableDt(allLabs(), rope, "xpbd");
  ASSERT_TRUE(std::isfinite(predicted) && predicted > 0.0) << predicted;
  const studies::RunResult below = trialAt(rope, "xpbd", predicted, 0.97);
  EXPECT_TRUE(below.stable) << below.failure;
  const studies::RunResult above = trialAt(rope, "xpbd", predicted, 1.3);
  EXPECT_FALSE(above.stable) << "1.3 x " << predicted << " s must be reported";
  EXPECT_NE(above.failure.find("passivity"), std::string::npos) << above.failure;
}

// ---- position Verlet on projected contacts: the ball under the user's sphere ---------------------
// The contacts set the velocities of the masses they touch after each step. Position Verlet's
// wrapper kept its own record of the last positions as history and ignored those velocities, so
// its step was not a map of the state it leaves (positions and velocities): the two-step probe
// measured a radius of 1.25 at 0.8 ms and the prediction was 45.5 ms, where runs fail at 1.97 ms.
// Restarting the history of a mass the contact touched (x - dt v) makes the step the same map
// as symplectic Euler's, and the limits agree.
TEST(BallUnderTheUsersSphere, PositionVerletAgreesWithSymplecticEulerItsTwin) {
  expectPositionVerletsLimitIsSymplecticEulers(shippedScene("softbody_user_sphere.json"));
}

// ---- a step that is not smooth: explicit Euler on a ball resting on projected obstacles ----------
// Projection contacts respond only to a mass strictly inside: a mass the settling left on the
// surface at rest stays there in explicit Euler's first step (x' = x + dt v), and a perturbation
// into the obstacle switches the contact's absorption on. The finite differences then measure a
// jump, not a derivative: the "radius" scales with dt over the perturbation, and the limit read
// from it was "unlimited". The oracle: the same radius with a perturbation 100 times smaller,
// which a derivative would match. The limit holds the masses the contacts hold one-sidedly (a
// fallen body at rest on what it hit) and is computable again: sim's runs of 30 s at 0.97 and
// 1.03 times it end in exit 0 and 4 (studies.sim_at_the_limit_of_bodies_resting_on_contacts);
// before, the limit was NaN. Symplectic Euler's first step moves the mass into the obstacle in
// both runs (the contact acts in both), and its limit needs no holding.
TEST(BallUnderTheUsersSphere, ExplicitEulersStepIsNotSmoothOnItsContactsAndItsLimitHoldsThem) {
  const SceneDocument ball = shippedScene("softbody_user_sphere.json");
  LoadedScene loaded = allLabs().loadScene(ball);
  loaded.sim->setIntegrator(allLabs().makeIntegrator("explicit_euler"));
  StepStabilityOptions coarse;
  coarse.holdRestingContacts = false;  // the finite differences as they come
  StepStabilityOptions fine = coarse;
  fine.relativePerturbation = coarse.relativePerturbation / 100.0;
  const double r = stepSpectralRadius(*loaded.sim, 1e-4, coarse).radius;
  const double rFine = stepSpectralRadius(*loaded.sim, 1e-4, fine).radius;
  EXPECT_GT(rFine, 10.0 * r) << "a jump: the radius grows as the perturbation shrinks (" << r << ", " << rFine << ")";
  const double held = studies::sceneStepStableDt(allLabs(), ball, "explicit_euler");
  const double symplectic = studies::sceneStepStableDt(allLabs(), ball, "symplectic_euler");
  EXPECT_TRUE(std::isfinite(symplectic) && symplectic > 0.0) << symplectic;
  EXPECT_TRUE(std::isfinite(held) && held > 0.0 && held < symplectic) << held;
  // The radius as the limit sees it (the contacts held) brackets the limit as a smooth step's does.
  const double slack = StepStabilityOptions{}.radiusSlack;
  EXPECT_LE(stepSpectralRadius(*loaded.sim, 0.97 * held).radius, 1.0 + slack) << "limit " << held << " s";
  EXPECT_GT(stepSpectralRadius(*loaded.sim, 1.03 * held).radius, 1.0 + slack) << "limit " << held << " s";
}

// The chart's trial lasts until the growth at 1.03 times the limit would show, read from the
// step's radius there (stabilityTrialDuration). On the ball resting under the user's sphere that
// growth is a slow wobble on the floor. Read without the contacts held, the radius was the
// jump's (not smooth), and the trial fell back to its floor of 3 s, which the run at 1.03 times
// survives: the chart measured 1.059 times the limit here and 1.238 on the squeezed ball. The
// oracle: the run at 1.03 times the limit, as the chart's trial runs it (held to the swing at
// half the limit), for 20 s; the trial must last until that run is stopped (at 0.97 times it
// runs to its end: studies.sim_at_the_limit_of_bodies_resting_on_contacts, 30 s).
TEST(BallUnderTheUsersSphere, TheChartsTrialOfExplicitEulerLastsUntilTheWobbleOnTheFloorShows) {
  const SceneDocument ball = shippedScene("softbody_user_sphere.json");
  const double predicted = studies::sceneStepStableDt(allLabs(), ball, "explicit_euler");
  ASSERT_TRUE(std::isfinite(predicted) && predicted > 0.0) << predicted;
  const double floor = studies::defaultStabilityDuration(studies::sceneLanczosEstimate(allLabs(), ball));
  const double duration = studies::stabilityTrialDuration(allLabs(), ball, "explicit_euler", predicted, floor);
  const double dt = 1.03 * predicted;
  studies::RunSpec spec{ball, "explicit_euler", dt, std::lround(20.0 / dt), 1};
  spec.keepPositions = false;
  spec.swingDt = 0.5 * predicted;
  const studies::RunResult above = studies::runScene(allLabs(), spec);
  ASSERT_FALSE(above.stable) << "1.03 times " << predicted << " s runs 20 s";
  const double stoppedAt = static_cast<double>(above.steps) * dt;
  EXPECT_GT(stoppedAt, floor) << "the trial's floor alone would miss it: " << above.failure;
  EXPECT_GE(duration, stoppedAt) << "stopped at " << stoppedAt << " s: " << above.failure;
}

// ---- a light fabric: damping, not stiffness, sets the limit -----------------------------------
TEST(FabricLimit, IsFarBelow2OverWmaxWhenTheStiffestModesAreOverdamped) {
  SceneDocument cloth = shippedScene("net_hanging.json");
  cloth.set("net.resolution=16");
  cloth.set("net.stretch_limit.enabled=false");
  const double w = studies::sceneLanczosEstimate(allLabs(), cloth);
  const double predicted = studies::sceneStepStableDt(allLabs(), cloth, "symplectic_euler");
  EXPECT_LT(predicted, 0.8 * 2.0 / w) << "structural kd / m dominates the stiffest modes";
}

// ---- the rest and the landing -----------------------------------------------------------------
// The smallest limit of `integrator` linearised at states of its own run from the scene's start
// at runDt (StepStabilityOptions::at): at t = from, from + every, ..., from + count x every.
double smallestLimitAlongRun(const SceneDocument& scene, const std::string& integrator, double runDt, double from,
                             double every, int count) {
  LoadedScene run = allLabs().loadScene(scene);
  run.sim->setIntegrator(allLabs().makeIntegrator(integrator));
  double smallest = INFINITY;
  for (int k = 0; k <= count; ++k) {
    while (run.sim->state.time < from + every * k - 1e-9) run.sim->operate(runDt);
    LoadedScene probe = allLabs().loadScene(scene);
    probe.sim->setIntegrator(allLabs().makeIntegrator(integrator));
    StepStabilityOptions o;
    o.at = run.sim->state;
    smallest = std::min(smallest, stepStableDt(*probe.sim, o));
  }
  return smallest;
}

// The prediction is a claim about the scene's rest: the step linearised where it settles. A run
// from the scene's start may pass through a stiffer state first. The cloth dropped on the sphere
// and the slope in a weak wind, under the midpoint rule: from its start, 0.97 times the limit
// blows up at t = 0.45 s, after the landing, where a calm run (0.5 ms) linearises to 1.87 ms at
// t = 0.34 s against 2.02 ms at rest (the chart measures 0.968 times the prediction from the
// start). The oracle for the claim is a run from the rest: the method's own run at half the
// limit for 3 s, then 3 s at 0.97 times the limit survive and 1.03 times is reported. From the
// start the message names the landing: dt is past the limit of a state stiffer than the rest;
// the oracle for that is the calm run's landing, linearised below 0.97 times the rest's limit.
TEST(LandingCloth, MidpointRuleHoldsItsLimitFromRestAndFailsEarlierInTheLanding) {
  const SceneDocument slope = shippedScene("net_sphere_slope_weak_wind.json");
  const double predicted = studies::sceneStepStableDt(allLabs(), slope, "midpoint");
  ASSERT_TRUE(std::isfinite(predicted) && predicted > 0.0) << predicted;
  // The blow-up's message, or empty when the run reached t = until.
  auto run = [&](double restUntil, double factor, double until) -> std::string {
    LoadedScene loaded = allLabs().loadScene(slope);
    Simulation& sim = *loaded.sim;
    sim.setIntegrator(allLabs().makeIntegrator("midpoint"));
    sim.setBlowUpCheck(false);
    while (sim.state.time < restUntil) sim.operate(0.5 * predicted);
    sim.setBlowUpCheck(true);
    try {
      while (sim.state.time < until) sim.operate(factor * predicted);
    } catch (const BlowUp& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(run(3.0, 0.97, 6.0), "") << "from rest, 0.97 x " << predicted << " s";
  EXPECT_NE(run(3.0, 1.03, 6.0), "") << "from rest, 1.03 x " << predicted << " s must be reported";
  const std::string landing = run(0.0, 0.97, 3.0);
  EXPECT_NE(landing.find("in a state stiffer than the rest"), std::string::npos) << landing;
  // The landing of a calm run (0.5 ms, a quarter of the limit), linearised every 10 ms.
  const double stiffest = smallestLimitAlongRun(slope, "midpoint", 5e-4, 0.30, 0.01, 10);
  EXPECT_LT(stiffest, 0.97 * predicted) << "the landing's limit, against " << predicted << " s at rest";
}

// The chart's trials from the rest (StabilityOptions::fromRest): each runs the method at half
// its limit for 3 s first. From the start the bisection finds the landing (0.968 times the
// prediction); from the rest it finds the prediction. The chart's stiffest state on the way (a
// calm run up to where the smallest failing trial was stopped) names the landing from the start,
// and the measured limit lies between its limit and the rest's; from the rest the calm run looks
// only past the rest's start (it passes through the landing too) and finds no state more than 2 %
// stiffer.
TEST(LandingCloth, TheChartFromRestMeasuresThePredictionAndFromTheStartTheLanding) {
  const SceneDocument slope = shippedScene("net_sphere_slope_weak_wind.json");
  studies::StabilityOptions o = chartRow("midpoint");
  o.stiffestOnTheWay = true;
  const studies::CriticalDt fromStart = studies::stability(allLabs(), slope, o).methods.at(0);
  o.fromRest = 3.0;
  const studies::CriticalDt fromRest = studies::stability(allLabs(), slope, o).methods.at(0);
  ASSERT_TRUE(std::isfinite(fromRest.predicted) && fromRest.predicted > 0.0) << fromRest.predicted;
  EXPECT_NEAR(fromRest.measured / fromRest.predicted, 1.0, 0.02) << fromRest.measured << " s from rest";
  EXPECT_LT(fromStart.measured / fromStart.predicted, 0.975) << fromStart.measured << " s from the start";
  EXPECT_LT(fromStart.stiffestOnTheWay, 0.975 * fromStart.predicted) << "on the way, at t = " << fromStart.stiffestOnTheWayAt << " s";
  // The trials fail between the landing's frozen limit and the rest's (1.857, 1.953, 2.018 ms):
  // the friction there caps part of what the frozen step grows.
  EXPECT_LT(fromStart.stiffestOnTheWay, fromStart.measured) << fromStart.stiffestOnTheWay << " s on the way";
  EXPECT_GT(fromStart.stiffestOnTheWayAt, 0.25) << "the landing, not the fall";
  EXPECT_LT(fromStart.stiffestOnTheWayAt, fromStart.failedAt) << "a state before the trial failed";
  // In the weak wind the rest flutters: its states linearise within 2 % of the settled one.
  EXPECT_NEAR(fromRest.stiffestOnTheWay / fromRest.predicted, 1.0, 0.02) << "from the rest, at t = " << fromRest.stiffestOnTheWayAt << " s";
  EXPECT_FALSE(fromRest.stiffestOnTheWayAt < o.fromRest) << "the landing, where the trials from the rest do not go";
}

// ---- the trampoline's catch: a stiffer state on the way, in its first 60 ms ----------------
// The trampoline in the wind under explicit Euler measures 0.746 times its limit at rest
// (0.318 ms): the wind accelerates the net until, at t = 0.046-0.054 s, the tethers and the
// stretch limit catch it, and there the step (the corrections included) linearises to 0.242 ms
// on a fine run (2e-5 s). Runs from the start hold to that: 0.93 times it lasts, 0.8 times the
// rest's limit (1.05 times it) blows up, and the message names a state stiffer than the rest,
// with a dt below it, found on a run from the start at half the dt (where the run was stopped
// the state is the blow-up's own: linearised, 0.094 ms). Without the stretch limit there is no
// catch, and 0.8 times the rest's limit lasts.
TEST(TrampolineInTheWind, ExplicitEulerFailsBelowItsRestLimitWhereTheStretchLimitCatchesTheNet) {
  const SceneDocument trampoline = shippedScene("net_trampoline.json");
  const double rest = studies::sceneStepStableDt(allLabs(), trampoline, "explicit_euler");
  ASSERT_TRUE(std::isfinite(rest) && rest > 0.0) << rest;
  // The catch: a fine run linearised every 2 ms from 40 to 60 ms.
  const double caught = smallestLimitAlongRun(trampoline, "explicit_euler", 2e-5, 0.040, 0.002, 10);
  EXPECT_LT(caught, 0.8 * rest) << "the catch's limit, against " << rest << " s at rest";
  // The blow-up's message, or empty when the run lasts 0.3 s from the start.
  auto run = [&](const SceneDocument& scene, double dt) -> std::string {
    LoadedScene loaded = allLabs().loadScene(scene);
    loaded.sim->setIntegrator(allLabs().makeIntegrator("explicit_euler"));
    try {
      while (loaded.sim->state.time < 0.3) loaded.sim->operate(dt);
    } catch (const BlowUp& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(run(trampoline, 0.93 * caught), "") << "0.93 x the catch's " << caught << " s";
  const std::string blown = run(trampoline, 0.8 * rest);
  EXPECT_NE(blown.find("in a state stiffer than the rest"), std::string::npos) << blown;
  EXPECT_NE(blown.find("a run from the start at half this dt"), std::string::npos) << blown;
  // The dt it gives to try is near the catch's limit (not 0.094 ms, the blown state's), and lasts.
  const std::size_t at = blown.find("try a dt below ");
  ASSERT_NE(at, std::string::npos) << blown;
  const double advised = std::stod(blown.substr(at + std::string("try a dt below ").size()));
  EXPECT_GT(advised, 0.8 * caught) << blown;
  EXPECT_EQ(run(trampoline, 0.99 * advised), "") << "the advised dt, " << advised << " s";
  SceneDocument unlimited = trampoline;
  unlimited.set("net.stretch_limit.enabled=false");
  EXPECT_EQ(run(unlimited, 0.8 * rest), "") << "without the stretch limit, 0.8 x " << rest << " s";
}

// The chart's row for it: the limit at rest is 0.318 ms and the bisection measures 0.75 times it;
// the stiffest state on the way (a calm run at half the rest's limit up to where the smallest
// failing trial was stopped, 128 states) is the catch, its limit within 5 % of the fine run's (the
// oracle: 11 states 2 ms apart on a run at 2e-5 s), and the measured limit within 5 % of that.
TEST(TrampolineInTheWind, TheChartFindsExplicitEulersFailureAtTheCatch) {
  const SceneDocument trampoline = shippedScene("net_trampoline.json");
  studies::StabilityOptions o = chartRow("explicit_euler");
  o.stiffestOnTheWay = true;
  const studies::CriticalDt row = studies::stability(allLabs(), trampoline, o).methods.at(0);
  ASSERT_TRUE(std::isfinite(row.predicted) && row.predicted > 0.0) << row.predicted;
  EXPECT_LT(row.measured, 0.8 * row.predicted) << row.measured << " s, against " << row.predicted << " s at rest";
  const double caught = smallestLimitAlongRun(trampoline, "explicit_euler", 2e-5, 0.040, 0.002, 10);
  EXPECT_NEAR(row.stiffestOnTheWay / caught, 1.0, 0.05) << row.stiffestOnTheWay << " s, the catch's " << caught << " s";
  EXPECT_NEAR(row.stiffestOnTheWayAt, 0.05, 0.006) << "the catch, at t = 0.046-0.054 s";
  EXPECT_NEAR(row.measured / row.stiffestOnTheWay, 1.0, 0.05) << row.measured << " s measured";
}

// ---- a frozen state's limit is not a prediction: the stretch limit caps what it grows ----------
// The hanging cloth falls from flat until the stretch limit catches it at t = 0.125-0.142 s. The
// step linearised at those states (a calm run at half explicit Euler's limit) grows a
// perturbation about twice per step at 0.95 times the limit at rest (its frozen limit there is
// 0.22-0.32 ms against 0.465 ms), for some 38 steps; yet a run from the start at 0.95 times that
// limit goes through the catch and lasts. Without the stretch limit the same states' radius stays
// below 1. The stretch limit's projection caps the stretch the frozen step would grow: where it
// acts, the smallest frozen limit on the way is far below what the runs survive (the chart's
// stiffest state on the way: 0.234 ms against a measured 0.450 ms), and is a diagnostic, not the
// limit.
TEST(HangingCloth, TheStretchLimitCapsWhatTheFrozenStepGrowsInTheCatch) {
  const SceneDocument hanging = shippedScene("net_hanging.json");
  const std::string method = "explicit_euler";
  const double rest = studies::sceneStepStableDt(allLabs(), hanging, method);
  ASSERT_TRUE(std::isfinite(rest) && rest > 0.0) << rest;
  // The step's radius at 0.95 times the rest's limit, linearised on a calm run at `times`.
  auto radii = [&](const SceneDocument& scene, std::vector<double> times) {
    LoadedScene run = allLabs().loadScene(scene);
    run.sim->setIntegrator(allLabs().makeIntegrator(method));
    std::vector<double> out;
    for (double t : times) {
      while (run.sim->state.time < t - 1e-9) run.sim->operate(0.5 * rest);
      LoadedScene probe = allLabs().loadScene(scene);
      probe.sim->setIntegrator(allLabs().makeIntegrator(method));
      StepStabilityOptions o;
      o.at = run.sim->state;
      out.push_back(stepSpectralRadius(*probe.sim, 0.95 * rest, o).radius);
    }
    return out;
  };
  const std::vector<double> caught = radii(hanging, {0.134, 0.136, 0.138, 0.140});
  for (double r : caught) EXPECT_GT(r, 1.5) << "in the catch, at 0.95 x " << rest << " s";
  SceneDocument unlimited = hanging;
  unlimited.set("net.stretch_limit.enabled=false");
  for (double r : radii(unlimited, {0.134, 0.140})) EXPECT_LT(r, 1.0) << "without the stretch limit";
  // The run at that dt through the catch, under its blow-up check.
  LoadedScene loaded = allLabs().loadScene(hanging);
  loaded.sim->setIntegrator(allLabs().makeIntegrator(method));
  EXPECT_NO_THROW(while (loaded.sim->state.time < 0.3) loaded.sim->operate(0.95 * rest))
      << "0.95 x " << rest << " s from the start";
}

// ---- a runaway the step does not explain: the message says so ---------------------------------
// The self-colliding cloth under RK4 blows up below its limit at rest (0.673 ms) by chance (runs
// of 1500 steps: 0.634, 0.637, 0.640, 0.645 ms blow up, 0.65 and 0.66 ms last): at 0.637 ms the
// fastest mass goes from 2.7 to 62 m/s in 15 ms from t = 0.365 s while the pair separations put
// energy in, and the step linearised at the run's own states on the way stays stable. The
// message's calm run clears every state, and it says the step is not the likely cause (the
// "every state" verdict), with no dt to try. The oracle: the run's own states at 0.30 and 0.36 s
// (check off), linearised, have limits above the dt.
TEST(SelfCollidingCloth, RungeKuttaRunsAwayWhereTheStepIsStableOnTheWayAndTheMessageSaysSo) {
  const SceneDocument cloth = shippedScene("net_self_collision.json");
  const std::string method = "rk4";
  const double rest = studies::sceneStepStableDt(allLabs(), cloth, method);
  ASSERT_NEAR(rest, 0.6727e-3, 0.01e-3) << "the chance below depends on the scene as measured";
  const double dt = 0.637e-3;
  std::string message;
  {
    LoadedScene loaded = allLabs().loadScene(cloth);
    loaded.sim->setIntegrator(allLabs().makeIntegrator(method));
    try {
      while (loaded.sim->state.time < 1.0) loaded.sim->operate(dt);
    } catch (const BlowUp& e) {
      message = e.what();
    }
  }
  ASSERT_NE(message, "") << "at " << dt << " s the run blew up at t = 0.398 s when measured";
  EXPECT_NE(message.find("at every state of a run from the start"), std::string::npos) << message;
  EXPECT_NE(message.find("the step is not the likely cause"), std::string::npos) << message;
  EXPECT_EQ(message.find("try a dt below"), std::string::npos) << message;
  LoadedScene run = allLabs().loadScene(cloth);
  run.sim->setIntegrator(allLabs().makeIntegrator(method));
  run.sim->setBlowUpCheck(false);
  for (double t : {0.30, 0.36}) {
    while (run.sim->state.time < t) run.sim->operate(dt);
    EXPECT_GT(stepLimitAt(*run.sim, run.sim->state), dt) << "the run's own state at t = " << run.sim->state.time;
  }
}

// ---- a trial that reaches the rest the prediction is about -------------------------------------
// Velocity Verlet's limit on the self-colliding cloth is its rest's on the floor (0.0367 ms, 8
// times below symplectic Euler's: a contact's correction in its hidden history), and there its
// step grows 1.1 times a step at 1.03 times that limit: 18 ms to grow by 1e20. A run from the
// start gets there only after its fall and fold: at 1.03 times the limit it is stopped at t =
// 1.05 s. The chart's trials lasted max(300 periods, 18 ms) = 0.73 s and measured 2.6 times the
// limit; now they count the growth from when the cloth comes to rest (restArrival: symplectic
// Euler's kinetic energy below a thousandth of its peak for good, 2.46 s), and 1.03 times the
// limit is reported within the trial (the chart's row: measured 1.00 times the limit).
TEST(SelfCollidingCloth, VelocityVerletsTrialLastsUntilTheClothRestsWhereItsLimitIs) {
  const SceneDocument cloth = shippedScene("net_self_collision.json");
  const std::string method = "velocity_verlet";
  const double predicted = studies::sceneStepStableDt(allLabs(), cloth, method);
  ASSERT_TRUE(std::isfinite(predicted) && predicted > 0.0) << predicted;
  const double w = studies::sceneLanczosEstimate(allLabs(), cloth);
  const double floor = studies::defaultStabilityDuration(w);
  // The chart's methods share the scene's arrival (SceneRestArrival: one fall, not one per
  // method): the trial asks for it once, and it is that run's whatever is asked later.
  studies::SceneRestArrival shared;
  const double trial = studies::stabilityTrialDuration(allLabs(), cloth, method, predicted, floor, nullptr, &shared);
  const double arrival = shared.get(allLabs(), cloth, floor);
  EXPECT_GT(arrival, 1.2) << "the cloth's fall and fold";
  EXPECT_LT(arrival, 3.0) << "the cloth at rest";
  EXPECT_GT(trial, arrival);
  EXPECT_EQ(shared.get(allLabs(), cloth, 0.5 * floor), arrival) << "run again, not shared";
  const studies::RunResult past = trialAt(cloth, method, predicted, 1.03, true, trial);
  EXPECT_FALSE(past.stable) << "1.03 x " << predicted << " s";
  EXPECT_GT(past.stoppedAt, floor) << "after the old trial's end: " << past.failure;
}

// ---- a mode that the floor caps: the rest check sees what the run's check allows ---------------
// The ball in the wind under velocity Verlet, past its limit: a step-alternating wobble of the
// masses on the floor sets in at the limit and the floor caps it (1.2e-3 m/s at 1.04 times the
// limit), within the 64 times the swing run's that the check allows, so the run from the start
// survives 1.03 times its limit (the chart measured 1.215 times before the rest check). The
// rest does not hold there and holds at 0.97 times the limit.
TEST(WindBall, VelocityVerletRestBreaksJustPastTheLimitWhereTheRunFromTheStartSurvives) {
  const SceneDocument ball = shippedScene("softbody_wind.json");
  const std::string method = "velocity_verlet";
  const double predicted = studies::sceneStepStableDt(allLabs(), ball, method);
  ASSERT_TRUE(predicted > 0.0 && std::isfinite(predicted)) << predicted;
  const double duration = 3.0;
  EXPECT_TRUE(trialAt(ball, method, predicted, 1.03).stable) << "the run's own check now sees it: the rest check "
                                                                  "is no longer what catches this row";
  auto growth = [&](double factor) {
    return studies::measureRestGrowth(allLabs(), ball, method, 1.0, factor * predicted, duration);
  };
  const studies::RestGrowth half = growth(0.5), below = growth(0.97), past = growth(1.03);
  EXPECT_TRUE(studies::restCheckApplies(half)) << half.growth;
  EXPECT_FALSE(studies::restBroken(below)) << below.growth;
  EXPECT_TRUE(studies::restBroken(past)) << past.growth;
}

// The verdict does not hang on the disturbance's direction: at 1.03 times the limit each of 60
// directions (seeds 1-60) breaks the rest alone, at 0.97 times each holds, and the check's
// growth is their median. Past the limit the capped wobble is a limit cycle that flips sign
// every step, and a disturbance sets its phase: where the moved run's wobble ends in step with
// the reference's the two stay close. Linearised where its settling stopped before it followed
// the ball's fall (1.445 ms), 9 of 300 directions did so at 1.03 times (449 times the disturbance,
// once 3.2 times), hence the median of three; at 1.01 times the present limit 4 of 120 do
// (22-994 times), and every three consecutive seeds' median breaks there.
TEST(WindBall, RestVerdictIsTheSameForEveryDirection) {
  const SceneDocument ball = shippedScene("softbody_wind.json");
  const std::string method = "velocity_verlet";
  const double predicted = studies::sceneStepStableDt(allLabs(), ball, method);
  ASSERT_TRUE(predicted > 0.0 && std::isfinite(predicted)) << predicted;
  const int directions = 60;
  for (const double factor : {0.97, 1.03}) {
    const studies::RestGrowth each =
        studies::measureRestGrowth(allLabs(), ball, method, 1.0, factor * predicted, 3.0, 1, directions);
    ASSERT_EQ(each.growths.size(), static_cast<std::size_t>(directions));
    for (int d = 0; d < directions; ++d) {
      const double g = each.growths[static_cast<std::size_t>(d)];
      if (factor < 1.0) EXPECT_LE(g, studies::kRestGrowthLimit) << "seed " << d + 1 << " at " << factor;
      else EXPECT_GT(g, studies::kRestGrowthLimit) << "seed " << d + 1 << " at " << factor;
    }
    std::vector<double> sorted = each.growths;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(each.growth, sorted[sorted.size() / 2]) << "the check's growth is the directions' median";
  }
}

// The chart's bisection, its trials past the limit held to the rest check, measures the wind
// ball's velocity Verlet within 3 % of the prediction (1.215 times without it).
TEST(WindBall, ChartMeasuresVelocityVerletAtItsPredictedLimit) {
  studies::StabilityOptions o = chartRow("velocity_verlet");
  const studies::CriticalDt m = studies::stability(allLabs(), shippedScene("softbody_wind.json"), o).methods.at(0);
  ASSERT_TRUE(std::isfinite(m.predicted) && m.predicted > 0.0) << m.predicted;
  EXPECT_NEAR(m.measured / m.predicted, 1.0, 0.03) << m.measured << " s measured, " << m.predicted << " s predicted";
}

// A flag in the wind never rests: at half its limit its own motion separates two runs a
// millimetre apart by far more than the rest check allows, so the check does not apply there
// (and cannot call the flag's flutter an instability).
TEST(WindFlag, IsNotHeldToTheRestCheck) {
  const SceneDocument flag = shippedScene("net_flag.json");
  const double predicted = studies::sceneStepStableDt(allLabs(), flag, "symplectic_euler");
  ASSERT_TRUE(predicted > 0.0 && std::isfinite(predicted)) << predicted;
  const studies::RestGrowth half =
      studies::measureRestGrowth(allLabs(), flag, "symplectic_euler", 1.0, 0.5 * predicted, 0.6);
  EXPECT_FALSE(studies::restCheckApplies(half)) << half.growth;
}

}  // namespace
}  // namespace springlab

namespace springlab {
namespace {
// ---- one radius instead of the limit: what `sim` asks before it runs ---------------------------
// `sim` takes dt as within the limit when the step's spectral radius at dt is at most 1 + the
// slack, and computes the limit (a bisection, ten radii) only when it is not. That shortcut is
// exact where the radius crosses 1 once, at the limit: just below it the radius is within the
// slack, just past it above. Held on the rope (the dense Jacobian), the inflated ball (the modal
// runs, pressure and floor) and the flag (wind, never at rest), each under a method whose limit a
// different mechanism sets.
struct RadiusCase {
  const char* scene;
  const char* method;
};
void PrintTo(const RadiusCase& c, std::ostream* os) { *os << c.scene << " " << c.method; }
class RadiusAtDt : public ::testing::TestWithParam<RadiusCase> {};
TEST_P(RadiusAtDt, IsWithinOneJustBelowTheLimitAndAboveItJustPast) {
  const RadiusCase c = GetParam();
  LoadedScene loaded = allLabs().loadScene(shippedScene(c.scene));
  Simulation& sim = *loaded.sim;
  sim.setIntegrator(allLabs().makeIntegrator(c.method));
  const double limit = stepStableDt(sim);
  ASSERT_TRUE(limit > 0.0 && std::isfinite(limit)) << limit;
  const double slack = StepStabilityOptions{}.radiusSlack;
  EXPECT_LE(stepSpectralRadius(sim, 0.97 * limit).radius, 1.0 + slack) << "limit " << limit << " s";
  EXPECT_GT(stepSpectralRadius(sim, 1.03 * limit).radius, 1.0 + slack) << "limit " << limit << " s";
}
INSTANTIATE_TEST_SUITE_P(ShippedScenes, RadiusAtDt,
                         ::testing::Values(RadiusCase{"rope.json", "symplectic_euler"},
                                           RadiusCase{"softbody_ball.json", "midpoint"},
                                           RadiusCase{"net_flag.json", "explicit_euler"}),
                         [](const auto& p) {
                           const std::string scene = p.param.scene;
                           return scene.substr(0, scene.find('.')) + "_" + p.param.method;
                         });
}  // namespace
}  // namespace springlab
