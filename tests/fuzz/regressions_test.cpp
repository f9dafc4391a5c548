// scansurf fuzzing in the ordinary test suite: every file of tests/fuzz/regressions/<target>
// (inputs that crashed or hung a reader once) and of tests/fuzz/corpus/<target> (the seeds) fed
// to its reader target as the fuzzer feeds it; each must read or fail with an error, in
// seconds (the test's timeout catches a hang).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "fuzz/fuzz_readers.h"

namespace scansurf::fuzz {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> filesIn(const fs::path& dir) {
  std::vector<fs::path> files;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (it->is_regular_file() && it->path().filename().string().front() != '.') files.push_back(it->path());
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<std::uint8_t> bytesOf(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class FuzzInputs : public ::testing::TestWithParam<std::string_view> {};

TEST_P(FuzzInputs, ReadOrFailCleanly) {
  const Target* target = findTarget(GetParam());
  ASSERT_NE(target, nullptr);
  const fs::path root = SCANSURF_FUZZ_DIR;
  std::vector<fs::path> files = filesIn(root / "regressions" / target->name);
  const std::size_t regressions = files.size();
  for (const fs::path& f : filesIn(root / "corpus" / target->name)) files.push_back(f);
  EXPECT_GT(files.size() - regressions, 0u) << "no seed corpus in " << (root / "corpus" / target->name);
  for (const fs::path& file : files) {
    const auto start = std::chrono::steady_clock::now();
    const Verdict verdict = target->run(bytesOf(file));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_NE(verdict.outcome, Outcome::Bug) << file << ": " << verdict.detail;
    // A seed of another format would fuzz nothing of its target.
    if (file.parent_path().parent_path().filename() == "corpus") {
      EXPECT_EQ(verdict.outcome, Outcome::Read) << file << ": read as another format than " << target->name;
    }
    EXPECT_LT(seconds, 10.0) << file << ": took " << seconds << " s";
  }
  std::printf("%s: %zu regression inputs, %zu seeds\n", std::string(target->name).c_str(), regressions,
              files.size() - regressions);
}

std::string nameOf(const ::testing::TestParamInfo<std::string_view>& info) { return std::string(info.param); }

INSTANTIATE_TEST_SUITE_P(Readers, FuzzInputs, ::testing::Values("contours_json", "rtstruct", "ct_series", "reconstruct", "imod"),
                         nameOf);

}  // namespace
}  // namespace scansurf::fuzz
