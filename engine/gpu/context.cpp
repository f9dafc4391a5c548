// scansurf gpu: instance, device choice and device of the Vulkan context (see context.h).
#include "gpu/context.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "gpu/check.h"

namespace scansurf::gpu {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

bool envFlag(const char* name) {
  const char* v = std::getenv(name);
  return v != nullptr && std::strcmp(v, "") != 0 && std::strcmp(v, "0") != 0;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

const char* typeName(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
    default: return "other";
  }
}

int typeRank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 1;
    default: return 0;
  }
}

// The queue family with graphics and compute, or -1.
int graphicsComputeFamily(VkPhysicalDevice device) {
  std::uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  for (std::uint32_t i = 0; i < count; ++i)
    if ((families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) && (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT))
      return static_cast<int>(i);
  return -1;
}

// Why a device cannot run scansurf, or empty when it can.
std::string rejection(VkPhysicalDevice device) {
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(device, &props);
  if (props.apiVersion < VK_API_VERSION_1_3)
    return "supports Vulkan " + std::to_string(VK_API_VERSION_MAJOR(props.apiVersion)) + "." +
           std::to_string(VK_API_VERSION_MINOR(props.apiVersion)) + ", needs 1.3";
  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f13, {}};
  vkGetPhysicalDeviceFeatures2(device, &f2);
  if (!f13.dynamicRendering) return "no dynamicRendering";
  if (!f13.synchronization2) return "no synchronization2";
  if (graphicsComputeFamily(device) < 0) return "no queue family with graphics and compute";
  return {};
}

// A selector of digits names a device by index (compared as text: no number to overflow).
bool selectorIsIndex(const std::string& selector) {
  return !selector.empty() && std::all_of(selector.begin(), selector.end(), [](unsigned char c) { return std::isdigit(c); });
}

// Why the application's queue family cannot run scansurf, or empty.
std::string queueFamilyRejection(VkPhysicalDevice device, std::uint32_t family) {
  std::uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  if (family >= count)
    return "queueFamilyIndex " + std::to_string(family) + " is not a queue family of the device (it has " +
           std::to_string(count) + ")";
  std::string missing;
  if (!(families[family].queueFlags & VK_QUEUE_GRAPHICS_BIT)) missing += " graphics";
  if (!(families[family].queueFlags & VK_QUEUE_COMPUTE_BIT)) missing += " compute";
  return missing.empty() ? std::string() : "queue family " + std::to_string(family) + " lacks" + missing;
}

// Why the features the application enabled (a VkDeviceCreateInfo pNext chain) do not suffice,
// or empty. Both the core 1.3 struct and the extension structs count.
std::string enabledFeatureRejection(const void* chain) {
  bool dynamicRendering = false, synchronization2 = false;
  for (auto* s = static_cast<const VkBaseInStructure*>(chain); s; s = s->pNext) {
    if (s->sType == VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES) {
      const auto* f = reinterpret_cast<const VkPhysicalDeviceVulkan13Features*>(s);
      dynamicRendering |= f->dynamicRendering == VK_TRUE;
      synchronization2 |= f->synchronization2 == VK_TRUE;
    } else if (s->sType == VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES) {
      dynamicRendering |= reinterpret_cast<const VkPhysicalDeviceDynamicRenderingFeatures*>(s)->dynamicRendering == VK_TRUE;
    } else if (s->sType == VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES) {
      synchronization2 |= reinterpret_cast<const VkPhysicalDeviceSynchronization2Features*>(s)->synchronization2 == VK_TRUE;
    }
  }
  std::string missing;
  if (!dynamicRendering) missing += " dynamicRendering";
  if (!synchronization2) missing += " synchronization2";
  return missing.empty() ? std::string() : "the device was created without the feature(s)" + missing;
}

bool hasLayer(const char* name) {
  std::uint32_t count = 0;
  vkEnumerateInstanceLayerProperties(&count, nullptr);
  std::vector<VkLayerProperties> layers(count);
  vkEnumerateInstanceLayerProperties(&count, layers.data());
  return std::any_of(layers.begin(), layers.end(),
                     [&](const VkLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
}

struct Candidate {
  VkPhysicalDevice device;
  DeviceListing listing;
  int rank;
};

// Every physical device with its type and, when scansurf cannot run on it, why.
Result<std::vector<Candidate>> candidates(VkInstance instance) {
  std::uint32_t count = 0;
  SCANSURF_VK_TRY(vkEnumeratePhysicalDevices(instance, &count, nullptr));
  std::vector<VkPhysicalDevice> devices(count);
  SCANSURF_VK_TRY(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
  std::vector<Candidate> out;
  for (std::uint32_t i = 0; i < count; ++i) {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(devices[i], &props);
    out.push_back({devices[i],
                   {static_cast<int>(i), props.deviceName, typeName(props.deviceType), rejection(devices[i])},
                   typeRank(props.deviceType)});
  }
  return out;
}

// The candidate the selector (an index or part of a name) picks, else the best device type
// that can run scansurf; -1 when none.
int chooseCandidate(const std::vector<Candidate>& all, const std::string& selector) {
  int chosen = -1, bestRank = -1;
  for (std::size_t i = 0; i < all.size(); ++i) {
    const DeviceListing& d = all[i].listing;
    const bool matches =
        selector.empty() || (selectorIsIndex(selector) ? selector == std::to_string(d.index)
                                                       : lower(d.name).find(lower(selector)) != std::string::npos);
    if (!matches || !d.unusable.empty() || all[i].rank <= bestRank) continue;
    bestRank = all[i].rank;
    chosen = static_cast<int>(i);
  }
  return chosen;
}

// The chosen device; the error lists every device and why each was passed over.
Result<VkPhysicalDevice> choosePhysicalDevice(VkInstance instance, const std::string& selector) {
  SCANSURF_ASSIGN_OR_RETURN(const std::vector<Candidate> all, candidates(instance));
  if (all.empty())
    return makeError(Errc::NoDevice, "no Vulkan device found (install a GPU driver, or Mesa's lavapipe: mesa-vulkan-drivers)");
  const int chosen = chooseCandidate(all, selector);
  if (chosen >= 0) return all[static_cast<std::size_t>(chosen)].device;
  std::string report;
  for (const Candidate& c : all)
    report += "\n  [" + std::to_string(c.listing.index) + "] " + c.listing.name + " (" + c.listing.type + ")" +
              (c.listing.unusable.empty() ? "" : ": unusable, " + c.listing.unusable);
  return makeError(Errc::NoDevice, (selector.empty() ? std::string("no usable Vulkan device")
                                                     : "no usable Vulkan device matches \"" + selector + "\"") +
                                       "; devices:" + report);
}

}  // namespace

VKAPI_ATTR VkBool32 VKAPI_CALL Context::debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                      VkDebugUtilsMessageTypeFlagsEXT,
                                                      const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  auto* self = static_cast<Context*>(user);
  self->validationMessages_.fetch_add(1);
  std::string message =
      std::string(severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "validation error: " : "validation warning: ") +
      (data && data->pMessage ? data->pMessage : "(no message)");
  if (self->onValidationMessage_)
    self->onValidationMessage_(message);
  else
    std::fprintf(stderr, "scansurf: %s\n", message.c_str());
  return VK_FALSE;
}

VkDebugUtilsMessengerCreateInfoEXT Context::messengerInfo() {
  VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  info.pfnUserCallback = &Context::debugCallback;
  info.pUserData = this;
  return info;
}

Result<void> Context::createInstance(bool validation) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "scansurf";
  app.pEngineName = "scansurf";
  app.apiVersion = VK_API_VERSION_1_3;
  const VkDebugUtilsMessengerCreateInfoEXT messenger = messengerInfo();
  std::vector<const char*> layers;
  std::vector<const char*> extensions;
  if (validation) {
    layers.push_back(kValidationLayer);
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }
  VkInstanceCreateInfo instanceInfo{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  instanceInfo.pApplicationInfo = &app;
  instanceInfo.enabledLayerCount = static_cast<std::uint32_t>(layers.size());
  instanceInfo.ppEnabledLayerNames = layers.data();
  instanceInfo.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
  instanceInfo.ppEnabledExtensionNames = extensions.data();
  if (validation) instanceInfo.pNext = &messenger;  // also reports on instance creation
  VkInstance instance = VK_NULL_HANDLE;
  const VkResult created = vkCreateInstance(&instanceInfo, nullptr, &instance);
  if (created == VK_ERROR_INCOMPATIBLE_DRIVER)
    return makeError(Errc::NoDevice, "no Vulkan driver found (install a GPU driver, or Mesa's lavapipe: mesa-vulkan-drivers)");
  SCANSURF_VK_TRY(created);
  ownedInstance_ = Owned<VkInstance>(instance, [](VkInstance i) { vkDestroyInstance(i, nullptr); });
  instance_ = instance;
  return validation ? createMessenger() : Result<void>{};
}

Result<void> Context::createMessenger() {
  VkInstance instance = instance_;
  auto createFn =
      reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
  auto destroyFn =
      reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
  if (!createFn || !destroyFn) return makeError(Errc::Vulkan, "VK_EXT_debug_utils is not available");
  const VkDebugUtilsMessengerCreateInfoEXT info = messengerInfo();
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  SCANSURF_VK_TRY(createFn(instance, &info, nullptr, &messenger));
  messenger_ = Owned<VkDebugUtilsMessengerEXT>(
      messenger, [instance, destroyFn](VkDebugUtilsMessengerEXT m) { destroyFn(instance, m, nullptr); });
  return {};
}

Result<void> Context::createDevice(VkPhysicalDevice physicalDevice) {
  physicalDevice_ = physicalDevice;
  queueFamily_ = static_cast<std::uint32_t>(graphicsComputeFamily(physicalDevice_));
  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueFamilyIndex = queueFamily_;
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
  SCANSURF_VK_TRY(vkCreateDevice(physicalDevice_, &deviceInfo, nullptr, &device));
  ownedDevice_ = Owned<VkDevice>(device, [](VkDevice d) { vkDestroyDevice(d, nullptr); });
  device_ = device;
  vkGetDeviceQueue(device, queueFamily_, 0, &queue_);
  return {};
}

Result<std::unique_ptr<Context>> Context::create(const EngineOptions& options) {
  std::unique_ptr<Context> ctx(new Context());
  ctx->onValidationMessage_ = options.onValidationMessage;
  const bool validation = options.validation || envFlag("SCANSURF_VALIDATION");
  if (validation && !hasLayer(kValidationLayer))
    return makeError(Errc::NoDevice, std::string("validation requested but ") + kValidationLayer +
                                         " is not installed (Debian: vulkan-validationlayers)");
  SCANSURF_TRY(ctx->createInstance(validation));
  std::string selector = options.device;
  if (selector.empty())
    if (const char* env = std::getenv("SCANSURF_DEVICE")) selector = env;
  SCANSURF_ASSIGN_OR_RETURN(VkPhysicalDevice physical, choosePhysicalDevice(ctx->instance_, selector));
  SCANSURF_TRY(ctx->createDevice(physical));
  SCANSURF_TRY(ctx->finishSetup());
  return ctx;
}

Result<std::vector<DeviceListing>> Context::listDevices() {
  Context probe;
  SCANSURF_TRY(probe.createInstance(false));
  SCANSURF_ASSIGN_OR_RETURN(const std::vector<Candidate> all, candidates(probe.instance_));
  std::vector<DeviceListing> out;
  for (const Candidate& c : all) out.push_back(c.listing);
  if (const int best = chooseCandidate(all, {}); best >= 0) out[static_cast<std::size_t>(best)].best = true;
  return out;
}

Result<std::unique_ptr<Context>> Context::adopt(const ExternalVulkan& vulkan, const EngineOptions& options) {
  if (!vulkan.instance || !vulkan.physicalDevice || !vulkan.device || !vulkan.queue)
    return makeError(Errc::InvalidArgument, "ExternalVulkan: instance, physicalDevice, device and queue are all required");
  std::string why = rejection(vulkan.physicalDevice);
  if (why.empty()) why = queueFamilyRejection(vulkan.physicalDevice, vulkan.queueFamilyIndex);
  if (why.empty() && vulkan.enabledFeatures) why = enabledFeatureRejection(vulkan.enabledFeatures);
  if (!why.empty()) return makeError(Errc::NoDevice, "the application's Vulkan device cannot run scansurf: " + why);
  std::unique_ptr<Context> ctx(new Context());
  ctx->onValidationMessage_ = options.onValidationMessage;
  ctx->instance_ = vulkan.instance;
  ctx->physicalDevice_ = vulkan.physicalDevice;
  ctx->device_ = vulkan.device;
  ctx->queue_ = vulkan.queue;
  ctx->queueFamily_ = vulkan.queueFamilyIndex;
  ctx->info_.borrowed = true;
  SCANSURF_TRY(ctx->finishSetup());
  return ctx;
}

Result<void> Context::finishSetup() {
  vkGetPhysicalDeviceProperties(physicalDevice_, &properties_);
  vkGetPhysicalDeviceMemoryProperties(physicalDevice_, &memory_);
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceProperties2 props2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &driver, {}};
  vkGetPhysicalDeviceProperties2(physicalDevice_, &props2);
  info_.name = properties_.deviceName;
  info_.type = typeName(properties_.deviceType);
  info_.driver = std::string(driver.driverName) + " " + driver.driverInfo;
  info_.apiVersion = properties_.apiVersion;
  for (std::uint32_t h = 0; h < memory_.memoryHeapCount; ++h)
    if (memory_.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
      info_.deviceMemory = std::max<std::uint64_t>(info_.deviceMemory, memory_.memoryHeaps[h].size);

  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT | VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  poolInfo.queueFamilyIndex = queueFamily_;
  VkCommandPool pool = VK_NULL_HANDLE;
  SCANSURF_VK_TRY(vkCreateCommandPool(device_, &poolInfo, nullptr, &pool));
  commandPool_ = Owned<VkCommandPool>(pool, [d = device_](VkCommandPool p) { vkDestroyCommandPool(d, p, nullptr); });
  return {};
}

Context::~Context() {
  // Every submission was waited for on its own fence, so nothing of ours is in flight. A
  // borrowed device is never waited on as a whole: the application may be using it.
  if (ownedDevice_) vkDeviceWaitIdle(device_);
  commandPool_.reset();
  ownedDevice_.reset();
  messenger_.reset();
  ownedInstance_.reset();
}

Result<std::uint32_t> Context::findMemoryType(std::uint32_t typeBits, VkMemoryPropertyFlags required,
                                              VkMemoryPropertyFlags preferred) const {
  int best = -1;
  for (std::uint32_t i = 0; i < memory_.memoryTypeCount; ++i) {
    const VkMemoryPropertyFlags flags = memory_.memoryTypes[i].propertyFlags;
    if (!(typeBits & (1u << i)) || (flags & required) != required) continue;
    if ((flags & preferred) == preferred) return i;
    if (best < 0) best = static_cast<int>(i);
  }
  if (best < 0) return makeError(Errc::Vulkan, "no Vulkan memory type with the required properties");
  return static_cast<std::uint32_t>(best);
}

VkMemoryPropertyFlags Context::memoryTypeFlags(std::uint32_t type) const { return memory_.memoryTypes[type].propertyFlags; }

}  // namespace scansurf::gpu
