// The call trace between worker and judge (call_trace.hpp): values arrive as they were sent,
// exceptions keep their kind, and a trace that ends, lies about its function or claims a huge
// vector fails the judge's test instead of crashing or fooling it.
#include "call_trace.hpp"

#include <gtest/gtest.h>
#include <gtest/gtest-spi.h>
#include <unistd.h>

#include <cstdlib>
#include <string>

#include <springlab/not_implemented.hpp>

namespace springlab::trace {
namespace {

// Writer and Reader are one per process and take their descriptor from the environment: a
// forked child plays the worker, this process the judge, joined by a pipe.
TEST(CallTrace, ValuesExceptionsAndLiesBetweenWorkerAndJudge) {
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  const pid_t child = ::fork();
  if (child == 0) {
    ::close(fds[0]);
    ::setenv("SPRINGLAB_CALL_TRACE_FD", std::to_string(fds[1]).c_str(), 1);
    Writer& w = Writer::instance();
    // A return: a vector of springs, a Vec3, a bool.
    beginRecord(w, 7, Outcome::Returned);
    put(w, std::vector<Spring>{{0, 1, 10.0, 0.5, 0.1, SpringKind::Shear}, {1, 2, 20.0, 0.25, 0.0, SpringKind::Bend}});
    put(w, Vec3(1.0, -2.0, 3.5));
    put(w, true);
    // A NotImplemented, an invalid_argument.
    try {
      throw NotImplemented("2.3", "wind force", "handouts/02_net.md#wind");
    } catch (...) {
      try {
        recordException(w, 8);
      } catch (...) {
      }
    }
    try {
      throw std::invalid_argument("negative stiffness");
    } catch (...) {
      try {
        recordException(w, 9);
      } catch (...) {
      }
    }
    // A vector that claims 2^40 elements.
    beginRecord(w, 12, Outcome::Returned);
    putSize(w, std::size_t{1} << 40);
    // A record of another function than the judge expects.
    beginRecord(w, 99, Outcome::Returned);
    w.flush();
    std::_Exit(0);
  }
  ::close(fds[1]);
  ::setenv("SPRINGLAB_CALL_TRACE_FD", std::to_string(fds[0]).c_str(), 1);
  Reader& r = Reader::instance();

  replayCall(7, "buildNet");
  std::vector<Spring> springs;
  Vec3 v;
  bool flag = false;
  get(r, springs);
  get(r, v);
  get(r, flag);
  ASSERT_EQ(springs.size(), 2u);
  EXPECT_EQ(springs[1].mass2, 2);
  EXPECT_EQ(springs[0].kind, SpringKind::Shear);
  EXPECT_DOUBLE_EQ(springs[1].springConstant, 20.0);
  EXPECT_EQ(v, Vec3(1.0, -2.0, 3.5));
  EXPECT_TRUE(flag);

  try {
    replayCall(8, "windForce");
    ADD_FAILURE() << "a recorded NotImplemented was not thrown again";
  } catch (const NotImplemented& e) {
    EXPECT_EQ(e.exerciseId(), "2.3");
    EXPECT_EQ(e.title(), "wind force");
    EXPECT_EQ(e.handoutSection(), "handouts/02_net.md#wind");
  }
  EXPECT_THROW(replayCall(9, "springDamperForce"), std::invalid_argument);

  replayCall(12, "closePairs");
  std::vector<Vec3> huge;
  EXPECT_THROW(get(r, huge), std::length_error);

  // Another function than the judge calls: the test fails (and the call throws).
  EXPECT_NONFATAL_FAILURE(EXPECT_THROW(replayCall(10, "windForce"), TraceEnded), "behaves differently");
  // The worker is gone: the next call fails the test, even when the test catches everything.
  EXPECT_NONFATAL_FAILURE(
      {
        try {
          replayCall(11, "windForce");
        } catch (...) {
        }
      },
      "did not return from its call of windForce");
}

}  // namespace
}  // namespace springlab::trace
