// scansurf fuzzing: the reader targets (fuzz_readers.h). Each writes the input into a scratch
// folder of its process and reads it through the public API (readContours, listRois,
// listObjects), or, for the CT series that only --reference reads, through readCtSeries inside
// guarded() as readContours calls it.
#include "fuzz/fuzz_readers.h"

#include <unistd.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <vector>

#include "core/guard.h"
#include "io/ct_series.h"
#include "scansurf/input.h"

namespace scansurf::fuzz {
namespace {

namespace fs = std::filesystem;

// A folder of this process's own, emptied before each input and removed at exit.
class Scratch {
 public:
  Scratch() : dir_(fs::temp_directory_path() / ("scansurf-fuzz-" + std::to_string(::getpid()))) {}
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  const fs::path& fresh() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
    fs::create_directories(dir_);
    return dir_;
  }

 private:
  fs::path dir_;
};

const fs::path& freshScratch() {
  static Scratch scratch;
  return scratch.fresh();
}

std::string_view textOf(std::span<const std::uint8_t> input) {
  return {reinterpret_cast<const char*>(input.data()), input.size()};
}

// The input cut at kNextFile.
std::vector<std::string_view> partsOf(std::span<const std::uint8_t> input) {
  std::vector<std::string_view> parts;
  std::string_view rest = textOf(input);
  for (std::size_t at = rest.find(kNextFile); at != std::string_view::npos; at = rest.find(kNextFile)) {
    parts.push_back(rest.substr(0, at));
    rest.remove_prefix(at + kNextFile.size());
  }
  parts.push_back(rest);
  return parts;
}

void writeFile(const fs::path& path, std::string_view bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// Errc::Internal is a bug whatever the input; every other error is an answer.
template <typename T>
bool isBug(const Result<T>& result, Verdict& verdict, std::string_view call) {
  if (result || result.error().code != Errc::Internal) return false;
  verdict = {Outcome::Bug, std::string(call) + ": internal error: " + result.error().message};
  return true;
}

Verdict contoursJson(std::span<const std::uint8_t> input) {
  const fs::path path = freshScratch() / "input.json";
  writeFile(path, textOf(input));
  if (detectInputFormat(path) != InputFormat::ContoursJson) return {Outcome::OtherFormat, {}};
  Verdict verdict;
  isBug(readContours(path), verdict, "readContours");
  return verdict;
}

// One input file of `format`: read, then listed (listRois or listObjects).
template <typename List>
Verdict readAndList(std::span<const std::uint8_t> input, const char* name, InputFormat format, List list, const char* listName) {
  const fs::path path = freshScratch() / name;
  writeFile(path, textOf(input));
  if (detectInputFormat(path) != format) return {Outcome::OtherFormat, {}};
  Verdict verdict;
  if (isBug(readContours(path), verdict, "readContours")) return verdict;
  isBug(list(path), verdict, listName);
  return verdict;
}

Verdict rtStruct(std::span<const std::uint8_t> input) {
  return readAndList(
      input, "input.dcm", InputFormat::RtStruct, [](const fs::path& p) { return listRois(p); }, "listRois");
}

// The images of a series, one file each; read as --reference reads them, then a two-slice
// contour set placed on the first and last slice.
Verdict ctSeries(std::span<const std::uint8_t> input) {
  const fs::path& dir = freshScratch();
  const std::vector<std::string_view> parts = partsOf(input);
  for (std::size_t i = 0; i < parts.size(); ++i) writeFile(dir / ("ct_" + std::to_string(i) + ".dcm"), parts[i]);
  Verdict verdict;
  const auto ct = guarded("reading the series", [&] { return readCtSeries(dir); });
  if (isBug(ct, verdict, "readCtSeries") || !ct) return verdict;
  if (ct->sliceZ.empty() || ct->files.size() != ct->sliceZ.size())
    return {Outcome::Bug, "readCtSeries: a series without slices, or not one file per slice"};
  const auto placed = guarded("placing contours", [&]() -> Result<void> {
    (void)gridReferenceOf(*ct);
    ContourSet contours;
    Feature feature;
    feature.name = "square";
    const std::vector<Point2> square{{ct->originX, ct->originY},
                                     {ct->originX + 4 * ct->spacingX, ct->originY},
                                     {ct->originX + 4 * ct->spacingX, ct->originY + 4 * ct->spacingY},
                                     {ct->originX, ct->originY + 4 * ct->spacingY}};
    feature.slices.push_back({ct->sliceZ.front(), {{square}}});
    if (ct->sliceZ.size() > 1) feature.slices.push_back({ct->sliceZ.back(), {{square}}});
    contours.features.push_back(std::move(feature));
    SCANSURF_TRY(placeOnCtSlices(contours, *ct, 0.01));
    return {};
  });
  isBug(placed, verdict, "placeOnCtSlices");
  return verdict;
}

// A series file and its sections: the first part is s.ser, the next ones s.1, s.2, ...; read
// from the series file and, when there are sections, from the first section file.
Verdict reconstruct(std::span<const std::uint8_t> input) {
  const fs::path& dir = freshScratch();
  const std::vector<std::string_view> parts = partsOf(input);
  writeFile(dir / "s.ser", parts.front());
  for (std::size_t i = 1; i < parts.size(); ++i) writeFile(dir / ("s." + std::to_string(i)), parts[i]);
  if (detectInputFormat(dir / "s.ser") != InputFormat::ReconstructSeries) return {Outcome::OtherFormat, {}};
  Verdict verdict;
  if (isBug(readContours(dir / "s.ser"), verdict, "readContours") || isBug(listObjects(dir / "s.ser"), verdict, "listObjects"))
    return verdict;
  if (parts.size() > 1 && detectInputFormat(dir / "s.1") == InputFormat::ReconstructSeries)
    isBug(readContours(dir / "s.1"), verdict, "readContours of a section file");
  return verdict;
}

Verdict imod(std::span<const std::uint8_t> input) {
  return readAndList(
      input, "input.mod", InputFormat::ImodModel, [](const fs::path& p) { return listObjects(p); }, "listObjects");
}

constexpr std::array kTargets{
    Target{"contours_json", contoursJson}, Target{"rtstruct", rtStruct}, Target{"ct_series", ctSeries},
    Target{"reconstruct", reconstruct},    Target{"imod", imod},
};

}  // namespace

std::span<const Target> targets() { return kTargets; }

const Target* findTarget(std::string_view name) {
  for (const Target& t : kTargets)
    if (t.name == name) return &t;
  return nullptr;
}

}  // namespace scansurf::fuzz
