// scansurf gpu: VkResult failures as scansurf::Error (see check.h).
#include "gpu/check.h"

#include <filesystem>

namespace scansurf::gpu {

const char* vkResultName(VkResult result) {
  switch (result) {
#define SCANSURF_CASE(name) \
  case name: return #name;
    SCANSURF_CASE(VK_SUCCESS)
    SCANSURF_CASE(VK_NOT_READY)
    SCANSURF_CASE(VK_TIMEOUT)
    SCANSURF_CASE(VK_INCOMPLETE)
    SCANSURF_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
    SCANSURF_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    SCANSURF_CASE(VK_ERROR_INITIALIZATION_FAILED)
    SCANSURF_CASE(VK_ERROR_DEVICE_LOST)
    SCANSURF_CASE(VK_ERROR_MEMORY_MAP_FAILED)
    SCANSURF_CASE(VK_ERROR_LAYER_NOT_PRESENT)
    SCANSURF_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
    SCANSURF_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
    SCANSURF_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
    SCANSURF_CASE(VK_ERROR_TOO_MANY_OBJECTS)
    SCANSURF_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
    SCANSURF_CASE(VK_ERROR_FRAGMENTED_POOL)
    SCANSURF_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
#undef SCANSURF_CASE
    default: return "VkResult";
  }
}

Unexpected vulkanError(VkResult result, const char* call, const char* file, int line) {
  return makeError(Errc::Vulkan, std::string("Vulkan call failed: ") + call + " returned " + vkResultName(result) + " (" +
                                     std::to_string(static_cast<int>(result)) + ") at " +
                                     std::filesystem::path(file).filename().string() + ":" + std::to_string(line));
}

}  // namespace scansurf::gpu
