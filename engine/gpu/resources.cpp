// scansurf gpu: buffers and images that own their memory (see resources.h).
#include "gpu/resources.h"

#include "gpu/check.h"

namespace scansurf::gpu {
namespace {

Result<Owned<VkDeviceMemory>> allocate(const Context& ctx, const VkMemoryRequirements& req, VkMemoryPropertyFlags required,
                                       VkMemoryPropertyFlags preferred, std::uint32_t* typeOut) {
  SCANSURF_ASSIGN_OR_RETURN(const std::uint32_t type, ctx.findMemoryType(req.memoryTypeBits, required, preferred));
  VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  info.allocationSize = req.size;
  info.memoryTypeIndex = type;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  const VkResult r = vkAllocateMemory(ctx.device(), &info, nullptr, &memory);
  if (r == VK_ERROR_OUT_OF_DEVICE_MEMORY || r == VK_ERROR_OUT_OF_HOST_MEMORY)
    return makeError(Errc::OutOfMemory, "out of GPU memory allocating " + std::to_string(req.size >> 20) + " MiB");
  SCANSURF_VK_TRY(r);
  *typeOut = type;
  return Owned<VkDeviceMemory>(memory, [d = ctx.device()](VkDeviceMemory m) { vkFreeMemory(d, m, nullptr); });
}

}  // namespace

Result<Buffer> Buffer::create(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryDomain domain) {
  Buffer b;
  b.device_ = ctx.device();
  b.size_ = size;
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer buffer = VK_NULL_HANDLE;
  SCANSURF_VK_TRY(vkCreateBuffer(ctx.device(), &info, nullptr, &buffer));
  b.buffer_ = Owned<VkBuffer>(buffer, [d = ctx.device()](VkBuffer x) { vkDestroyBuffer(d, x, nullptr); });

  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(ctx.device(), buffer, &req);
  VkMemoryPropertyFlags required = 0;
  VkMemoryPropertyFlags preferred = 0;
  switch (domain) {
    case MemoryDomain::Device: preferred = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT; break;
    case MemoryDomain::Upload: required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT; break;
    case MemoryDomain::Readback:
      required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
      preferred = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
      break;
  }
  std::uint32_t type = 0;
  SCANSURF_ASSIGN_OR_RETURN(b.memory_, allocate(ctx, req, required, preferred, &type));
  SCANSURF_VK_TRY(vkBindBufferMemory(ctx.device(), buffer, b.memory_.get(), 0));
  if (domain != MemoryDomain::Device) {
    SCANSURF_VK_TRY(vkMapMemory(ctx.device(), b.memory_.get(), 0, VK_WHOLE_SIZE, 0, &b.mapped_));
    b.coherent_ = (ctx.memoryTypeFlags(type) & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT) != 0;
  }
  return b;
}

Result<void> Buffer::invalidate() const {
  if (coherent_ || !mapped_) return {};
  VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE};
  range.memory = memory_.get();
  range.size = VK_WHOLE_SIZE;
  SCANSURF_VK_TRY(vkInvalidateMappedMemoryRanges(device_, 1, &range));
  return {};
}

Result<void> Buffer::flush() const {
  if (coherent_ || !mapped_) return {};
  VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE};
  range.memory = memory_.get();
  range.size = VK_WHOLE_SIZE;
  SCANSURF_VK_TRY(vkFlushMappedMemoryRanges(device_, 1, &range));
  return {};
}

Result<Image> Image::create(const Context& ctx, VkFormat format, std::uint32_t width, std::uint32_t height, std::uint32_t layers,
                            VkImageUsageFlags usage, VkImageAspectFlags aspect) {
  Image img;
  img.format_ = format;
  img.aspect_ = aspect;
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = format;
  info.extent = {width, height, 1};
  info.mipLevels = 1;
  info.arrayLayers = layers;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkImage image = VK_NULL_HANDLE;
  SCANSURF_VK_TRY(vkCreateImage(ctx.device(), &info, nullptr, &image));
  img.image_ = Owned<VkImage>(image, [d = ctx.device()](VkImage x) { vkDestroyImage(d, x, nullptr); });

  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(ctx.device(), image, &req);
  std::uint32_t type = 0;
  SCANSURF_ASSIGN_OR_RETURN(img.memory_, allocate(ctx, req, 0, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, &type));
  SCANSURF_VK_TRY(vkBindImageMemory(ctx.device(), image, img.memory_.get(), 0));

  img.views_.reserve(layers);
  for (std::uint32_t layer = 0; layer < layers; ++layer) {
    VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    viewInfo.image = image;
    viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
    viewInfo.format = format;
    viewInfo.subresourceRange = {aspect, 0, 1, layer, 1};
    VkImageView view = VK_NULL_HANDLE;
    SCANSURF_VK_TRY(vkCreateImageView(ctx.device(), &viewInfo, nullptr, &view));
    img.views_.emplace_back(view, [d = ctx.device()](VkImageView v) { vkDestroyImageView(d, v, nullptr); });
  }
  return img;
}

}  // namespace scansurf::gpu
