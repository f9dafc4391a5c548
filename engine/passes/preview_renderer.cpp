// scansurf passes: the offscreen preview, rendered with Vulkan graphics pipelines and read
// back supersampled; see preview_renderer.h.
#include "passes/preview_renderer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <span>
#include <string>

#include "core/memory.h"
#include "geometry/mesh/vec3.h"
#include "gpu/check.h"
#include "gpu/commands.h"
#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "passes/shader_registry.h"
#include "preview_push.h"

namespace scansurf {

std::optional<ViewPreset> parseViewPreset(std::string_view name) {
  static constexpr std::pair<std::string_view, ViewPreset> kNames[] = {
      {"oblique", ViewPreset::Oblique}, {"front", ViewPreset::Front}, {"back", ViewPreset::Back},    {"left", ViewPreset::Left},
      {"right", ViewPreset::Right},     {"top", ViewPreset::Top},     {"bottom", ViewPreset::Bottom}};
  for (const auto& [n, v] : kNames)
    if (n == name) return v;
  return std::nullopt;
}

}  // namespace scansurf

namespace scansurf {

std::uint64_t estimatePreviewBytes(const PreviewOptions& options) {
  // At twice the size: colour and depth images, the readback buffer and its host copy (4 bytes
  // a pixel each), then the picture, its averaging and its encoding at the size asked for.
  const std::uint64_t pixels = std::uint64_t{options.width} * options.height;
  return pixels * (4 * 4 * 4 + 3 * 4);
}

}  // namespace scansurf

namespace scansurf::passes {
namespace {

constexpr VkFormat kColorFormat = VK_FORMAT_R8G8B8A8_UNORM;  // values are sRGB, written as they are
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
constexpr std::uint32_t kSupersample = 2;

using glm::cross;
using glm::dot;
// a / |a| (not glm::normalize's a * inversesqrt: the camera stays the one the tests measured).
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
    case ViewPreset::Left: forward = {-1, 0, 0}; break;  // from the patient's left side
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

// The camera's axes in patient space, right-handed: right, up and forward (into the picture).
struct CameraBasis {
  Vec3 forward, up, right;
};

CameraBasis cameraBasis(ViewPreset view) {
  Vec3 forward{0, 1, 0}, up{0, 0, 1};
  viewBasis(view, forward, up);
  const Vec3 right = cross(forward, up);
  up = cross(right, forward);
  return {forward, up, right};
}

// One feature's triangles in the index buffer, and its colour.
struct Draw {
  std::uint32_t first, count;
  float color[4];
};

// What the preview draws: every feature's triangles in one index list, the opaque and the
// translucent draws, and the extent of the vertices they use along the camera's right, up and
// forward axes.
struct PreviewScene {
  std::vector<std::uint32_t> indices;
  std::vector<Draw> opaque, translucent;
  double lo[3] = {std::numeric_limits<double>::max(), std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
  double hi[3] = {std::numeric_limits<double>::lowest(), std::numeric_limits<double>::lowest(),
                  std::numeric_limits<double>::lowest()};
};

// The draw of feature f's triangles, which start at index `first`, in its colour and opacity.
Draw featureDraw(std::size_t f, const std::vector<std::uint32_t>& tris, std::size_t first, const PreviewOptions& options) {
  const Rgb c = f < options.colors.size() ? options.colors[f] : Rgb{160, 160, 160};
  const float alpha = f < options.opacity.size() ? std::clamp(options.opacity[f], 0.01f, 1.0f) : 1.0f;
  return Draw{static_cast<std::uint32_t>(first),
              static_cast<std::uint32_t>(tris.size()),
              {c[0] / 255.0f, c[1] / 255.0f, c[2] / 255.0f, alpha}};
}

// Gathers every feature with triangles into the scene. Errors (Internal): an index beyond the mesh.
Result<PreviewScene> gatherScene(const Surfaces& surfaces, const PreviewOptions& options, const CameraBasis& camera) {
  const MultiLabelMesh& mesh = surfaces.mesh;
  PreviewScene scene;
  for (std::size_t f = 0; f < surfaces.features.size(); ++f) {
    const std::vector<std::uint32_t>& tris = surfaces.features[f].triangles;
    if (tris.empty()) continue;
    const Draw d = featureDraw(f, tris, scene.indices.size(), options);
    const float alpha = d.color[3];
    (alpha < 1.0f ? scene.translucent : scene.opaque).push_back(d);
    for (std::uint32_t v : tris) {
      if (v >= mesh.vertexCount()) return makeError(Errc::Internal, "preview: a feature indexes a vertex beyond the mesh");
      const Vec3 p{mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]};
      const double q[3] = {dot(p, camera.right), dot(p, camera.up), dot(p, camera.forward)};
      for (int a = 0; a < 3; ++a) scene.lo[a] = std::min(scene.lo[a], q[a]), scene.hi[a] = std::max(scene.hi[a], q[a]);
    }
    scene.indices.insert(scene.indices.end(), tris.begin(), tris.end());
  }
  return scene;
}

// The push constants every draw shares: the orthographic camera fitted to the scene with a
// 6 % margin and square pixels, and a light over the viewer's shoulder.
shared::PreviewPush fitCamera(const CameraBasis& camera, const PreviewScene& scene, std::uint32_t width, std::uint32_t height) {
  const Vec3& forward = camera.forward;
  const Vec3& up = camera.up;
  const Vec3& right = camera.right;
  const double* lo = scene.lo;
  const double* hi = scene.hi;
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
    for (int c = 0; c < 3; ++c) push.clip[c * 4 + r] = static_cast<float>(rows[r][c]);
    push.clip[12 + r] = static_cast<float>(offset[r]);
  }
  push.clip[15] = 1.0f;
  // A light over the viewer's shoulder (up and to the left of the camera).
  const Vec3 light = normalized({-forward[0] + 0.35 * up[0] - 0.25 * right[0], -forward[1] + 0.35 * up[1] - 0.25 * right[1],
                                 -forward[2] + 0.35 * up[2] - 0.25 * right[2]});
  for (int a = 0; a < 3; ++a) push.light[a] = static_cast<float>(light[a]);
  return push;
}

// A host-visible buffer holding a copy of `bytes` bytes at data.
Result<gpu::Buffer> uploadBuffer(const gpu::Context& ctx, const void* data, std::size_t bytes, VkBufferUsageFlags usage) {
  SCANSURF_ASSIGN_OR_RETURN(gpu::Buffer buffer, gpu::Buffer::create(ctx, bytes, usage, gpu::MemoryDomain::Upload));
  std::memcpy(buffer.mapped(), data, bytes);
  return buffer;
}

// The supersampled picture's colour and depth images and the buffer it is read back in.
struct PreviewTargets {
  gpu::Image color;
  gpu::Image depth;
  gpu::Buffer readback;
};

Result<PreviewTargets> createPreviewTargets(const gpu::Context& ctx, std::uint32_t width, std::uint32_t height) {
  SCANSURF_ASSIGN_OR_RETURN(
      gpu::Image color,
      gpu::Image::create(ctx, kColorFormat, width, height, 1,
                         VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_IMAGE_ASPECT_COLOR_BIT));
  SCANSURF_ASSIGN_OR_RETURN(gpu::Image depth,
                            gpu::Image::create(ctx, kDepthFormat, width, height, 1, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                                               VK_IMAGE_ASPECT_DEPTH_BIT));
  SCANSURF_ASSIGN_OR_RETURN(
      gpu::Buffer readback,
      gpu::Buffer::create(ctx, std::size_t{4} * width * height, VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::MemoryDomain::Readback));
  return PreviewTargets{std::move(color), std::move(depth), std::move(readback)};
}

void transitionToAttachments(VkCommandBuffer cmd, const PreviewTargets& targets) {
  gpu::imageBarrier(cmd, targets.color.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                    VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                    VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  gpu::imageBarrier(cmd, targets.depth.handle(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                    VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                    VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
}

// Copies the colour image to the readback buffer, visible to the host.
void recordReadback(VkCommandBuffer cmd, const PreviewTargets& targets, std::uint32_t width, std::uint32_t height) {
  gpu::imageBarrier(cmd, targets.color.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                    VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {width, height, 1};
  vkCmdCopyImageToBuffer(cmd, targets.color.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, targets.readback.handle(), 1,
                         &region);
  gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                     VK_ACCESS_2_HOST_READ_BIT);
}

// Every pixel the background colour, opaque.
void fillWithBackground(std::vector<std::uint8_t>& rgba, const Rgb& background) {
  for (std::size_t p = 0; p < rgba.size(); p += 4)
    rgba[p] = background[0], rgba[p + 1] = background[1], rgba[p + 2] = background[2], rgba[p + 3] = 255;
}

// The width x height picture whose pixels average each kSupersample x kSupersample block of
// big (bigWidth pixels wide), rounded to nearest.
std::vector<std::uint8_t> averageBlocks(const std::vector<std::uint8_t>& big, std::uint32_t bigWidth, std::uint32_t width,
                                        std::uint32_t height) {
  std::vector<std::uint8_t> rgba(std::size_t{4} * width * height);
  for (std::uint32_t y = 0; y < height; ++y)
    for (std::uint32_t x = 0; x < width; ++x)
      for (int c = 0; c < 4; ++c) {
        unsigned sum = 0;
        for (std::uint32_t dy = 0; dy < kSupersample; ++dy)
          for (std::uint32_t dx = 0; dx < kSupersample; ++dx)
            sum +=
                big[4 * ((std::size_t{y} * kSupersample + dy) * bigWidth + x * kSupersample + dx) + static_cast<std::size_t>(c)];
        rgba[4 * (std::size_t{y} * width + x) + static_cast<std::size_t>(c)] =
            static_cast<std::uint8_t>((sum + kSupersample * kSupersample / 2) / (kSupersample * kSupersample));
      }
  return rgba;
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

namespace {

// The opaque draws, then the translucent ones blended over them.
void recordDraws(VkCommandBuffer cmd, const PreviewRenderer::State& state, const PreviewScene& scene, shared::PreviewPush& push) {
  for (const auto* pass : {&scene.opaque, &scene.translucent}) {
    if (pass->empty()) continue;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pass == &scene.opaque ? state.opaque.get() : state.translucent.get());
    for (const Draw& d : *pass) {
      std::memcpy(push.color, d.color, sizeof push.color);
      vkCmdPushConstants(cmd, state.layout.get(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof push,
                         &push);
      vkCmdDrawIndexed(cmd, d.count, 1, d.first, 0, 0);
    }
  }
}

// Renders the scene into a width x height picture on the device and reads it back into rgba.
Result<void> renderOnDevice(const PreviewRenderer::State& state, const MultiLabelMesh& mesh, const PreviewScene& scene,
                            shared::PreviewPush push, const Rgb& background, std::uint32_t width, std::uint32_t height,
                            std::vector<std::uint8_t>& rgba) {
  const gpu::Context& ctx = *state.ctx;
  SCANSURF_ASSIGN_OR_RETURN(
      gpu::Buffer vertexBuffer,
      uploadBuffer(ctx, mesh.positions.data(), mesh.positions.size() * sizeof(float), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT));
  SCANSURF_ASSIGN_OR_RETURN(
      gpu::Buffer indexBuffer,
      uploadBuffer(ctx, scene.indices.data(), scene.indices.size() * sizeof(std::uint32_t), VK_BUFFER_USAGE_INDEX_BUFFER_BIT));
  SCANSURF_ASSIGN_OR_RETURN(const PreviewTargets targets, createPreviewTargets(ctx, width, height));

  SCANSURF_ASSIGN_OR_RETURN(gpu::OneShotCommands commands, gpu::OneShotCommands::begin(ctx));
  VkCommandBuffer cmd = commands.cmd();
  transitionToAttachments(cmd, targets);
  gpu::RenderingDesc rendering;
  rendering.color = targets.color.layerView(0);
  rendering.clearColor = {{background[0] / 255.0f, background[1] / 255.0f, background[2] / 255.0f, 1.0f}};
  rendering.depth = targets.depth.layerView(0);
  rendering.area = {width, height};
  rendering.viewport = {width, height};
  gpu::beginRendering(cmd, rendering);
  const VkDeviceSize zero = 0;
  VkBuffer vb = vertexBuffer.handle();
  vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &zero);
  vkCmdBindIndexBuffer(cmd, indexBuffer.handle(), 0, VK_INDEX_TYPE_UINT32);
  recordDraws(cmd, state, scene, push);
  vkCmdEndRendering(cmd);
  recordReadback(cmd, targets, width, height);
  SCANSURF_TRY(commands.submitAndWait());
  SCANSURF_TRY(targets.readback.invalidate());
  std::memcpy(rgba.data(), targets.readback.mapped(), rgba.size());
  return {};
}

}  // namespace

Result<PreviewImage> PreviewRenderer::render(const Surfaces& surfaces, const PreviewOptions& options) {
  const gpu::Context& ctx = *state_->ctx;
  const std::uint32_t width = options.width * kSupersample, height = options.height * kSupersample;
  if (options.width == 0 || options.height == 0 || width > ctx.limits().maxImageDimension2D ||
      height > ctx.limits().maxImageDimension2D)
    return makeError(Errc::InvalidArgument, "preview: a " + std::to_string(options.width) + " x " +
                                                std::to_string(options.height) + " picture is empty or too large for the device");
  HostMemory limit{options.memoryLimit, "the limit asked for"};
  if (limit.bytes == 0) limit = availableHostMemory();
  if (const std::uint64_t need = estimatePreviewBytes(options); limit.bytes > 0 && need > limit.bytes)
    return makeError(Errc::ResourceLimit, "preview: a " + std::to_string(options.width) + " x " + std::to_string(options.height) +
                                              " picture needs about " + formatBytes(need) + " of memory to render; " +
                                              formatBytes(limit.bytes) + " may be used: " + limit.source);
  const CameraBasis camera = cameraBasis(options.view);
  SCANSURF_ASSIGN_OR_RETURN(const PreviewScene scene, gatherScene(surfaces, options, camera));

  std::vector<std::uint8_t> big(std::size_t{4} * width * height);
  if (!scene.indices.empty()) {
    const shared::PreviewPush push = fitCamera(camera, scene, width, height);
    SCANSURF_TRY(renderOnDevice(*state_, surfaces.mesh, scene, push, options.background, width, height, big));
  } else {
    fillWithBackground(big, options.background);
  }
  PreviewImage image;
  image.width = options.width;
  image.height = options.height;
  image.rgba = averageBlocks(big, width, image.width, image.height);
  return image;
}

}  // namespace scansurf::passes
