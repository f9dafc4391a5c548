// The fork-join loops of the CPU stages: every item once, on any thread count.
#include "core/parallel.h"

#include <gtest/gtest.h>

#include <atomic>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace scansurf {
namespace {

TEST(ParallelBlocks, VisitsEveryItemOnceInBlocksOfTheGivenSize) {
  for (int threads : {1, 2, 3, 8})
    for (std::size_t block : {std::size_t{1}, std::size_t{7}, std::size_t{64}, std::size_t{1000}}) {
      const std::size_t count = 997;
      std::vector<std::atomic<int>> visits(count);
      std::atomic<int> workersOutOfRange{0}, badBlocks{0};
      parallelBlocks(count, threads, block, [&](int worker, std::size_t begin, std::size_t end) {
        if (worker < 0 || worker >= threads) ++workersOutOfRange;
        if (begin % block != 0 || end - begin > block || (end - begin < block && end != count)) ++badBlocks;
        for (std::size_t i = begin; i < end; ++i) ++visits[i];
      });
      int once = 0;
      for (const auto& v : visits) once += v == 1;
      EXPECT_EQ(once, static_cast<int>(count)) << threads << " threads, blocks of " << block;
      EXPECT_EQ(workersOutOfRange, 0);
      EXPECT_EQ(badBlocks, 0);
    }
}

TEST(ParallelBlocks, PerItemResultsAreTheSameForAnyThreadCount) {
  const auto squares = [](int threads) {
    std::vector<long> out(5000);
    parallelBlocks(out.size(), threads, 16, [&](int, std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) out[i] = static_cast<long>(i * i);
    });
    return out;
  };
  const std::vector<long> one = squares(1);
  EXPECT_EQ(one[4999], 4999L * 4999L);
  for (int threads : {2, 3, 5}) EXPECT_EQ(squares(threads), one);
}

TEST(ParallelBlocks, RethrowsABodysException) {
  EXPECT_THROW(parallelBlocks(100, 2, 10,
                              [](int, std::size_t begin, std::size_t) {
                                if (begin == 50) throw std::runtime_error("block 5");
                              }),
               std::runtime_error);
}

TEST(ParallelBlocks, NothingToDoCallsNothing) {
  int calls = 0;
  parallelBlocks(0, 2, 8, [&](int, std::size_t, std::size_t) { ++calls; });
  EXPECT_EQ(calls, 0);
}

}  // namespace
}  // namespace scansurf
