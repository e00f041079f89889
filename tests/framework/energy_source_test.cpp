// energySourceWarning: `sim` and the viewer name a force term that feeds energy into a run that
// did not blow up (a wind with its sign turned drives a flag to 137 J where the correct code
// gives 0.065 J). A velocity-dependent force is passive when doubling the velocities does not
// raise its power v . f; the check must name the term that breaks this, and only that one.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include <springlab/energy_source.hpp>
#include <springlab/rk4.hpp>
#include <springlab/simulation.hpp>

namespace springlab {
namespace {

// Masses tied to the origin (term 0) in a stream of air (term 1): f = c (w - v), a drag
// towards the air's velocity w that does work on a mass at rest but takes energy out of any
// motion relative to the air. c < 0 is the sign error.
class MassesInAStream final : public Simulation {
 public:
  MassesInAStream(double c, Vec3 w) : Simulation(3), drag(c), air(w) {
    for (int i = 0; i < 4; ++i) {
      masses.push_back(Mass{0.5, false});
      state.pos.push_back(Vec3(0.1 * i, 0.2, 0.0));
      state.vel.push_back(Vec3(0.3, -0.1 * i, 0.2));
    }
    markInitialState();
  }
  std::string kind() const override { return "stream"; }
  std::vector<std::string> forceTermNames() const override { return {"anchors", "air drag (exercise 9.9, airDrag)"}; }

 protected:
  void accumulateForces(const State& s, std::vector<Vec3>& f) override {
    for (int i = 0; i < numOfMasses(); ++i) {
      if (forceTermOn(0)) f[i] += -20.0 * s.pos[i];
      if (forceTermOn(1)) f[i] += drag * (air - s.vel[i]);
    }
  }

 private:
  double drag;
  Vec3 air;
};

// The run so far has fed energy in: every mass three times as fast as it started.
void gainEnergy(Simulation& sim) {
  for (Vec3& v : sim.state.vel) v *= 3.0;
}

TEST(EnergySource, NamesADragWithItsSignTurned) {
  MassesInAStream sim(-0.4, Vec3(0.0, 0.0, -2.0));
  gainEnergy(sim);
  const auto warning = energySourceWarning(sim);
  ASSERT_TRUE(warning.has_value()) << "a force pushing the masses along their velocity feeds energy in";
  EXPECT_NE(warning->find("air drag (exercise 9.9, airDrag)"), std::string::npos) << *warning;
  EXPECT_EQ(warning->find("anchors"), std::string::npos) << "only the term at fault is named: " << *warning;
  EXPECT_NE(warning->find("kinetic energy now"), std::string::npos) << *warning;
}

TEST(EnergySource, ADragTowardsAMovingAirIsPassive) {
  // The air does work on the masses (the wind drives a flag) without being an energy source
  // in the sense of the check: faster motion against it loses more.
  MassesInAStream sim(0.4, Vec3(0.0, 0.0, -2.0));
  gainEnergy(sim);
  EXPECT_FALSE(energySourceWarning(sim).has_value());
}

TEST(EnergySource, SaysNothingWhileTheSceneHoldsNoMoreThanItStartedWith) {
  // A force that releases what it stored (a contact spring pushing a ball back out) raises its
  // power for a moment; only a scene that has gained energy can have a source.
  MassesInAStream sim(-0.4, Vec3(0.0, 0.0, -2.0));
  EXPECT_FALSE(energySourceWarning(sim).has_value());
}

TEST(EnergySource, SaysNothingAtRestAndLeavesTheStatisticsAlone) {
  MassesInAStream moving(-0.4, Vec3::Zero());
  gainEnergy(moving);
  const Stats before = moving.stats;
  EXPECT_TRUE(energySourceWarning(moving).has_value());
  EXPECT_EQ(moving.stats.forceEvaluations, before.forceEvaluations) << "diagnostic evaluations do not count";
  MassesInAStream still(-0.4, Vec3::Zero());
  for (Vec3& v : still.state.vel) v.setZero();
  EXPECT_FALSE(energySourceWarning(still).has_value()) << "nothing moves: no power to compare";
}

}  // namespace
}  // namespace springlab

namespace springlab {
namespace {

// ---- the sources' work (Simulation::sourcePower, sourceWork) ------------------------------------
// Free masses m, released at rest in a stream of air w: f = c (w - v), the only force, and the
// source the scene counts. Each mass then moves as v(t) = w (1 - exp(-c t / m)), and since
// nothing else acts, the work of the stream is all the kinetic energy there is: the energy
// balance (total less the sources' work) stays at its start. The passivity detector holds a
// windy scene to that balance.
class MassesCarriedByAStream final : public Simulation {
 public:
  MassesCarriedByAStream(double c, Vec3 w) : Simulation(3), drag(c), air(w) {
    for (int i = 0; i < 3; ++i) {
      masses.push_back(Mass{0.5 + 0.25 * i, false});
      state.pos.push_back(Vec3(0.1 * i, 0.0, 0.0));
      state.vel.push_back(Vec3::Zero());
    }
    gravitation = Vec3::Zero();
    markInitialState();
  }
  std::string kind() const override { return "stream"; }
  bool suppliesEnergy() const override { return true; }
  std::optional<double> sourcePower(const State& s) const override {
    double p = 0.0;
    for (int i = 0; i < numOfMasses(); ++i) p += (drag * (air - s.vel[i])).dot(s.vel[i]);
    return p;
  }

 protected:
  void accumulateForces(const State& s, std::vector<Vec3>& f) override {
    for (int i = 0; i < numOfMasses(); ++i) f[i] += drag * (air - s.vel[i]);
  }

 private:
  double drag;
  Vec3 air;
};

TEST(SourceWork, TheStreamsWorkIsAllTheKineticEnergyOfTheMassesItCarries) {
  const Vec3 w(1.0, -2.0, 0.5);
  const double c = 0.8, dt = 1e-3;
  MassesCarriedByAStream sim(c, w);
  sim.setIntegrator(std::make_unique<RungeKutta4>());
  for (int k = 0; k < 2000; ++k) sim.operate(dt);  // t = 2 s: 2 to 3 time constants m / c
  double exact = 0.0;  // the closed form of the kinetic energy, mass by mass
  for (const Mass& m : sim.masses) {
    exact += 0.5 * m.m * w.squaredNorm() * std::pow(1.0 - std::exp(-c * sim.state.time / m.m), 2.0);
  }
  EXPECT_NEAR(sim.energies().kinetic / exact, 1.0, 1e-9);
  // The trapezoid rule on the power: second order in dt, 1e-7 of the energy here.
  EXPECT_NEAR(sim.sourceWork() / exact, 1.0, 1e-6) << "work " << sim.sourceWork() << " J, kinetic " << exact << " J";
  EXPECT_NEAR(sim.energyBalance(), 0.0, 1e-6 * exact);
  EXPECT_TRUE(sim.lastStepWorkKnown());
  sim.reset();
  EXPECT_EQ(sim.sourceWork(), 0.0) << "a reset forgets the work";
}

TEST(SourceWork, APassiveScenesSourcesDoNoWork) {
  MassesInAStream sim(0.4, Vec3(0.0, 0.0, -2.0));  // does not say it supplies energy
  sim.setIntegrator(std::make_unique<RungeKutta4>());
  for (int k = 0; k < 100; ++k) sim.operate(1e-3);
  EXPECT_EQ(sim.sourceWork(), 0.0);
  EXPECT_EQ(sim.energyBalance(), sim.energies().total());
}

}  // namespace
}  // namespace springlab

