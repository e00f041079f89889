#pragma once
// The fixture of each lab's hidden suite `MatchesReference` (the student's functions against
// the reference on random inputs), shared by every hidden test file of the lab.
//
// GoogleTest accepts one fixture class per test suite in a program: two files that each
// declare their own `class MatchesReference` make every test of the suite fail ("All tests
// in the same test suite must use the same test fixture class"). So the fixture is declared
// once per lab, in the lab's tests/support/<lab>_fixtures.hpp (class springlab::<lab>::
// MatchesReference, derived from MatchesReferenceFixture below, with the lab's random inputs),
// and a new hidden file joins the suite by name:
//
//     #include "rope_fixtures.hpp"
//     namespace springlab::rope { namespace {
//     TEST_F(MatchesReference, ElasticEnergy) { ... }   // graded as MatchesReference.ElasticEnergy
//     } }
//
// tools/author_check.py reports a test file that declares a second fixture for a suite.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <springlab/math.hpp>

#include "seeded.hpp"

namespace springlab::testing {

// Random inputs (Seeded: uniform, integer, vec3, vec3s; the seed printed), a tolerance and a
// number of trials per test.
template <int Trials>
class MatchesReferenceFixture : public Seeded {
 protected:
  static constexpr double kTolerance = 1e-9;
  static constexpr int kTrials = Trials;
};

// Relative distance of two numbers, safe near zero (an absolute error below 1).
inline double relativeError(double got, double want) {
  if (!std::isfinite(got)) return std::numeric_limits<double>::infinity();
  return std::abs(got - want) / std::max(1.0, std::abs(want));
}

// The largest relative distance of two lists of vectors; infinite when their sizes differ.
inline double relativeError(const std::vector<Vec3>& got, const std::vector<Vec3>& want) {
  if (got.size() != want.size()) return std::numeric_limits<double>::infinity();
  double worst = 0.0;
  for (std::size_t i = 0; i < got.size(); ++i) {
    const double e = (got[i] - want[i]).norm() / std::max(1.0, want[i].norm());
    worst = std::isfinite(e) ? std::max(worst, e) : std::numeric_limits<double>::infinity();
  }
  return worst;
}

// An input as text for a failure message: "(x, y, z)".
inline std::string describe(const Vec3& v) {
  std::ostringstream os;
  os << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
  return os.str();
}
inline std::string describe(double x) {
  std::ostringstream os;
  os << x;
  return os.str();
}

}  // namespace springlab::testing
