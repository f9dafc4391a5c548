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
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);

// A layout transition of all layers of an image.
void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to,
                  VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage,
                  VkAccessFlags2 dstAccess);

}  // namespace scansurf::gpu
