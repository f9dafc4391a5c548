// scansurf passes: shape-based interpolation between the contour planes on the GPU (Grevera &
// Udupa 1996; exact distances after Felzenszwalb & Huttenlocher 2012); see interpolator.h.
#include "passes/interpolator.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <optional>
#include <span>

#include "geometry/interpolation/interpolated_volume.h"
#include "geometry/interpolation/interpolation_reference.h"
#include "gpu/check.h"
#include "gpu/commands.h"
#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "passes/shader_registry.h"

namespace scansurf::passes {
namespace {
constexpr std::uint32_t kBindings = 11;
constexpr std::uint32_t kLineGroup = 64;  // rows and columns: one invocation each
constexpr std::uint32_t kPixelGroup = 8;  // interpolation: 8 x 8 pixels
constexpr std::uint32_t kMaxGroupsY = 65535;

enum Binding : std::uint32_t {
  kPlanes,
  kFields,
  kValues,
  kScratch,
  kEntries,
  kPairs,
  kTileRanges,
  kTileEntries,
  kOutput,
  kLayerTable,
  kCrossings
};

// One buffer per binding, kept from batch to batch and grown when a batch needs more (fresh
// memory for every batch cost more in page faults than the work).
struct BatchBuffers {
  std::array<gpu::Buffer, kBindings> buffers;

  static gpu::MemoryDomain domainOf(std::uint32_t binding) {
    if (binding == kValues || binding == kScratch) return gpu::MemoryDomain::Device;
    return binding == kOutput ? gpu::MemoryDomain::Readback : gpu::MemoryDomain::Upload;
  }
  // Device buffers are cleared by fills; the planes may arrive by a device copy, and the
  // output leaves by one into the device words (InterpolationDeviceIo).
  static VkBufferUsageFlags usageOf(std::uint32_t binding) {
    VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    if (domainOf(binding) == gpu::MemoryDomain::Device || binding == kPlanes) usage |= VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    if (binding == kOutput || binding == kValues) usage |= VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    return usage;
  }
  // Whether the binding now has a new buffer (the descriptor set needs rewriting).
  Result<bool> reserve(const gpu::Context& ctx, std::uint32_t binding, std::size_t bytes) {
    bytes = std::max<std::size_t>(16, (bytes + 3) / 4 * 4);
    if (buffers[binding].handle() != VK_NULL_HANDLE && buffers[binding].size() >= bytes) return false;
    buffers[binding] = gpu::Buffer{};  // release before allocating the larger one
    SCANSURF_ASSIGN_OR_RETURN(buffers[binding], gpu::Buffer::create(ctx, bytes + bytes / 4, usageOf(binding), domainOf(binding)));
    return true;
  }
  Result<bool> upload(const gpu::Context& ctx, std::uint32_t binding, const void* data, std::size_t bytes) {
    SCANSURF_ASSIGN_OR_RETURN(const bool fresh, reserve(ctx, binding, bytes));
    if (bytes > 0) std::memcpy(buffers[binding].mapped(), data, bytes);
    return fresh;
  }
  template <typename T>
  Result<bool> upload(const gpu::Context& ctx, std::uint32_t binding, const std::vector<T>& v) {
    return upload(ctx, binding, v.data(), v.size() * sizeof(T));
  }
};

}  // namespace

struct Interpolator::State {
  const gpu::Context* ctx = nullptr;
  gpu::Owned<VkShaderModule> linesModule, envelopesModule, finishModule, interpolateModule;
  gpu::Owned<VkDescriptorSetLayout> setLayout;
  gpu::Owned<VkPipelineLayout> layout;
  gpu::Owned<VkPipeline> lines, envelopes, finish, interpolate;
  gpu::Owned<VkDescriptorPool> pool;
  VkDescriptorSet set = VK_NULL_HANDLE;
  BatchBuffers buffers;
  gpu::Buffer tableFields;  // the fields the layer table is read off, read back
  std::size_t batchBudget = std::size_t{64} << 20;
  int lastBatches = 0;
};

Interpolator::Interpolator(std::unique_ptr<State> state) : state_(std::move(state)) {}
Interpolator::~Interpolator() = default;
void Interpolator::setBatchBudget(std::size_t bytes) { state_->batchBudget = bytes; }
int Interpolator::lastBatchCount() const { return state_->lastBatches; }

namespace {

Result<void> createPipelines(const gpu::Context& ctx, Interpolator::State& s) {
  SCANSURF_ASSIGN_OR_RETURN(s.linesModule, gpu::createShaderModule(ctx, shaders::spirv("edt_lines.comp")));
  SCANSURF_ASSIGN_OR_RETURN(s.envelopesModule, gpu::createShaderModule(ctx, shaders::spirv("edt_envelopes.comp")));
  SCANSURF_ASSIGN_OR_RETURN(s.finishModule, gpu::createShaderModule(ctx, shaders::spirv("edt_finish.comp")));
  SCANSURF_ASSIGN_OR_RETURN(s.interpolateModule, gpu::createShaderModule(ctx, shaders::spirv("interpolate.comp")));
  SCANSURF_ASSIGN_OR_RETURN(s.setLayout, gpu::createStorageBufferSetLayout(ctx, kBindings, VK_SHADER_STAGE_COMPUTE_BIT));
  const VkDescriptorSetLayout setLayout = s.setLayout.get();
  SCANSURF_ASSIGN_OR_RETURN(s.layout, gpu::createPipelineLayout(ctx, std::span(&setLayout, 1), sizeof(shared::InterpolatePush),
                                                                VK_SHADER_STAGE_COMPUTE_BIT));
  const std::uint32_t lines[] = {kLineGroup, 1};
  const std::uint32_t pixels[] = {kPixelGroup, kPixelGroup};
  SCANSURF_ASSIGN_OR_RETURN(s.lines, gpu::createComputePipeline(ctx, s.layout.get(), s.linesModule.get(), lines));
  SCANSURF_ASSIGN_OR_RETURN(s.envelopes, gpu::createComputePipeline(ctx, s.layout.get(), s.envelopesModule.get(), lines));
  SCANSURF_ASSIGN_OR_RETURN(s.finish, gpu::createComputePipeline(ctx, s.layout.get(), s.finishModule.get(), lines));
  SCANSURF_ASSIGN_OR_RETURN(s.interpolate, gpu::createComputePipeline(ctx, s.layout.get(), s.interpolateModule.get(), pixels));

  SCANSURF_ASSIGN_OR_RETURN(gpu::StorageBufferSet set, gpu::createStorageBufferSet(ctx, setLayout, kBindings));
  s.pool = std::move(set.pool);
  s.set = set.set;
  return {};
}

// Fills the buffers for `batch` (the planes only when they are not copied on the device from
// devicePlanes); true when any buffer is new.
Result<bool> prepareBatch(const gpu::Context& ctx, BatchBuffers& b, const LabelVolume& volume,
                          const std::vector<std::uint16_t>& crossings, const InterpolationBatch& batch, bool devicePlanes) {
  const std::size_t plane = static_cast<std::size_t>(volume.grid.nx) * static_cast<std::size_t>(volume.grid.ny);
  const std::size_t first = plane * static_cast<std::size_t>(batch.firstPlane),
                    count = plane * static_cast<std::size_t>(batch.planes);
  bool fresh = false;
  auto track = [&](Result<bool> r) -> Result<void> {
    if (!r) return Unexpected(std::move(r).takeError());
    fresh = fresh || *r;
    return {};
  };
  SCANSURF_TRY(track(devicePlanes ? b.reserve(ctx, kPlanes, count * sizeof(Label))
                                  : b.upload(ctx, kPlanes, volume.labels.data() + first, count * sizeof(Label))));
  SCANSURF_TRY(track(b.upload(ctx, kCrossings, crossings.data() + first, count * sizeof(std::uint16_t))));
  SCANSURF_TRY(track(b.upload(ctx, kFields, batch.fields)));
  SCANSURF_TRY(track(b.reserve(ctx, kValues, batch.fieldValues * 4)));
  SCANSURF_TRY(track(b.reserve(ctx, kScratch, batch.scratchInts * 4)));
  SCANSURF_TRY(track(b.upload(ctx, kEntries, batch.entries)));
  SCANSURF_TRY(track(b.upload(ctx, kPairs, batch.pairs)));
  SCANSURF_TRY(track(b.upload(ctx, kTileRanges, batch.tileRanges)));
  SCANSURF_TRY(track(b.upload(ctx, kTileEntries, batch.tileEntries)));
  SCANSURF_TRY(track(b.reserve(ctx, kOutput, plane * static_cast<std::size_t>(batch.outputLayers) * 4)));
  SCANSURF_TRY(track(b.reserve(ctx, kLayerTable, batch.layerInts * 4)));  // filled once the fields are made
  return fresh;
}

void bindBatch(const gpu::Context& ctx, VkDescriptorSet set, const BatchBuffers& s) {
  std::array<VkBuffer, kBindings> buffers{};
  for (std::uint32_t i = 0; i < kBindings; ++i) buffers[i] = s.buffers[i].handle();
  gpu::bindStorageBuffers(ctx, set, buffers);
}

void computeBarrier(VkCommandBuffer cmd) {
  gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                     VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

// One dispatch per 65535 fields: x over the longest row or column, y over fields.
void dispatchFields(VkCommandBuffer cmd, VkPipelineLayout layout, shared::InterpolatePush push, std::size_t fields,
                    std::uint32_t lines) {
  for (std::size_t first = 0; first < fields; first += kMaxGroupsY) {
    push.pair = static_cast<std::uint32_t>(first);
    vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
    vkCmdDispatch(cmd, (lines + kLineGroup - 1) / kLineGroup,
                  static_cast<std::uint32_t>(std::min<std::size_t>(kMaxGroupsY, fields - first)), 1);
  }
}

}  // namespace

Result<std::unique_ptr<Interpolator>> Interpolator::create(const gpu::Context& ctx) {
  auto s = std::make_unique<State>();
  s->ctx = &ctx;
  SCANSURF_TRY(createPipelines(ctx, *s));
  return std::unique_ptr<Interpolator>(new Interpolator(std::move(s)));
}

// The batch's planes from the scan-converted labels on the device, instead of an upload.
void recordPlanesCopy(VkCommandBuffer cmd, const gpu::Buffer& devicePlanes, const gpu::Buffer& planes, VkDeviceSize offset,
                      VkDeviceSize bytes) {
  gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                     VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT);
  const VkBufferCopy region{offset, 0, bytes};
  vkCmdCopyBuffer(cmd, devicePlanes.handle(), planes.handle(), 1, &region);
  gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                     VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
}

// The batch's words into the device volume of words (its output layers are consecutive fine
// layers): with the interpolation, and again when the host has amended them (host writes
// before a submit are visible to it).
void recordWordsCopy(VkCommandBuffer cmd, const gpu::Buffer& output, const gpu::Buffer& words, VkDeviceSize offset,
                     VkDeviceSize bytes) {
  gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  const VkBufferCopy region{0, offset, bytes};
  vkCmdCopyBuffer(cmd, output.handle(), words.handle(), 1, &region);
}

namespace {

// The batch's distance fields: three passes over every field.
void recordFields(VkCommandBuffer cmd, const Interpolator::State& s, const InterpolationBatch& batch,
                  const shared::InterpolatePush& push) {
  std::uint32_t longest = 0, widest = 0;
  for (const shared::DistanceField& f : batch.fields)
    longest = std::max({longest, static_cast<std::uint32_t>(f.w), static_cast<std::uint32_t>(f.h)}),
    widest = std::max(widest, static_cast<std::uint32_t>(f.w));
  for (const auto& [pipeline, lines] :
       {std::pair{s.lines.get(), longest}, std::pair{s.envelopes.get(), longest}, std::pair{s.finish.get(), widest}}) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    dispatchFields(cmd, s.layout.get(), push, batch.fields.size(), lines);
    computeBarrier(cmd);
  }
}

// The layer table (buildLayerTable: dome erosions, area-keeping offsets) from the fields it
// needs, read back once made, into the buffer the interpolation pass reads.
Result<void> fillLayerTable(const gpu::Context& ctx, Interpolator::State& s, const InterpolationBatch& batch, int threads) {
  std::vector<std::size_t> at(batch.fields.size(), SIZE_MAX);
  std::vector<VkBufferCopy> regions;
  std::size_t ints = 0;
  auto need = [&](int index) {
    const auto field = static_cast<std::size_t>(index);
    if (at[field] != SIZE_MAX) return;
    const shared::DistanceField& f = batch.fields[field];
    const std::size_t n = static_cast<std::size_t>(f.w) * static_cast<std::size_t>(f.h);
    at[field] = ints;
    regions.push_back({static_cast<VkDeviceSize>(f.offset) * 4, ints * 4, n * 4});
    ints += n;
  };
  for (const InterpolationBatch::CappedEntry& c : batch.cappedEntries) need(c.field);
  for (const InterpolationBatch::BlendedEntry& b : batch.blendedEntries)
    for (const int field : {batch.entries[b.entry].fieldBefore, batch.entries[b.entry].fieldA, batch.entries[b.entry].fieldB,
                            batch.entries[b.entry].fieldAfter})
      if (field >= 0) need(field);
  if (s.tableFields.size() < std::max<std::size_t>(ints, 1) * 4) {
    s.tableFields = gpu::Buffer{};
    SCANSURF_ASSIGN_OR_RETURN(s.tableFields, gpu::Buffer::create(ctx, std::max<std::size_t>(ints, 1) * 4,
                                                                 VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::MemoryDomain::Readback));
  }
  SCANSURF_ASSIGN_OR_RETURN(gpu::OneShotCommands commands, gpu::OneShotCommands::begin(ctx));
  VkCommandBuffer cmd = commands.cmd();
  gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  vkCmdCopyBuffer(cmd, s.buffers.buffers[kValues].handle(), s.tableFields.handle(), static_cast<std::uint32_t>(regions.size()),
                  regions.data());
  gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                     VK_ACCESS_2_HOST_READ_BIT);
  SCANSURF_TRY(commands.submitAndWait());
  SCANSURF_TRY(s.tableFields.invalidate());
  const auto* mapped = static_cast<const std::int32_t*>(s.tableFields.mapped());
  std::vector<const std::int32_t*> values;
  for (std::size_t place : at) values.push_back(place == SIZE_MAX ? nullptr : mapped + place);
  const std::vector<std::int32_t> table = buildLayerTable(batch, values, threads);
  std::memcpy(s.buffers.buffers[kLayerTable].mapped(), table.data(), table.size() * 4);
  return {};
}

}  // namespace

Result<void> Interpolator::runBatch(const LabelVolume& volume, const std::vector<std::uint16_t>& crossings,
                                    const InterpolationBatch& batch, const DistanceWeights& weights, CapShape caps, int threads,
                                    const BatchWords& store, const InterpolationDeviceIo& device) {
  const gpu::Context& ctx = *state_->ctx;
  const Grid& g = volume.grid;
  BatchBuffers& buffers = state_->buffers;
  SCANSURF_ASSIGN_OR_RETURN(const bool fresh, prepareBatch(ctx, buffers, volume, crossings, batch, device.planes != nullptr));
  if (fresh) bindBatch(ctx, state_->set, buffers);
  const VkDeviceSize plane = static_cast<VkDeviceSize>(g.nx) * static_cast<VkDeviceSize>(g.ny);
  shared::InterpolatePush push{static_cast<std::uint32_t>(g.nx),
                               static_cast<std::uint32_t>(g.ny),
                               static_cast<std::uint32_t>(batch.fields.size()),
                               0,
                               weights.x,
                               weights.y,
                               weights.fixedScale,
                               caps == CapShape::Round ? 1u : 0u,
                               static_cast<std::uint32_t>(kTileSize),
                               static_cast<std::uint32_t>(batch.tilesX),
                               weights.unit,
                               farDistance(g, weights),
                               deepDistance(g)};
  // The fields first; the layer table needs their values before interpolation.
  const bool tables = batch.layerInts > 0;
  SCANSURF_ASSIGN_OR_RETURN(gpu::OneShotCommands commands, gpu::OneShotCommands::begin(ctx));
  VkCommandBuffer cmd = commands.cmd();
  if (device.planes)
    recordPlanesCopy(cmd, *device.planes, buffers.buffers[kPlanes],
                     plane * static_cast<VkDeviceSize>(batch.firstPlane) * sizeof(Label),
                     plane * static_cast<VkDeviceSize>(batch.planes) * sizeof(Label));
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, state_->layout.get(), 0, 1, &state_->set, 0, nullptr);
  recordFields(cmd, *state_, batch, push);
  std::optional<gpu::OneShotCommands> second;
  if (tables) {
    SCANSURF_TRY(commands.submitAndWait());
    SCANSURF_TRY(fillLayerTable(ctx, *state_, batch, threads));
    SCANSURF_ASSIGN_OR_RETURN(second, gpu::OneShotCommands::begin(ctx));
    cmd = second->cmd();
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, state_->layout.get(), 0, 1, &state_->set, 0, nullptr);
  }
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, state_->interpolate.get());
  for (std::size_t p = 0; p < batch.pairs.size(); ++p) {
    push.pair = static_cast<std::uint32_t>(p);
    vkCmdPushConstants(cmd, state_->layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
    vkCmdDispatch(cmd, (static_cast<std::uint32_t>(g.nx) + kPixelGroup - 1) / kPixelGroup,
                  (static_cast<std::uint32_t>(g.ny) + kPixelGroup - 1) / kPixelGroup,
                  static_cast<std::uint32_t>(batch.pairs[p].layers));
  }
  const gpu::Buffer& output = buffers.buffers[kOutput];
  const VkDeviceSize bytes = plane * static_cast<VkDeviceSize>(batch.outputLayers) * 4;
  if (device.words) recordWordsCopy(cmd, output, *device.words, device.wordsOffset, bytes);
  gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
  SCANSURF_TRY(second ? second->submitAndWait() : commands.submitAndWait());
  SCANSURF_TRY(output.invalidate());
  if (!store(static_cast<std::uint32_t*>(output.mapped())) || !device.words) return {};
  // The host relabelled some voxels (the slab rule's topology kept): the device volume gets the
  // batch again, as the host left it.
  SCANSURF_TRY(output.flush());
  SCANSURF_ASSIGN_OR_RETURN(gpu::OneShotCommands copy, gpu::OneShotCommands::begin(ctx));
  recordWordsCopy(copy.cmd(), output, *device.words, device.wordsOffset, bytes);
  return copy.submitAndWait();
}

Result<InterpolatedVolume> Interpolator::run(const LabelVolume& volume, const std::vector<std::uint16_t>& crossings,
                                             const std::vector<int>& factors, CapShape caps, int threads,
                                             InterpolationDeviceIo device, const std::vector<bool>& containers) {
  if (crossings.size() != volume.labels.size())
    return makeError(Errc::InvalidArgument, "interpolation: one edge-crossing word per voxel is needed");
  SCANSURF_ASSIGN_OR_RETURN(const DistanceWeights weights, distanceWeights(volume.grid));
  const std::size_t budget = std::min<std::size_t>(state_->batchBudget, state_->ctx->limits().maxStorageBufferRange);
  state_->lastBatches = 0;
  const std::vector<int> fineOf = fineLayerOfPlane(factors);
  const VkDeviceSize plane = static_cast<VkDeviceSize>(volume.grid.nx) * static_cast<VkDeviceSize>(volume.grid.ny);
  return interpolateVolume(
      volume, factors, budget, threads,
      [&](const InterpolationBatch& batch, const BatchWords& store) {
        ++state_->lastBatches;
        device.wordsOffset = plane * static_cast<VkDeviceSize>(fineOf[static_cast<std::size_t>(batch.firstPairPlane())]) * 4;
        return runBatch(volume, crossings, batch, weights, caps, threads, store, device);
      },
      device.words == nullptr, containers);
}

}  // namespace scansurf::passes
