// scansurf passes: slice scan conversion (Lee et al., "Scanline Surfacing", §3.4): triangle
// fans with an even-odd stencil, inner features winning by depth; see scan_conversion.h.
#include "passes/scan_conversion.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <span>
#include <string>

#include "geometry/overlaps/raster_rules.h"
#include "gpu/check.h"
#include "gpu/commands.h"
#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "passes/shader_registry.h"
#include "scan_push.h"

namespace scansurf::passes {
namespace {

constexpr VkFormat kLabelFormat = VK_FORMAT_R16_UINT;

Result<VkFormat> pickDepthStencilFormat(const gpu::Context& ctx) {
  for (VkFormat f : {VK_FORMAT_D32_SFLOAT_S8_UINT, VK_FORMAT_D24_UNORM_S8_UINT}) {
    VkFormatProperties props;
    vkGetPhysicalDeviceFormatProperties(ctx.physicalDevice(), f, &props);
    if (props.optimalTilingFeatures & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT) return f;
  }
  return makeError(Errc::NoDevice, "the device has no depth-stencil format with 8 stencil bits");
}

// One feature's drawing on one layer: its contours' fans, then its cover quad.
struct FeatureDraw {
  std::uint32_t firstVertex = 0;
  std::vector<std::uint32_t> contourCounts;
  std::uint32_t coverFirst = 0;
  float depth = 0;
  Label label = 0;
};

// One feature's contours on one slice.
struct SliceRef {
  int feature;
  const FeatureSlice* slice;
};

// What every batch of one run shares.
struct RunPlan {
  const Grid* grid = nullptr;
  std::vector<std::vector<SliceRef>> byLayer;  // which feature slices land on which layer
  std::vector<int> rank;                       // nesting rank of each feature, 0 = innermost
  int featureCount = 0;
  int subPixelBits = 0;
  float invScale = 0;                          // sub-pixel units to pixels
  std::uint32_t viewportW = 0, viewportH = 0;  // see viewportExtent
  std::size_t layerBytes = 0;                  // labels of one layer
};

// The render targets every batch reuses: a label image with a layer per slice layer of the
// batch, one depth-stencil image shared by the layers, and the buffer labels are read back in
// (none when only the device keeps them).
struct BatchTargets {
  gpu::Image labels;
  gpu::Image depthStencil;
  gpu::Buffer readback;
};

// Where a run's labels go: the host volume, a whole-volume device buffer, or both.
struct LabelSinks {
  LabelVolume* host = nullptr;
  const gpu::Buffer* device = nullptr;
};

// A batch's vertices (x, y in pixels): each contour's points (a fan), then the feature's cover
// quad; and per layer of the batch, the draws that use them.
struct BatchGeometry {
  std::vector<float> vertices;
  std::vector<std::vector<FeatureDraw>> draws;
};

// The sub-pixel bounding box of points.
struct SubpixelBox {
  std::int64_t minU = std::numeric_limits<std::int64_t>::max(), minV = std::numeric_limits<std::int64_t>::max();
  std::int64_t maxU = std::numeric_limits<std::int64_t>::min(), maxV = std::numeric_limits<std::int64_t>::min();

  void add(const SubpixelPoint& sp) {
    minU = std::min(minU, sp.u), maxU = std::max(maxU, sp.u);
    minV = std::min(minV, sp.v), maxV = std::max(maxV, sp.v);
  }
};

Result<void> checkRunArguments(const VkPhysicalDeviceLimits& limits, const Grid& grid, std::size_t featureCount,
                               std::size_t orderSize) {
  if (orderSize != featureCount)
    return makeError(Errc::InvalidArgument, "scan conversion: the order must name every feature once");
  if (grid.nx < 3 || grid.ny < 3 || grid.nz < 3)
    return makeError(Errc::InvalidArgument, "scan conversion: the grid needs at least 3 voxels per axis");
  if (static_cast<std::uint32_t>(grid.nx) > limits.maxImageDimension2D ||
      static_cast<std::uint32_t>(grid.ny) > limits.maxImageDimension2D ||
      viewportExtent(grid.nx) > limits.maxViewportDimensions[0] || viewportExtent(grid.ny) > limits.maxViewportDimensions[1])
    return makeError(Errc::InvalidArgument, "scan conversion: a " + std::to_string(grid.nx) + " x " + std::to_string(grid.ny) +
                                                " grid exceeds the device's image limits");
  return {};
}

// Which feature slices land on which layer; a slice off the grid's layers is a bug upstream.
Result<std::vector<std::vector<SliceRef>>> slicesByLayer(const ContourSet& contours, const Grid& grid) {
  std::vector<std::vector<SliceRef>> byLayer(static_cast<std::size_t>(grid.nz));
  for (int f = 0; f < static_cast<int>(contours.features.size()); ++f)
    for (const FeatureSlice& s : contours.features[static_cast<std::size_t>(f)].slices) {
      const int layer = grid.layerOfPlane(s.z);
      if (layer < 1 || layer > grid.nz - 2)
        return makeError(Errc::Internal, "scan conversion: slice z=" + std::to_string(s.z) + " of feature \"" +
                                             contours.features[static_cast<std::size_t>(f)].name +
                                             "\" is not a layer of the grid");
      byLayer[static_cast<std::size_t>(layer)].push_back({f, &s});
    }
  return byLayer;
}

Result<RunPlan> planRun(const ContourSet& contours, const Grid& grid, const std::vector<int>& order, int subPixelBits) {
  RunPlan plan;
  plan.grid = &grid;
  plan.featureCount = static_cast<int>(contours.features.size());
  plan.rank.assign(static_cast<std::size_t>(plan.featureCount), -1);
  for (int r = 0; r < plan.featureCount; ++r) plan.rank[static_cast<std::size_t>(order[static_cast<std::size_t>(r)])] = r;
  SCANSURF_ASSIGN_OR_RETURN(plan.byLayer, slicesByLayer(contours, grid));
  plan.subPixelBits = subPixelBits;
  plan.invScale = static_cast<float>(std::ldexp(1.0, -subPixelBits));
  plan.viewportW = viewportExtent(grid.nx);
  plan.viewportH = viewportExtent(grid.ny);
  plan.layerBytes = static_cast<std::size_t>(grid.nx) * static_cast<std::size_t>(grid.ny) * sizeof(Label);
  return plan;
}

// As many layers as the budget allows, at least one, at most the device's array layers and the
// layers there are.
int batchLayerCount(std::size_t batchBudget, std::size_t layerBytes, std::uint32_t maxImageArrayLayers, int sliceLayers) {
  return static_cast<int>(std::clamp<std::size_t>(
      batchBudget / layerBytes, 1, std::min<std::size_t>(maxImageArrayLayers, static_cast<std::size_t>(sliceLayers))));
}

Result<BatchTargets> createBatchTargets(const gpu::Context& ctx, VkFormat depthStencilFormat, const Grid& grid, int batchLayers,
                                        std::size_t layerBytes, bool toHost) {
  SCANSURF_ASSIGN_OR_RETURN(
      gpu::Image labels,
      gpu::Image::create(ctx, kLabelFormat, static_cast<std::uint32_t>(grid.nx), static_cast<std::uint32_t>(grid.ny),
                         static_cast<std::uint32_t>(batchLayers),
                         VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_IMAGE_ASPECT_COLOR_BIT));
  SCANSURF_ASSIGN_OR_RETURN(
      gpu::Image depthStencil,
      gpu::Image::create(ctx, depthStencilFormat, static_cast<std::uint32_t>(grid.nx), static_cast<std::uint32_t>(grid.ny), 1,
                         VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT));
  BatchTargets targets{std::move(labels), std::move(depthStencil), {}};
  if (toHost) {
    SCANSURF_ASSIGN_OR_RETURN(targets.readback,
                              gpu::Buffer::create(ctx, layerBytes * static_cast<std::size_t>(batchLayers),
                                                  VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::MemoryDomain::Readback));
  }
  return targets;
}

// Cover quad: the fans stay inside the contours' bounding box; one pixel of margin.
void appendCoverQuad(const SubpixelBox& box, const Grid& grid, float invScale, std::vector<float>& vertices) {
  const float x0 = std::max(0.0f, std::floor(static_cast<float>(box.minU) * invScale) - 1.0f);
  const float y0 = std::max(0.0f, std::floor(static_cast<float>(box.minV) * invScale) - 1.0f);
  const float x1 = std::min(static_cast<float>(grid.nx), std::ceil(static_cast<float>(box.maxU) * invScale) + 1.0f);
  const float y1 = std::min(static_cast<float>(grid.ny), std::ceil(static_cast<float>(box.maxV) * invScale) + 1.0f);
  vertices.insert(vertices.end(), {x0, y0, x1, y0, x1, y1, x0, y1});
}

// Appends the feature slice's contours (a fan each) and its cover quad to vertices.
FeatureDraw appendFeatureDraw(const RunPlan& plan, const SliceRef& ref, std::vector<float>& vertices) {
  FeatureDraw draw;
  draw.firstVertex = static_cast<std::uint32_t>(vertices.size() / 2);
  draw.label = labelOfFeature(ref.feature);
  draw.depth = rankDepth(plan.rank[static_cast<std::size_t>(ref.feature)], plan.featureCount);
  SubpixelBox box;
  for (const Contour& c : ref.slice->contours) {
    for (const Point2& p : c.points) {
      const SubpixelPoint sp = toSubpixel(*plan.grid, p.x, p.y, plan.subPixelBits);
      box.add(sp);
      vertices.push_back(static_cast<float>(sp.u) * plan.invScale);
      vertices.push_back(static_cast<float>(sp.v) * plan.invScale);
    }
    draw.contourCounts.push_back(static_cast<std::uint32_t>(c.points.size()));
  }
  draw.coverFirst = static_cast<std::uint32_t>(vertices.size() / 2);
  appendCoverQuad(box, *plan.grid, plan.invScale, vertices);
  return draw;
}

BatchGeometry buildBatchGeometry(const RunPlan& plan, int first, int count) {
  BatchGeometry geometry;
  geometry.draws.resize(static_cast<std::size_t>(count));
  for (int l = 0; l < count; ++l)
    for (const SliceRef& ref : plan.byLayer[static_cast<std::size_t>(first + l)])
      geometry.draws[static_cast<std::size_t>(l)].push_back(appendFeatureDraw(plan, ref, geometry.vertices));
  if (geometry.vertices.empty()) geometry.vertices.assign(2, 0.0f);  // a buffer of size 0 is not allowed
  return geometry;
}

// Both images from whatever they held (the previous batch's copy reads the labels) to attachments.
void transitionToAttachments(VkCommandBuffer cmd, const BatchTargets& targets) {
  gpu::imageBarrier(cmd, targets.labels.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                    VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                    VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  gpu::imageBarrier(cmd, targets.depthStencil.handle(), VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT,
                    VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
                    VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                    VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
}

// The depth-stencil image is reused: the next layer's clear waits for this layer's tests.
void waitForDepthStencilTests(VkCommandBuffer cmd) {
  gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                     VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT,
                     VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                     VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT);
}

// Copies the batch's `count` label layers (from layer `first` of the volume) to the readback
// buffer, visible to the host, and into the device volume.
void recordCopyOut(VkCommandBuffer cmd, const BatchTargets& targets, const LabelSinks& sinks, const Grid& grid, int first,
                   int count) {
  gpu::imageBarrier(cmd, targets.labels.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                    VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, static_cast<std::uint32_t>(count)};
  region.imageExtent = {static_cast<std::uint32_t>(grid.nx), static_cast<std::uint32_t>(grid.ny), 1};
  if (sinks.host)
    vkCmdCopyImageToBuffer(cmd, targets.labels.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, targets.readback.handle(), 1,
                           &region);
  if (sinks.device) {
    region.bufferOffset = grid.index(0, 0, first) * sizeof(Label);
    vkCmdCopyImageToBuffer(cmd, targets.labels.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, sinks.device->handle(), 1,
                           &region);
  }
  // The classifier's first command waits on every earlier write before it reads the device volume.
  gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                     VK_ACCESS_2_HOST_READ_BIT);
}

// The device volume starts as background (its padding layers are never drawn); the first
// batch clears it before its copy.
void recordClear(VkCommandBuffer cmd, const gpu::Buffer& device) {
  vkCmdFillBuffer(cmd, device.handle(), 0, VK_WHOLE_SIZE, kBackground);
  gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                     VK_ACCESS_2_TRANSFER_WRITE_BIT);
}

}  // namespace

struct ScanConverter::State {
  const gpu::Context* ctx = nullptr;
  VkFormat depthStencilFormat = VK_FORMAT_UNDEFINED;
  gpu::Owned<VkShaderModule> vertex;
  gpu::Owned<VkShaderModule> fragment;
  gpu::Owned<VkPipelineLayout> layout;
  gpu::Owned<VkPipeline> stencilPipeline;
  gpu::Owned<VkPipeline> coverPipeline;
  int subPixelBits = 8;
  int lastBatches = 0;
  std::size_t batchBudget = std::size_t{64} << 20;
};

ScanConverter::ScanConverter(std::unique_ptr<State> state) : state_(std::move(state)) {}
ScanConverter::~ScanConverter() = default;
int ScanConverter::subPixelBits() const { return state_->subPixelBits; }
int ScanConverter::lastBatchCount() const { return state_->lastBatches; }
void ScanConverter::setBatchBudget(std::size_t bytes) { state_->batchBudget = bytes; }

Result<std::unique_ptr<ScanConverter>> ScanConverter::create(const gpu::Context& ctx) {
  auto s = std::make_unique<State>();
  s->ctx = &ctx;
  s->subPixelBits = static_cast<int>(ctx.limits().subPixelPrecisionBits);
  SCANSURF_ASSIGN_OR_RETURN(s->depthStencilFormat, pickDepthStencilFormat(ctx));
  SCANSURF_ASSIGN_OR_RETURN(s->vertex, gpu::createShaderModule(ctx, shaders::spirv("scan.vert")));
  SCANSURF_ASSIGN_OR_RETURN(s->fragment, gpu::createShaderModule(ctx, shaders::spirv("scan_label.frag")));
  SCANSURF_ASSIGN_OR_RETURN(s->layout, gpu::createPipelineLayout(ctx, {}, sizeof(shared::ScanPush),
                                                                 VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT));

  gpu::RasterPipelineDesc desc;
  desc.vertex = s->vertex.get();
  desc.fragment = s->fragment.get();
  desc.layout = s->layout.get();
  desc.colorFormat = kLabelFormat;
  desc.depthFormat = s->depthStencilFormat;
  desc.stencilFormat = s->depthStencilFormat;
  desc.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_FAN;

  // Fans toggle stencil bit 0: after all of a feature's contours, bit 0 is the even-odd parity.
  desc.stencilTest = true;
  desc.stencil = {VK_STENCIL_OP_KEEP, VK_STENCIL_OP_INVERT, VK_STENCIL_OP_INVERT, VK_COMPARE_OP_ALWAYS, 1u, 1u, 0u};
  desc.colorWrite = 0;
  desc.depthTest = false;
  SCANSURF_ASSIGN_OR_RETURN(s->stencilPipeline, gpu::createRasterPipeline(ctx, desc));

  // Cover: label where parity is odd and the feature is nearer (inner) than what is there;
  // the stencil is zeroed whether or not the depth test passes, ready for the next feature.
  desc.stencil = {VK_STENCIL_OP_KEEP, VK_STENCIL_OP_ZERO, VK_STENCIL_OP_ZERO, VK_COMPARE_OP_EQUAL, 1u, 0xFFu, 1u};
  desc.colorWrite = VK_COLOR_COMPONENT_R_BIT;
  desc.depthTest = true;
  desc.depthWrite = true;
  SCANSURF_ASSIGN_OR_RETURN(s->coverPipeline, gpu::createRasterPipeline(ctx, desc));
  return std::unique_ptr<ScanConverter>(new ScanConverter(std::move(s)));
}

namespace {

// One layer's features: each feature's fans toggle the stencil parity, then its cover quad
// writes its label where the parity is odd.
void recordFeatureDraws(VkCommandBuffer cmd, const ScanConverter::State& state, const std::vector<FeatureDraw>& draws,
                        shared::ScanPush& push) {
  for (const FeatureDraw& d : draws) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, state.stencilPipeline.get());
    push.depth = d.depth;
    push.label = d.label;
    vkCmdPushConstants(cmd, state.layout.get(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(push),
                       &push);
    std::uint32_t v = d.firstVertex;
    for (std::uint32_t n : d.contourCounts) {
      vkCmdDraw(cmd, n, 1, v, 0);
      v += n;
    }
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, state.coverPipeline.get());
    vkCmdDraw(cmd, 4, 1, d.coverFirst, 0);
  }
}

// Renders each layer of the batch into its layer of the label image, then copies them out.
void recordBatch(VkCommandBuffer cmd, const ScanConverter::State& state, const RunPlan& plan, const BatchTargets& targets,
                 const LabelSinks& sinks, int first, const BatchGeometry& geometry, VkBuffer vertexBuffer) {
  const Grid& grid = *plan.grid;
  if (sinks.device && first == 1) recordClear(cmd, *sinks.device);
  transitionToAttachments(cmd, targets);
  const VkDeviceSize zero = 0;
  gpu::RenderingDesc rendering;
  rendering.clearColor.uint32[0] = kBackground;
  rendering.depth = targets.depthStencil.layerView(0);
  rendering.stencil = true;
  rendering.area = {static_cast<std::uint32_t>(grid.nx), static_cast<std::uint32_t>(grid.ny)};
  rendering.viewport = {plan.viewportW, plan.viewportH};
  shared::ScanPush push{{2.0f / static_cast<float>(plan.viewportW), 2.0f / static_cast<float>(plan.viewportH)}, 0.0f, 0};
  const int count = static_cast<int>(geometry.draws.size());
  for (int l = 0; l < count; ++l) {
    if (l > 0) waitForDepthStencilTests(cmd);
    rendering.color = targets.labels.layerView(static_cast<std::uint32_t>(l));
    gpu::beginRendering(cmd, rendering);
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertexBuffer, &zero);
    recordFeatureDraws(cmd, state, geometry.draws[static_cast<std::size_t>(l)], push);
    vkCmdEndRendering(cmd);
  }
  recordCopyOut(cmd, targets, sinks, grid, first, count);
}

// Scan converts layers first .. first + count - 1 in one submit into the sinks.
Result<void> convertBatch(const ScanConverter::State& state, const RunPlan& plan, const BatchTargets& targets, int first,
                          int count, const LabelSinks& sinks) {
  const gpu::Context& ctx = *state.ctx;
  const BatchGeometry geometry = buildBatchGeometry(plan, first, count);
  const std::size_t vertexBytes = geometry.vertices.size() * sizeof(float);
  SCANSURF_ASSIGN_OR_RETURN(gpu::Buffer vertexBuffer,
                            gpu::Buffer::create(ctx, vertexBytes, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, gpu::MemoryDomain::Upload));
  std::memcpy(vertexBuffer.mapped(), geometry.vertices.data(), vertexBytes);

  SCANSURF_ASSIGN_OR_RETURN(gpu::OneShotCommands commands, gpu::OneShotCommands::begin(ctx));
  recordBatch(commands.cmd(), state, plan, targets, sinks, first, geometry, vertexBuffer.handle());
  SCANSURF_TRY(commands.submitAndWait());
  if (!sinks.host) return {};
  SCANSURF_TRY(targets.readback.invalidate());
  std::memcpy(sinks.host->labels.data() + plan.grid->index(0, 0, first), targets.readback.mapped(),
              plan.layerBytes * static_cast<std::size_t>(count));
  return {};
}

// The volume before drawing: padding layers are never drawn and stay background.
LabelVolume backgroundVolume(const Grid& grid) { return LabelVolume{grid, std::vector<Label>(grid.voxelCount(), kBackground)}; }

// Scan converts every slice layer, batch by batch, into the sinks.
Result<void> convertAll(ScanConverter::State& state, const ContourSet& contours, const Grid& grid, const std::vector<int>& order,
                        const LabelSinks& sinks) {
  const gpu::Context& ctx = *state.ctx;
  SCANSURF_ASSIGN_OR_RETURN(const RunPlan plan, planRun(contours, grid, order, state.subPixelBits));
  const int sliceLayers = grid.nz - 2;
  const int batchLayers = batchLayerCount(state.batchBudget, plan.layerBytes, ctx.limits().maxImageArrayLayers, sliceLayers);
  SCANSURF_ASSIGN_OR_RETURN(const BatchTargets targets, createBatchTargets(ctx, state.depthStencilFormat, grid, batchLayers,
                                                                           plan.layerBytes, sinks.host != nullptr));
  state.lastBatches = 0;
  for (int first = 1; first <= sliceLayers; first += batchLayers) {
    const int count = std::min(batchLayers, sliceLayers + 1 - first);
    SCANSURF_TRY(convertBatch(state, plan, targets, first, count, sinks));
    ++state.lastBatches;
  }
  return {};
}

}  // namespace

Result<LabelVolume> ScanConverter::run(const ContourSet& contours, const Grid& grid, const std::vector<int>& order) {
  SCANSURF_TRY(checkRunArguments(state_->ctx->limits(), grid, contours.features.size(), order.size()));
  LabelVolume volume = backgroundVolume(grid);
  SCANSURF_TRY(convertAll(*state_, contours, grid, order, LabelSinks{&volume, nullptr}));
  return volume;
}

Result<ScanConverter::DeviceLabels> ScanConverter::runOnDevice(const ContourSet& contours, const Grid& grid,
                                                               const std::vector<int>& order, LabelVolume* host) {
  SCANSURF_TRY(checkRunArguments(state_->ctx->limits(), grid, contours.features.size(), order.size()));
  const VkDeviceSize bytes = (grid.voxelCount() * sizeof(Label) + 3) / 4 * 4;  // fills take whole words
  SCANSURF_ASSIGN_OR_RETURN(gpu::Buffer buffer,
                            gpu::Buffer::create(*state_->ctx, bytes,
                                                VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                                    VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                                gpu::MemoryDomain::Device));
  if (host) *host = backgroundVolume(grid);
  SCANSURF_TRY(convertAll(*state_, contours, grid, order, LabelSinks{host, &buffer}));
  return DeviceLabels{std::move(buffer), grid};
}

}  // namespace scansurf::passes
