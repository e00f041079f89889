#include "parallel.hpp"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <exception>
#include <mutex>
#include <thread>
#include <unistd.h>
#include <vector>

namespace springlab::studies {

void parallelFor(int count, int threads, const std::function<void(int)>& task, const std::string& label) {
  if (count <= 0) return;
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  threads = std::min(threads, count);
  // Progress only on a terminal: logs (ctest, CI) get the summary lines alone.
  const bool show = !label.empty() && isatty(fileno(stderr));

  // Workers take the next index until none is left; the first error stops new work.
  std::atomic<int> next{0};
  std::atomic<int> done{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::mutex mutex;
  auto worker = [&] {
    for (int i = next++; i < count && !failed; i = next++) {
      try {
        task(i);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!error) error = std::current_exception();
        failed = true;
      }
      const int finished = ++done;
      if (show) {
        std::lock_guard<std::mutex> lock(mutex);
        std::fprintf(stderr, "\r%s: %d/%d", label.c_str(), finished, count);
        if (finished == count) std::fprintf(stderr, "\n");
        std::fflush(stderr);
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace springlab::studies
