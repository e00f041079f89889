#pragma once
// Random inputs for grading tests: a seed per test, printed so a failure can be replayed
// exactly (SPRINGLAB_SEED=<seed> ./grading --gtest_filter=...).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include <springlab/math.hpp>

namespace springlab::testing {

class Seeded : public ::testing::Test {
 protected:
  void SetUp() override {
    const char* fixed = std::getenv("SPRINGLAB_SEED");
    seed_ = fixed ? std::strtoull(fixed, nullptr, 10) : std::random_device{}();
    rng_.seed(seed_);
    std::cout << "[   SEED   ] SPRINGLAB_SEED=" << seed_ << "\n";
    RecordProperty("seed", std::to_string(seed_));
  }

  // How many random numbers the test drew: tools/seed_sweep.py sweeps only tests that drew some.
  void TearDown() override { RecordProperty("random_draws", std::to_string(draws_)); }

  double uniform(double lo, double hi) {
    ++draws_;
    return std::uniform_real_distribution<double>(lo, hi)(rng_);
  }
  int integer(int lo, int hi) {
    ++draws_;
    return std::uniform_int_distribution<int>(lo, hi)(rng_);
  }
  Vec3 vec3(double lo, double hi) { return {uniform(lo, hi), uniform(lo, hi), uniform(lo, hi)}; }
  // n random vectors with coordinates in [lo, hi).
  std::vector<Vec3> vec3s(int n, double lo, double hi) {
    std::vector<Vec3> out;
    for (int i = 0; i < n; ++i) out.push_back(vec3(lo, hi));
    return out;
  }
  std::string seedText() const { return "(seed " + std::to_string(seed_) + ")"; }

 private:
  std::uint64_t seed_ = 0;
  std::uint64_t draws_ = 0;
  std::mt19937_64 rng_;
};

// Relative distance of two vectors, safe near zero.
inline double relativeError(const Vec3& got, const Vec3& want) {
  return (got - want).norm() / std::max(1.0, want.norm());
}

}  // namespace springlab::testing
