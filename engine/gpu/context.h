// scansurf gpu: the Vulkan context every pass is handed (never a global). Owns the instance,
// debug messenger, device and command pool, or borrows the application's instance, device
// and queue (then owns only its command pool).
#pragma once

#include <vulkan/vulkan.h>

#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "gpu/handle.h"
#include "scansurf/device.h"
#include "scansurf/result.h"
#include "scansurf/vulkan_interop.h"

namespace scansurf::gpu {

class Context {
 public:
  static Result<std::unique_ptr<Context>> create(const EngineOptions& options);
  static Result<std::unique_ptr<Context>> adopt(const ExternalVulkan& vulkan, const EngineOptions& options);
  static Result<std::vector<DeviceListing>> listDevices();
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physicalDevice() const { return physicalDevice_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  std::uint32_t queueFamily() const { return queueFamily_; }
  VkCommandPool commandPool() const { return commandPool_.get(); }
  const VkPhysicalDeviceLimits& limits() const { return properties_.limits; }
  const DeviceInfo& info() const { return info_; }

  // A memory type allowed by typeBits with all `required` flags, preferring `preferred` ones.
  Result<std::uint32_t> findMemoryType(std::uint32_t typeBits, VkMemoryPropertyFlags required,
                                       VkMemoryPropertyFlags preferred) const;
  VkMemoryPropertyFlags memoryTypeFlags(std::uint32_t type) const;

  std::uint64_t validationMessageCount() const { return validationMessages_.load(); }

 private:
  Context() = default;
  Result<void> finishSetup();
  // create()'s steps, as vk-bootstrap splits them: the instance (with the validation layer and
  // its messenger when asked), then the logical device and queue on the chosen physical device.
  VkDebugUtilsMessengerCreateInfoEXT messengerInfo();
  Result<void> createInstance(bool validation);
  Result<void> createMessenger();
  Result<void> createDevice(VkPhysicalDevice physicalDevice);
  static VKAPI_ATTR VkBool32 VKAPI_CALL debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                      VkDebugUtilsMessageTypeFlagsEXT types,
                                                      const VkDebugUtilsMessengerCallbackDataEXT* data, void* user);

  // Destroyed in reverse order of declaration: pool, then device, messenger, instance.
  Owned<VkInstance> ownedInstance_;
  Owned<VkDebugUtilsMessengerEXT> messenger_;
  Owned<VkDevice> ownedDevice_;
  Owned<VkCommandPool> commandPool_;

  VkInstance instance_ = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  std::uint32_t queueFamily_ = 0;
  VkPhysicalDeviceProperties properties_{};
  VkPhysicalDeviceMemoryProperties memory_{};
  DeviceInfo info_;
  std::function<void(std::string_view)> onValidationMessage_;
  std::atomic<std::uint64_t> validationMessages_{0};
};

}  // namespace scansurf::gpu
