// The Vulkan context: device selection, errors that explain, and borrowing an application's device.
#include <cstring>

#include "gpu/gpu_test_env.h"
#include "scansurf/vulkan_interop.h"

namespace scansurf::test {
namespace {

using ContextTest = GpuTest;

TEST_F(ContextTest, PicksADeviceAndReportsIt) {
  auto engine = Engine::create(validatedEngineOptions());
  ASSERT_TRUE(engine) << engine.error().message;
  EXPECT_FALSE(engine->device().name.empty());
  EXPECT_FALSE(engine->device().type.empty());
  EXPECT_GE(engine->device().apiVersion, VK_API_VERSION_1_3);
  EXPECT_FALSE(engine->device().borrowed);
}

TEST_F(ContextTest, SelectsByIndexAndNameAndExplainsAMiss) {
  EngineOptions options = validatedEngineOptions();
  // std::string("0"), not "0": GCC 12 warns -Wrestrict in error on assigning a one-character
  // literal to a std::string (GCC bug 105329).
  options.device = std::string("0");
  auto byIndex = Engine::create(options);
  ASSERT_TRUE(byIndex) << byIndex.error().message;
  options.device = byIndex->device().name.substr(0, 4);
  auto byName = Engine::create(options);
  ASSERT_TRUE(byName) << byName.error().message;
  EXPECT_EQ(byName->device().name, byIndex->device().name);
  options.device = "no-such-gpu-xyz";
  auto missing = Engine::create(options);
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().code, Errc::NoDevice);
  EXPECT_NE(missing.error().message.find("no-such-gpu-xyz"), std::string::npos);
  EXPECT_NE(missing.error().message.find(byIndex->device().name), std::string::npos) << "lists the devices it saw";
}

// An application that owns its Vulkan objects hands them to the engine, which borrows them.
TEST_F(ContextTest, AdoptsTheApplicationsDevice) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.apiVersion = VK_API_VERSION_1_3;
  VkInstanceCreateInfo instanceInfo{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  instanceInfo.pApplicationInfo = &app;
  VkInstance instance = VK_NULL_HANDLE;
  ASSERT_EQ(vkCreateInstance(&instanceInfo, nullptr, &instance), VK_SUCCESS);
  std::uint32_t count = 1;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  ASSERT_NE(vkEnumeratePhysicalDevices(instance, &count, &physical), VK_ERROR_INITIALIZATION_FAILED);
  ASSERT_EQ(count, 1u);
  const float priority = 1;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueFamilyIndex = 0;
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;
  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  f13.dynamicRendering = VK_TRUE;
  f13.synchronization2 = VK_TRUE;
  VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  deviceInfo.pNext = &f13;
  deviceInfo.queueCreateInfoCount = 1;
  deviceInfo.pQueueCreateInfos = &queueInfo;
  VkDevice device = VK_NULL_HANDLE;
  ASSERT_EQ(vkCreateDevice(physical, &deviceInfo, nullptr, &device), VK_SUCCESS);
  VkQueue queue = VK_NULL_HANDLE;
  vkGetDeviceQueue(device, 0, 0, &queue);
  {
    auto engine = Engine::adopt(ExternalVulkan{instance, physical, device, queue, 0});
    ASSERT_TRUE(engine) << engine.error().message;
    EXPECT_TRUE(engine->device().borrowed);
    ContourSet set;
    set.source = "adopted";
    set.features.push_back({"square", {}, {{0.0, {Contour{{{0, 0}, {4, 0}, {4, 4}, {0, 4}}}}}}});
    auto built = engine->build(set, {});
    ASSERT_TRUE(built) << built.error().message;
    EXPECT_GT(built->surfaces.features[0].triangleCount(), 0u);
  }
  // The engine released only what it created: the application's handles are still valid.
  EXPECT_EQ(vkDeviceWaitIdle(device), VK_SUCCESS);
  vkDestroyDevice(device, nullptr);
  vkDestroyInstance(instance, nullptr);
}

TEST_F(ContextTest, RejectsIncompleteExternalHandles) {
  auto engine = Engine::adopt(ExternalVulkan{});
  ASSERT_FALSE(engine);
  EXPECT_EQ(engine.error().code, Errc::InvalidArgument);
}

}  // namespace
}  // namespace scansurf::test
