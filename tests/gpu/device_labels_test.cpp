// A GPU pipeline that segments on the device hands scansurf its label buffer: the application
// creates the instance (validation on), device and buffer itself, fills the buffer on the
// device, adopts, extracts, and gets exactly what the host path gives.
#include <cstring>

#include "gpu/gpu_test_env.h"
#include "scansurf/vulkan_interop.h"
#include "support/shapes.h"

namespace scansurf::test {
namespace {

VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                                         const VkDebugUtilsMessengerCallbackDataEXT* data, void*) {
  recordValidationMessage(data && data->pMessage ? data->pMessage : "(validation message)");
  return VK_FALSE;
}

// The application's own Vulkan objects, as an embedding pipeline would have them.
class AppVulkan {
 public:
  AppVulkan() {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.apiVersion = VK_API_VERSION_1_3;
    const char* layer = "VK_LAYER_KHRONOS_validation";
    const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    VkDebugUtilsMessengerCreateInfoEXT messenger{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messenger.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messenger.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
    messenger.pfnUserCallback = onMessage;
    VkInstanceCreateInfo instanceInfo{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    instanceInfo.pNext = &messenger;  // reports for the instance's whole life through this chain
    instanceInfo.pApplicationInfo = &app;
    instanceInfo.enabledLayerCount = 1;
    instanceInfo.ppEnabledLayerNames = &layer;
    instanceInfo.enabledExtensionCount = 1;
    instanceInfo.ppEnabledExtensionNames = &extension;
    ok = vkCreateInstance(&instanceInfo, nullptr, &instance) == VK_SUCCESS;
    std::uint32_t count = 1;
    ok = ok && vkEnumeratePhysicalDevices(instance, &count, &physical) >= VK_SUCCESS && count == 1;
    ok = ok && createDevice();
  }
  ~AppVulkan() {
    if (device) vkDestroyDevice(device, nullptr);
    if (instance) vkDestroyInstance(instance, nullptr);
  }

  // A device-local buffer holding `bytes`, filled on the device by a copy submitted to the
  // queue and NOT waited for: scansurf must order its reads after it on the same queue.
  VkBuffer uploadOnDevice(const void* bytes, VkDeviceSize size) {
    staging_ = makeBuffer(size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                          VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    labels_ = makeBuffer(size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                         VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    void* mapped = nullptr;
    vkMapMemory(device, staging_.memory, 0, size, 0, &mapped);
    std::memcpy(mapped, bytes, size);
    vkUnmapMemory(device, staging_.memory);
    VkCommandBufferAllocateInfo allocate{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocate.commandPool = pool_;
    allocate.commandBufferCount = 1;
    vkAllocateCommandBuffers(device, &allocate, &cmd_);
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    vkBeginCommandBuffer(cmd_, &begin);
    const VkBufferCopy region{0, 0, size};
    vkCmdCopyBuffer(cmd_, staging_.buffer, labels_.buffer, 1, &region);
    vkEndCommandBuffer(cmd_);
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd_;
    vkQueueSubmit(queue, 1, &submit, VK_NULL_HANDLE);
    return labels_.buffer;
  }
  void release() {
    vkQueueWaitIdle(queue);  // the application's own synchronization, before freeing its objects
    for (Owned* b : {&staging_, &labels_}) {
      vkDestroyBuffer(device, b->buffer, nullptr);
      vkFreeMemory(device, b->memory, nullptr);
      *b = {};
    }
    vkDestroyCommandPool(device, pool_, nullptr);
    pool_ = VK_NULL_HANDLE;
  }

  bool ok = false;
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  VkPhysicalDeviceVulkan13Features features13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};

 private:
  struct Owned {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
  };

  bool createDevice() {
    const float priority = 1;
    VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queueInfo.queueFamilyIndex = 0;
    queueInfo.queueCount = 1;
    queueInfo.pQueuePriorities = &priority;
    features13.dynamicRendering = VK_TRUE;
    features13.synchronization2 = VK_TRUE;
    VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    deviceInfo.pNext = &features13;
    deviceInfo.queueCreateInfoCount = 1;
    deviceInfo.pQueueCreateInfos = &queueInfo;
    if (vkCreateDevice(physical, &deviceInfo, nullptr, &device) != VK_SUCCESS) return false;
    vkGetDeviceQueue(device, 0, 0, &queue);
    VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    return vkCreateCommandPool(device, &poolInfo, nullptr, &pool_) == VK_SUCCESS;
  }

  Owned makeBuffer(VkDeviceSize size, VkBufferUsageFlags usage, VkMemoryPropertyFlags flags) {
    Owned b;
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = usage;
    vkCreateBuffer(device, &info, nullptr, &b.buffer);
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device, b.buffer, &req);
    VkPhysicalDeviceMemoryProperties memory;
    vkGetPhysicalDeviceMemoryProperties(physical, &memory);
    VkMemoryAllocateInfo allocate{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    allocate.allocationSize = req.size;
    for (std::uint32_t t = 0; t < memory.memoryTypeCount; ++t)
      if ((req.memoryTypeBits & (1u << t)) && (memory.memoryTypes[t].propertyFlags & flags) == flags) {
        allocate.memoryTypeIndex = t;
        break;
      }
    vkAllocateMemory(device, &allocate, nullptr, &b.memory);
    vkBindBufferMemory(device, b.buffer, b.memory, 0);
    return b;
  }

  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  Owned staging_, labels_;
};

void expectSameSurfaces(const Surfaces& a, const Surfaces& b) {
  EXPECT_EQ(a.mesh.positions, b.mesh.positions);
  EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
  EXPECT_EQ(a.mesh.labels, b.mesh.labels);
  ASSERT_EQ(a.features.size(), b.features.size());
  for (std::size_t f = 0; f < a.features.size(); ++f) EXPECT_EQ(a.features[f].triangles, b.features[f].triangles);
}

class DeviceLabelsTest : public GpuTest {
 protected:
  // The host path on the adopted engine, and the label volume to hand over on the device.
  void SetUp() override {
    GpuTest::SetUp();
    ASSERT_TRUE(app_.ok) << "cannot create the application's Vulkan device";
    auto engine = Engine::adopt(ExternalVulkan{app_.instance, app_.physical, app_.device, app_.queue, 0, &app_.features13});
    ASSERT_TRUE(engine) << engine.error().message;
    engine_ = std::make_unique<Engine>(std::move(engine).value());
    options_.grid.voxelSize = 1.0;
    options_.smoothing.enabled = true;
    options_.smoothing.iterations = 10;
    auto built = engine_->build(set_, options_);
    ASSERT_TRUE(built) << built.error().message;
    host_ = std::move(built).value();
  }
  void TearDown() override {
    engine_.reset();  // before the application's device goes
    app_.release();
    GpuTest::TearDown();
  }

  template <typename LabelT>
  Result<Surfaces> extractOnDevice(std::uint32_t bits, std::vector<LabelT> labels) {
    DeviceLabelVolume volume;
    volume.buffer = app_.uploadOnDevice(labels.data(), labels.size() * sizeof(LabelT));
    volume.bitsPerLabel = bits;
    volume.grid = host_.volume.grid;
    return engine_->extract(volume, host_.nesting, options_, &set_);
  }

  const ContourSet set_ = nestedSpheresContours(12, 5, 2.0);
  AppVulkan app_;
  std::unique_ptr<Engine> engine_;
  BuildOptions options_;
  BuildResult host_;
};

TEST_F(DeviceLabelsTest, SixteenBitLabelsOnTheDeviceGiveTheHostPathsSurfaces) {
  auto surfaces = extractOnDevice<std::uint16_t>(16, host_.volume.labels);
  ASSERT_TRUE(surfaces) << surfaces.error().message;
  EXPECT_GT(surfaces->mesh.triangleCount(), 0u);
  expectSameSurfaces(*surfaces, host_.surfaces);
}

TEST_F(DeviceLabelsTest, ThirtyTwoBitLabelsOnTheDeviceGiveTheHostPathsSurfaces) {
  auto surfaces = extractOnDevice<std::uint32_t>(32, {host_.volume.labels.begin(), host_.volume.labels.end()});
  ASSERT_TRUE(surfaces) << surfaces.error().message;
  expectSameSurfaces(*surfaces, host_.surfaces);
}

TEST_F(DeviceLabelsTest, ALabelBeyondSixteenBitsIsRefused) {
  std::vector<std::uint32_t> labels(host_.volume.labels.begin(), host_.volume.labels.end());
  labels[host_.volume.grid.index(3, 3, 2)] = 70000;
  auto surfaces = extractOnDevice<std::uint32_t>(32, labels);
  ASSERT_FALSE(surfaces);
  EXPECT_EQ(surfaces.error().code, Errc::InvalidInput);
  EXPECT_NE(surfaces.error().message.find("70000"), std::string::npos) << surfaces.error().message;
}

TEST_F(DeviceLabelsTest, BadDescriptionsAreRefused) {
  DeviceLabelVolume volume;
  volume.grid = host_.volume.grid;
  auto none = engine_->extract(volume, host_.nesting, options_);
  ASSERT_FALSE(none);
  EXPECT_EQ(none.error().code, Errc::InvalidArgument);
  volume.buffer = reinterpret_cast<VkBuffer>(std::uintptr_t{1});  // never touched: bits are checked first
  volume.bitsPerLabel = 8;
  auto bits = engine_->extract(volume, host_.nesting, options_);
  ASSERT_FALSE(bits);
  EXPECT_NE(bits.error().message.find("bitsPerLabel"), std::string::npos);
}

// adopt says what the application's device lacks.
TEST_F(DeviceLabelsTest, AdoptNamesWhatTheDeviceLacks) {
  auto badFamily = Engine::adopt(ExternalVulkan{app_.instance, app_.physical, app_.device, app_.queue, 99});
  ASSERT_FALSE(badFamily);
  EXPECT_EQ(badFamily.error().code, Errc::NoDevice);
  EXPECT_NE(badFamily.error().message.find("queueFamilyIndex 99"), std::string::npos) << badFamily.error().message;
  VkPhysicalDeviceVulkan13Features without{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  without.dynamicRendering = VK_TRUE;
  auto noSync2 = Engine::adopt(ExternalVulkan{app_.instance, app_.physical, app_.device, app_.queue, 0, &without});
  ASSERT_FALSE(noSync2);
  EXPECT_NE(noSync2.error().message.find("synchronization2"), std::string::npos) << noSync2.error().message;
}

}  // namespace
}  // namespace scansurf::test
