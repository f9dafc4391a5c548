// scansurf: minimal fork-join loops for the CPU stages: equal chunks, or blocks taken in turn.
#pragma once

#include <cstddef>
#include <functional>

namespace scansurf {

// Threads to use when a caller passes 0: SCANSURF_THREADS if set, else the hardware's.
int defaultThreadCount();

// Splits [0, count) into at most `threads` contiguous chunks (0 = defaultThreadCount()) and
// runs body(chunkIndex, begin, end) on each, the first on the calling thread. Returns when
// all are done. Chunks are the same for the same count and threads, so results that depend
// only on the chunk split are deterministic. Exceptions in a body are rethrown here.
void parallelChunks(std::size_t count, int threads,
                    const std::function<void(int chunk, std::size_t begin, std::size_t end)>& body);

// The number of chunks parallelChunks will use for count and threads.
int chunkCount(std::size_t count, int threads);

// Runs body(worker, begin, end) over [0, count) in blocks of `block` items that up to `threads`
// workers (0 = defaultThreadCount()) take in turn as each finishes its last: for work whose
// cost per item varies, where equal chunks would leave a worker idle. Which worker takes a
// block varies from run to run, so a body must write only what its items own (per-item
// results); `worker` (below the thread count) indexes per-worker scratch. Exceptions in a body
// are rethrown here.
void parallelBlocks(std::size_t count, int threads, std::size_t block,
                    const std::function<void(int worker, std::size_t begin, std::size_t end)>& body);

}  // namespace scansurf
