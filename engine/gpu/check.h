// scansurf gpu: turning VkResult failures into scansurf::Error with the call and location.
#pragma once

#include <vulkan/vulkan.h>

#include <string>

#include "scansurf/result.h"

namespace scansurf::gpu {

const char* vkResultName(VkResult result);
Unexpected vulkanError(VkResult result, const char* call, const char* file, int line);

}  // namespace scansurf::gpu

// Runs a Vulkan call; on failure returns an Errc::Vulkan error naming the call, the VkResult,
// file and line. Never compiled away.
#define SCANSURF_VK_TRY(call)                                                                                               \
  do {                                                                                                                      \
    const VkResult scansurfVkResult_ = (call);                                                                              \
    if (scansurfVkResult_ != VK_SUCCESS) return ::scansurf::gpu::vulkanError(scansurfVkResult_, #call, __FILE__, __LINE__); \
  } while (false)
