// scansurf: choosing the Vulkan device, and what the engine reports about it.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>

namespace scansurf {

struct EngineOptions {
  // Which device: an index into the list of devices, or part of its name (case-insensitive).
  // Empty: the SCANSURF_DEVICE environment variable, else the best device
  // (discrete > integrated > virtual > CPU). Ignored by Engine::adopt.
  std::string device;
  // Enable VK_LAYER_KHRONOS_validation. Also on when SCANSURF_VALIDATION=1. Ignored by
  // Engine::adopt (the application's instance decides).
  bool validation = false;
  // Receives every validation message; default: printed to stderr. Called on the thread of
  // the Vulkan call that caused the message.
  std::function<void(std::string_view)> onValidationMessage;
};

struct DeviceInfo {
  std::string name;
  std::string type;  // "discrete", "integrated", "virtual", "cpu" or "other"
  std::string driver;
  std::uint32_t apiVersion = 0;
  bool borrowed = false;           // the application's device (Engine::adopt)
  std::uint64_t deviceMemory = 0;  // bytes of the largest device-local memory heap
};

}  // namespace scansurf
