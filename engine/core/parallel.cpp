// scansurf: the fork-join loops of the CPU stages (see parallel.h).
#include "core/parallel.h"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

namespace scansurf {

int defaultThreadCount() {
  if (const char* env = std::getenv("SCANSURF_THREADS")) {
    const int n = std::atoi(env);
    if (n > 0) return n;
  }
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

int chunkCount(std::size_t count, int threads) {
  if (threads <= 0) threads = defaultThreadCount();
  return static_cast<int>(std::max<std::size_t>(1, std::min<std::size_t>(count, static_cast<std::size_t>(threads))));
}

void parallelChunks(std::size_t count, int threads, const std::function<void(int, std::size_t, std::size_t)>& body) {
  const int chunks = chunkCount(count, threads);
  auto bounds = [&](int c) { return count * static_cast<std::size_t>(c) / static_cast<std::size_t>(chunks); };
  if (chunks == 1) {
    body(0, 0, count);
    return;
  }
  std::exception_ptr failure;
  std::mutex failureMutex;
  auto run = [&](int c) {
    try {
      body(c, bounds(c), bounds(c + 1));
    } catch (...) {
      std::lock_guard lock(failureMutex);
      if (!failure) failure = std::current_exception();
    }
  };
  std::vector<std::thread> workers;
  workers.reserve(static_cast<std::size_t>(chunks - 1));
  for (int c = 1; c < chunks; ++c) {
    try {
      workers.emplace_back(run, c);
    } catch (const std::system_error&) {
      run(c);  // no thread to be had (a thread limit): this one does the chunk, same result
    }
  }
  run(0);
  for (std::thread& t : workers) t.join();
  if (failure) std::rethrow_exception(failure);
}

void parallelBlocks(std::size_t count, int threads, std::size_t block,
                    const std::function<void(int, std::size_t, std::size_t)>& body) {
  block = std::max<std::size_t>(block, 1);
  const std::size_t blocks = (count + block - 1) / block;
  std::atomic<std::size_t> next{0};
  parallelChunks(blocks, threads, [&](int worker, std::size_t, std::size_t) {
    for (std::size_t b = next++; b < blocks; b = next++) body(worker, b * block, std::min(count, (b + 1) * block));
  });
}

}  // namespace scansurf
