// scansurf gpu: shader modules, layouts and pipelines (see pipeline.h).
#include "gpu/pipeline.h"

#include "gpu/check.h"

namespace scansurf::gpu {

Result<Owned<VkShaderModule>> createShaderModule(const Context& ctx, std::span<const std::uint32_t> spirv) {
  if (spirv.empty()) return makeError(Errc::Internal, "a shader is missing from this build (empty SPIR-V)");
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = spirv.size_bytes();
  info.pCode = spirv.data();
  VkShaderModule module = VK_NULL_HANDLE;
  SCANSURF_VK_TRY(vkCreateShaderModule(ctx.device(), &info, nullptr, &module));
  return Owned<VkShaderModule>(module, [d = ctx.device()](VkShaderModule m) { vkDestroyShaderModule(d, m, nullptr); });
}

Result<Owned<VkDescriptorSetLayout>> createStorageBufferSetLayout(const Context& ctx, std::uint32_t count,
                                                                  VkShaderStageFlags stages) {
  std::vector<VkDescriptorSetLayoutBinding> bindings(count);
  for (std::uint32_t i = 0; i < count; ++i) bindings[i] = {i, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, stages, nullptr};
  VkDescriptorSetLayoutCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  info.bindingCount = count;
  info.pBindings = bindings.data();
  VkDescriptorSetLayout layout = VK_NULL_HANDLE;
  SCANSURF_VK_TRY(vkCreateDescriptorSetLayout(ctx.device(), &info, nullptr, &layout));
  return Owned<VkDescriptorSetLayout>(
      layout, [d = ctx.device()](VkDescriptorSetLayout l) { vkDestroyDescriptorSetLayout(d, l, nullptr); });
}

Result<Owned<VkPipelineLayout>> createPipelineLayout(const Context& ctx, std::span<const VkDescriptorSetLayout> sets,
                                                     std::uint32_t pushConstantBytes, VkShaderStageFlags pushStages) {
  VkPushConstantRange range{pushStages, 0, pushConstantBytes};
  VkPipelineLayoutCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  info.setLayoutCount = static_cast<std::uint32_t>(sets.size());
  info.pSetLayouts = sets.data();
  info.pushConstantRangeCount = pushConstantBytes > 0 ? 1 : 0;
  info.pPushConstantRanges = &range;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  SCANSURF_VK_TRY(vkCreatePipelineLayout(ctx.device(), &info, nullptr, &layout));
  return Owned<VkPipelineLayout>(layout, [d = ctx.device()](VkPipelineLayout l) { vkDestroyPipelineLayout(d, l, nullptr); });
}

Result<Owned<VkPipeline>> createComputePipeline(const Context& ctx, VkPipelineLayout layout, VkShaderModule module,
                                                std::span<const std::uint32_t> specialization) {
  std::vector<VkSpecializationMapEntry> entries(specialization.size());
  for (std::uint32_t i = 0; i < entries.size(); ++i)
    entries[i] = {i, static_cast<std::uint32_t>(i * sizeof(std::uint32_t)), sizeof(std::uint32_t)};
  VkSpecializationInfo spec{static_cast<std::uint32_t>(entries.size()), entries.data(), specialization.size_bytes(),
                            specialization.data()};
  VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = module;
  info.stage.pName = "main";
  info.stage.pSpecializationInfo = entries.empty() ? nullptr : &spec;
  info.layout = layout;
  VkPipeline pipeline = VK_NULL_HANDLE;
  SCANSURF_VK_TRY(vkCreateComputePipelines(ctx.device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
  return Owned<VkPipeline>(pipeline, [d = ctx.device()](VkPipeline p) { vkDestroyPipeline(d, p, nullptr); });
}

Result<Owned<VkPipeline>> createRasterPipeline(const Context& ctx, const RasterPipelineDesc& desc) {
  VkPipelineShaderStageCreateInfo stages[2] = {};
  stages[0] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = desc.vertex;
  stages[0].pName = "main";
  stages[1] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = desc.fragment;
  stages[1].pName = "main";

  VkVertexInputBindingDescription binding{0, desc.vertexStride, VK_VERTEX_INPUT_RATE_VERTEX};
  VkVertexInputAttributeDescription attribute{0, 0, desc.vertexFormat, 0};
  VkPipelineVertexInputStateCreateInfo vertexInput{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  vertexInput.vertexBindingDescriptionCount = 1;
  vertexInput.pVertexBindingDescriptions = &binding;
  vertexInput.vertexAttributeDescriptionCount = 1;
  vertexInput.pVertexAttributeDescriptions = &attribute;

  VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = desc.topology;
  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = VK_CULL_MODE_NONE;
  raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  depth.depthTestEnable = desc.depthTest;
  depth.depthWriteEnable = desc.depthWrite;
  depth.depthCompareOp = desc.depthCompare;
  depth.stencilTestEnable = desc.stencilTest;
  depth.front = desc.stencil;
  depth.back = desc.stencil;
  VkPipelineColorBlendAttachmentState blendAttachment{};
  blendAttachment.colorWriteMask = desc.colorWrite;
  if (desc.alphaBlend) {
    blendAttachment.blendEnable = VK_TRUE;
    blendAttachment.srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
    blendAttachment.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    blendAttachment.colorBlendOp = VK_BLEND_OP_ADD;
    blendAttachment.srcAlphaBlendFactor = VK_BLEND_FACTOR_ZERO;
    blendAttachment.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
    blendAttachment.alphaBlendOp = VK_BLEND_OP_ADD;
  }
  VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  blend.attachmentCount = 1;
  blend.pAttachments = &blendAttachment;
  const VkDynamicState dynamicStates[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dynamic.dynamicStateCount = 2;
  dynamic.pDynamicStates = dynamicStates;

  VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  rendering.colorAttachmentCount = 1;
  rendering.pColorAttachmentFormats = &desc.colorFormat;
  rendering.depthAttachmentFormat = desc.depthFormat;
  rendering.stencilAttachmentFormat = desc.stencilFormat;

  VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  info.pNext = &rendering;
  info.stageCount = 2;
  info.pStages = stages;
  info.pVertexInputState = &vertexInput;
  info.pInputAssemblyState = &assembly;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = &depth;
  info.pColorBlendState = &blend;
  info.pDynamicState = &dynamic;
  info.layout = desc.layout;
  VkPipeline pipeline = VK_NULL_HANDLE;
  SCANSURF_VK_TRY(vkCreateGraphicsPipelines(ctx.device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
  return Owned<VkPipeline>(pipeline, [d = ctx.device()](VkPipeline p) { vkDestroyPipeline(d, p, nullptr); });
}

Result<StorageBufferSet> createStorageBufferSet(const Context& ctx, VkDescriptorSetLayout layout, std::uint32_t count) {
  VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, count};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = 1;
  poolInfo.poolSizeCount = 1;
  poolInfo.pPoolSizes = &size;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  SCANSURF_VK_TRY(vkCreateDescriptorPool(ctx.device(), &poolInfo, nullptr, &pool));
  StorageBufferSet out;
  out.pool = Owned<VkDescriptorPool>(pool, [d = ctx.device()](VkDescriptorPool p) { vkDestroyDescriptorPool(d, p, nullptr); });
  VkDescriptorSetAllocateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  setInfo.descriptorPool = pool;
  setInfo.descriptorSetCount = 1;
  setInfo.pSetLayouts = &layout;
  SCANSURF_VK_TRY(vkAllocateDescriptorSets(ctx.device(), &setInfo, &out.set));
  return out;
}

namespace {

VkWriteDescriptorSet storageBufferWrite(VkDescriptorSet set, std::uint32_t binding, const VkDescriptorBufferInfo& info) {
  VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  write.dstSet = set;
  write.dstBinding = binding;
  write.descriptorCount = 1;
  write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  write.pBufferInfo = &info;
  return write;
}

}  // namespace

void bindStorageBuffers(const Context& ctx, VkDescriptorSet set, std::span<const VkBuffer> buffers) {
  std::vector<VkDescriptorBufferInfo> infos(buffers.size());
  std::vector<VkWriteDescriptorSet> writes(buffers.size());
  for (std::uint32_t i = 0; i < buffers.size(); ++i) {
    infos[i] = {buffers[i], 0, VK_WHOLE_SIZE};
    writes[i] = storageBufferWrite(set, i, infos[i]);
  }
  vkUpdateDescriptorSets(ctx.device(), static_cast<std::uint32_t>(writes.size()), writes.data(), 0, nullptr);
}

void bindStorageBuffer(const Context& ctx, VkDescriptorSet set, std::uint32_t binding, VkBuffer buffer, VkDeviceSize offset,
                       VkDeviceSize range) {
  const VkDescriptorBufferInfo info{buffer, offset, range};
  const VkWriteDescriptorSet write = storageBufferWrite(set, binding, info);
  vkUpdateDescriptorSets(ctx.device(), 1, &write, 0, nullptr);
}

}  // namespace scansurf::gpu
