// scansurf: running the engine on a Vulkan device the application already owns.
// The only public header that includes Vulkan; include it only to embed scansurf.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>

namespace scansurf {

// Handles of the application's Vulkan objects. scansurf borrows them (never destroys them)
// and creates its own command pool, pipelines and buffers on the device.
// Requirements: a Vulkan 1.3 device created with the dynamicRendering and synchronization2 features; `queue` from
// `queueFamilyIndex`, which supports graphics and compute. scansurf submits to the queue and
// waits inside each call, so the application must not use the queue from another thread
// during a call (Vulkan's external synchronization rule for queues).
struct ExternalVulkan {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  std::uint32_t queueFamilyIndex = 0;
};

}  // namespace scansurf
