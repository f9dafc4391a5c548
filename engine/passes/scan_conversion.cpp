#include "passes/scan_conversion.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <span>
#include <string>

#include "geometry/raster_rules.h"
#include "gpu/check.h"
#include "passes/shader_registry.h"
#include "gpu/commands.h"
#include "gpu/pipeline.h"
#include "gpu/resources.h"
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
  int lastSlabs = 0;
  std::size_t slabBudget = std::size_t{64} << 20;
};

ScanConverter::ScanConverter(std::unique_ptr<State> state) : state_(std::move(state)) {}
ScanConverter::~ScanConverter() = default;
int ScanConverter::subPixelBits() const { return state_->subPixelBits; }
int ScanConverter::lastSlabCount() const { return state_->lastSlabs; }
void ScanConverter::setSlabBudget(std::size_t bytes) { state_->slabBudget = bytes; }

Result<std::unique_ptr<ScanConverter>> ScanConverter::create(const gpu::Context& ctx) {
  auto s = std::make_unique<State>();
  s->ctx = &ctx;
  s->subPixelBits = static_cast<int>(ctx.limits().subPixelPrecisionBits);
  SCANSURF_ASSIGN_OR_RETURN(s->depthStencilFormat, pickDepthStencilFormat(ctx));
  SCANSURF_ASSIGN_OR_RETURN(s->vertex, gpu::createShaderModule(ctx, shaders::spirv("scan.vert")));
  SCANSURF_ASSIGN_OR_RETURN(s->fragment, gpu::createShaderModule(ctx, shaders::spirv("scan_label.frag")));
  SCANSURF_ASSIGN_OR_RETURN(
      s->layout, gpu::createPipelineLayout(ctx, {}, sizeof(shared::ScanPush),
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

Result<LabelVolume> ScanConverter::run(const ContourSet& contours, const Grid& grid, const std::vector<int>& order,
                                       double sliceTolerance) {
  const gpu::Context& ctx = *state_->ctx;
  const int featureCount = static_cast<int>(contours.features.size());
  if (static_cast<int>(order.size()) != featureCount)
    return makeError(Errc::InvalidArgument, "scan conversion: the order must name every feature once");
  if (grid.nx < 3 || grid.ny < 3 || grid.nz < 3)
    return makeError(Errc::InvalidArgument, "scan conversion: the grid needs at least 3 voxels per axis");
  const auto& limits = ctx.limits();
  const std::uint32_t viewportW = viewportExtent(grid.nx);
  const std::uint32_t viewportH = viewportExtent(grid.ny);
  if (static_cast<std::uint32_t>(grid.nx) > limits.maxImageDimension2D ||
      static_cast<std::uint32_t>(grid.ny) > limits.maxImageDimension2D || viewportW > limits.maxViewportDimensions[0] ||
      viewportH > limits.maxViewportDimensions[1])
    return makeError(Errc::InvalidArgument, "scan conversion: a " + std::to_string(grid.nx) + " x " +
                                                std::to_string(grid.ny) + " grid exceeds the device's image limits");

  std::vector<int> rank(static_cast<std::size_t>(featureCount), -1);
  for (int r = 0; r < featureCount; ++r) rank[static_cast<std::size_t>(order[static_cast<std::size_t>(r)])] = r;

  // Which feature slices land on which layer.
  struct SliceRef {
    int feature;
    const FeatureSlice* slice;
  };
  std::vector<std::vector<SliceRef>> byLayer(static_cast<std::size_t>(grid.nz));
  for (int f = 0; f < featureCount; ++f)
    for (const FeatureSlice& s : contours.features[static_cast<std::size_t>(f)].slices) {
      const int layer = layerOfZ(grid, s.z, sliceTolerance);
      if (layer < 1 || layer > grid.nz - 2)
        return makeError(Errc::Internal, "scan conversion: slice z=" + std::to_string(s.z) + " of feature \"" +
                                             contours.features[static_cast<std::size_t>(f)].name + "\" is not a layer of the grid");
      byLayer[static_cast<std::size_t>(layer)].push_back({f, &s});
    }

  LabelVolume volume;
  volume.grid = grid;
  volume.labels.assign(grid.voxelCount(), kBackground);

  const std::size_t layerBytes = static_cast<std::size_t>(grid.nx) * static_cast<std::size_t>(grid.ny) * sizeof(Label);
  const int sliceLayers = grid.nz - 2;
  const int slabLayers = static_cast<int>(std::clamp<std::size_t>(
      state_->slabBudget / layerBytes, 1, std::min<std::size_t>(limits.maxImageArrayLayers, static_cast<std::size_t>(sliceLayers))));

  SCANSURF_ASSIGN_OR_RETURN(
      gpu::Image labelImage,
      gpu::Image::create(ctx, kLabelFormat, static_cast<std::uint32_t>(grid.nx), static_cast<std::uint32_t>(grid.ny),
                         static_cast<std::uint32_t>(slabLayers),
                         VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_IMAGE_ASPECT_COLOR_BIT));
  SCANSURF_ASSIGN_OR_RETURN(
      gpu::Image depthImage,
      gpu::Image::create(ctx, state_->depthStencilFormat, static_cast<std::uint32_t>(grid.nx),
                         static_cast<std::uint32_t>(grid.ny), 1, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                         VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT));
  SCANSURF_ASSIGN_OR_RETURN(gpu::Buffer readback,
                            gpu::Buffer::create(ctx, layerBytes * static_cast<std::size_t>(slabLayers),
                                                VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::MemoryDomain::Readback));

  const int bits = state_->subPixelBits;
  const float invScale = static_cast<float>(std::ldexp(1.0, -bits));
  state_->lastSlabs = 0;

  for (int first = 1; first <= sliceLayers; first += slabLayers) {
    const int count = std::min(slabLayers, sliceLayers + 1 - first);

    // Vertices of the slab: each contour's points (a fan), then the feature's cover quad.
    std::vector<float> vertices;
    std::vector<std::vector<FeatureDraw>> draws(static_cast<std::size_t>(count));
    for (int l = 0; l < count; ++l) {
      for (const SliceRef& ref : byLayer[static_cast<std::size_t>(first + l)]) {
        FeatureDraw draw;
        draw.firstVertex = static_cast<std::uint32_t>(vertices.size() / 2);
        draw.label = labelOfFeature(ref.feature);
        draw.depth = rankDepth(rank[static_cast<std::size_t>(ref.feature)], featureCount);
        std::int64_t minU = std::numeric_limits<std::int64_t>::max(), minV = minU;
        std::int64_t maxU = std::numeric_limits<std::int64_t>::min(), maxV = maxU;
        for (const Contour& c : ref.slice->contours) {
          for (const Point2& p : c.points) {
            const SubpixelPoint sp = toSubpixel(grid, p.x, p.y, bits);
            minU = std::min(minU, sp.u), maxU = std::max(maxU, sp.u);
            minV = std::min(minV, sp.v), maxV = std::max(maxV, sp.v);
            vertices.push_back(static_cast<float>(sp.u) * invScale);
            vertices.push_back(static_cast<float>(sp.v) * invScale);
          }
          draw.contourCounts.push_back(static_cast<std::uint32_t>(c.points.size()));
        }
        // Cover quad: the fans stay inside the contours' bounding box; one pixel of margin.
        draw.coverFirst = static_cast<std::uint32_t>(vertices.size() / 2);
        const float x0 = std::max(0.0f, std::floor(static_cast<float>(minU) * invScale) - 1.0f);
        const float y0 = std::max(0.0f, std::floor(static_cast<float>(minV) * invScale) - 1.0f);
        const float x1 = std::min(static_cast<float>(grid.nx), std::ceil(static_cast<float>(maxU) * invScale) + 1.0f);
        const float y1 = std::min(static_cast<float>(grid.ny), std::ceil(static_cast<float>(maxV) * invScale) + 1.0f);
        vertices.insert(vertices.end(), {x0, y0, x1, y0, x1, y1, x0, y1});
        draws[static_cast<std::size_t>(l)].push_back(std::move(draw));
      }
    }
    if (vertices.empty()) vertices.assign(2, 0.0f);  // a buffer of size 0 is not allowed
    SCANSURF_ASSIGN_OR_RETURN(gpu::Buffer vertexBuffer,
                              gpu::Buffer::create(ctx, vertices.size() * sizeof(float), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT,
                                                  gpu::MemoryDomain::Upload));
    std::memcpy(vertexBuffer.mapped(), vertices.data(), vertices.size() * sizeof(float));

    SCANSURF_ASSIGN_OR_RETURN(gpu::OneShotCommands commands, gpu::OneShotCommands::begin(ctx));
    VkCommandBuffer cmd = commands.cmd();
    gpu::imageBarrier(cmd, labelImage.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                      VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                      VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
    gpu::imageBarrier(cmd, depthImage.handle(), VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT,
                      VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
                      VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);

    const VkDeviceSize zero = 0;
    VkBuffer vb = vertexBuffer.handle();
    gpu::RenderingDesc rendering;
    rendering.clearColor.uint32[0] = kBackground;
    rendering.depth = depthImage.layerView(0);
    rendering.stencil = true;
    rendering.area = {static_cast<std::uint32_t>(grid.nx), static_cast<std::uint32_t>(grid.ny)};
    rendering.viewport = {viewportW, viewportH};
    shared::ScanPush push{{2.0f / static_cast<float>(viewportW), 2.0f / static_cast<float>(viewportH)}, 0.0f, 0};

    for (int l = 0; l < count; ++l) {
      if (l > 0)  // the depth-stencil image is reused: the next clear waits for this layer's tests
        gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                           VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT,
                           VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                           VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT);
      rendering.color = labelImage.layerView(static_cast<std::uint32_t>(l));
      gpu::beginRendering(cmd, rendering);
      vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &zero);
      for (const FeatureDraw& d : draws[static_cast<std::size_t>(l)]) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, state_->stencilPipeline.get());
        push.depth = d.depth;
        push.label = d.label;
        vkCmdPushConstants(cmd, state_->layout.get(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           sizeof(push), &push);
        std::uint32_t v = d.firstVertex;
        for (std::uint32_t n : d.contourCounts) {
          vkCmdDraw(cmd, n, 1, v, 0);
          v += n;
        }
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, state_->coverPipeline.get());
        vkCmdDraw(cmd, 4, 1, d.coverFirst, 0);
      }
      vkCmdEndRendering(cmd);
    }

    gpu::imageBarrier(cmd, labelImage.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                      VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                      VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, static_cast<std::uint32_t>(count)};
    region.imageExtent = {static_cast<std::uint32_t>(grid.nx), static_cast<std::uint32_t>(grid.ny), 1};
    vkCmdCopyImageToBuffer(cmd, labelImage.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.handle(), 1, &region);
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                       VK_ACCESS_2_HOST_READ_BIT);
    SCANSURF_TRY(commands.submitAndWait());
    SCANSURF_TRY(readback.invalidate());
    std::memcpy(volume.labels.data() + grid.index(0, 0, first), readback.mapped(), layerBytes * static_cast<std::size_t>(count));
    ++state_->lastSlabs;
  }
  return volume;
}

}  // namespace scansurf::passes
