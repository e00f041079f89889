// SpringBatches: batches two apart never share a mass, so they may run at once.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "fast/spring_batches.hpp"

#include <springlab/net/net.hpp>

namespace springlab {
namespace {

std::vector<Spring> gridSprings(int r) {
  net::NetParameters p;
  p.resolution = r;
  p.massModel = net::MassModel::Constant;
  for (auto& k : p.springs) k = {true, 10.0, 0.1};
  return net::buildNet(p).springs;
}

std::set<int> massesOf(const std::vector<Spring>& springs, const SpringBatches& batches, int b) {
  std::set<int> out;
  for (int k = batches.begin(b); k < batches.end(b); ++k) {
    out.insert(springs[static_cast<std::size_t>(k)].mass1);
    out.insert(springs[static_cast<std::size_t>(k)].mass2);
  }
  return out;
}

TEST(SpringBatches, BatchesTwoApartOfAGridShareNoMass) {
  const std::vector<Spring> springs = gridSprings(40);
  const SpringBatches batches(springs, 16);
  ASSERT_GT(batches.count(), 4) << "a 40 x 40 grid should split into several batches";
  EXPECT_TRUE(batches.fits(springs.size()));
  for (int b = 0; b + 2 < batches.count(); ++b) {
    for (int c = b + 2; c < batches.count(); c += 2) {
      const std::set<int> first = massesOf(springs, batches, b), second = massesOf(springs, batches, c);
      std::vector<int> shared;
      std::set_intersection(first.begin(), first.end(), second.begin(), second.end(), std::back_inserter(shared));
      EXPECT_TRUE(shared.empty()) << "batches " << b << " and " << c << " share mass " << shared.front();
    }
  }
}

TEST(SpringBatches, AShuffledListStillRunsEverySpringOnceAndSafely) {
  std::vector<Spring> springs = gridSprings(12);
  std::shuffle(springs.begin(), springs.end(), std::mt19937(7));
  const SpringBatches batches(springs);
  EXPECT_LE(batches.count(), 2) << "a shuffled list cannot be split for threads: one or two batches";
  std::vector<int> visits(springs.size(), 0);
  batches.forEachBatch([&](int first, int last) {
    for (int k = first; k < last; ++k) ++visits[static_cast<std::size_t>(k)];
  });
  EXPECT_TRUE(std::all_of(visits.begin(), visits.end(), [](int v) { return v == 1; }));
}

}  // namespace
}  // namespace springlab
