// scansurf: a minimal fork-join loop for the CPU stages (assembly, smoothing).
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

}  // namespace scansurf
