// scansurf fuzzing: every contour reader fed one input, as the file (or files) it reads.
//
// The input is what libFuzzer makes, or a file of tests/fuzz/corpus or tests/fuzz/regressions.
// A reader's error is a fine answer to any input; a crash, a sanitizer report, a hang or an
// internal error (Errc::Internal: a broken invariant) is a finding. Readers that read several
// files (a Reconstruct series, a CT series) get the input cut at kNextFile into one file each.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace scansurf::fuzz {

// Separates the files of one input (a line of its own, so the seeds stay readable text).
inline constexpr std::string_view kNextFile = "\n--scansurf-fuzz-next-file--\n";

enum class Outcome {
  Read,         // the reader read it or refused it with an error (either is fine)
  OtherFormat,  // the content is another format than the target's: not read (libFuzzer drops it)
  Bug,          // Errc::Internal, or a reader broke its contract: `detail` says which
};

struct Verdict {
  Outcome outcome = Outcome::Read;
  std::string detail;
};

struct Target {
  std::string_view name;  // also the folder of its corpus and regressions
  Verdict (*run)(std::span<const std::uint8_t> input);
};

// The targets: contours_json, rtstruct, ct_series, reconstruct, imod.
std::span<const Target> targets();
const Target* findTarget(std::string_view name);

}  // namespace scansurf::fuzz
