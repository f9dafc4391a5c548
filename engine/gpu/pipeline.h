// scansurf gpu: shader modules, layouts and pipelines.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>
#include <vector>

#include "gpu/context.h"
#include "gpu/handle.h"

namespace scansurf::gpu {

Result<Owned<VkShaderModule>> createShaderModule(const Context& ctx, std::span<const std::uint32_t> spirv);

// A set layout of `count` storage buffers at bindings 0..count-1.
Result<Owned<VkDescriptorSetLayout>> createStorageBufferSetLayout(const Context& ctx, std::uint32_t count,
                                                                  VkShaderStageFlags stages);

// One descriptor set of `layout` (createStorageBufferSetLayout with `count` buffers) from a
// pool of its own; the set lives as long as the pool.
struct StorageBufferSet {
  Owned<VkDescriptorPool> pool;
  VkDescriptorSet set = VK_NULL_HANDLE;
};
Result<StorageBufferSet> createStorageBufferSet(const Context& ctx, VkDescriptorSetLayout layout, std::uint32_t count);
// Points binding i of `set` at the whole of buffers[i].
void bindStorageBuffers(const Context& ctx, VkDescriptorSet set, std::span<const VkBuffer> buffers);
// Points one binding of `set` at [offset, offset + range) of `buffer`.
void bindStorageBuffer(const Context& ctx, VkDescriptorSet set, std::uint32_t binding, VkBuffer buffer, VkDeviceSize offset = 0,
                       VkDeviceSize range = VK_WHOLE_SIZE);

Result<Owned<VkPipelineLayout>> createPipelineLayout(const Context& ctx, std::span<const VkDescriptorSetLayout> sets,
                                                     std::uint32_t pushConstantBytes, VkShaderStageFlags pushStages);

// Compute pipeline; specialization constant i (constant_id = i) gets specialization[i].
Result<Owned<VkPipeline>> createComputePipeline(const Context& ctx, VkPipelineLayout layout, VkShaderModule module,
                                                std::span<const std::uint32_t> specialization);

// What scansurf's graphics pipelines vary in, named by intent.
struct RasterPipelineDesc {
  VkShaderModule vertex = VK_NULL_HANDLE;
  VkShaderModule fragment = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkFormat colorFormat = VK_FORMAT_UNDEFINED;
  VkFormat depthFormat = VK_FORMAT_UNDEFINED;    // UNDEFINED: no depth attachment
  VkFormat stencilFormat = VK_FORMAT_UNDEFINED;  // UNDEFINED: no stencil attachment
  VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_FAN;
  VkFormat vertexFormat = VK_FORMAT_R32G32_SFLOAT;  // one attribute at location 0
  std::uint32_t vertexStride = 8;
  VkColorComponentFlags colorWrite = 0;  // 0: colour untouched (stencil-only passes)
  bool alphaBlend = false;               // colour = src-alpha over dst; dst alpha kept
  bool depthTest = false;
  bool depthWrite = false;
  VkCompareOp depthCompare = VK_COMPARE_OP_LESS;
  bool stencilTest = false;
  VkStencilOpState stencil{};
};

// Graphics pipeline for dynamic rendering with dynamic viewport and scissor; no culling.
Result<Owned<VkPipeline>> createRasterPipeline(const Context& ctx, const RasterPipelineDesc& desc);

}  // namespace scansurf::gpu
