// The cloth's fast spring pass (framework/labs/net/src/fast_spring_forces.cpp) sorts its
// springs into families (fast/spring_families.hpp) and sums them per mass in its own order:
// the forces must still be every spring's force added to both its ends, as the plain loop of
// net.cpp gives them, to round-off; a spring list edited (reordered, rewired, with a duplicate,
// new k) through editModel, the springs' one writer, must be followed, not the families and
// copies made from the old one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <vector>

#include <springlab/net/net.hpp>

#include "fast/avx2.hpp"
#include "fast/spring_families.hpp"

namespace springlab {
namespace {

// A 24 x 24 cloth with gravity and air friction, every mass moved and set moving at random,
// every spring's k, L0 and kd drawn at random.
std::unique_ptr<net::Net> randomCloth(unsigned seed) {
  net::NetParameters p;
  p.resolution = 24;
  p.massModel = net::MassModel::Constant;
  p.particleMass = 0.5;
  p.springs[SpringKind::Structural] = {true, 75.0, 0.25};
  p.springs[SpringKind::Shear] = {true, 22.0, 0.25};
  p.springs[SpringKind::Bend] = {true, 8.0, 0.25};
  p.pins = {net::Pin::Corner00, net::Pin::Corner10};
  p.airFriction = 0.3;
  p.wind.drag = 0.0;  // no wind: the pass compared here is springs, gravity and air friction
  auto cloth = std::make_unique<net::Net>(3, p);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.02, 0.02), speed(-1.0, 1.0), factor(0.5, 2.0);
  for (Vec3& x : cloth->state.pos) x += Vec3(jitter(rng), jitter(rng), jitter(rng));
  for (Vec3& v : cloth->state.vel) v = Vec3(speed(rng), speed(rng), speed(rng));
  cloth->editModel([&](Simulation& model) {
    for (Spring& s : model.editSprings()) {
      s.springConstant *= factor(rng);
      s.springLength *= factor(rng);
      s.frictionConstant *= factor(rng);
    }
  });
  return cloth;
}

// The forces as the handout adds them: springs in list order, each on both ends, then gravity
// and air friction. Also the size of what met at each mass (|each term| summed), the scale of
// its round-off.
void plainForces(const net::Net& cloth, std::vector<Vec3>& f, std::vector<double>& scale) {
  const State& s = cloth.state;
  f.assign(s.pos.size(), Vec3::Zero());
  scale.assign(s.pos.size(), 0.0);
  for (const Spring& sp : cloth.springs()) {
    const Vec3 f1 = net::springDamperForce(s.pos[sp.mass1], s.pos[sp.mass2], s.vel[sp.mass1], s.vel[sp.mass2],
                                           sp.springConstant, sp.springLength, sp.frictionConstant);
    f[sp.mass1] += f1;
    f[sp.mass2] -= f1;
    scale[sp.mass1] += f1.norm();
    scale[sp.mass2] += f1.norm();
  }
  for (std::size_t i = 0; i < f.size(); ++i) {
    const Vec3 own = cloth.masses[i].m * (cloth.gravitation - cloth.settings.airFriction * s.vel[i]);
    f[i] += own;
    scale[i] += own.norm();
  }
}

// The largest difference between the force pass and the plain sum, relative to the size of
// what met at that mass.
double largestRelativeDifference(net::Net& cloth) {
  std::vector<Vec3> expected;
  std::vector<double> scale;
  plainForces(cloth, expected, scale);
  cloth.evaluateForces(cloth.state, cloth.force);
  double worst = 0.0;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    worst = std::max(worst, (cloth.force[i] - expected[i]).norm() / std::max(scale[i], 1e-300));
  }
  return worst;
}

TEST(NetForcePass, AddsEverySpringsForceToBothEndsToRoundOff) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    std::unique_ptr<net::Net> cloth = randomCloth(seed);
    EXPECT_LE(largestRelativeDifference(*cloth), 1e-12)
        << "seed " << seed << ": the force pass is not the sum of every spring's force on both its ends (plus gravity "
        << "and air friction) beyond round-off";
  }
}

TEST(NetForcePass, FollowsSpringsEditedThroughEditModel) {
  std::unique_ptr<net::Net> cloth = randomCloth(7);
  ASSERT_LE(largestRelativeDifference(*cloth), 1e-12);
  std::mt19937 rng(7);

  // The same springs in another order: the families' records moved.
  cloth->editModel([&](Simulation& model) {
    std::vector<Spring>& springs = model.editSprings();
    std::shuffle(springs.begin(), springs.end(), rng);
  });
  EXPECT_LE(largestRelativeDifference(*cloth), 1e-12) << "after shuffling the spring list";

  // Rewired ends with the same count: one spring now joins two far masses, another is reversed.
  cloth->editModel([&](Simulation& model) {
    std::vector<Spring>& springs = model.editSprings();
    springs[10].mass2 = static_cast<int>(model.masses.size()) - 1;
    std::swap(springs[20].mass1, springs[20].mass2);
  });
  EXPECT_LE(largestRelativeDifference(*cloth), 1e-12) << "after rewiring two springs";

  // A second spring between the same masses (it fits no family) and one spring fewer.
  cloth->editModel([&](Simulation& model) {
    std::vector<Spring>& springs = model.editSprings();
    springs.push_back(springs[30]);
    springs.erase(springs.begin() + 40);
  });
  EXPECT_LE(largestRelativeDifference(*cloth), 1e-12) << "after duplicating one spring and removing another";

  // Every spring's k, L0 and kd changed in place (what the panel's sliders do): the force pass
  // works from copies, which the edit must refresh.
  cloth->editModel([&](Simulation& model) {
    for (Spring& s : model.editSprings()) {
      s.springConstant *= 3.0;
      s.springLength *= 0.9;
      s.frictionConstant *= 2.0;
    }
  });
  EXPECT_LE(largestRelativeDifference(*cloth), 1e-12) << "after changing every spring's k, L0 and kd";
}

TEST(NetForcePass, FollowsAListReplacedByOneWithNoFamilyThroughThePlainLoop) {
  // Twenty springs of a 576-mass cloth share no offset often enough for a family: the fast
  // pass declines and net.cpp's plain loop adds them; back to the whole grid, the fast pass again.
  std::unique_ptr<net::Net> cloth = randomCloth(8);
  const std::vector<Spring> all = cloth->springs();
  cloth->editModel([&](Simulation& model) { model.editSprings().resize(20); });
  EXPECT_LE(largestRelativeDifference(*cloth), 1e-12) << "after keeping 20 springs (no family)";
  cloth->editModel([&](Simulation& model) { model.editSprings() = all; });
  EXPECT_LE(largestRelativeDifference(*cloth), 1e-12) << "after restoring the whole grid";
}

TEST(SpringFamilies, Avx2AndBaselineLoopsGiveTheSameBits) {
  // The force pass's loops are built twice (baseline, AVX2 without FMA): the same operations
  // in the same order, so the same forces to the last bit on every mass.
  if (!hasAvx2()) GTEST_SKIP() << "this build or CPU has no AVX2 variant of the force pass";
  for (unsigned seed = 1; seed <= 3; ++seed) {
    std::unique_ptr<net::Net> cloth = randomCloth(seed);
    allowAvx2(true);
    cloth->evaluateForces(cloth->state, cloth->force);
    const std::vector<Vec3> avx2 = cloth->force;
    allowAvx2(false);
    cloth->evaluateForces(cloth->state, cloth->force);
    allowAvx2(true);
    ASSERT_EQ(avx2.size(), cloth->force.size());
    EXPECT_EQ(std::memcmp(avx2.data(), cloth->force.data(), avx2.size() * sizeof(Vec3)), 0)
        << "seed " << seed << ": the AVX2 loops' forces differ from the baseline's";
  }
}

TEST(SpringFamilies, SortAGridIntoItsSixOffsetsAndTakeEverySpringOnce) {
  std::unique_ptr<net::Net> cloth = randomCloth(3);
  const int n = static_cast<int>(cloth->masses.size());
  const SpringFamilies families(cloth->springs(), n);
  // Structural (1, 24), shear (23, 25), bend (2, 48) on a 24-wide grid.
  EXPECT_EQ(families.families(), 6);
  EXPECT_TRUE(families.leftovers().empty());
  std::vector<int> seen(cloth->springs().size(), 0);
  for (const int k : families.order()) ++seen[static_cast<std::size_t>(k)];
  for (const int k : families.leftovers()) ++seen[static_cast<std::size_t>(k)];
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), static_cast<long>(seen.size())) << "a spring is missing or twice";
  // Every run's springs join first + t to first + t + d.
  for (const SpringFamilies::Run& run : families.runs()) {
    for (int t = 0; t < run.count; ++t) {
      const int k = families.order()[static_cast<std::size_t>(run.spring + t)];
      const Spring& s = cloth->springs()[static_cast<std::size_t>(k)];
      ASSERT_EQ(s.mass1, run.first + t);
      ASSERT_EQ(s.mass2, run.first + t + families.offset(run.family));
    }
  }
}

TEST(SpringFamilies, LeaveARareOffsetAndADuplicateOver) {
  // Ten masses in a row: nine springs of offset 1, one of offset 5, one duplicate of 0-1.
  std::vector<Spring> springs;
  for (int i = 0; i + 1 < 10; ++i) springs.push_back(Spring{i, i + 1, 1.0, 1.0, 0.0, SpringKind::Structural});
  springs.push_back(Spring{2, 7, 1.0, 5.0, 0.0, SpringKind::Structural});
  springs.push_back(Spring{0, 1, 1.0, 1.0, 0.0, SpringKind::Structural});
  const SpringFamilies families(springs, 10);
  ASSERT_EQ(families.families(), 1);
  EXPECT_EQ(families.offset(0), 1);
  ASSERT_EQ(families.runs().size(), 1u);
  EXPECT_EQ(families.runs()[0].count, 9);
  EXPECT_EQ(families.leftovers(), (std::vector<int>{9, 10}));
}

}  // namespace
}  // namespace springlab
