// scansurf gpu: one-shot command recording. Work is recorded, submitted and waited for
// inside one call, so nothing is in flight when a pass returns and RAII suffices.
#pragma once

#include <vulkan/vulkan.h>

#include "gpu/context.h"
#include "gpu/handle.h"

namespace scansurf::gpu {

class OneShotCommands {
 public:
  static Result<OneShotCommands> begin(const Context& ctx);
  VkCommandBuffer cmd() const { return cmd_.get(); }
  // Ends recording, submits to the context's queue and waits for completion.
  Result<void> submitAndWait();

 private:
  const Context* ctx_ = nullptr;
  Owned<VkCommandBuffer> cmd_;
};

// A global memory barrier between two stages (buffers and images alike).
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage,
                   VkAccessFlags2 dstAccess);

// A layout transition of all layers of an image.
void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to,
                  VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage,
                  VkAccessFlags2 dstAccess);

// One dynamic-rendering pass over a single layer, as scansurf's passes draw: a colour
// attachment cleared and stored, and a depth attachment (optionally also the stencil one)
// cleared to depth 1, stencil 0 and not stored, since only colour is read back.
struct RenderingDesc {
  VkImageView color = VK_NULL_HANDLE;  // in COLOR_ATTACHMENT_OPTIMAL
  VkClearColorValue clearColor{};
  VkImageView depth = VK_NULL_HANDLE;  // in DEPTH_ATTACHMENT_OPTIMAL, or DEPTH_STENCIL_ATTACHMENT_OPTIMAL with stencil
  bool stencil = false;                // the depth view is the stencil attachment too
  VkExtent2D area{};                   // render area and scissor, from the origin
  VkExtent2D viewport{};               // from the origin; may exceed area (scan conversion's power-of-two viewport)
};

// Begins rendering as `desc` says and sets the viewport and scissor, which every scansurf
// pipeline takes as dynamic state. The caller records its draws, then vkCmdEndRendering.
void beginRendering(VkCommandBuffer cmd, const RenderingDesc& desc);

}  // namespace scansurf::gpu
