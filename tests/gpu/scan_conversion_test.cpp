// Scan conversion on the GPU against the CPU reference rasterizer, pixel for pixel.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <random>

#include "geometry/grid/content_tiles.h"
#include "geometry/overlaps/raster_rules.h"
#include "gpu/gpu_test_env.h"
#include "passes/classification.h"
#include "passes/scan_conversion.h"
#include "scansurf/vulkan_interop.h"
#include "support/reference_rasterizer.h"

namespace scansurf::test {
namespace {

Grid smallGrid(int nx, int ny, int slices, double spacing = 0.5) {
  Grid g;
  g.nx = nx;
  g.ny = ny;
  g.nz = slices + 2;
  g.originX = -1.0;
  g.originY = 2.0;
  g.spacingX = spacing;
  g.spacingY = spacing * 1.25;
  for (int k = 0; k < g.nz; ++k) g.layerZ.push_back(1.5 * k);
  return g;
}

// A random star-shaped (generally concave) polygon inside the grid's interior.
Contour randomStar(std::mt19937& rng, const Grid& g, int points) {
  std::uniform_real_distribution<double> cx(g.originX + 0.3 * g.nx * g.spacingX, g.originX + 0.7 * g.nx * g.spacingX);
  std::uniform_real_distribution<double> cy(g.originY + 0.3 * g.ny * g.spacingY, g.originY + 0.7 * g.ny * g.spacingY);
  const double maxR = 0.28 * std::min(g.nx * g.spacingX, g.ny * g.spacingY);
  std::uniform_real_distribution<double> r(0.15 * maxR, maxR);
  const double x = cx(rng), y = cy(rng);
  Contour c;
  for (int i = 0; i < points; ++i) {
    const double a = 2 * M_PI * i / points, rr = r(rng);
    c.points.push_back({x + rr * std::cos(a), y + rr * std::sin(a)});
  }
  return c;
}

std::vector<int> identityOrder(std::size_t n) {
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  return order;
}

std::size_t countMismatches(const LabelVolume& gpu, const LabelVolume& ref) {
  std::size_t bad = 0;
  for (std::size_t i = 0; i < gpu.labels.size(); ++i) bad += gpu.labels[i] != ref.labels[i];
  return bad;
}

class ScanConversionTest : public GpuTest {
 protected:
  void expectMatchesReference(const ContourSet& set, const Grid& grid, const std::vector<int>& order,
                              std::size_t batchBudget = std::size_t{64} << 20) {
    auto converter = passes::ScanConverter::create(sharedContext());
    ASSERT_TRUE(converter) << converter.error().message;
    (*converter)->setBatchBudget(batchBudget);
    auto gpu = (*converter)->run(set, grid, order);
    ASSERT_TRUE(gpu) << gpu.error().message;
    const LabelVolume ref = referenceScanConvert(set, grid, order, (*converter)->subPixelBits());
    ASSERT_EQ(gpu->labels.size(), ref.labels.size());
    EXPECT_EQ(countMismatches(*gpu, ref), 0u);
    lastBatches_ = (*converter)->lastBatchCount();
    std::size_t filled = 0;
    for (Label l : ref.labels) filled += l != kBackground;
    EXPECT_GT(filled, 0u) << "the test drew nothing";
  }
  int lastBatches_ = 0;
};

TEST_F(ScanConversionTest, RandomConcavePolygonsWithHolesAndOverlapsMatchReference) {
  for (unsigned seed = 1; seed <= 6; ++seed) {
    std::mt19937 rng(seed);
    const Grid grid = smallGrid(61 + static_cast<int>(seed), 47, 5);
    ContourSet set;
    set.source = "random";
    for (int f = 0; f < 4; ++f) {
      Feature feature;
      // std::string("f"), not "f": GCC 12 warns -Wrestrict in error on "f" + std::string here (GCC bug 105329).
      feature.name = std::string("f") + std::to_string(f);
      for (int s = 0; s < 5; ++s) {
        FeatureSlice slice;
        slice.z = grid.layerZ[static_cast<std::size_t>(s + 1)];
        const int contours = 1 + static_cast<int>(rng() % 3);  // overlapping contours: even-odd holes
        for (int c = 0; c < contours; ++c) slice.contours.push_back(randomStar(rng, grid, 5 + static_cast<int>(rng() % 30)));
        feature.slices.push_back(slice);
      }
      set.features.push_back(feature);
    }
    std::vector<int> order = identityOrder(set.features.size());
    std::shuffle(order.begin(), order.end(), rng);
    SCOPED_TRACE("seed " + std::to_string(seed));
    expectMatchesReference(set, grid, order);
  }
}

// Vertices on the half-pixel lattice put many pixel centres exactly on edges and vertices:
// the tie-breaking rule must agree, and abutting features must share their boundary
// without gap or overlap.
TEST_F(ScanConversionTest, LatticeAlignedEdgesAndAbuttingFeaturesMatchReference) {
  for (unsigned seed = 1; seed <= 6; ++seed) {
    std::mt19937 rng(100 + seed);
    const Grid grid = smallGrid(40, 36, 3, 1.0);
    auto lattice = [&](int a, int b) {  // a, b in half pixels
      return Point2{grid.originX + 0.5 * a * grid.spacingX, grid.originY + 0.5 * b * grid.spacingY};
    };
    std::uniform_int_distribution<int> coord(4, 66);
    ContourSet set;
    set.source = "lattice";
    for (int f = 0; f < 3; ++f) {
      Feature feature;
      feature.name = "f" + std::to_string(f);
      for (int s = 0; s < 3; ++s) {
        FeatureSlice slice;
        slice.z = grid.layerZ[static_cast<std::size_t>(s + 1)];
        for (int c = 0; c < 2; ++c) {
          Contour contour;
          const int n = 3 + static_cast<int>(rng() % 8);
          for (int i = 0; i < n; ++i) contour.points.push_back(lattice(coord(rng), coord(rng)));
          slice.contours.push_back(contour);
        }
        feature.slices.push_back(slice);
      }
      set.features.push_back(feature);
    }
    // Two features abutting along a shared polyline through pixel centres.
    Feature left, right;
    left.name = "left";
    right.name = "right";
    for (int s = 0; s < 3; ++s) {
      const double z = grid.layerZ[static_cast<std::size_t>(s + 1)];
      const Point2 top = lattice(35, 6), mid = lattice(31 + 2 * s, 30), bottom = lattice(37, 62);
      left.slices.push_back({z, {Contour{{lattice(6, 6), top, mid, bottom, lattice(6, 62)}}}});
      right.slices.push_back({z, {Contour{{top, lattice(70, 6), lattice(70, 62), bottom, mid}}}});
    }
    set.features.push_back(left);
    set.features.push_back(right);
    std::vector<int> order = identityOrder(set.features.size());
    std::shuffle(order.begin(), order.end(), rng);
    SCOPED_TRACE("seed " + std::to_string(seed));
    expectMatchesReference(set, grid, order);
  }
}

TEST_F(ScanConversionTest, NestedFeatureWinsAndHoleStaysEmpty) {
  Grid grid = smallGrid(24, 24, 1, 1.0);
  grid.spacingY = 1.0;
  auto square = [&](double x0, double y0, double x1, double y1) { return Contour{{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}}; };
  const double ox = grid.originX, oy = grid.originY, z = grid.layerZ[1];
  ContourSet set;
  set.source = "nested";
  // outer: a ring (square with a square hole); inner: a square inside the ring's body.
  set.features.push_back(
      {"outer", {}, {{z, {square(ox + 1.5, oy + 1.5, ox + 20.5, oy + 20.5), square(ox + 8.5, oy + 8.5, ox + 13.5, oy + 13.5)}}}});
  set.features.push_back({"inner", {}, {{z, {square(ox + 2.5, oy + 2.5, ox + 5.5, oy + 5.5)}}}});
  auto converter = passes::ScanConverter::create(sharedContext());
  ASSERT_TRUE(converter);
  auto volume = (*converter)->run(set, grid, {1, 0});
  ASSERT_TRUE(volume) << volume.error().message;
  EXPECT_EQ(volume->at(4, 4, 1), labelOfFeature(1));    // inner wins inside the outer
  EXPECT_EQ(volume->at(16, 16, 1), labelOfFeature(0));  // the ring's body
  EXPECT_EQ(volume->at(11, 11, 1), kBackground);        // the hole
  EXPECT_EQ(volume->at(0, 0, 1), kBackground);          // padding
  for (int i = 0; i < grid.nx; ++i)
    for (int j = 0; j < grid.ny; ++j) {
      EXPECT_EQ(volume->at(i, j, 0), kBackground);
      EXPECT_EQ(volume->at(i, j, 2), kBackground);
    }
  // The same with the order reversed: the outer feature covers the inner one.
  auto reversed = (*converter)->run(set, grid, {0, 1});
  ASSERT_TRUE(reversed);
  EXPECT_EQ(reversed->at(4, 4, 1), labelOfFeature(0));
}

TEST_F(ScanConversionTest, BatchesGiveTheSameVolumeAsOneSubmission) {
  std::mt19937 rng(7);
  const Grid grid = smallGrid(33, 29, 9);
  ContourSet set;
  set.source = "batches";
  Feature feature{"blob", {}, {}};
  for (int s = 0; s < 9; ++s)
    feature.slices.push_back({grid.layerZ[static_cast<std::size_t>(s + 1)], {randomStar(rng, grid, 17)}});
  set.features.push_back(feature);
  const std::size_t layerBytes = static_cast<std::size_t>(grid.nx * grid.ny) * sizeof(Label);
  expectMatchesReference(set, grid, {0}, 2 * layerBytes);
  EXPECT_EQ(lastBatches_, 5);
  expectMatchesReference(set, grid, {0});
  EXPECT_EQ(lastBatches_, 1);
}

// Labels left on the device (issue 12, item 3), in batches of an odd-sized layer (2-byte copy
// offsets): the host copy matches the reference, and classifying the device buffer gives the
// records of the host volume, so the device copy holds the same labels, padding included.
TEST_F(ScanConversionTest, LabelsLeftOnTheDeviceMatchTheHostVolume) {
  std::mt19937 rng(11);
  const Grid grid = smallGrid(33, 29, 9);
  ContourSet set;
  set.source = "device";
  set.features = {Feature{"a", {}, {}}, Feature{"b", {}, {}}};
  for (int s = 0; s < 9; ++s)
    for (Feature& f : set.features)
      f.slices.push_back({grid.layerZ[static_cast<std::size_t>(s + 1)], {randomStar(rng, grid, 13)}});
  auto converter = passes::ScanConverter::create(sharedContext());
  auto classifier = passes::Classifier::create(sharedContext());
  ASSERT_TRUE(converter && classifier);
  (*converter)->setBatchBudget(3 * static_cast<std::size_t>(grid.nx * grid.ny) * sizeof(Label));
  LabelVolume host;
  auto device = (*converter)->runOnDevice(set, grid, {0, 1}, &host);
  ASSERT_TRUE(device) << device.error().message;
  EXPECT_EQ((*converter)->lastBatchCount(), 3);
  const LabelVolume ref = referenceScanConvert(set, grid, {0, 1}, (*converter)->subPixelBits());
  ASSERT_EQ(host.labels.size(), ref.labels.size());
  EXPECT_EQ(countMismatches(host, ref), 0u);
  auto fromHost = (*classifier)->run(ref);
  auto fromDevice = (*classifier)->run(DeviceLabelVolume{device->buffer.handle(), 0, 16, device->grid});
  ASSERT_TRUE(fromHost && fromDevice);
  ASSERT_FALSE(fromHost->empty());
  ASSERT_EQ(fromDevice->size(), fromHost->size());
  EXPECT_EQ(std::memcmp(fromDevice->data(), fromHost->data(), fromHost->size() * sizeof(CellCase)), 0);
  // Bound in place, batch by batch: a layer of 1914 bytes puts most batches off the offset
  // alignment, so the shader skips the labels before the batch's first.
  auto deviceOnly = (*converter)->runOnDevice(set, grid, {0, 1}, nullptr);
  ASSERT_TRUE(deviceOnly);
  (*classifier)->setBatchBudget(4 * static_cast<std::size_t>(grid.nx * grid.ny) * sizeof(Label));
  auto inPlace =
      (*classifier)
          ->runInPlace(DeviceLabelVolume{deviceOnly->buffer.handle(), 0, 16, deviceOnly->grid}, deviceOnly->buffer.size());
  ASSERT_TRUE(inPlace) << inPlace.error().message;
  EXPECT_EQ((*classifier)->lastBatchCount(), 5);  // 2 cell layers each
  ASSERT_EQ(inPlace->size(), fromHost->size());
  EXPECT_EQ(std::memcmp(inPlace->data(), fromHost->data(), fromHost->size() * sizeof(CellCase)), 0);
  auto tooSmall =
      (*classifier)
          ->runInPlace(DeviceLabelVolume{deviceOnly->buffer.handle(), 4, 16, deviceOnly->grid}, deviceOnly->buffer.size());
  EXPECT_FALSE(tooSmall);
}

// The tiles the contours say (their boxes) hold every label scan conversion draws, on the
// layer it draws it, including contours that reach past the grid and lattice-aligned edges;
// classifying only those tiles gives every record.
TEST_F(ScanConversionTest, ContentTilesOfTheContoursHoldEveryLabel) {
  std::mt19937 rng(23);
  const Grid grid = smallGrid(96, 80, 7);
  std::uniform_real_distribution<double> unit(0, 1);
  ContourSet set;
  set.source = "tiles";
  set.features = {Feature{"a", {}, {}}, Feature{"b", {}, {}}, Feature{"c", {}, {}}};
  for (int s = 0; s < 7; ++s)
    for (std::size_t f = 0; f < set.features.size(); ++f) {
      if (unit(rng) < 0.3) continue;
      Contour c;  // a small star somewhere, some of them over the grid's edge
      const double x = grid.originX + (unit(rng) * 1.1 - 0.05) * grid.nx * grid.spacingX;
      const double y = grid.originY + (unit(rng) * 1.1 - 0.05) * grid.ny * grid.spacingY;
      for (int i = 0; i < 11; ++i) {
        const double a = 2 * M_PI * i / 11, r = (1 + 3 * unit(rng)) * grid.spacingX;
        c.points.push_back({x + r * std::cos(a), y + r * std::sin(a)});
      }
      if (s == 3 && f == 0)  // a square on pixel centres
        c.points = {{grid.originX + 10 * grid.spacingX, grid.originY + 16 * grid.spacingY},
                    {grid.originX + 24 * grid.spacingX, grid.originY + 16 * grid.spacingY},
                    {grid.originX + 24 * grid.spacingX, grid.originY + 40 * grid.spacingY},
                    {grid.originX + 10 * grid.spacingX, grid.originY + 40 * grid.spacingY}};
      set.features[f].slices.push_back({grid.layerZ[static_cast<std::size_t>(s + 1)], {c}});
    }
  auto converter = passes::ScanConverter::create(sharedContext());
  auto classifier = passes::Classifier::create(sharedContext());
  ASSERT_TRUE(converter && classifier);
  LabelVolume host;
  auto device = (*converter)->runOnDevice(set, grid, {0, 1, 2}, &host);
  ASSERT_TRUE(device) << device.error().message;
  const ContentTiles exact = contentTilesOf(host), content = contentTilesOf(grid, set);
  ASSERT_EQ(exact.marks.size(), content.marks.size());
  std::size_t marked = 0, drawn = 0;
  for (std::size_t t = 0; t < exact.marks.size(); ++t) {
    EXPECT_TRUE(!exact.marks[t] || content.marks[t]) << "tile " << t << " holds a label the contours did not mark";
    marked += content.marks[t], drawn += exact.marks[t];
  }
  EXPECT_GT(drawn, 10u);
  EXPECT_LT(marked, content.marks.size() / 2);  // most of the volume is skipped
  auto all = (*classifier)->run(host);
  auto tiled =
      (*classifier)
          ->runInPlace(DeviceLabelVolume{device->buffer.handle(), 0, 16, device->grid}, device->buffer.size(), false, &content);
  ASSERT_TRUE(all && tiled) << (tiled ? "" : tiled.error().message);
  ASSERT_FALSE(all->empty());
  ASSERT_EQ(tiled->size(), all->size());
  EXPECT_EQ(std::memcmp(tiled->data(), all->data(), all->size() * sizeof(CellCase)), 0);
}

}  // namespace
}  // namespace scansurf::test
