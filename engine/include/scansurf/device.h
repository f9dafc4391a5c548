// scansurf: choosing the Vulkan device, and what the engine reports about it.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "scansurf/result.h"

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

// One Vulkan device as scansurf sees it (listDevices).
struct DeviceListing {
  int index = 0;  // what EngineOptions::device takes
  std::string name;
  std::string type;      // as DeviceInfo::type
  std::string unusable;  // why scansurf cannot run on it; empty when it can
  bool best = false;     // the one Engine::create picks when no device is named
};

// Every Vulkan device of the machine, whether scansurf can use it, and which it picks by
// default (SCANSURF_DEVICE aside). Errors: Errc::NoDevice (no Vulkan driver), Errc::Vulkan.
Result<std::vector<DeviceListing>> listDevices();

}  // namespace scansurf
