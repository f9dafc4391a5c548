// Electron-microscopy tracing formats: Reconstruct series and IMOD models written by the tests
// (several objects, holes, branches, every Transform dimension, uneven section thickness,
// hidden and open traces, micrometre units), read back and surfaced with the CPU pipeline;
// input recognised by content; every refusal.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>

#include "geometry/extraction/assembly.h"
#include "geometry/extraction/cell_cases.h"
#include "geometry/extraction/feature_surfaces.h"
#include "io/imod_reader.h"
#include "io/reconstruct_reader.h"
#include "scansurf/grid.h"
#include "scansurf/input.h"
#include "scansurf/nesting.h"
#include "support/em_writers.h"
#include "support/reference_rasterizer.h"
#include "support/scratch_dir_test.h"

namespace scansurf {
namespace {

namespace fs = std::filesystem;
using test::TestImodContour;
using test::TestImodModel;
using test::TestImodObject;
using test::TestSection;
using test::TestSeries;
using test::TestTrace;
using test::TestTransform;

const std::string kMicrometre = "\xC2\xB5m";

std::vector<Point2> square(double cx, double cy, double half) {
  return {{cx - half, cy - half}, {cx + half, cy - half}, {cx + half, cy + half}, {cx - half, cy + half}};
}

// A regular polygon of n corners (counter-clockwise).
std::vector<Point2> polygon(double cx, double cy, double r, int n) {
  std::vector<Point2> pts;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * i / n;
    pts.push_back({cx + r * std::cos(a), cy + r * std::sin(a)});
  }
  return pts;
}

double polygonArea(const std::vector<Point2>& pts) {
  double twice = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Point2 a = pts[i], b = pts[(i + 1) % pts.size()];
    twice += a.x * b.y - b.x * a.y;
  }
  return std::abs(twice) / 2;
}

bool containsText(const std::vector<std::string>& lines, const std::string& text) {
  for (const std::string& line : lines)
    if (line.find(text) != std::string::npos) return true;
  return false;
}

void expectSamePoints(const std::vector<Point2>& got, const std::vector<Point2>& want, double tolerance,
                      const std::string& what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_NEAR(got[i].x, want[i].x, tolerance) << what << " point " << i;
    EXPECT_NEAR(got[i].y, want[i].y, tolerance) << what << " point " << i;
  }
}

// ------------------------------------------------------------------ the CPU surfacing pipeline

struct Built {
  Grid grid;
  Nesting nesting;
  MultiLabelMesh mesh;
  std::vector<FeatureSurface> features;
  MeshStats stats(int f) const { return computeMeshStats(mesh.positions, features[static_cast<std::size_t>(f)].triangles); }
  // Bounding box (min x, min y, min z, max x, max y, max z) of a feature's surface.
  std::array<double, 6> box(int f) const {
    std::array<double, 6> b{1e300, 1e300, 1e300, -1e300, -1e300, -1e300};
    for (std::uint32_t v : features[static_cast<std::size_t>(f)].triangles)
      for (int c = 0; c < 3; ++c) {
        b[c] = std::min(b[c], static_cast<double>(mesh.positions[3 * v + c]));
        b[c + 3] = std::max(b[c + 3], static_cast<double>(mesh.positions[3 * v + c]));
      }
    return b;
  }
};

Built buildCpu(const ContourSet& set, double voxelSize) {
  Built b;
  b.nesting = computeNesting(set);
  GridOptions options;
  options.voxelSize = voxelSize;
  auto grid = makeGrid(set, options);
  EXPECT_TRUE(grid) << grid.error().message;
  if (!grid) return b;
  b.grid = *grid;
  const LabelVolume volume = test::referenceScanConvert(set, b.grid, b.nesting.order, 8);
  b.mesh = assembleMesh(b.grid, classifyCellsReference(volume));
  b.features = extractFeatureSurfaces(b.mesh, static_cast<int>(set.features.size()), b.nesting, SurfaceConvention::Enclosing);
  return b;
}

// The volume the method gives a stack of slices: each slice's area over the slab halfway to
// its neighbours (the end slices reach as far as their one neighbour is away).
double slabVolume(const std::vector<double>& z, const std::vector<double>& area) {
  double v = 0;
  for (std::size_t i = 0; i < z.size(); ++i) {
    const double below = i > 0 ? z[i] - z[i - 1] : z[1] - z[0];
    const double above = i + 1 < z.size() ? z[i + 1] - z[i] : z[i] - z[i - 1];
    v += area[i] * (below + above) / 2;
  }
  return v;
}

// ------------------------------------------------------------------------- Reconstruct

// One transform per dimension, each a plausible alignment of a section (units: µm).
TestTransform transformOfDim(int dim) {
  TestTransform t;
  t.dim = dim;
  const double c = std::cos(0.17), s = std::sin(0.17);
  switch (dim) {
    case 0: break;
    case 1: t.xcoef = {0.31, 1, 0, 0, 0, 0}, t.ycoef = {-0.22, 0, 1, 0, 0, 0}; break;
    case 2: t.xcoef = {0.12, 1.05, 0, 0, 0, 0}, t.ycoef = {-0.08, 0.93, 0, 0, 0, 0}; break;  // b1 scales y
    case 3: t.xcoef = {0.4, 1.02 * c, -1.02 * s, 0, 0, 0}, t.ycoef = {-0.3, 0.98 * s, 0.98 * c, 0, 0, 0}; break;
    case 4: t.xcoef = {0.2, c, -s, 0.011, 0, 0}, t.ycoef = {0.1, s, c, -0.019, 0, 0}; break;
    case 5: t.xcoef = {-0.1, 1.01, 0.02, 0.008, 0.006, 0}, t.ycoef = {0.15, -0.03, 0.99, 0.004, -0.005, 0}; break;
    default: t.xcoef = {0.05, 0.97, 0.04, -0.01, 0.004, -0.006}, t.ycoef = {-0.12, 0.05, 1.03, 0.007, 0.003, 0.009}; break;
  }
  return t;
}

struct SeriesSpec {
  TestSeries series;
  std::vector<double> thickness;
};

// Seven sections of uneven thickness, the traces of section k (1..7) under a Transform of dim
// k - 1, each section with its image and domain outline:
// - "axon": a 1 µm square around (2, 2) on every section, with a 0.4 µm hole on sections 3-5;
//   hidden on section 2 (still data);
// - "dendrite": a 1 x 0.6 µm rectangle around (4, 1) on sections 1-3 that branches into two
//   squares on 4-7 (the second branch in a second trace Transform on section 4);
// - "spine": closed on sections 2-4, one open trace on section 5;
// - "marker": open traces only (sections 1 and 2).
SeriesSpec cellsSeries() {
  SeriesSpec spec;
  spec.series.name = "cells";
  spec.thickness = {0.05, 0.07, 0.05, 0.06, 0.05, 0.08, 0.045};
  for (int k = 1; k <= 7; ++k) {
    TestSection section;
    section.index = k;
    section.thickness = spec.thickness[static_cast<std::size_t>(k - 1)];
    TestTransform image;
    image.image = true;
    section.transforms.push_back(image);
    TestTransform traces = transformOfDim(k - 1);
    TestTrace axon{"axon", square(2, 2, 0.5)};
    axon.border = {1, 0.5, 0};
    axon.hidden = k == 2;
    traces.traces.push_back(axon);
    if (k >= 3 && k <= 5) {
      TestTrace hole{"axon", square(2, 2, 0.2)};
      hole.border = {1, 0.5, 0};
      traces.traces.push_back(hole);
    }
    TestTrace dendrite{"dendrite", {{3.5, 0.7}, {4.5, 0.7}, {4.5, 1.3}, {3.5, 1.3}}};
    if (k >= 4) dendrite.points = square(3.75, 1, 0.2);
    dendrite.border = {0, 0, 1};
    traces.traces.push_back(dendrite);
    TestTrace branch{"dendrite", square(4.3, 1, 0.15)};
    branch.border = {0, 0, 1};
    if (k >= 5) traces.traces.push_back(branch);
    if (k >= 2 && k <= 4) traces.traces.push_back(TestTrace{"spine", polygon(0.8, 3.2, 0.2, 12), true, false, {0, 1, 0}});
    if (k == 5) traces.traces.push_back(TestTrace{"spine", {{0.7, 3}, {0.9, 3.4}}, false, false, {0, 1, 0}});
    if (k <= 2) traces.traces.push_back(TestTrace{"marker", {{5, 5}, {5.5, 5.2}, {6, 5}}, false, false, {1, 1, 0}});
    section.transforms.push_back(traces);
    if (k == 4) {  // the second branch drawn under another alignment
      TestTransform other = transformOfDim(3);
      other.xcoef[0] = -0.5;
      branch.hidden = true;
      other.traces.push_back(branch);
      section.transforms.push_back(other);
    }
    spec.series.sections.push_back(section);
  }
  return spec;
}

// Reconstruct's section depth: thicknesses of the lower sections plus the own (or half).
std::vector<double> sectionZ(const std::vector<double>& thickness, bool middle) {
  std::vector<double> z;
  double below = 0;
  for (double t : thickness) {
    z.push_back(below + (middle ? t / 2 : t));
    below += t;
  }
  return z;
}

class Reconstruct : public test::ScratchDirTest {
 protected:
  fs::path write(const TestSeries& series) {
    test::writeReconstructSeries(series, dir_);
    return dir_ / (series.name + ".ser");
  }
  std::string errorOf(const fs::path& path, Errc code = Errc::InvalidInput) {
    auto r = readReconstructSeries(path);
    EXPECT_FALSE(r);
    if (r) return {};
    EXPECT_EQ(r.error().code, code) << r.error().message;
    return r.error().message;
  }
};

TEST(ReconstructTransform, EveryDimensionInvertsItsForwardMapping) {
  for (int dim = 0; dim <= 6; ++dim) {
    const TestTransform t = transformOfDim(dim);
    auto transform = ReconstructTransform::fromFile(dim, {t.xcoef.begin(), t.xcoef.end()}, {t.ycoef.begin(), t.ycoef.end()});
    ASSERT_TRUE(transform) << transform.error().message;
    for (double x = -3; x <= 6; x += 0.75)
      for (double y = -2; y <= 7; y += 0.8) {
        const Point2 stored = test::reconstructForward(dim, t.xcoef, t.ycoef, {x, y});
        const Point2 mine = transform->forward({x, y});
        EXPECT_NEAR(mine.x, stored.x, 1e-12) << "dim " << dim;
        EXPECT_NEAR(mine.y, stored.y, 1e-12) << "dim " << dim;
        auto back = transform->inverse(stored);
        ASSERT_TRUE(back) << back.error().message;
        EXPECT_NEAR(back->x, x, 1e-10) << "dim " << dim;
        EXPECT_NEAR(back->y, y, 1e-10) << "dim " << dim;
      }
  }
}

TEST(ReconstructTransform, DimSelectsTheTermsAndBadTransformsAreRefused) {
  // dim 1 is a translation whatever the other coefficients say; dim 3 ignores the x y term.
  auto t1 = ReconstructTransform::fromFile(1, {2, 5, 5, 5, 5, 5}, {3, 5, 5, 5, 5, 5});
  ASSERT_TRUE(t1);
  EXPECT_EQ(t1->forward({1, 1}).x, 3);
  EXPECT_EQ(t1->forward({1, 1}).y, 4);
  auto t3 = ReconstructTransform::fromFile(3, {0, 2, 0, 7, 0, 0}, {0, 0, 2, 7, 0, 0});
  ASSERT_TRUE(t3);
  EXPECT_EQ(t3->forward({1, 1}).x, 2);
  EXPECT_FALSE(ReconstructTransform::fromFile(7, {}, {}));
  EXPECT_FALSE(ReconstructTransform::fromFile(-1, {}, {}));
  auto singular = ReconstructTransform::fromFile(3, {0, 1, 2, 0, 0, 0}, {0, 2, 4, 0, 0, 0});
  ASSERT_TRUE(singular);
  auto inverse = singular->inverse({1, 1});
  ASSERT_FALSE(inverse);
  EXPECT_NE(inverse.error().message.find("singular"), std::string::npos);
}

TEST_F(Reconstruct, SeriesReadsObjectsSectionsTransformsAndColours) {
  const SeriesSpec spec = cellsSeries();
  auto r = readReconstructSeries(write(spec.series));
  ASSERT_TRUE(r) << r.error().message;
  const ContourSet& set = r->contours;
  EXPECT_EQ(set.units, kMicrometre);
  EXPECT_EQ(r->sections, 7);
  EXPECT_EQ(r->name, "cells");
  // Objects by name; "marker" (open traces only) is listed but not surfaced, and neither the
  // palette trace nor the domain outlines are objects.
  ASSERT_EQ(r->objects.size(), 4u);
  EXPECT_EQ(r->objects[0].name, "axon");
  EXPECT_EQ(r->objects[1].name, "dendrite");
  EXPECT_EQ(r->objects[2].name, "marker");
  EXPECT_EQ(r->objects[3].name, "spine");
  EXPECT_EQ(r->objects[2].feature, -1);
  EXPECT_EQ(r->objects[2].skipped, 2);
  EXPECT_EQ(r->objects[3].skipped, 1);
  EXPECT_EQ(r->objects[0].contours, 10);
  EXPECT_EQ(r->objects[1].contours, 11);
  ASSERT_EQ(set.features.size(), 3u);
  EXPECT_EQ(set.features[0].name, "axon");
  EXPECT_EQ(set.features[1].name, "dendrite");
  EXPECT_EQ(set.features[2].name, "spine");
  EXPECT_EQ(set.features[0].color, (Rgb{255, 128, 0}));
  EXPECT_EQ(set.features[1].color, (Rgb{0, 0, 255}));
  EXPECT_EQ(set.features[2].color, (Rgb{0, 255, 0}));
  // One warning per object with open traces.
  EXPECT_TRUE(containsText(set.warnings, "object \"spine\": skipped 1 open trace(s)"));
  EXPECT_TRUE(containsText(set.warnings, "object \"marker\": skipped 2 open trace(s) (it has no closed trace)"));
  EXPECT_EQ(set.warnings.size(), 2u);

  // z: the depth through the uneven thicknesses, to the top of each section.
  const std::vector<double> z = sectionZ(spec.thickness, false);
  const Feature& axon = set.features[0];
  ASSERT_EQ(axon.slices.size(), 7u);
  for (std::size_t k = 0; k < 7; ++k) {
    EXPECT_DOUBLE_EQ(axon.slices[k].z, z[k]) << "section " << k + 1;
    // Every Transform dimension maps the stored points back onto the drawn square.
    ASSERT_EQ(axon.slices[k].contours.size(), k >= 2 && k <= 4 ? 2u : 1u) << "section " << k + 1;
    expectSamePoints(axon.slices[k].contours[0].points, square(2, 2, 0.5), 1e-9, "axon, section " + std::to_string(k + 1));
    if (k >= 2 && k <= 4)
      expectSamePoints(axon.slices[k].contours[1].points, square(2, 2, 0.2), 1e-9, "axon hole, section " + std::to_string(k + 1));
  }
  const Feature& dendrite = set.features[1];
  ASSERT_EQ(dendrite.slices.size(), 7u);
  for (std::size_t k = 0; k < 7; ++k) EXPECT_EQ(dendrite.slices[k].contours.size(), k >= 3 ? 2u : 1u) << "section " << k + 1;
  expectSamePoints(dendrite.slices[3].contours[1].points, square(4.3, 1, 0.15), 1e-9, "dendrite branch, section 4");
  const Feature& spine = set.features[2];
  ASSERT_EQ(spine.slices.size(), 3u);
  EXPECT_DOUBLE_EQ(spine.slices[0].z, z[1]);
  EXPECT_DOUBLE_EQ(spine.slices[2].z, z[3]);
  expectSamePoints(spine.slices[1].contours[0].points, polygon(0.8, 3.2, 0.2, 12), 1e-9, "spine");
  EXPECT_DOUBLE_EQ(r->objects[0].zMin, z.front());
  EXPECT_DOUBLE_EQ(r->objects[0].zMax, z.back());
  EXPECT_EQ(r->objects[0].slices, 7);
}

// A Transform far off (a translation of 1e20) maps every point of a trace onto one double:
// refused naming the section, trace and point, where the trace once vanished as degenerate and
// took its section with it (exit 0).
TEST_F(Reconstruct, ATransformBeyondTheCoordinateLimitIsRefused) {
  for (const char* name : {"tiny.ser", "tiny.1", "tiny.2", "tiny.3"})
    fs::copy_file(fs::path(SCANSURF_TEST_DATA) / "reconstruct" / name, dir_ / name);
  std::ifstream in(dir_ / "tiny.2");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  in.close();
  const std::size_t at = text.find("xcoef=\" 0.1 1 0 0 0 0\"");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, std::string("xcoef=\" 0.1 1 0 0 0 0\"").size(), "xcoef=\" 1e20 1 0 0 0 0\"");
  std::ofstream(dir_ / "tiny.2", std::ios::trunc) << text;
  const std::string message = errorOf(dir_ / "tiny.ser");
  EXPECT_NE(message.find("tiny.2: section 2, trace \"soma\""), std::string::npos) << message;
  EXPECT_NE(message.find("point 1: its Transform maps it to (-1e+20"), std::string::npos) << message;
  EXPECT_NE(message.find("beyond 1e+07 units from the origin"), std::string::npos) << message;
}

TEST_F(Reconstruct, ZMidSectionPlacesSectionsAtTheirMiddles) {
  SeriesSpec spec = cellsSeries();
  spec.series.zMidSection = true;
  auto r = readReconstructSeries(write(spec.series));
  ASSERT_TRUE(r) << r.error().message;
  const std::vector<double> z = sectionZ(spec.thickness, true);
  for (std::size_t k = 0; k < 7; ++k) EXPECT_DOUBLE_EQ(r->contours.features[0].slices[k].z, z[k]);
}

TEST_F(Reconstruct, MissingSectionNumbersLeaveNoGapAndSectionZeroStaysAtZero) {
  TestSeries series;
  series.name = "gaps";
  for (int index : {0, 2, 5}) {
    TestSection s;
    s.index = index;
    s.thickness = index == 2 ? 0.1 : 0.05;
    TestTransform t;
    t.traces.push_back(TestTrace{"cell", square(0, 0, 1)});
    s.transforms.push_back(t);
    series.sections.push_back(s);
  }
  auto r = readReconstructSeries(write(series));
  ASSERT_TRUE(r) << r.error().message;
  const Feature& cell = r->contours.features[0];
  ASSERT_EQ(cell.slices.size(), 3u);
  EXPECT_DOUBLE_EQ(cell.slices[0].z, 0);
  EXPECT_DOUBLE_EQ(cell.slices[1].z, 0.1);
  EXPECT_DOUBLE_EQ(cell.slices[2].z, 0.15);
}

TEST_F(Reconstruct, ASectionFileReadsTheWholeSeries) {
  const SeriesSpec spec = cellsSeries();
  const fs::path ser = write(spec.series);
  auto fromSeries = readReconstructSeries(ser);
  auto fromSection = readReconstructSeries(dir_ / "cells.4");
  ASSERT_TRUE(fromSeries) << fromSeries.error().message;
  ASSERT_TRUE(fromSection) << fromSection.error().message;
  EXPECT_EQ(fromSection->seriesFile, ser);
  EXPECT_EQ(fromSection->sections, 7);
  ASSERT_EQ(fromSection->contours.features.size(), fromSeries->contours.features.size());
  for (std::size_t f = 0; f < fromSeries->contours.features.size(); ++f)
    EXPECT_EQ(fromSection->contours.features[f].slices.size(), fromSeries->contours.features[f].slices.size());
  // Through the public entry, by content.
  EXPECT_EQ(detectInputFormat(dir_ / "cells.4"), InputFormat::ReconstructSeries);
  EXPECT_EQ(detectInputFormat(ser), InputFormat::ReconstructSeries);
  auto viaApi = readContours(dir_ / "cells.4");
  ASSERT_TRUE(viaApi) << viaApi.error().message;
  EXPECT_EQ(viaApi->features.size(), 3u);
  EXPECT_EQ(viaApi->units, kMicrometre);
  EXPECT_TRUE(containsText(viaApi->notes, "Reconstruct series \"cells\": 7 sections"));
}

TEST_F(Reconstruct, SectionsWithoutTheirSeriesFileUseReconstructsDefaults) {
  SeriesSpec spec = cellsSeries();
  spec.series.writeSeriesFile = false;
  spec.series.units = "nm";  // not written: the defaults apply
  write(spec.series);
  auto r = readReconstructSeries(dir_ / "cells.2");
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(r->seriesFile.empty());
  EXPECT_EQ(r->sections, 7);
  EXPECT_EQ(r->contours.units, kMicrometre);
  EXPECT_TRUE(containsText(r->contours.warnings, "no series file cells.ser beside it"));
}

TEST_F(Reconstruct, ObjectPatternsSelectAndAPatternMatchingNothingIsRefused) {
  const fs::path ser = write(cellsSeries().series);
  ReconstructOptions options;
  options.objectPatterns = {"D*", "sp?ne"};
  auto r = readReconstructSeries(ser, options);
  ASSERT_TRUE(r) << r.error().message;
  ASSERT_EQ(r->contours.features.size(), 2u);
  EXPECT_EQ(r->contours.features[0].name, "dendrite");
  EXPECT_EQ(r->contours.features[1].name, "spine");
  EXPECT_FALSE(r->objects[0].selected);

  options.objectPatterns = {"axon", "nucleus*"};
  auto none = readReconstructSeries(ser, options);
  ASSERT_FALSE(none);
  EXPECT_EQ(none.error().code, Errc::InvalidArgument);
  EXPECT_NE(none.error().message.find("cells.ser: the object pattern \"nucleus*\" matches no object; the file holds \"axon\", "
                                      "\"dendrite\", \"marker\", \"spine\""),
            std::string::npos)
      << none.error().message;

  // Through the public API, and the listing.
  ReadOptions read;
  read.objectPatterns = {"nucleus*"};
  auto viaApi = readContours(ser, read);
  ASSERT_FALSE(viaApi);
  EXPECT_EQ(viaApi.error().code, Errc::InvalidArgument);
  auto listing = listObjects(ser, {"axon"});
  ASSERT_TRUE(listing) << listing.error().message;
  EXPECT_EQ(listing->format, InputFormat::ReconstructSeries);
  EXPECT_EQ(listing->units, kMicrometre);
  ASSERT_EQ(listing->objects.size(), 4u);
  EXPECT_TRUE(listing->objects[0].selected);
  EXPECT_EQ(listing->objects[0].feature, 0);
  EXPECT_FALSE(listing->objects[1].selected);
  EXPECT_EQ(listing->objects[1].slices, 7);
  EXPECT_EQ(listing->objects[2].contours, 0);
  // ROI options do not apply to Reconstruct input, nor object patterns to JSON.
  ReadOptions roi;
  roi.roiPatterns = {"axon"};
  auto wrong = readContours(ser, roi);
  ASSERT_FALSE(wrong);
  EXPECT_EQ(wrong.error().code, Errc::InvalidArgument);
  EXPECT_NE(wrong.error().message.find("an object pattern"), std::string::npos);
}

TEST_F(Reconstruct, SurfacesAreClosedWithTheVolumesAndPositionsOfTheTraces) {
  const SeriesSpec spec = cellsSeries();
  auto r = readReconstructSeries(write(spec.series));
  ASSERT_TRUE(r) << r.error().message;
  const Built b = buildCpu(r->contours, 0.01);
  const std::vector<double> z = sectionZ(spec.thickness, false);
  std::vector<double> axonArea, dendriteArea;
  for (int k = 1; k <= 7; ++k) {
    axonArea.push_back(1.0 - (k >= 3 && k <= 5 ? 0.16 : 0.0));
    dendriteArea.push_back(k >= 4 ? 0.16 + 0.09 : 0.6);
  }
  const double expected[2] = {slabVolume(z, axonArea), slabVolume(z, dendriteArea)};
  for (int f = 0; f < 3; ++f) {
    const MeshStats s = b.stats(f);
    EXPECT_TRUE(s.closed && s.manifold && s.oriented) << r->contours.features[static_cast<std::size_t>(f)].name;
    if (f < 2) {
      EXPECT_NEAR(s.volume, expected[f], 0.02 * expected[f]) << r->contours.features[static_cast<std::size_t>(f)].name;
    }
  }
  EXPECT_EQ(b.stats(0).components, 2);  // the outside and the cavity the hole of sections 3-5 makes
  EXPECT_EQ(b.stats(1).components, 1);  // one dendrite, branching
  const auto axon = b.box(0);
  EXPECT_NEAR(axon[0], 1.5, 0.02);
  EXPECT_NEAR(axon[1], 1.5, 0.02);
  EXPECT_NEAR(axon[3], 2.5, 0.02);
  EXPECT_NEAR(axon[4], 2.5, 0.02);
  EXPECT_GT(axon[2], z.front() - (z[1] - z[0]));
  EXPECT_LT(axon[2], z.front());
  EXPECT_GT(axon[5], z.back());
  EXPECT_LT(axon[5], z.back() + (z[6] - z[5]));
}

TEST_F(Reconstruct, MalformedFilesAreRefusedNamingFileSectionAndTrace) {
  const fs::path ser = write(cellsSeries().series);
  {
    std::ofstream(dir_ / "cells.3") << "<?xml version=\"1.0\"?>\n<Section index=\"3\" thickness=\"0.05\">\n"
                                       "<Transform dim=\"0\" xcoef=\"0 1 0 0 0 0\" ycoef=\"0 0 1 0 0 0\">\n"
                                       "<Contour name=\"axon\" closed=\"true\" points=\"1 1, 2 2, 1 2,\"/>\n"
                                       "</Section>\n";
  }
  std::string message = errorOf(ser);
  EXPECT_NE(message.find("cells.3: malformed XML at line 5"), std::string::npos) << message;

  std::ofstream(dir_ / "cells.3")
      << "<Section index=\"3\" thickness=\"0.05\"><Transform dim=\"7\" xcoef=\"0 1 0 0 0 0\" "
         "ycoef=\"0 0 1 0 0 0\"><Contour name=\"axon\" points=\"1 1, 2 2, 1 2\"/></Transform></Section>";
  message = errorOf(ser);
  EXPECT_NE(message.find("cells.3: section 3, Transform #1: Transform dim=7 (Reconstruct defines 0 to 6)"), std::string::npos)
      << message;

  std::ofstream(dir_ / "cells.3")
      << "<Section index=\"3\" thickness=\"0.05\"><Transform dim=\"0\"><Contour name=\"axon\" "
         "points=\"1 1, 2 2, 1 2\"/><Contour name=\"axon\" points=\"1 1, 2 x, 1 2\"/></Transform></Section>";
  message = errorOf(ser);
  EXPECT_NE(message.find("cells.3: section 3, trace \"axon\" (#2 in the section): points hold \"x\", not a number"),
            std::string::npos)
      << message;

  std::ofstream(dir_ / "cells.3") << "<Section index=\"3\" thickness=\"0.05\"><Transform dim=\"0\"><Contour name=\"axon\" "
                                     "points=\"1 1, 2 2, 1\"/></Transform></Section>";
  message = errorOf(ser);
  EXPECT_NE(message.find("points hold 5 numbers, not x y pairs"), std::string::npos) << message;

  std::ofstream(dir_ / "cells.3") << "<Section index=\"3\"><Transform dim=\"0\"/></Section>";
  message = errorOf(ser);
  EXPECT_NE(message.find("cells.3: section 3: missing attribute thickness"), std::string::npos) << message;

  std::ofstream(dir_ / "cells.3") << "<Section index=\"4\" thickness=\"0.05\"><Transform dim=\"0\"/></Section>";
  message = errorOf(ser);
  EXPECT_NE(message.find("section index 4 is also"), std::string::npos) << message;

  std::ofstream(dir_ / "cells.3")
      << "<Section index=\"3\" thickness=\"0.05\"><Transform dim=\"3\" xcoef=\"0 1 1 0 0 0\" "
         "ycoef=\"0 1 1 0 0 0\"><Contour name=\"axon\" points=\"1 1, 2 2, 1 2\"/></Transform></Section>";
  message = errorOf(ser);
  EXPECT_NE(message.find("cells.3: section 3, trace \"axon\" (#1 in the section), point 1: the Transform (dim 3) is singular"),
            std::string::npos)
      << message;

  std::ofstream(dir_ / "cells.3") << "<Series units=\"microns\"/>";
  message = errorOf(ser);
  EXPECT_NE(message.find("cells.3: not a Reconstruct section file (root element <Series>, expected <Section>)"),
            std::string::npos)
      << message;

  fs::remove_all(dir_);
  fs::create_directories(dir_);
  std::ofstream(dir_ / "lonely.ser") << "<?xml version=\"1.0\"?>\n<Series units=\"microns\"></Series>\n";
  message = errorOf(dir_ / "lonely.ser");
  EXPECT_NE(message.find("lonely.ser: no section files lonely.<number> beside it"), std::string::npos) << message;
}

// ----------------------------------------------------------------------------------- IMOD

TestImodContour contourAt(const std::vector<Point2>& pts, float z, std::uint32_t flags = 0) {
  TestImodContour c;
  c.flags = flags;
  for (const Point2& p : pts) c.points.push_back({static_cast<float>(p.x), static_cast<float>(p.y), z});
  return c;
}

// 10 nm pixels, 50 nm sections (zscale 5), in µm:
// 1 "mito": an octagon (radius 40 px) around (100, 100) on z 10-14, a hole on z 12, and a
//   branch around (200, 100) on z 13-14; a mesh and a material chunk;
// 2 "er": an open object;
// 3 unnamed: closed contours on z 20-22 and one open contour;
// 4 "vesicles": scattered points;
// 5 "mito" again: one square on z 30.
TestImodModel cellModel() {
  TestImodModel m;
  m.name = "cell model";
  m.pixelSize = 0.01f;
  m.units = -6;
  m.scale = {1, 1, 5};
  m.unknownChunks = true;
  TestImodObject mito{"mito", 0, {0, 1, 0}, {}, true, true};
  for (int z = 10; z <= 14; ++z) {
    mito.contours.push_back(contourAt(polygon(100, 100, 40, 8), static_cast<float>(z)));
    if (z == 12) mito.contours.push_back(contourAt(polygon(100, 100, 15, 8), 12));
    if (z >= 13) mito.contours.push_back(contourAt(square(200, 100, 20), static_cast<float>(z)));
  }
  TestImodObject er{"er", 1u << 3, {1, 0, 0}, {contourAt({{0, 0}, {50, 50}, {100, 0}}, 10)}};
  TestImodObject unnamed{"", 0, {0.2f, 0.4f, 0.6f}, {}};
  for (int z = 20; z <= 22; ++z) unnamed.contours.push_back(contourAt(square(300, 300, 30), static_cast<float>(z)));
  unnamed.contours.push_back(contourAt({{290, 290}, {310, 310}}, 21, 1u << 3));
  TestImodObject vesicles{"vesicles", 1u << 9, {1, 1, 0}, {contourAt({{10, 10}, {20, 20}}, 15)}};
  TestImodObject mito2{"mito", 0, {0, 0, 1}, {contourAt(square(400, 400, 10), 30)}};
  m.objects = {mito, er, unnamed, vesicles, mito2};
  return m;
}

class Imod : public test::ScratchDirTest {
 protected:
  fs::path write(const TestImodModel& model, const std::string& name = "cell.mod") {
    test::writeImodModel(model, dir_ / name);
    return dir_ / name;
  }
  std::string errorOf(const fs::path& path, Errc code = Errc::InvalidInput, ImodOptions options = {}) {
    auto r = readImodModel(path, options);
    EXPECT_FALSE(r);
    if (r) return {};
    EXPECT_EQ(r.error().code, code) << r.error().message;
    return r.error().message;
  }
};

TEST_F(Imod, ModelReadsClosedObjectsInModelUnits) {
  auto r = readImodModel(write(cellModel()));
  ASSERT_TRUE(r) << r.error().message;
  const ContourSet& set = r->contours;
  EXPECT_EQ(set.units, kMicrometre);
  EXPECT_EQ(r->name, "cell model");
  ASSERT_EQ(r->objects.size(), 5u);
  EXPECT_EQ(r->objects[2].name, "object 3");
  EXPECT_EQ(r->objects[4].name, "mito #5");
  EXPECT_EQ(r->objects[1].skipped, 1);
  EXPECT_EQ(r->objects[2].skipped, 1);
  EXPECT_EQ(r->objects[3].feature, -1);
  ASSERT_EQ(set.features.size(), 3u);
  EXPECT_EQ(set.features[0].name, "mito");
  EXPECT_EQ(set.features[1].name, "object 3");
  EXPECT_EQ(set.features[2].name, "mito #5");
  EXPECT_EQ(set.features[0].color, (Rgb{0, 255, 0}));
  EXPECT_EQ(set.features[1].color, (Rgb{51, 102, 153}));
  EXPECT_TRUE(containsText(set.warnings, "cell.mod: object 2 \"er\": an open object, skipped (1 contours)"));
  EXPECT_TRUE(containsText(set.warnings, "cell.mod: object 4 \"vesicles\": scattered points, skipped"));
  EXPECT_TRUE(containsText(set.warnings, "cell.mod: object 3 \"object 3\": skipped 1 open contour(s)"));
  EXPECT_TRUE(containsText(set.warnings, "name used by another object; the feature is called \"mito #5\""));
  EXPECT_EQ(set.warnings.size(), 4u);

  // Contours grouped by z; (x, y, z) * scale * pixel size.
  const Feature& mito = set.features[0];
  ASSERT_EQ(mito.slices.size(), 5u);
  for (std::size_t k = 0; k < 5; ++k) {
    EXPECT_NEAR(mito.slices[k].z, (10.0 + static_cast<double>(k)) * 5 * 0.01, 1e-7);
    EXPECT_EQ(mito.slices[k].contours.size(), k == 2 || k >= 3 ? 2u : 1u);
  }
  std::vector<Point2> octagon;
  for (const Point2& p : polygon(100, 100, 40, 8))
    octagon.push_back({static_cast<float>(p.x) * 0.01, static_cast<float>(p.y) * 0.01});
  expectSamePoints(mito.slices[0].contours[0].points, octagon, 1e-6, "mito");
  EXPECT_NEAR(set.features[2].slices[0].z, 1.5, 1e-6);
  EXPECT_NEAR(r->objects[0].zMin, 0.5, 1e-7);
  EXPECT_NEAR(r->objects[0].zMax, 0.7, 1e-7);
  EXPECT_EQ(r->objects[0].slices, 5);
  EXPECT_EQ(r->objects[0].contours, 8);
}

TEST_F(Imod, SurfacesAreClosedWithTheVolumesAndPositionsOfTheContours) {
  TestImodModel model = cellModel();
  model.objects.resize(1);  // mito alone
  auto r = readImodModel(write(model));
  ASSERT_TRUE(r) << r.error().message;
  const Built b = buildCpu(r->contours, 0.01);
  const MeshStats s = b.stats(0);
  EXPECT_TRUE(s.closed && s.manifold && s.oriented);
  const double octagon = polygonArea(polygon(0, 0, 0.4, 8)), hole = polygonArea(polygon(0, 0, 0.15, 8));
  std::vector<double> z, area;
  for (int k = 10; k <= 14; ++k) {
    z.push_back(k * 0.05);
    area.push_back(octagon - (k == 12 ? hole : 0) + (k >= 13 ? 0.16 : 0));
  }
  const double expected = slabVolume(z, area);
  EXPECT_NEAR(s.volume, expected, 0.02 * expected);
  const auto box = b.box(0);
  EXPECT_NEAR(box[0], 0.6, 0.02);
  EXPECT_NEAR(box[3], 2.2, 0.02);
  EXPECT_NEAR(box[1], 0.6, 0.02);
}

TEST_F(Imod, ThroughThePublicApiAndTheListing) {
  const fs::path path = write(cellModel());
  EXPECT_EQ(detectInputFormat(path), InputFormat::ImodModel);
  ReadOptions options;
  options.objectPatterns = {"MITO*"};
  auto r = readContours(path, options);
  ASSERT_TRUE(r) << r.error().message;
  ASSERT_EQ(r->features.size(), 2u);
  EXPECT_EQ(r->features[1].name, "mito #5");
  EXPECT_EQ(r->features[1].sourceNumber, 5) << "the object's number, for the report";
  EXPECT_EQ(r->frame, CoordinateFrame::Specimen) << "an EM model is no patient";
  EXPECT_TRUE(containsText(r->notes, "IMOD model \"cell model\": 5 objects, 2 surfaced; pixel size 0.01"));
  auto listing = listObjects(path, {"object ?"});
  ASSERT_TRUE(listing) << listing.error().message;
  EXPECT_EQ(listing->format, InputFormat::ImodModel);
  ASSERT_EQ(listing->objects.size(), 5u);
  EXPECT_FALSE(listing->objects[0].selected);
  EXPECT_TRUE(listing->objects[2].selected);
  EXPECT_EQ(listing->objects[2].feature, 0);
  EXPECT_EQ(listing->objects[2].slices, 3);
  options.objectPatterns = {"nucleus"};
  auto none = readContours(path, options);
  ASSERT_FALSE(none);
  EXPECT_EQ(none.error().code, Errc::InvalidArgument);
  EXPECT_NE(none.error().message.find("the object pattern \"nucleus\" matches no object; the file holds \"mito\", \"er\", "
                                      "\"object 3\", \"vesicles\", \"mito #5\""),
            std::string::npos)
      << none.error().message;
}

TEST_F(Imod, ANonPlanarContourIsAnErrorNamingObjectAndContour) {
  TestImodModel model = cellModel();
  model.objects[0].contours[3].points[2][2] = 13.5f;  // z 12's hole, one point off its plane
  const fs::path path = write(model);
  const std::string message = errorOf(path);
  EXPECT_NE(message.find("cell.mod: object 1 \"mito\", contour 4: not planar: its points span z 12 .. 13.5"), std::string::npos)
      << message;
  // Unselected, or only listed, it does not stop the reading.
  ImodOptions others;
  others.objectPatterns = {"object*"};
  EXPECT_TRUE(readImodModel(path, others));
  auto listing = listObjects(path);
  ASSERT_TRUE(listing) << listing.error().message;
  EXPECT_EQ(listing->objects[0].skipped, 1);
}

TEST_F(Imod, TruncatedModelsAreRefusedAtEveryLength) {
  const std::string bytes = test::imodModelBytes(cellModel());
  for (std::size_t length = 0; length < bytes.size(); length += length < 300 ? 1 : 37) {
    test::writeBytes(bytes.substr(0, length), dir_ / "cut.mod");
    auto r = readImodModel(dir_ / "cut.mod");
    ASSERT_FALSE(r) << "length " << length;
    EXPECT_EQ(r.error().code, Errc::InvalidInput) << "length " << length;
    EXPECT_NE(r.error().message.find("cut.mod: truncated"), std::string::npos)
        << "length " << length << ": " << r.error().message;
  }
  test::writeBytes(bytes.substr(0, 8 + 232 + 4 + 100), dir_ / "cut.mod");
  const std::string message = errorOf(dir_ / "cut.mod");
  EXPECT_NE(message.find("cut.mod: truncated: object 1: the OBJT chunk needs 176 bytes at offset 244, but the file ends at 344"),
            std::string::npos)
      << message;
}

TEST_F(Imod, BadHeadersAndChunksAreRefused) {
  TestImodModel model = cellModel();
  model.pixelSize = 0;
  EXPECT_NE(errorOf(write(model)).find("pixel size 0 in the model header"), std::string::npos);
  model = cellModel();
  model.scale[2] = -5;
  EXPECT_NE(errorOf(write(model)).find("zscale -5 in the model header"), std::string::npos);

  std::string bytes = test::imodModelBytes(cellModel());
  std::string version = bytes;
  version.replace(4, 4, "V9.9");
  test::writeBytes(version, dir_ / "version.mod");
  EXPECT_NE(errorOf(dir_ / "version.mod").find("IMOD model version \"V9.9\""), std::string::npos);
  // The object count of the header (offset 8 + 140) raised by one.
  std::string count = bytes;
  count[8 + 143] = static_cast<char>(count[8 + 143] + 1);
  test::writeBytes(count, dir_ / "count.mod");
  EXPECT_NE(errorOf(dir_ / "count.mod").find("the model header gives 6 objects, the file holds 5"), std::string::npos);
  // A chunk with a negative size.
  std::string negative = bytes;
  const auto zzzz = negative.find("ZZZZ");
  ASSERT_NE(zzzz, std::string::npos);
  negative.replace(zzzz + 4, 4, "\xff\xff\xff\xf0");
  test::writeBytes(negative, dir_ / "negative.mod");
  EXPECT_NE(errorOf(dir_ / "negative.mod").find("chunk \"ZZZZ\" at offset"), std::string::npos);
}

// -------------------------------------------------------------------- input by content

class InputByContent : public test::ScratchDirTest {
 protected:
  fs::path file(const std::string& name, const std::string& bytes) {
    test::writeBytes(bytes, dir_ / name);
    return dir_ / name;
  }
};

TEST_F(InputByContent, EachFormatIsRecognisedByItsContent) {
  EXPECT_EQ(detectInputFormat(file("a.txt", "  \n{\"version\": 1}")), InputFormat::ContoursJson);
  EXPECT_EQ(detectInputFormat(file("broken.json", "not json")), InputFormat::ContoursJson);  // its parser explains
  EXPECT_EQ(detectInputFormat(file("p10", std::string(128, '\0') + "DICM" + std::string(20, '\0'))), InputFormat::RtStruct);
  // Data sets without the Part 10 header: implicit VR (a length) or explicit VR.
  EXPECT_EQ(detectInputFormat(file("implicit", std::string("\x08\x00\x05\x00\x0a\x00\x00\x00ISO_IR 100", 18))),
            InputFormat::RtStruct);
  EXPECT_EQ(detectInputFormat(file("explicit", std::string("\x08\x00\x16\x00UI\x1a\x00", 8) + std::string(26, '1'))),
            InputFormat::RtStruct);
  EXPECT_EQ(detectInputFormat(file("odd-group", std::string("\x09\x00\x05\x00\x0a\x00\x00\x00ISO_IR 100", 18))),
            InputFormat::Unknown);
  EXPECT_EQ(detectInputFormat(file("model", test::imodModelBytes(cellModel()))), InputFormat::ImodModel);
  EXPECT_EQ(detectInputFormat(file("s.ser",
                                   "\xEF\xBB\xBF<?xml version=\"1.0\"?>\n<!DOCTYPE Series SYSTEM \"series.dtd\">\n"
                                   "<!-- a comment -->\n<Series units=\"microns\"/>")),
            InputFormat::ReconstructSeries);
  EXPECT_EQ(detectInputFormat(file("s.7", "<Section index=\"7\" thickness=\"0.05\"/>")), InputFormat::ReconstructSeries);
  EXPECT_EQ(detectInputFormat(file("other.xml", "<?xml version=\"1.0\"?><svg/>")), InputFormat::Unknown);
  EXPECT_EQ(detectInputFormat(file("empty", "")), InputFormat::Unknown);
  EXPECT_EQ(detectInputFormat(file("png", "\x89PNG\r\n\x1a\n")), InputFormat::Unknown);
}

TEST_F(InputByContent, AHeaderlessDicomDataSetIsReadAsDicom) {
  const fs::path sample = fs::path(SCANSURF_RTSTRUCT_SAMPLES) / "pydicom-rtstruct.dcm";
  if (!fs::exists(sample)) GTEST_SKIP() << "no public RTSTRUCT sample at " << sample << " (../shared beside the clone)";
  EXPECT_EQ(detectInputFormat(sample), InputFormat::RtStruct);
  auto r = readContours(sample);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_EQ(r->units, "mm");
  EXPECT_FALSE(r->features.empty());
}

TEST_F(InputByContent, AnythingElseIsRefusedListingTheSupportedFormats) {
  const std::vector<std::array<std::string, 3>> cases = {
      {"notes.txt", "hello, contours", "it starts with \"hello, contours\""},
      {"image.png", "\x89PNG\r\n\x1a\n", "it starts with \"\\x89PNG\\x0D\\x0A\\x1A\\x0A\""},
      {"empty.dat", "", "it is empty"},
      {"page.xml", "<html></html>", "it starts with \"<html></html>\""}};
  for (const auto& [name, bytes, start] : cases) {
    const fs::path path = file(name, bytes);
    auto r = readContours(path);
    ASSERT_FALSE(r) << name;
    EXPECT_EQ(r.error().code, Errc::InvalidInput) << name;
    const std::string& m = r.error().message;
    EXPECT_NE(m.find(path.string() + ": not a contour file scansurf reads (" + start + ")"), std::string::npos) << m;
    for (const char* format : {"contour-set JSON", "DICOM RT Structure Set", "Reconstruct series", "IMOD binary model"})
      EXPECT_NE(m.find(format), std::string::npos) << m;
    auto listing = listObjects(path);
    ASSERT_FALSE(listing);
    EXPECT_EQ(listing.error().code, Errc::InvalidInput);
  }
  auto missing = readContours(dir_ / "no-such-file");
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().code, Errc::Io);
  auto json = listObjects(file("set.json", "{}"));
  ASSERT_FALSE(json);
  EXPECT_EQ(json.error().code, Errc::InvalidArgument);
}

}  // namespace
}  // namespace scansurf
