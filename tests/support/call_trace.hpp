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

#include <algorithm>
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
// every size is checked against a cap before anything is allocated, and a test reads at most
// kMaxTraceBytes of it.
constexpr std::size_t kMaxTraceBytes = std::size_t{1} << 30;

class Reader {
 public:
  static Reader& instance();
  void bytes(void* data, std::size_t size);  // throws TraceEnded at the end of the stream
  std::size_t calls() const { return calls_; }
  void countCall() { ++calls_; }
  std::size_t remaining() const { return kMaxTraceBytes - consumed_; }  // bytes the test may still read
  // The function whose record is being read ("" while reading a record's header).
  void reading(const char* function) { function_ = function; }
  const std::string& function() const { return function_; }

 private:
  Reader();
  int fd_ = -1;
  std::vector<unsigned char> buffer_;
  std::size_t begin_ = 0, end_ = 0, calls_ = 0, consumed_ = 0;
  std::string function_;
};

// The worker's records ran out: its process ended (crash, exit, time limit) before the call
// the judge is making returned there. The test fails; the grader names the worker's fate.
struct TraceEnded : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// What the worker sent cannot be what an exercise function gives back (a size, an index, a
// kind out of range, a record cut short): the judge's test fails with this sentence, whatever
// the test catches, and the call throws (MalformedTrace, a TraceEnded: nothing more is read).
struct MalformedTrace : TraceEnded {
  using TraceEnded::TraceEnded;
};
[[noreturn]] void malformed(const std::string& what);

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
  // A bool is one byte of 0 or 1, a spring's kind one of its values: anything else would be
  // undefined behaviour in the judge (a kind indexes tables).
  if constexpr (std::is_same_v<T, bool>) {
    unsigned char byte = 0;
    r.bytes(&byte, 1);
    if (byte > 1) malformed("a bool that is neither true nor false");
    v = byte != 0;
  } else if constexpr (std::is_same_v<T, SpringKind>) {
    std::underlying_type_t<SpringKind> raw = 0;
    r.bytes(&raw, sizeof raw);
    if (raw < 0 || raw > static_cast<int>(SpringKind::Extra)) malformed("a spring kind out of range");
    v = static_cast<SpringKind>(raw);
  } else {
    r.bytes(&v, sizeof v);
  }
}

inline void putSize(Writer& w, std::size_t n) { put(w, static_cast<std::uint64_t>(n)); }
std::size_t getSize(Reader& r);  // malformed when above kMaxElements or what the trace can still hold

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
    if (cols != 0 && rows > std::min(kMaxElements, r.remaining() / sizeof(double)) / cols)
      malformed("a matrix of " + std::to_string(rows) + " x " + std::to_string(cols) + " values");
    // A matrix the judge passed in with values (a written argument) keeps its shape.
    if (m.size() != 0 && (static_cast<std::size_t>(m.rows()) != rows || static_cast<std::size_t>(m.cols()) != cols))
      malformed("a matrix of " + std::to_string(m.rows()) + " x " + std::to_string(m.cols()) +
                " values your function was given came back with " + std::to_string(rows) + " x " +
                std::to_string(cols));
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
// The fewest bytes one element of T takes in the trace: a count of more than the trace can
// still hold is refused before anything is read.
template <class T>
constexpr std::size_t leastBytes() {
  if constexpr (Plain<T>) {
    return std::is_same_v<T, bool> ? 1 : sizeof(T);
  } else if constexpr (requires { T::SizeAtCompileTime; typename T::Scalar; }) {
    return T::SizeAtCompileTime > 0 ? sizeof(typename T::Scalar) * T::SizeAtCompileTime : 1;
  } else {
    return 1;
  }
}

template <class T, class Alloc>
void get(Reader& r, std::vector<T, Alloc>& v) {
  const std::size_t n = getSize(r);
  if (n > r.remaining() / leastBytes<T>()) malformed("a vector of " + std::to_string(n) + " elements");
  // A vector the judge passed in with elements (a written argument: forces, positions) keeps
  // its size: the code after the call indexes it as it was.
  if (!v.empty() && n != v.size())
    malformed("a vector of " + std::to_string(v.size()) + " elements your function was given came back with " +
              std::to_string(n));
  v.clear();
  v.reserve(std::min<std::size_t>(n, 4096));  // grows with what actually arrives
  for (std::size_t i = 0; i < n; ++i) {
    T x{};
    get(r, x);
    v.push_back(std::move(x));
  }
}

// ---- indices ---------------------------------------------------------------------------
// The judge hands what the worker gave back to the given code and the tests, which index
// arrays with it. So every index in a call's values (a spring's two masses, a triangle's or a
// segment's corners, a pair of masses) must lie among the call's points: the fewest among its
// position, velocity and mass vectors (a mesh's vertices), given or given back; checked
// before the replayed call returns. A lab's struct is looked into through the forEachField
// its call layer generates (values.hpp).
constexpr std::size_t kNoPoints = ~std::size_t{0};

inline void measure(std::size_t& points, const std::vector<Vec3>& v) { points = std::min(points, v.size()); }
inline void measure(std::size_t& points, const std::vector<Mass>& v) { points = std::min(points, v.size()); }
inline void measure(std::size_t& points, const SurfaceMesh& m) { measure(points, m.vertices); }
template <class T>
void measure(std::size_t& points, const T& v) {
  if constexpr (requires { forEachField(v, [](const auto&) {}); })
    forEachField(v, [&](const auto& field) { measure(points, field); });
}

void checkIndex(std::size_t points, long long index, const char* what);  // malformed if outside [0, points)
inline void checkIndices(std::size_t points, const Spring& s) {
  checkIndex(points, s.mass1, "a spring's first mass"), checkIndex(points, s.mass2, "a spring's second mass");
}
inline void checkIndices(std::size_t points, const Triangle& t) {
  checkIndex(points, t.a, "a triangle's corner"), checkIndex(points, t.b, "a triangle's corner"),
      checkIndex(points, t.c, "a triangle's corner");
}
inline void checkIndices(std::size_t points, const Segment& s) {
  checkIndex(points, s.a, "a segment's end"), checkIndex(points, s.b, "a segment's end");
}
inline void checkIndices(std::size_t points, const std::pair<int, int>& p) {
  checkIndex(points, p.first, "a pair's first mass"), checkIndex(points, p.second, "a pair's second mass");
}
template <class T, class Alloc>
void checkIndices(std::size_t points, const std::vector<T, Alloc>& v);
template <class T>
void checkIndices(std::size_t points, const T& v) {
  if constexpr (requires { forEachField(v, [](const auto&) {}); })
    forEachField(v, [&](const auto& field) { checkIndices(points, field); });
}
template <class T, class Alloc>
void checkIndices(std::size_t points, const std::vector<T, Alloc>& v) {
  for (const T& x : v) checkIndices(points, x);
}

// Judge, after a replayed call read its values: the call's indices against its points.
template <class... Values>
void checkReplayedIndices(const Values&... values) {
  std::size_t points = kNoPoints;
  (measure(points, values), ...);
  if (points == kNoPoints) points = kMaxElements;  // no points in the call: within the trace's caps
  (checkIndices(points, values), ...);
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
