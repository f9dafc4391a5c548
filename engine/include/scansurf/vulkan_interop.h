// scansurf: running the engine on a Vulkan device the application already owns, and
// extracting surfaces from labels already on that device.
// The only public header that includes Vulkan; include it only to embed scansurf.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>

#include "scansurf/grid.h"

namespace scansurf {

// Handles of the application's Vulkan objects. scansurf borrows them (never destroys them)
// and creates its own command pool, pipelines, buffers and fences on the device.
// Requirements, checked by Engine::adopt (Errc::NoDevice names what is missing):
//  - a physical device with Vulkan 1.3 and a device created with the dynamicRendering and
//    synchronization2 features enabled (pass the VkDeviceCreateInfo's feature chain in
//    `enabledFeatures` to have that checked too);
//  - `queue` from `queueFamilyIndex`, a family that supports graphics and compute.
// Synchronization: scansurf submits to `queue` and waits on its own fence inside each call,
// so nothing of scansurf's is in flight between calls. The application must not use that
// queue from another thread during a call (Vulkan's external synchronization rule for
// queues); it may use its other queues freely. scansurf never calls vkDeviceWaitIdle or
// vkQueueWaitIdle on a borrowed device, and destroying the Engine waits for nothing.
struct ExternalVulkan {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  std::uint32_t queueFamilyIndex = 0;
  // Optional: the pNext chain of features the device was created with (VkDeviceCreateInfo::
  // pNext, e.g. a VkPhysicalDeviceFeatures2 or VkPhysicalDeviceVulkan13Features). When given,
  // adopt checks that the required features are in it.
  const void* enabledFeatures = nullptr;
};

// Labels the application holds on the adopted device (e.g. the output of its segmentation
// network), for Engine::extract without a round trip through the host.
// Layout: one label per voxel of `grid`, x fastest, then y, then z, tightly packed from
// `offset`, as `bitsPerLabel` unsigned integers (16 or 32; 32-bit values must be at most
// 65535). Label 0 is background, label i + 1 is feature i; the outermost voxels of the grid
// (its one-voxel border) must be background so that every surface closes.
// The buffer must hold offset + nx*ny*nz*bitsPerLabel/8 bytes (not checkable from the handle:
// with validation on, a shorter buffer is reported by the layers), needs
// VK_BUFFER_USAGE_TRANSFER_SRC_BIT and must be owned by the queue family
// scansurf was given. Writes to it must be complete before the call: submitted earlier to the
// same queue (scansurf's first command waits on them with a full memory barrier) or waited for
// by the application. scansurf only reads it.
struct DeviceLabelVolume {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceSize offset = 0;
  std::uint32_t bitsPerLabel = 16;
  Grid grid;
};

}  // namespace scansurf
