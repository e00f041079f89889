// The Lanczos estimate of w_max from finite differences of the forces.
#include <gtest/gtest.h>

#include <cmath>

#include <springlab/frequency_estimate.hpp>

#include "test_systems.hpp"

namespace springlab {
namespace {

// Independent masses tied to the origin, each with its own m and k: the frequencies are
// sqrt(k_i / m_i) exactly, and the highest one is what the estimate must find.
class MixedOscillators final : public Simulation {
 public:
  MixedOscillators(std::vector<double> m, std::vector<double> k, int dim = 3) : Simulation(dim), k_(std::move(k)) {
    for (size_t i = 0; i < m.size(); ++i) {
      masses.push_back(Mass{m[i], false});
      state.pos.push_back(Vec3(0.1 * static_cast<double>(i), 0.2, 0.0));
      state.vel.push_back(Vec3::Zero());
    }
    markInitialState();
  }
  std::string kind() const override { return "mixed oscillators"; }

 protected:
  void accumulateForces(const State& s, std::vector<Vec3>& f) override {
    for (int i = 0; i < numOfMasses(); ++i) f[i] += -k_[i] * s.pos[i] + masses[i].m * gravitation;
  }

 private:
  std::vector<double> k_;
};

TEST(FrequencyEstimate, FindsTheHighestOfIndependentOscillators) {
  MixedOscillators sim({1.0, 0.5, 2.0, 1.0}, {4.0, 50.0, 8.0, 9.0});
  const FrequencyEstimate e = lanczosEstimate(sim, sim.state);
  EXPECT_NEAR(e.maxAngularFrequency, 10.0, 1e-5) << "w_max = sqrt(50 / 0.5) = 10 rad/s";
  EXPECT_EQ(e.forceEvaluations, 2 * e.iterations);
}

TEST(FrequencyEstimate, LeavesPinnedMassesOut) {
  MixedOscillators sim({1.0, 0.5, 2.0, 1.0}, {4.0, 50.0, 8.0, 9.0});
  sim.togglePinned(1);
  EXPECT_NEAR(lanczosEstimate(sim, sim.state).maxAngularFrequency, 3.0, 1e-5)
      << "with the stiffest mass pinned, w_max = sqrt(9/1)";
}

TEST(FrequencyEstimate, DoesNotCountItsForceEvaluations) {
  MixedOscillators sim({1.0, 2.0}, {1.0, 3.0});
  sim.operate(0.01);
  const Stats before = sim.stats;
  (void)lanczosEstimate(sim, sim.state);
  EXPECT_EQ(sim.stats.forceEvaluations, before.forceEvaluations);
  EXPECT_EQ(sim.stats.steps, before.steps);
}

TEST(FrequencyEstimate, IsTheSameOnEveryRun) {
  MixedOscillators sim({1.0, 0.5, 2.0}, {4.0, 50.0, 8.0});
  EXPECT_EQ(lanczosEstimate(sim, sim.state).maxAngularFrequency, lanczosEstimate(sim, sim.state).maxAngularFrequency);
}

TEST(FrequencyEstimate, IsZeroWhenNothingCanMove) {
  MixedOscillators sim({1.0}, {4.0});
  sim.togglePinned(0);
  EXPECT_EQ(lanczosEstimate(sim, sim.state).maxAngularFrequency, 0.0);
}

TEST(FrequencyEstimate, BlowUpMessageNamesTheSafeStepFromIt) {
  // The Gershgorin fallback of AnchoredOscillators is overridden to 1 rad/s; the forces say
  // sqrt(k/m) = 3 rad/s, and the message's limit 2 / 3 s must come from them.
  testing::AnchoredOscillators sim(1, 1.0, 9.0);
  try {
    for (int n = 0; n < 20000; ++n) sim.operate(0.7);
    FAIL() << "symplectic Euler at w dt = 2.1 must blow up";
  } catch (const BlowUp& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("stable only below dt = 0.66"), std::string::npos) << "2 / 3 rad/s must be named: " << what;
  }
}

}  // namespace
}  // namespace springlab
