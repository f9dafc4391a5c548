#include "passes/preview.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <span>
#include <string>

#include "gpu/check.h"
#include "passes/shader_registry.h"
#include "gpu/commands.h"
#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "preview_push.h"

namespace scansurf {

std::optional<ViewPreset> parseViewPreset(std::string_view name) {
  static constexpr std::pair<std::string_view, ViewPreset> kNames[] = {
      {"oblique", ViewPreset::Oblique}, {"front", ViewPreset::Front}, {"back", ViewPreset::Back},
      {"left", ViewPreset::Left},       {"right", ViewPreset::Right}, {"top", ViewPreset::Top},
      {"bottom", ViewPreset::Bottom}};
  for (const auto& [n, v] : kNames)
    if (n == name) return v;
  return std::nullopt;
}

}  // namespace scansurf

namespace scansurf::passes {
namespace {

constexpr VkFormat kColorFormat = VK_FORMAT_R8G8B8A8_UNORM;  // values are sRGB, written as they are
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
constexpr std::uint32_t kSupersample = 2;

using Vec3 = std::array<double, 3>;
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 normalized(const Vec3& a) {
  const double l = std::sqrt(dot(a, a));
  return {a[0] / l, a[1] / l, a[2] / l};
}

// The direction the camera looks in and the screen's up, in patient axes (LPS).
void viewBasis(ViewPreset view, Vec3& forward, Vec3& up) {
  up = {0, 0, 1};
  switch (view) {
    case ViewPreset::Front: forward = {0, 1, 0}; break;
    case ViewPreset::Back: forward = {0, -1, 0}; break;
    case ViewPreset::Left: forward = {-1, 0, 0}; break;   // from the patient's left side
    case ViewPreset::Right: forward = {1, 0, 0}; break;
    case ViewPreset::Top: forward = {0, 0, -1}, up = {0, -1, 0}; break;
    case ViewPreset::Bottom: forward = {0, 0, 1}, up = {0, -1, 0}; break;
    case ViewPreset::Oblique: forward = normalized({0.55, 1.0, -0.45}); break;  // front, right, above
  }
}

// Graphics pipeline for the preview: vec3 positions, RGBA output, depth LESS_OR_EQUAL, two-sided
// (inner cavities stay visible); translucent surfaces blend and leave the depth buffer alone.
Result<gpu::Owned<VkPipeline>> createPreviewPipeline(const gpu::Context& ctx, VkShaderModule vertex, VkShaderModule fragment,
                                                     VkPipelineLayout layout, bool translucent) {
  gpu::RasterPipelineDesc desc;
  desc.vertex = vertex;
  desc.fragment = fragment;
  desc.layout = layout;
  desc.colorFormat = kColorFormat;
  desc.depthFormat = kDepthFormat;
  desc.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  desc.vertexFormat = VK_FORMAT_R32G32B32_SFLOAT;
  desc.vertexStride = 3 * sizeof(float);
  desc.colorWrite = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
  desc.alphaBlend = translucent;
  desc.depthTest = true;
  desc.depthWrite = !translucent;
  desc.depthCompare = VK_COMPARE_OP_LESS_OR_EQUAL;
  return gpu::createRasterPipeline(ctx, desc);
}

}  // namespace

struct PreviewRenderer::State {
  const gpu::Context* ctx = nullptr;
  gpu::Owned<VkShaderModule> vertex;
  gpu::Owned<VkShaderModule> fragment;
  gpu::Owned<VkPipelineLayout> layout;
  gpu::Owned<VkPipeline> opaque;
  gpu::Owned<VkPipeline> translucent;
};

PreviewRenderer::PreviewRenderer(std::unique_ptr<State> state) : state_(std::move(state)) {}
PreviewRenderer::~PreviewRenderer() = default;

Result<std::unique_ptr<PreviewRenderer>> PreviewRenderer::create(const gpu::Context& ctx) {
  VkFormatProperties props;
  vkGetPhysicalDeviceFormatProperties(ctx.physicalDevice(), kDepthFormat, &props);
  if (!(props.optimalTilingFeatures & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT))
    return makeError(Errc::NoDevice, "the device cannot render to a D32_SFLOAT depth buffer");
  auto s = std::make_unique<State>();
  s->ctx = &ctx;
  SCANSURF_ASSIGN_OR_RETURN(s->vertex, gpu::createShaderModule(ctx, shaders::spirv("preview.vert")));
  SCANSURF_ASSIGN_OR_RETURN(s->fragment, gpu::createShaderModule(ctx, shaders::spirv("preview.frag")));
  SCANSURF_ASSIGN_OR_RETURN(s->layout, gpu::createPipelineLayout(ctx, {}, sizeof(shared::PreviewPush),
                                                                 VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT));
  SCANSURF_ASSIGN_OR_RETURN(s->opaque, createPreviewPipeline(ctx, s->vertex.get(), s->fragment.get(), s->layout.get(), false));
  SCANSURF_ASSIGN_OR_RETURN(s->translucent,
                            createPreviewPipeline(ctx, s->vertex.get(), s->fragment.get(), s->layout.get(), true));
  return std::unique_ptr<PreviewRenderer>(new PreviewRenderer(std::move(s)));
}

Result<PreviewImage> PreviewRenderer::render(const Surfaces& surfaces, const PreviewOptions& options) {
  const gpu::Context& ctx = *state_->ctx;
  const std::uint32_t width = options.width * kSupersample, height = options.height * kSupersample;
  if (options.width == 0 || options.height == 0 || width > ctx.limits().maxImageDimension2D ||
      height > ctx.limits().maxImageDimension2D)
    return makeError(Errc::InvalidArgument, "preview: a " + std::to_string(options.width) + " x " +
                                                std::to_string(options.height) + " picture is empty or too large for the device");
  const MultiLabelMesh& mesh = surfaces.mesh;

  // Camera: orthographic, fitted to the projected extent of every vertex a feature uses.
  Vec3 forward{0, 1, 0}, up{0, 0, 1};
  viewBasis(options.view, forward, up);
  const Vec3 right = cross(forward, up);
  up = cross(right, forward);
  std::vector<std::uint32_t> indices;
  struct Draw {
    std::uint32_t first, count;
    float color[4];
  };
  std::vector<Draw> opaque, translucent;
  double lo[3] = {std::numeric_limits<double>::max(), std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
  double hi[3] = {std::numeric_limits<double>::lowest(), std::numeric_limits<double>::lowest(),
                  std::numeric_limits<double>::lowest()};
  for (std::size_t f = 0; f < surfaces.features.size(); ++f) {
    const std::vector<std::uint32_t>& tris = surfaces.features[f].triangles;
    if (tris.empty()) continue;
    const Rgb c = f < options.colors.size() ? options.colors[f] : Rgb{160, 160, 160};
    const float alpha = f < options.opacity.size() ? std::clamp(options.opacity[f], 0.01f, 1.0f) : 1.0f;
    Draw d{static_cast<std::uint32_t>(indices.size()), static_cast<std::uint32_t>(tris.size()),
           {c[0] / 255.0f, c[1] / 255.0f, c[2] / 255.0f, alpha}};
    (alpha < 1.0f ? translucent : opaque).push_back(d);
    for (std::uint32_t v : tris) {
      if (v >= mesh.vertexCount()) return makeError(Errc::Internal, "preview: a feature indexes a vertex beyond the mesh");
      const Vec3 p{mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]};
      const double q[3] = {dot(p, right), dot(p, up), dot(p, forward)};
      for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], q[a]), hi[a] = std::max(hi[a], q[a]);
    }
    indices.insert(indices.end(), tris.begin(), tris.end());
  }

  PreviewImage image;
  image.width = options.width;
  image.height = options.height;
  std::vector<std::uint8_t> big(std::size_t{4} * width * height);
  if (!indices.empty()) {
    // Fit with a 6 % margin; keep pixels square.
    const double cx = 0.5 * (lo[0] + hi[0]), cy = 0.5 * (lo[1] + hi[1]);
    const double spanX = std::max(hi[0] - lo[0], 1e-9) * 1.06, spanY = std::max(hi[1] - lo[1], 1e-9) * 1.06;
    const double aspect = static_cast<double>(width) / height;
    const double halfW = 0.5 * std::max(spanX, spanY * aspect), halfH = halfW / aspect;
    const double depthLo = lo[2] - 1e-6 * (1 + std::abs(lo[2])), depthSpan = (hi[2] - depthLo) * (1 + 1e-6) + 1e-9;
    // clip = M * (p, 1), column-major; Vulkan's y points down and depth runs 0 (near) .. 1.
    shared::PreviewPush push{};
    const Vec3 rowX{right[0] / halfW, right[1] / halfW, right[2] / halfW};
    const Vec3 rowY{-up[0] / halfH, -up[1] / halfH, -up[2] / halfH};
    const Vec3 rowZ{forward[0] / depthSpan, forward[1] / depthSpan, forward[2] / depthSpan};
    const double offset[3] = {-cx / halfW, cy / halfH, -depthLo / depthSpan};
    const Vec3 rows[3] = {rowX, rowY, rowZ};
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) push.clip[c * 4 + r] = static_cast<float>(rows[r][static_cast<std::size_t>(c)]);
      push.clip[12 + r] = static_cast<float>(offset[r]);
    }
    push.clip[15] = 1.0f;
    // A light over the viewer's shoulder (up and to the left of the camera).
    const Vec3 light = normalized({-forward[0] + 0.35 * up[0] - 0.25 * right[0], -forward[1] + 0.35 * up[1] - 0.25 * right[1],
                                   -forward[2] + 0.35 * up[2] - 0.25 * right[2]});
    for (int a = 0; a < 3; ++a) push.light[a] = static_cast<float>(light[static_cast<std::size_t>(a)]);

    SCANSURF_ASSIGN_OR_RETURN(gpu::Buffer vertexBuffer,
                              gpu::Buffer::create(ctx, mesh.positions.size() * sizeof(float), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT,
                                                  gpu::MemoryDomain::Upload));
    std::memcpy(vertexBuffer.mapped(), mesh.positions.data(), mesh.positions.size() * sizeof(float));
    SCANSURF_ASSIGN_OR_RETURN(gpu::Buffer indexBuffer,
                              gpu::Buffer::create(ctx, indices.size() * sizeof(std::uint32_t), VK_BUFFER_USAGE_INDEX_BUFFER_BIT,
                                                  gpu::MemoryDomain::Upload));
    std::memcpy(indexBuffer.mapped(), indices.data(), indices.size() * sizeof(std::uint32_t));
    SCANSURF_ASSIGN_OR_RETURN(gpu::Image color, gpu::Image::create(ctx, kColorFormat, width, height, 1,
                                                                   VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                                                   VK_IMAGE_ASPECT_COLOR_BIT));
    SCANSURF_ASSIGN_OR_RETURN(gpu::Image depth, gpu::Image::create(ctx, kDepthFormat, width, height, 1,
                                                                   VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT));
    SCANSURF_ASSIGN_OR_RETURN(gpu::Buffer readback,
                              gpu::Buffer::create(ctx, big.size(), VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::MemoryDomain::Readback));

    SCANSURF_ASSIGN_OR_RETURN(gpu::OneShotCommands commands, gpu::OneShotCommands::begin(ctx));
    VkCommandBuffer cmd = commands.cmd();
    gpu::imageBarrier(cmd, color.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                      VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                      VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
    gpu::imageBarrier(cmd, depth.handle(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                      VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                      VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
    gpu::RenderingDesc rendering;
    rendering.color = color.layerView(0);
    rendering.clearColor = {{options.background[0] / 255.0f, options.background[1] / 255.0f,
                             options.background[2] / 255.0f, 1.0f}};
    rendering.depth = depth.layerView(0);
    rendering.area = {width, height};
    rendering.viewport = {width, height};
    gpu::beginRendering(cmd, rendering);
    const VkDeviceSize zero = 0;
    VkBuffer vb = vertexBuffer.handle();
    vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &zero);
    vkCmdBindIndexBuffer(cmd, indexBuffer.handle(), 0, VK_INDEX_TYPE_UINT32);
    for (const auto* pass : {&opaque, &translucent}) {
      if (pass->empty()) continue;
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                        pass == &opaque ? state_->opaque.get() : state_->translucent.get());
      for (const Draw& d : *pass) {
        std::memcpy(push.color, d.color, sizeof push.color);
        vkCmdPushConstants(cmd, state_->layout.get(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           sizeof push, &push);
        vkCmdDrawIndexed(cmd, d.count, 1, d.first, 0, 0);
      }
    }
    vkCmdEndRendering(cmd);
    gpu::imageBarrier(cmd, color.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                      VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                      VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {width, height, 1};
    vkCmdCopyImageToBuffer(cmd, color.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.handle(), 1, &region);
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                       VK_ACCESS_2_HOST_READ_BIT);
    SCANSURF_TRY(commands.submitAndWait());
    SCANSURF_TRY(readback.invalidate());
    std::memcpy(big.data(), readback.mapped(), big.size());
  } else {
    for (std::size_t p = 0; p < big.size(); p += 4)
      big[p] = options.background[0], big[p + 1] = options.background[1], big[p + 2] = options.background[2], big[p + 3] = 255;
  }

  // Average each kSupersample x kSupersample block.
  image.rgba.resize(std::size_t{4} * image.width * image.height);
  for (std::uint32_t y = 0; y < image.height; ++y)
    for (std::uint32_t x = 0; x < image.width; ++x)
      for (int c = 0; c < 4; ++c) {
        unsigned sum = 0;
        for (std::uint32_t dy = 0; dy < kSupersample; ++dy)
          for (std::uint32_t dx = 0; dx < kSupersample; ++dx)
            sum += big[4 * ((std::size_t{y} * kSupersample + dy) * width + x * kSupersample + dx) + static_cast<std::size_t>(c)];
        image.rgba[4 * (std::size_t{y} * image.width + x) + static_cast<std::size_t>(c)] =
            static_cast<std::uint8_t>((sum + kSupersample * kSupersample / 2) / (kSupersample * kSupersample));
      }
  return image;
}

}  // namespace scansurf::passes
