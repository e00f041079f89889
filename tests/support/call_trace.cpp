// The call trace's streams and the framework types' values (see call_trace.hpp).
#include "call_trace.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <new>

#include <springlab/not_implemented.hpp>

#include "launch.hpp"

namespace springlab::trace {
namespace {

constexpr std::size_t kBuffer = std::size_t{1} << 16;
constexpr std::size_t kMaxMessage = 4000;

}  // namespace

// ---- worker ----------------------------------------------------------------------------
Writer::Writer() : fd_(launch::channelFromEnvironment()) {
  if (fd_ >= 0) {
    buffer_.reserve(kBuffer);
    ::unsetenv("SPRINGLAB_CALL_TRACE_FD");
    std::atexit([] { Writer::instance().flush(); });
  }
}

Writer& Writer::instance() {
  static Writer writer;
  return writer;
}

void Writer::bytes(const void* data, std::size_t size) {
  const auto* p = static_cast<const unsigned char*>(data);
  if (buffer_.size() + size > kBuffer) flush();
  if (size > kBuffer) {  // larger than the buffer: straight through
    while (size > 0) {
      const ssize_t n = ::write(fd_, p, size);
      if (n <= 0 && errno != EINTR) return;
      if (n > 0) p += n, size -= static_cast<std::size_t>(n);
    }
    return;
  }
  buffer_.insert(buffer_.end(), p, p + size);
}

void Writer::flush() {
  std::size_t done = 0;
  while (fd_ >= 0 && done < buffer_.size()) {
    const ssize_t n = ::write(fd_, buffer_.data() + done, buffer_.size() - done);
    if (n <= 0 && errno != EINTR) break;  // the judge has stopped reading
    if (n > 0) done += static_cast<std::size_t>(n);
  }
  buffer_.clear();
}

void beginRecord(Writer& w, std::uint32_t function, Outcome outcome) {
  put(w, function);
  put(w, static_cast<std::uint8_t>(outcome));
}

void recordException(Writer& w, std::uint32_t function) {
  Outcome outcome = Outcome::Unknown;
  std::string message;
  try {
    throw;
  } catch (const NotImplemented& e) {
    outcome = Outcome::NotImplemented, message = e.what();
  } catch (const std::invalid_argument& e) {
    outcome = Outcome::InvalidArgument, message = e.what();
  } catch (const std::out_of_range& e) {
    outcome = Outcome::OutOfRange, message = e.what();
  } catch (const std::length_error& e) {
    outcome = Outcome::LengthError, message = e.what();
  } catch (const std::logic_error& e) {
    outcome = Outcome::LogicError, message = e.what();
  } catch (const std::runtime_error& e) {
    outcome = Outcome::RuntimeError, message = e.what();
  } catch (const std::exception& e) {
    outcome = Outcome::OtherException, message = e.what();
  } catch (...) {
  }
  message.resize(std::min(message.size(), kMaxMessage));
  beginRecord(w, function, outcome);
  putSize(w, message.size());
  w.bytes(message.data(), message.size());
  w.flush();  // an exception may end the test program: keep what came before it
}

// ---- judge -----------------------------------------------------------------------------
Reader::Reader() : fd_(launch::channelFromEnvironment()), buffer_(kBuffer) {}

Reader& Reader::instance() {
  static Reader reader;
  return reader;
}

void Reader::bytes(void* data, std::size_t size) {
  auto* p = static_cast<unsigned char*>(data);
  if (size > remaining()) malformed("more than " + std::to_string(kMaxTraceBytes >> 20) + " MiB in one test");
  consumed_ += size;
  while (size > 0) {
    if (begin_ == end_) {
      if (fd_ < 0) throw TraceEnded("no call trace: SPRINGLAB_CALL_TRACE_FD is not set");
      ssize_t n;
      do n = ::read(fd_, buffer_.data(), buffer_.size());
      while (n < 0 && errno == EINTR);
      if (n <= 0) {
        // Cut short inside a record: the test fails here, even if it catches every exception.
        if (!function_.empty())
          ADD_FAILURE() << "SPRINGLAB_TRACE_ENDED: your code stopped while giving back what its call of "
                        << function_ << " (call " << calls_ << " to your exercise file in this test) returned";
        throw TraceEnded("the student's code stopped before this call returned");
      }
      begin_ = 0, end_ = static_cast<std::size_t>(n);
    }
    const std::size_t take = std::min(size, end_ - begin_);
    std::memcpy(p, buffer_.data() + begin_, take);
    begin_ += take, p += take, size -= take;
  }
}

std::size_t getSize(Reader& r) {
  std::uint64_t n = 0;
  get(r, n);
  // Every element takes at least a byte of the trace: a count above what it can still hold is a lie.
  if (n > kMaxElements || n > r.remaining())
    malformed("a vector of " + std::to_string(n) + " elements");
  return static_cast<std::size_t>(n);
}

void malformed(const std::string& what) {
  const Reader& r = Reader::instance();
  ADD_FAILURE() << "the grader cannot use what your code gave back from call " << r.calls() << " to your exercise file"
                << (r.function().empty() ? std::string() : " (" + r.function() + ")") << ": " << what
                << ". The test fails (a malformed call record: only the grading program writes those)";
  throw MalformedTrace(what);
}

void checkIndex(std::size_t points, long long index, const char* what) {
  if (index < 0 || static_cast<std::size_t>(index) >= points)
    malformed(std::string(what) + " is " + std::to_string(index) + ", but the call has " + std::to_string(points) +
              " masses");
}

void replayCall(std::uint32_t function, const char* name) {
  Reader& r = Reader::instance();
  const std::size_t call = r.calls() + 1;
  std::uint32_t recorded = 0;
  std::uint8_t outcome = 0;
  r.reading("");
  try {
    get(r, recorded);
    get(r, outcome);
  } catch (const TraceEnded&) {
    // Fail the test here, not only by the exception: a test may catch exceptions.
    ADD_FAILURE() << "SPRINGLAB_TRACE_ENDED: your code did not return from its call of " << name << " (call "
                  << call << " to your exercise file in this test): it crashed, exited or ran out of time";
    throw;
  }
  r.countCall();
  if (recorded != function) {
    ADD_FAILURE() << "your code behaves differently from one run to the next: in the run of this test, call "
                  << call << " to your exercise file was another function than " << name
                  << " (random numbers, uninitialised values, or state kept between calls?)";
    throw TraceEnded("the test took another path in the student's run");
  }
  r.reading(name);
  if (outcome > static_cast<std::uint8_t>(Outcome::Unknown)) malformed("an outcome that is no outcome");
  if (outcome == 0) return;
  const std::size_t size = getSize(r);
  if (size > kMaxMessage) malformed("an exception message of " + std::to_string(size) + " bytes");
  std::string message(size, '\0');
  r.bytes(message.data(), message.size());
  switch (static_cast<Outcome>(outcome)) {
    case Outcome::NotImplemented: {
      // "not implemented: exercise ID (TITLE), see SECTION": rebuilt from its parts.
      const auto id = message.find("exercise "), open = message.find(" ("), see = message.rfind("), see ");
      if (id != std::string::npos && open != std::string::npos && see != std::string::npos && open < see)
        throw NotImplemented(message.substr(id + 9, open - id - 9), message.substr(open + 2, see - open - 2),
                             message.substr(see + 7));
      throw std::logic_error(message);
    }
    case Outcome::InvalidArgument: throw std::invalid_argument(message);
    case Outcome::OutOfRange: throw std::out_of_range(message);
    case Outcome::LengthError: throw std::length_error(message);
    case Outcome::LogicError: throw std::logic_error(message);
    case Outcome::RuntimeError: throw std::runtime_error(message);
    case Outcome::OtherException: throw std::runtime_error(message);
    default: throw std::runtime_error("an exception that is not a std::exception");
  }
}

// ---- framework types -------------------------------------------------------------------
void put(Writer& w, const Mass& m) { put(w, m.m), put(w, m.pinned); }
void get(Reader& r, Mass& m) { get(r, m.m), get(r, m.pinned); }
void put(Writer& w, const Spring& s) {
  put(w, s.mass1), put(w, s.mass2), put(w, s.springConstant), put(w, s.springLength), put(w, s.frictionConstant),
      put(w, s.kind);
}
void get(Reader& r, Spring& s) {
  get(r, s.mass1), get(r, s.mass2), get(r, s.springConstant), get(r, s.springLength), get(r, s.frictionConstant),
      get(r, s.kind);
}
void put(Writer& w, const Triangle& t) { put(w, t.a), put(w, t.b), put(w, t.c); }
void get(Reader& r, Triangle& t) { get(r, t.a), get(r, t.b), get(r, t.c); }
void put(Writer& w, const Segment& s) { put(w, s.a), put(w, s.b); }
void get(Reader& r, Segment& s) { get(r, s.a), get(r, s.b); }

void put(Writer& w, const BlockSystem& system) {
  put(w, system.diagonalBlocks());
  put(w, system.couplingBlocks());
  put(w, system.rhs());
}
void get(Reader& r, BlockSystem& system) {
  std::vector<Mat3> diagonal, coupling;
  Eigen::VectorXd rhs;
  get(r, diagonal);
  get(r, coupling);
  get(r, rhs);
  system.setValues(diagonal, coupling, rhs);  // throws when the sizes are not the layout's
}

}  // namespace springlab::trace
