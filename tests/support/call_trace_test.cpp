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
// forked child plays the worker (`send` writes its trace), this process the judge, joined by a
// pipe. (One test per process, as ctest runs them.)
template <class Send>
void playWorker(Send&& send) {
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  if (::fork() == 0) {
    ::close(fds[0]);
    ::setenv("SPRINGLAB_CALL_TRACE_FD", std::to_string(fds[1]).c_str(), 1);
    Writer& w = Writer::instance();
    send(w);
    w.flush();
    std::_Exit(0);
  }
  ::close(fds[1]);
  ::setenv("SPRINGLAB_CALL_TRACE_FD", std::to_string(fds[0]).c_str(), 1);
}

TEST(CallTrace, ValuesExceptionsAndLiesBetweenWorkerAndJudge) {
  playWorker([](Writer& w) {
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
  });
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
  EXPECT_NONFATAL_FAILURE(EXPECT_THROW(get(r, huge), MalformedTrace), "a vector of 1099511627776 elements");

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

using Pairs = std::vector<std::pair<int, int>>;

// Forged records, as a worker that writes to the channel itself could send them: each fails
// the judge's test with a sentence, and the judge goes on (no crash, nothing allocated).
TEST(CallTrace, ForgedRecordsFailTheTestWithASentence) {
  playWorker([](Writer& w) {
    // The right function, springs whose ends lie past the three masses it gives back.
    beginRecord(w, 3, Outcome::Returned);
    put(w, std::vector<Spring>{{0, 1, 1.0, 1.0, 0.0, SpringKind::Structural}, {1, 1000000000, 1.0, 1.0, 0.0,
                                                                                SpringKind::Structural}});
    put(w, std::vector<Vec3>(3, Vec3::Zero()));
    // A pair with a negative mass.
    beginRecord(w, 4, Outcome::Returned);
    put(w, Pairs{{-5, 1}});
    // A huge count: more elements than the trace may still hold.
    beginRecord(w, 5, Outcome::Returned);
    putSize(w, std::size_t{1} << 26);
    // A spring kind out of range; a bool that is 7.
    beginRecord(w, 6, Outcome::Returned);
    put(w, std::uint64_t{1});
    put(w, 0), put(w, 1), put(w, 1.0), put(w, 1.0), put(w, 0.0), put(w, 99);
    beginRecord(w, 7, Outcome::Returned);
    put(w, std::uint8_t{7});
    // A written vector of forces that comes back shorter than it was given (refused at its
    // count: its element is left out, so the records after it stay in step).
    beginRecord(w, 8, Outcome::Returned);
    putSize(w, 1);
    // An outcome that is none.
    beginRecord(w, 9, static_cast<Outcome>(200));
    // A record cut short: its function and half a Vec3.
    beginRecord(w, 10, Outcome::Returned);
    put(w, 1.0);
  });
  Reader& r = Reader::instance();

  EXPECT_NONFATAL_FAILURE(
      {
        replayCall(3, "buildRope");
        std::vector<Spring> springs;
        std::vector<Vec3> pos;
        get(r, springs);
        get(r, pos);
        EXPECT_THROW(checkReplayedIndices(springs, pos), MalformedTrace);
      },
      "a spring's second mass is 1000000000, but the call has 3 masses");
  EXPECT_NONFATAL_FAILURE(
      {
        replayCall(4, "closePairs");
        Pairs pairs;
        get(r, pairs);
        const std::vector<Vec3> given(4, Vec3::Zero());
        EXPECT_THROW(checkReplayedIndices(pairs, given), MalformedTrace);
      },
      "a pair's first mass is -5");
  EXPECT_NONFATAL_FAILURE(
      {
        replayCall(5, "closePairs");
        std::vector<Vec3> huge;
        EXPECT_THROW(get(r, huge), MalformedTrace);
      },
      "a vector of 67108864 elements");
  EXPECT_NONFATAL_FAILURE(
      {
        replayCall(6, "edgeSprings");
        std::vector<Spring> springs;
        EXPECT_THROW(get(r, springs), MalformedTrace);
      },
      "a spring kind out of range");
  EXPECT_NONFATAL_FAILURE(
      {
        replayCall(7, "touching");
        bool flag = false;
        EXPECT_THROW(get(r, flag), MalformedTrace);
      },
      "neither true nor false");
  EXPECT_NONFATAL_FAILURE(
      {
        replayCall(8, "addSpringForces");
        std::vector<Vec3> force(5, Vec3::Zero());
        EXPECT_THROW(get(r, force), MalformedTrace);
      },
      "a vector of 5 elements your function was given came back with 1");
  EXPECT_NONFATAL_FAILURE(EXPECT_THROW(replayCall(9, "windForce"), MalformedTrace), "an outcome that is no outcome");
  EXPECT_NONFATAL_FAILURE(
      {
        replayCall(10, "projectSpring");
        Vec3 v;
        try {
          get(r, v);
        } catch (...) {  // a test that catches everything still fails
        }
      },
      "stopped while giving back what its call of projectSpring");
  // Honest values pass: indices within the masses of the call.
  const std::vector<Spring> springs{{0, 2, 1.0, 1.0, 0.0, SpringKind::Bend}};
  EXPECT_NO_THROW(checkReplayedIndices(springs, std::vector<Vec3>(3, Vec3::Zero())));
}

}  // namespace
}  // namespace springlab::trace
