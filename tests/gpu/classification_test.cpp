// Tetrahedral classification on the GPU against the CPU reference: identical records.
#include <cmath>
#include <cstring>
#include <random>

#include "geometry/extraction/cell_cases.h"
#include "geometry/grid/content_tiles.h"
#include "gpu/gpu_test_env.h"
#include "gpu/resources.h"
#include "passes/classification.h"

namespace scansurf::test {
namespace {

// Random blobs of labels: smooth enough to have large uniform regions, with every pattern
// of 2, 3 and 4 labels per tetrahedron somewhere.
LabelVolume randomVolume(unsigned seed, int nx, int ny, int nz, int labels) {
  std::mt19937 rng(seed);
  LabelVolume v;
  v.grid.nx = nx;
  v.grid.ny = ny;
  v.grid.nz = nz;
  for (int k = 0; k < nz; ++k) v.grid.layerZ.push_back(k);
  v.labels.assign(v.grid.voxelCount(), 0);
  std::uniform_int_distribution<int> label(0, labels);
  std::uniform_real_distribution<double> unit(0, 1);
  struct Seed {
    double x, y, z, r;
    Label l;
  };
  std::vector<Seed> seeds;
  for (int s = 0; s < 12; ++s)
    seeds.push_back({unit(rng) * nx, unit(rng) * ny, unit(rng) * nz, 1 + unit(rng) * nx / 3, static_cast<Label>(label(rng))});
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        Label l = 0;
        for (const Seed& s : seeds) {
          const double dx = i - s.x, dy = j - s.y, dz = k - s.z;
          if (dx * dx + dy * dy + dz * dz < s.r * s.r) l = s.l;
        }
        if (unit(rng) < 0.02) l = static_cast<Label>(label(rng));  // salt: isolated voxels
        v.labels[v.grid.index(i, j, k)] = l;
      }
  return v;
}

void expectSameRecords(const std::vector<CellCase>& gpu, const std::vector<CellCase>& ref) {
  ASSERT_EQ(gpu.size(), ref.size());
  std::size_t bad = 0;
  for (std::size_t i = 0; i < gpu.size(); ++i) {
    const bool same = gpu[i].cell == ref[i].cell && gpu[i].tetCodes == ref[i].tetCodes && gpu[i].labels[0] == ref[i].labels[0] &&
                      gpu[i].labels[1] == ref[i].labels[1] && gpu[i].labels[2] == ref[i].labels[2] &&
                      gpu[i].labels[3] == ref[i].labels[3];
    if (!same && bad++ < 5) ADD_FAILURE() << "record " << i << " differs (cell " << gpu[i].cell << " vs " << ref[i].cell << ")";
  }
  EXPECT_EQ(bad, 0u);
}

using ClassificationTest = GpuTest;

// v's labels (16-bit) in a device buffer of their own, classified in place over content's tiles.
Result<std::vector<CellCase>> classifyTiled(passes::Classifier& classifier, const LabelVolume& v, const ContentTiles& content) {
  const std::size_t bytes = v.labels.size() * sizeof(Label);
  SCANSURF_ASSIGN_OR_RETURN(gpu::Buffer buffer, gpu::Buffer::create(sharedContext(), bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                                                    gpu::MemoryDomain::Upload));
  std::memcpy(buffer.mapped(), v.labels.data(), bytes);
  return classifier.runInPlace(DeviceLabelVolume{buffer.handle(), 0, 16, v.grid}, buffer.size(), false, &content);
}

TEST_F(ClassificationTest, RandomVolumesMatchReference) {
  auto classifier = passes::Classifier::create(sharedContext());
  ASSERT_TRUE(classifier) << classifier.error().message;
  for (unsigned seed = 1; seed <= 8; ++seed) {
    const LabelVolume v =
        randomVolume(seed, 17 + static_cast<int>(seed), 23, 11 + static_cast<int>(seed % 3), 2 + static_cast<int>(seed % 4));
    auto gpu = (*classifier)->run(v);
    ASSERT_TRUE(gpu) << gpu.error().message;
    const std::vector<CellCase> ref = classifyCellsReference(v);
    EXPECT_GT(ref.size(), 100u);
    SCOPED_TRACE("seed " + std::to_string(seed));
    expectSameRecords(*gpu, ref);
  }
}

// Batches and the growth of the record buffer (it starts with room for 4096 records).
TEST_F(ClassificationTest, BatchesAndBufferGrowthGiveTheSameRecords) {
  auto classifier = passes::Classifier::create(sharedContext());
  ASSERT_TRUE(classifier);
  const LabelVolume v = randomVolume(42, 40, 37, 30, 5);
  const std::vector<CellCase> ref = classifyCellsReference(v);
  ASSERT_GT(ref.size(), 4096u);
  (*classifier)->setBatchBudget(static_cast<std::size_t>(40 * 37 * 2) * 4 + 4);
  auto batchbed = (*classifier)->run(v);
  ASSERT_TRUE(batchbed) << batchbed.error().message;
  EXPECT_GE((*classifier)->lastBatchCount(), 10);
  expectSameRecords(*batchbed, ref);
}

// Labels already on the device (16 and 32 bits, at an offset in the buffer), classified in
// batches copied on the device: the same records as the CPU reference.
TEST_F(ClassificationTest, DeviceLabelsInBatchesMatchReference) {
  auto classifier = passes::Classifier::create(sharedContext());
  ASSERT_TRUE(classifier);
  const LabelVolume v = randomVolume(7, 40, 37, 30, 5);
  const std::vector<CellCase> ref = classifyCellsReference(v);
  (*classifier)->setBatchBudget(static_cast<std::size_t>(40 * 37 * 2) * 4 + 4);
  for (std::uint32_t bits : {16u, 32u}) {
    SCOPED_TRACE(std::to_string(bits) + "-bit labels");
    const std::size_t bytes = v.labels.size() * bits / 8, offset = 12;
    auto buffer =
        gpu::Buffer::create(sharedContext(), offset + bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, gpu::MemoryDomain::Upload);
    ASSERT_TRUE(buffer) << buffer.error().message;
    auto* out = static_cast<std::uint8_t*>(buffer->mapped()) + offset;
    if (bits == 16) {
      std::memcpy(out, v.labels.data(), bytes);
    } else {
      const std::vector<std::uint32_t> wide(v.labels.begin(), v.labels.end());
      std::memcpy(out, wide.data(), bytes);
    }
    DeviceLabelVolume device{buffer->handle(), offset, bits, v.grid};
    auto gpu = (*classifier)->run(device);
    ASSERT_TRUE(gpu) << gpu.error().message;
    EXPECT_GE((*classifier)->lastBatchCount(), 10);
    expectSameRecords(*gpu, ref);
  }
}

// Content tiles: blobs in a wide empty margin, and layers with nothing at all, classified in
// place over the marked tiles only (in small batches, some of them empty): the same records as
// every cell, and fewer visited.
TEST_F(ClassificationTest, ContentTilesGiveTheSameRecords) {
  auto classifier = passes::Classifier::create(sharedContext());
  ASSERT_TRUE(classifier);
  LabelVolume v = randomVolume(11, 70, 61, 24, 4);
  for (int k = 0; k < v.grid.nz; ++k)
    for (int j = 0; j < v.grid.ny; ++j)
      for (int i = 0; i < v.grid.nx; ++i)
        if (i < 20 || i > 45 || j < 9 || j > 38 || (k >= 8 && k < 16)) v.labels[v.grid.index(i, j, k)] = kBackground;
  const std::vector<CellCase> ref = classifyCellsReference(v);
  ASSERT_GT(ref.size(), 1000u);
  const ContentTiles content = contentTilesOf(v);
  EXPECT_LT(std::count(content.marks.begin(), content.marks.end(), 1), static_cast<long>(content.marks.size() / 4));
  (*classifier)->setBatchBudget(static_cast<std::size_t>(70 * 61 * 2) * 4 + 4);
  auto tiled = classifyTiled(**classifier, v, content);
  ASSERT_TRUE(tiled) << tiled.error().message;
  EXPECT_GE((*classifier)->lastBatchCount(), 6);
  expectSameRecords(*tiled, ref);
  ContentTiles wrong = content;
  wrong.layers += 1;
  EXPECT_FALSE(classifyTiled(**classifier, v, wrong));
}

// More tiles than one row of a dispatch holds (16384): 1030 x 1030 columns, 129 x 129 tiles,
// every one marked; rings of labels so that every row of tiles holds surface.
TEST_F(ClassificationTest, ContentTilesBeyondOneDispatchRow) {
  auto classifier = passes::Classifier::create(sharedContext());
  ASSERT_TRUE(classifier);
  LabelVolume v;
  v.grid.nx = v.grid.ny = 1030;
  v.grid.nz = 3;
  v.grid.layerZ = {0, 1, 2};
  v.labels.assign(v.grid.voxelCount(), kBackground);
  for (int j = 0; j < v.grid.ny; ++j)
    for (int i = 0; i < v.grid.nx; ++i) {
      const int r = static_cast<int>(std::hypot(i - 515.0, j - 515.0));
      v.labels[v.grid.index(i, j, 1)] = static_cast<Label>(r < 700 ? 1 + r / 37 % 3 : 0);
    }
  ContentTiles content = contentTilesOf(v);
  std::fill(content.marks.begin(), content.marks.end(), std::uint8_t{1});
  ASSERT_GT(content.tilesX * content.tilesY, 16384);
  auto tiled = classifyTiled(**classifier, v, content);
  ASSERT_TRUE(tiled) << tiled.error().message;
  expectSameRecords(*tiled, classifyCellsReference(v));
}

}  // namespace
}  // namespace scansurf::test
