// scansurf passes: tetrahedral classification on the GPU (Nielson & Franke 1997; Lee et al.,
// "Scanline Surfacing", §3.5): batch by batch, a compute shader writes a CellCase per cell that
// holds a separating surface; see classification.h.
#include "passes/classification.h"

#include <algorithm>
#include <cstring>
#include <span>
#include <string>

#include "classify_push.h"
#include "gpu/check.h"
#include "gpu/commands.h"
#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "passes/shader_registry.h"

namespace scansurf::passes {
namespace {
constexpr std::uint32_t kGroupX = 8;
constexpr std::uint32_t kGroupY = 8;
}  // namespace

struct Classifier::State {
  const gpu::Context* ctx = nullptr;
  gpu::Owned<VkShaderModule> module;
  gpu::Owned<VkDescriptorSetLayout> setLayout;
  gpu::Owned<VkPipelineLayout> layout;
  gpu::Owned<VkPipeline> pipeline;
  gpu::Owned<VkDescriptorPool> pool;
  VkDescriptorSet set = VK_NULL_HANDLE;
  gpu::Buffer noTiles;  // bound as the tile list when every column is visited
  std::size_t batchBudget = std::size_t{64} << 20;
  int lastBatches = 0;
};

Classifier::Classifier(std::unique_ptr<State> state) : state_(std::move(state)) {}
Classifier::~Classifier() = default;
void Classifier::setBatchBudget(std::size_t bytes) { state_->batchBudget = bytes; }
int Classifier::lastBatchCount() const { return state_->lastBatches; }

Result<std::unique_ptr<Classifier>> Classifier::create(const gpu::Context& ctx) {
  auto s = std::make_unique<State>();
  s->ctx = &ctx;
  SCANSURF_ASSIGN_OR_RETURN(s->module, gpu::createShaderModule(ctx, shaders::spirv("classify.comp")));
  SCANSURF_ASSIGN_OR_RETURN(s->setLayout, gpu::createStorageBufferSetLayout(ctx, 4, VK_SHADER_STAGE_COMPUTE_BIT));
  const VkDescriptorSetLayout setLayout = s->setLayout.get();
  SCANSURF_ASSIGN_OR_RETURN(s->layout, gpu::createPipelineLayout(ctx, std::span(&setLayout, 1), sizeof(shared::ClassifyPush),
                                                                 VK_SHADER_STAGE_COMPUTE_BIT));
  const std::uint32_t spec[] = {kGroupX, kGroupY};
  SCANSURF_ASSIGN_OR_RETURN(s->pipeline, gpu::createComputePipeline(ctx, s->layout.get(), s->module.get(), spec));

  SCANSURF_ASSIGN_OR_RETURN(gpu::StorageBufferSet set, gpu::createStorageBufferSet(ctx, setLayout, 4));
  s->pool = std::move(set.pool);
  s->set = set.set;
  SCANSURF_ASSIGN_OR_RETURN(s->noTiles,
                            gpu::Buffer::create(ctx, 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryDomain::Upload));
  return std::unique_ptr<Classifier>(new Classifier(std::move(s)));
}

// Where the labels come from: the host (copied into a mapped upload buffer per batch) or a
// buffer on the device (copied on the device per batch).
struct Classifier::Source {
  const Grid& grid;
  const LabelVolume* host = nullptr;
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceSize offset = 0;
  VkDeviceSize size = 0;  // of `buffer` when known: batches are then bound in place
  std::uint32_t bits = 16;
  bool upperIsData = false;               // 32-bit words: the label is the lower half
  const ContentTiles* content = nullptr;  // where labels can be other than background (none: anywhere)

  std::size_t layerBytes() const { return static_cast<std::size_t>(grid.nx) * static_cast<std::size_t>(grid.ny) * (bits / 8); }
  bool inPlace() const { return size > 0; }
};

namespace {

static_assert(ContentTiles::kTile == kGroupX && ContentTiles::kTile == kGroupY, "a workgroup covers one content tile");

// The tiles of cell columns whose cells in cell layers first .. first + layers - 1 may hold a
// surface: a cell column reads the label columns x, x + 1 and y, y + 1, so a tile's cells need
// a marked tile among the label tiles it and its neighbours at +x, +y hold, on a layer of the
// batch. Packed x | y << 16.
std::vector<std::uint32_t> batchTiles(const ContentTiles& content, int first, int layers) {
  std::vector<std::uint32_t> tiles;
  for (int ty = 0; ty < content.tilesY; ++ty)
    for (int tx = 0; tx < content.tilesX; ++tx) {
      bool any = false;
      for (int k = first; k <= first + layers && !any; ++k)
        any = content.marked(k, tx, ty) || content.marked(k, tx + 1, ty) || content.marked(k, tx, ty + 1) ||
              content.marked(k, tx + 1, ty + 1);
      if (any) tiles.push_back(static_cast<std::uint32_t>(tx) | static_cast<std::uint32_t>(ty) << 16);
    }
  return tiles;
}

// The batch's tiles (batchTiles) into `list` (grown when short), bound as the tile list;
// returns how many (0: nothing to visit, nothing bound).
Result<std::uint32_t> bindBatchTiles(const gpu::Context& ctx, VkDescriptorSet set, const ContentTiles& content, int first,
                                     int layers, gpu::Buffer& list) {
  const std::vector<std::uint32_t> tiles = batchTiles(content, first, layers);
  if (tiles.empty()) return 0u;
  if (list.size() < tiles.size() * 4) {
    SCANSURF_ASSIGN_OR_RETURN(
        list, gpu::Buffer::create(ctx, tiles.size() * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryDomain::Upload));
  }
  std::memcpy(list.mapped(), tiles.data(), tiles.size() * 4);
  SCANSURF_TRY(list.flush());
  gpu::bindStorageBuffer(ctx, set, 3, list.handle());
  return static_cast<std::uint32_t>(tiles.size());
}

// How the volume is cut into batches of cell layers that fit one storage buffer.
struct BatchPlan {
  std::size_t layerBytes = 0;
  int totalCellLayers = 0;
  int batchCellLayers = 0;
  std::size_t maxRecords = 0;
};

// Labels bound in place start up to one offset alignment before the batch's first.
Result<BatchPlan> planBatches(const gpu::Context& ctx, const Grid& grid, std::size_t layerBytes, std::size_t batchBudget,
                              bool inPlace) {
  if (cellCount(grid) > 0xFFFFFFFFull)
    return makeError(Errc::InvalidArgument, "classification: more than 2^32 cells; use a coarser grid");
  const std::size_t maxRange =
      ctx.limits().maxStorageBufferRange - (inPlace ? std::max<std::size_t>(4, ctx.limits().minStorageBufferOffsetAlignment) : 0);
  const std::size_t labelBudget = std::min(batchBudget, maxRange);
  if (2 * layerBytes + 4 > labelBudget)
    return makeError(Errc::InvalidArgument, "classification: two layers of " + std::to_string(grid.nx) + " x " +
                                                std::to_string(grid.ny) + " labels exceed the storage buffer limit");
  BatchPlan plan;
  plan.layerBytes = layerBytes;
  plan.totalCellLayers = grid.nz - 1;
  plan.batchCellLayers = std::max(1, std::min(plan.totalCellLayers, static_cast<int>((labelBudget - 4) / layerBytes) - 1));
  plan.maxRecords = maxRange / sizeof(CellCase);
  return plan;
}

// In place: binds the batch's labels (layers first .. first + layers) of the source buffer,
// from the aligned offset at or before them; returns how many labels precede them there.
std::uint32_t bindBatchInPlace(const gpu::Context& ctx, VkDescriptorSet set, const Classifier::Source& source, int first,
                               int layers) {
  const VkDeviceSize align = std::max<VkDeviceSize>(4, ctx.limits().minStorageBufferOffsetAlignment);
  const VkDeviceSize start = source.offset + source.layerBytes() * static_cast<VkDeviceSize>(first);
  const VkDeviceSize bound = start / align * align;
  const VkDeviceSize end = start + source.layerBytes() * static_cast<VkDeviceSize>(layers + 1);
  gpu::bindStorageBuffer(ctx, set, 0, source.buffer, bound, std::min((end - bound + 3) / 4 * 4, source.size - bound));
  return static_cast<std::uint32_t>((start - bound) / (source.bits / 8));
}

// The buffer a batch's labels are copied into: mapped for host labels, on the device for a
// device buffer copied batch by batch; none (an empty Buffer) when bound in place.
Result<gpu::Buffer> createBatchBuffer(const gpu::Context& ctx, const Classifier::Source& source, const BatchPlan& plan) {
  if (source.inPlace()) return gpu::Buffer{};
  const VkDeviceSize bytes = (plan.layerBytes * static_cast<std::size_t>(plan.batchCellLayers + 1) + 3) / 4 * 4;
  if (source.host) return gpu::Buffer::create(ctx, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryDomain::Upload);
  return gpu::Buffer::create(ctx, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                             gpu::MemoryDomain::Device);
}

// Host labels: written straight into the mapped batch buffer before recording.
// Device labels: a copy recorded ahead of the dispatch (the first after a barrier on every
// earlier write to the application's buffer).
void fillBatch(VkCommandBuffer cmd, const Classifier::Source& source, const gpu::Buffer& labels, int firstLayer, int layers) {
  const std::size_t bytes = source.layerBytes() * static_cast<std::size_t>(layers + 1);
  const std::size_t start = source.layerBytes() * static_cast<std::size_t>(firstLayer);
  if (source.host) {
    std::memcpy(labels.mapped(), reinterpret_cast<const std::uint8_t*>(source.host->labels.data()) + start, bytes);
    return;
  }
  if (source.inPlace()) {  // only wait for the earlier writes to the buffer
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    return;
  }
  gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                     VK_ACCESS_2_TRANSFER_READ_BIT);
  const VkBufferCopy region{source.offset + start, 0, bytes};
  vkCmdCopyBuffer(cmd, source.buffer, labels.handle(), 1, &region);
  gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                     VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
}

}  // namespace

Result<std::vector<CellCase>> Classifier::run(const LabelVolume& volume) {
  if (volume.labels.size() != volume.grid.voxelCount())
    return makeError(Errc::InvalidArgument, "classification: the label volume holds " + std::to_string(volume.labels.size()) +
                                                " labels for " + std::to_string(volume.grid.voxelCount()) + " voxels");
  Source source{volume.grid};
  source.host = &volume;
  return classify(source);
}

Result<Classifier::Source> Classifier::deviceSource(const DeviceLabelVolume& volume) const {
  if (volume.buffer == VK_NULL_HANDLE) return makeError(Errc::InvalidArgument, "DeviceLabelVolume: no buffer");
  if (volume.bitsPerLabel != 16 && volume.bitsPerLabel != 32)
    return makeError(Errc::InvalidArgument,
                     "DeviceLabelVolume: bitsPerLabel is " + std::to_string(volume.bitsPerLabel) + "; 16 and 32 are supported");
  if (volume.grid.nx < 0 || volume.grid.ny < 0 || volume.grid.nz < 0 ||
      volume.grid.layerZ.size() != static_cast<std::size_t>(volume.grid.nz))
    return makeError(Errc::InvalidArgument, "DeviceLabelVolume: the grid needs nz layer z values and non-negative sizes");
  Source source{volume.grid};
  source.buffer = volume.buffer;
  source.offset = volume.offset;
  source.bits = volume.bitsPerLabel;
  return source;
}

Result<std::vector<CellCase>> Classifier::run(const DeviceLabelVolume& volume) {
  SCANSURF_ASSIGN_OR_RETURN(const Source source, deviceSource(volume));
  return classify(source);
}

Result<std::vector<CellCase>> Classifier::runInPlace(const DeviceLabelVolume& volume, VkDeviceSize bufferSize, bool upperIsData,
                                                     const ContentTiles* content) {
  SCANSURF_ASSIGN_OR_RETURN(Source source, deviceSource(volume));
  source.upperIsData = upperIsData && volume.bitsPerLabel == 32;
  if (content && !content->empty()) {
    const Grid& g = volume.grid;
    if (content->layers != g.nz || content->tilesX != (g.nx + ContentTiles::kTile - 1) / ContentTiles::kTile ||
        content->tilesY != (g.ny + ContentTiles::kTile - 1) / ContentTiles::kTile)
      return makeError(Errc::InvalidArgument, "classification: the content tiles do not match the grid");
    source.content = content;
  }
  const VkDeviceSize need = volume.offset + volume.grid.voxelCount() * (volume.bitsPerLabel / 8);
  if (bufferSize < need)
    return makeError(Errc::InvalidArgument, "DeviceLabelVolume: the buffer holds " + std::to_string(bufferSize) +
                                                " bytes; the grid needs " + std::to_string(need));
  source.size = bufferSize;
  return classify(source);
}

void Classifier::recordBatch(VkCommandBuffer cmd, const Source& source, const gpu::Buffer& labels, const gpu::Buffer& counter,
                             int first, int layers, std::size_t capacity, std::uint32_t labelOffset, std::uint32_t tiles) const {
  const Grid& grid = source.grid;
  fillBatch(cmd, source, labels, first, layers);
  vkCmdFillBuffer(cmd, counter.handle(), 0, 8, 0);
  gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                     VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, state_->pipeline.get());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, state_->layout.get(), 0, 1, &state_->set, 0, nullptr);
  const shared::ClassifyPush push{static_cast<std::uint32_t>(grid.nx),
                                  static_cast<std::uint32_t>(grid.ny),
                                  static_cast<std::uint32_t>(layers),
                                  static_cast<std::uint32_t>(first),
                                  static_cast<std::uint32_t>(capacity),
                                  source.bits,
                                  labelOffset,
                                  source.upperIsData ? 1u : 0u,
                                  source.content ? 1u : 0u,
                                  tiles};
  vkCmdPushConstants(cmd, state_->layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
  if (source.content)  // a tile of columns each, in rows of shared::kTileRow
    vkCmdDispatch(cmd, std::min(tiles, shared::kTileRow), (tiles + shared::kTileRow - 1) / shared::kTileRow, 1);
  else
    vkCmdDispatch(cmd, (static_cast<std::uint32_t>(grid.nx - 1) + kGroupX - 1) / kGroupX,
                  (static_cast<std::uint32_t>(grid.ny - 1) + kGroupY - 1) / kGroupY, 1);  // a column of cells each
  gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
}

Result<std::vector<CellCase>> Classifier::classify(const Source& source) {
  const gpu::Context& ctx = *state_->ctx;
  const Grid& grid = source.grid;
  if (grid.nx < 2 || grid.ny < 2 || grid.nz < 2) return std::vector<CellCase>{};
  const bool inPlace = source.inPlace();
  SCANSURF_ASSIGN_OR_RETURN(const BatchPlan plan, planBatches(ctx, grid, source.layerBytes(), state_->batchBudget, inPlace));
  SCANSURF_ASSIGN_OR_RETURN(gpu::Buffer labels, createBatchBuffer(ctx, source, plan));
  SCANSURF_ASSIGN_OR_RETURN(gpu::Buffer counter,
                            gpu::Buffer::create(ctx, 8, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                                gpu::MemoryDomain::Readback));
  // Start with room for a surface through a few percent of the cells; grow on overflow.
  const std::size_t batchCells = static_cast<std::size_t>(grid.nx - 1) * static_cast<std::size_t>(grid.ny - 1) *
                                 static_cast<std::size_t>(plan.batchCellLayers);
  std::size_t capacity = std::clamp<std::size_t>(batchCells / 16, 4096, plan.maxRecords);
  gpu::Buffer cases, tileList;
  bool casesBound = false;
  if (!source.content) gpu::bindStorageBuffer(ctx, state_->set, 3, state_->noTiles.handle());

  std::vector<CellCase> result;
  state_->lastBatches = 0;
  int first = 0;
  int layers = plan.batchCellLayers;
  while (first < plan.totalCellLayers) {
    layers = std::min(layers, plan.totalCellLayers - first);
    if (!casesBound) {
      SCANSURF_ASSIGN_OR_RETURN(cases, gpu::Buffer::create(ctx, capacity * sizeof(CellCase), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                                           gpu::MemoryDomain::Readback));
      if (!inPlace) gpu::bindStorageBuffer(ctx, state_->set, 0, labels.handle());
      gpu::bindStorageBuffer(ctx, state_->set, 1, counter.handle());
      gpu::bindStorageBuffer(ctx, state_->set, 2, cases.handle());
      casesBound = true;
    }
    std::uint32_t tileCount = 0;
    if (source.content) {
      SCANSURF_ASSIGN_OR_RETURN(tileCount, bindBatchTiles(ctx, state_->set, *source.content, first, layers, tileList));
      if (tileCount == 0) {  // background throughout: no surface
        first += layers;
        ++state_->lastBatches;
        continue;
      }
    }
    const std::uint32_t labelOffset = inPlace ? bindBatchInPlace(ctx, state_->set, source, first, layers) : 0;
    SCANSURF_ASSIGN_OR_RETURN(gpu::OneShotCommands commands, gpu::OneShotCommands::begin(ctx));
    recordBatch(commands.cmd(), source, labels, counter, first, layers, capacity, labelOffset, tileCount);
    SCANSURF_TRY(commands.submitAndWait());
    SCANSURF_TRY(counter.invalidate());
    std::uint32_t counts[2] = {0, 0};
    std::memcpy(counts, counter.mapped(), sizeof(counts));
    if (counts[1] != 0)
      return makeError(Errc::InvalidInput, "DeviceLabelVolume: label " + std::to_string(counts[1]) + " in layers " +
                                               std::to_string(first) + ".." + std::to_string(first + layers) +
                                               " exceeds the largest label, 65535");
    const std::uint32_t count = counts[0];

    if (count > capacity) {
      // Too many records for the buffer: grow it, or halve the batch when at the limit.
      if (capacity < plan.maxRecords) {
        capacity = std::min<std::size_t>(plan.maxRecords, static_cast<std::size_t>(count) + count / 4);
        casesBound = false;
      } else if (layers > 1) {
        layers /= 2;
      } else {
        return makeError(Errc::InvalidArgument, "classification: one layer holds more surface cells than a storage buffer can");
      }
      continue;
    }
    SCANSURF_TRY(cases.invalidate());
    const auto* records = static_cast<const CellCase*>(cases.mapped());
    result.insert(result.end(), records, records + count);
    first += layers;
    ++state_->lastBatches;
  }
  // The atomic append leaves records in any order; sort for deterministic assembly.
  std::sort(result.begin(), result.end(), [](const CellCase& a, const CellCase& b) { return a.cell < b.cell; });
  return result;
}

}  // namespace scansurf::passes
