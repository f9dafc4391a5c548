// scansurf fuzzing: one libFuzzer executable per reader target; SCANSURF_FUZZ_TARGET names it
// (tests/fuzz/CMakeLists.txt builds this file once per target).
#include <cstdio>
#include <cstdlib>

#include "fuzz/fuzz_readers.h"

namespace {
const scansurf::fuzz::Target& target() {
  static const scansurf::fuzz::Target* t = scansurf::fuzz::findTarget(SCANSURF_FUZZ_TARGET);
  if (t == nullptr) {
    std::fprintf(stderr, "no fuzz target named %s\n", SCANSURF_FUZZ_TARGET);
    std::abort();
  }
  return *t;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const scansurf::fuzz::Verdict verdict = target().run({data, size});
  switch (verdict.outcome) {
    case scansurf::fuzz::Outcome::Read: return 0;
    case scansurf::fuzz::Outcome::OtherFormat: return -1;  // not kept in the corpus
    case scansurf::fuzz::Outcome::Bug: break;
  }
  std::fprintf(stderr, "scansurf fuzz target %s: %s\n", SCANSURF_FUZZ_TARGET, verdict.detail.c_str());
  std::abort();
}
