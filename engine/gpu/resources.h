// scansurf gpu: buffers and images that own their memory, chosen by intent.
#pragma once

#include <vulkan/vulkan.h>

#include <cstddef>
#include <vector>

#include "gpu/context.h"
#include "gpu/handle.h"

namespace scansurf::gpu {

enum class MemoryDomain {
  Device,    // GPU-only: fastest for the device
  Upload,    // host writes, device reads: host-visible, coherent, mapped
  Readback,  // device writes, host reads: host-visible, cached when possible, mapped
};

class Buffer {
 public:
  static Result<Buffer> create(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryDomain domain);

  VkBuffer handle() const { return buffer_.get(); }
  VkDeviceSize size() const { return size_; }
  // Host pointer for Upload and Readback buffers (persistently mapped), else nullptr.
  void* mapped() const { return mapped_; }
  // Makes device writes visible to the host on non-coherent memory (call after the wait).
  Result<void> invalidate() const;
  // Makes host writes visible to the device on non-coherent memory (call before the submit).
  Result<void> flush() const;

 private:
  Owned<VkDeviceMemory> memory_;  // declared first: released after the buffer
  Owned<VkBuffer> buffer_;
  VkDevice device_ = VK_NULL_HANDLE;
  VkDeviceSize size_ = 0;
  void* mapped_ = nullptr;
  bool coherent_ = true;
};

// A 2D image with `layers` array layers on device memory, with one view per layer.
class Image {
 public:
  static Result<Image> create(const Context& ctx, VkFormat format, std::uint32_t width, std::uint32_t height,
                              std::uint32_t layers, VkImageUsageFlags usage, VkImageAspectFlags aspect);

  VkImage handle() const { return image_.get(); }
  VkImageView layerView(std::uint32_t layer) const { return views_[layer].get(); }
  VkFormat format() const { return format_; }
  VkImageAspectFlags aspect() const { return aspect_; }

 private:
  Owned<VkDeviceMemory> memory_;
  Owned<VkImage> image_;
  std::vector<Owned<VkImageView>> views_;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  VkImageAspectFlags aspect_ = 0;
};

}  // namespace scansurf::gpu
