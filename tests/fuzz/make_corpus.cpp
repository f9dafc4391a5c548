// scansurf fuzzing: writes the generated seeds of tests/fuzz/corpus (run by hand; the output is
// committed): RT Structure Sets and CT series written with DCMTK (support/rtstruct_builder),
// Reconstruct series and IMOD models (support/em_writers), each a few hundred bytes to a few
// kilobytes; a multi-file input joined at kNextFile. The JSON seeds are written by hand.
// Usage: scansurf_fuzz_make_corpus CORPUSDIR
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz/fuzz_readers.h"
#include "support/em_writers.h"
#include "support/rtstruct_builder.h"

namespace fs = std::filesystem;
using namespace scansurf;
using namespace scansurf::test;

namespace {

std::string bytesOf(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The files of a folder joined at kNextFile, in name order (series file first: "s.ser" < ...).
std::string joined(std::vector<fs::path> files) {
  std::sort(files.begin(), files.end());
  std::string out;
  for (std::size_t i = 0; i < files.size(); ++i) out += (i ? std::string(fuzz::kNextFile) : "") + bytesOf(files[i]);
  return out;
}

std::vector<fs::path> filesIn(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir)) files.push_back(e.path());
  return files;
}

void put(const fs::path& path, const std::string& bytes) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << bytes;
  std::printf("wrote %s (%zu bytes)\n", path.string().c_str(), bytes.size());
}

std::vector<Point2> square(double cx, double cy, double half) {
  return {{cx - half, cy - half}, {cx + half, cy - half}, {cx + half, cy + half}, {cx - half, cy + half}};
}

void rtStructSeeds(const fs::path& out, const fs::path& tmp) {
  TestRoi organ{1, "Organ", "ORGAN", Rgb{255, 0, 0}, {}};
  for (double z : {0.0, 2.5, 5.0}) {
    organ.contours.push_back(closedContour(square(0, 0, 10), z));
    if (z == 2.5) organ.contours.push_back(closedContour(square(0, 0, 3), z));  // a hole
  }
  TestRoi body{2, "Body", "EXTERNAL", Rgb{0, 128, 255}, {}};
  for (double z : {0.0, 2.5, 5.0}) body.contours.push_back(closedContour(square(0, 0, 20), z));
  TestRoi marker{3, "Marker", "MARKER", std::nullopt, {}};
  TestContour point;
  point.type = "POINT";
  point.points = {{{1, 2, 2.5}}};
  marker.contours.push_back(point);

  TestRtStruct two;
  two.rois = {organ, body, marker};
  writeTestRtStruct(two, tmp / "a.dcm");
  put(out / "rtstruct" / "two_rois_and_a_point.dcm", bytesOf(tmp / "a.dcm"));

  TestRtStruct bare;
  bare.rois = {organ};
  bare.fileHeader = false;
  writeTestRtStruct(bare, tmp / "b.dcm");
  put(out / "rtstruct" / "no_file_header.dcm", bytesOf(tmp / "b.dcm"));

  // Near-valid: Contour Data not a multiple of 3, an ROI without contours item, a skewed contour.
  TestRoi odd{4, "Odd", "ORGAN", std::nullopt, {}};
  TestContour raw;
  raw.rawData = "1\\2\\3\\4\\5\\6\\7\\8";
  odd.contours.push_back(raw);
  TestRoi empty{5, "Empty", "ORGAN", std::nullopt, {}};
  empty.contourItem = false;
  TestRoi skew{6, "Skew", "ORGAN", std::nullopt, {}};
  TestContour tilted;
  tilted.points = {{{0, 0, 0}}, {{5, 0, 1}}, {{5, 5, 2}}};
  skew.contours.push_back(tilted);
  TestRtStruct broken;
  broken.rois = {odd, empty, skew};
  writeTestRtStruct(broken, tmp / "c.dcm");
  put(out / "rtstruct" / "malformed_rois.dcm", bytesOf(tmp / "c.dcm"));
}

void ctSeeds(const fs::path& out, const fs::path& tmp) {
  TestCt ct;
  ct.columns = 4;
  ct.rows = 4;
  ct.spacingX = 0.75;
  ct.spacingY = 0.75;
  ct.originX = -1.5;
  ct.originY = -1.5;
  ct.sliceZ = {0, 2.5, 5};
  writeTestCtSeries(ct, tmp / "ct1");
  put(out / "ct_series" / "three_slices", joined(filesIn(tmp / "ct1")));

  // Near-valid: two images at one z, and a tilted orientation in another seed.
  TestCt twice = ct;
  twice.sliceZ = {1, 1};
  writeTestCtSeries(twice, tmp / "ct2");
  put(out / "ct_series" / "two_images_at_one_z", joined(filesIn(tmp / "ct2")));

  TestCt tilted = ct;
  tilted.sliceZ = {0, 3};
  tilted.orientation = {0, 1, 0, 1, 0, 0};
  tilted.sliceThickness = 3;
  writeTestCtSeries(tilted, tmp / "ct3");
  put(out / "ct_series" / "tilted", joined(filesIn(tmp / "ct3")));
}

void reconstructSeeds(const fs::path& out, const fs::path& tmp) {
  TestSeries series;
  series.name = "s";
  series.zMidSection = true;
  for (int k = 1; k <= 3; ++k) {
    TestSection section;
    section.index = k;
    section.thickness = k == 2 ? 0.07 : 0.05;
    TestTransform image;
    image.image = true;
    section.transforms.push_back(image);
    TestTransform traces;
    traces.dim = k == 3 ? 4 : k;  // translation, scale, and a nonlinear one
    traces.xcoef = {0.1, 1.01, 0.02, k == 3 ? 0.001 : 0, 0, 0};
    traces.ycoef = {-0.1, 0.01, 0.99, k == 3 ? 0.001 : 0, 0, 0};
    traces.traces.push_back(TestTrace{"axon", square(2, 2, 0.5)});
    if (k == 2) traces.traces.push_back(TestTrace{"axon", square(2, 2, 0.2)});  // a hole
    traces.traces.push_back(TestTrace{"marker", {{0, 0}, {1, 1}}, false});
    section.transforms.push_back(traces);
    series.sections.push_back(section);
  }
  writeReconstructSeries(series, tmp / "rc");
  put(out / "reconstruct" / "three_sections", joined(filesIn(tmp / "rc")));
}

void imodSeeds(const fs::path& out) {
  TestImodModel model;
  model.pixelSize = 2.5;
  model.units = -9;
  model.scale = {1, 1, 1.5};
  model.unknownChunks = true;
  TestImodObject cell{"cell", 0, {1, 0.5, 0}, {}, true, true};
  for (float z : {0.f, 1.f, 2.f}) {
    TestImodContour c;
    for (const Point2& p : square(10, 10, 4)) c.points.push_back({static_cast<float>(p.x), static_cast<float>(p.y), z});
    cell.contours.push_back(c);
  }
  TestImodContour open{{{1, 1, 0}, {2, 2, 0}}, 1u << 3};
  cell.contours.push_back(open);
  TestImodObject scattered{"", 1u << 9, {0, 0, 1}, {TestImodContour{{{5, 5, 1}}, 0}}, false, false};
  model.objects = {cell, scattered};
  put(out / "imod" / "cell_and_scattered.mod", imodModelBytes(model));

  // Near-valid: a non-planar closed contour in an open object, and counts that disagree.
  TestImodModel odd;
  TestImodObject bent{"bent", 1u << 3, {0, 1, 0}, {TestImodContour{{{0, 0, 0}, {4, 0, 1}, {4, 4, 2}}, 0}}, false, false};
  odd.objects = {bent, bent};
  put(out / "imod" / "open_bent_objects.mod", imodModelBytes(odd));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s CORPUSDIR\n", argv[0]);
    return 2;
  }
  const fs::path out = argv[1];
  const fs::path tmp = fs::temp_directory_path() / "scansurf-fuzz-make-corpus";
  fs::remove_all(tmp);
  fs::create_directories(tmp);
  rtStructSeeds(out, tmp);
  ctSeeds(out, tmp);
  reconstructSeeds(out, tmp);
  imodSeeds(out);
  fs::remove_all(tmp);
  return 0;
}
