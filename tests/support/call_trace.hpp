#pragma once
// The call trace between the two processes of a graded test (see tools/make_call_layer.py).
//
// The worker runs the test with the student's exercise file and writes, for every call the
// test or the given code makes to one of that file's functions, what the call gave back: its
// return value and the arguments it wrote to, or the exception it threw. The judge runs the
// same test without any student code: its copy of those functions reads the next record
// instead of computing. The judge's checks, its reference "oracle" and its verdict therefore
// come from a process that never ran student code; the worker's own verdict is ignored.
//
// A record: [function id u32][outcome u8][payload]. Outcome 0 is a return (the payload holds
// the return value, then each written argument); the others are exceptions (the payload is
// the message). The judge checks each record's function against the call it is making: a
// mismatch means the worker's test took another path (student code that behaves differently
// between runs) and fails the test.
#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <springlab/mass.hpp>
#include <springlab/mesh.hpp>
#include <springlab/simulation.hpp>
#include <springlab/solvers/block_system.hpp>
#include <springlab/spring.hpp>

namespace springlab::trace {

// ---- the byte streams ------------------------------------------------------------------
// The worker's end: buffered writes to the descriptor in SPRINGLAB_CALL_TRACE_FD, flushed when
// the buffer fills and when the test program ends. Without that variable nothing is written
// (the worker then runs as a plain test program).
class Writer {
 public:
  static Writer& instance();
  bool active() const { return fd_ >= 0; }
  void bytes(const void* data, std::size_t size);
  void flush();

 private:
  Writer();
  int fd_ = -1;
  std::vector<unsigned char> buffer_;
};

// The judge's end: reads the descriptor in SPRINGLAB_CALL_TRACE_FD. The stream is untrusted:
// every size is checked against a cap before anything is allocated.
class Reader {
 public:
  static Reader& instance();
  void bytes(void* data, std::size_t size);  // throws TraceEnded at the end of the stream
  std::size_t calls() const { return calls_; }
  void countCall() { ++calls_; }

 private:
  Reader();
  int fd_ = -1;
  std::vector<unsigned char> buffer_;
  std::size_t begin_ = 0, end_ = 0, calls_ = 0;
};

// The worker's records ran out: its process ended (crash, exit, time limit) before the call
// the judge is making returned there. The test fails; the grader names the worker's fate.
struct TraceEnded : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// ---- values ----------------------------------------------------------------------------
// Each type an exercise returns or writes has a put (worker) and a get (judge). Lab types get
// theirs from the generated call layer, next to the functions.
constexpr std::size_t kMaxElements = std::size_t{1} << 27;  // a vector of more is rejected

template <class T>
concept Plain = std::is_arithmetic_v<T> || std::is_enum_v<T>;

template <Plain T>
void put(Writer& w, const T& v) {
  w.bytes(&v, sizeof v);
}
template <Plain T>
void get(Reader& r, T& v) {
  if constexpr (std::is_same_v<T, bool>) {
    unsigned char byte = 0;
    r.bytes(&byte, 1);
    v = byte != 0;
  } else {
    r.bytes(&v, sizeof v);
  }
}

inline void putSize(Writer& w, std::size_t n) { put(w, static_cast<std::uint64_t>(n)); }
std::size_t getSize(Reader& r);  // throws when above kMaxElements

// Fixed-size Eigen matrices (Vec3, Mat3) as their coefficients; dynamic ones with their size.
template <int R, int C, int O, int MR, int MC>
void put(Writer& w, const Eigen::Matrix<double, R, C, O, MR, MC>& m) {
  if constexpr (R == Eigen::Dynamic || C == Eigen::Dynamic) {
    putSize(w, static_cast<std::size_t>(m.rows()));
    putSize(w, static_cast<std::size_t>(m.cols()));
  }
  w.bytes(m.data(), sizeof(double) * static_cast<std::size_t>(m.size()));
}
template <int R, int C, int O, int MR, int MC>
void get(Reader& r, Eigen::Matrix<double, R, C, O, MR, MC>& m) {
  if constexpr (R == Eigen::Dynamic || C == Eigen::Dynamic) {
    const std::size_t rows = getSize(r), cols = getSize(r);
    if (cols != 0 && rows > kMaxElements / cols) throw std::length_error("call trace: matrix too large");
    m.resize(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols));
  }
  r.bytes(m.data(), sizeof(double) * static_cast<std::size_t>(m.size()));
}

// The framework's value types.
void put(Writer& w, const Mass& m);
void get(Reader& r, Mass& m);
void put(Writer& w, const Spring& s);
void get(Reader& r, Spring& s);
void put(Writer& w, const Triangle& t);
void get(Reader& r, Triangle& t);
void put(Writer& w, const Segment& s);
void get(Reader& r, Segment& s);
void put(Writer& w, const BlockSystem& system);  // the values; the layout is the caller's
void get(Reader& r, BlockSystem& system);

template <class A, class B>
void put(Writer& w, const std::pair<A, B>& p) {
  put(w, p.first);
  put(w, p.second);
}
template <class A, class B>
void get(Reader& r, std::pair<A, B>& p) {
  get(r, p.first);
  get(r, p.second);
}

template <class T, std::size_t N>
void put(Writer& w, const std::array<T, N>& a) {
  for (const T& x : a) put(w, x);
}
template <class T, std::size_t N>
void get(Reader& r, std::array<T, N>& a) {
  for (T& x : a) get(r, x);
}

template <class T, class Alloc>
void put(Writer& w, const std::vector<T, Alloc>& v) {
  putSize(w, v.size());
  for (const auto& x : v) put(w, x);
}
template <class T, class Alloc>
void get(Reader& r, std::vector<T, Alloc>& v) {
  const std::size_t n = getSize(r);
  v.clear();
  v.reserve(std::min<std::size_t>(n, 4096));  // grows with what actually arrives
  for (std::size_t i = 0; i < n; ++i) {
    T x{};
    get(r, x);
    v.push_back(std::move(x));
  }
}

// ---- one call --------------------------------------------------------------------------
// Worker: run `call` (the student's function), then record its outcome with `record` (which
// puts the return value and written arguments); an exception is recorded and rethrown.
enum class Outcome : std::uint8_t {
  Returned = 0,
  NotImplemented,
  InvalidArgument,
  OutOfRange,
  LengthError,
  LogicError,
  RuntimeError,
  OtherException,
  Unknown,
};

void beginRecord(Writer& w, std::uint32_t function, Outcome outcome);
void recordException(Writer& w, std::uint32_t function);  // inside a catch block: rethrows

template <class Call, class Record>
decltype(auto) recorded(std::uint32_t function, Call&& call, Record&& record) {
  Writer& w = Writer::instance();
  if (!w.active()) return call();
  try {
    if constexpr (std::is_void_v<decltype(call())>) {
      call();
      beginRecord(w, function, Outcome::Returned);
      record(w);
    } else {
      auto result = call();
      beginRecord(w, function, Outcome::Returned);
      record(w, result);
      return result;
    }
  } catch (...) {
    recordException(w, function);
    throw;
  }
}

// Judge: read the next record, which must be of `function` (named for messages); on a return
// `replay` gets the payload, else the recorded exception is thrown again.
void replayCall(std::uint32_t function, const char* name);  // reads the header; throws if not a return

}  // namespace springlab::trace
