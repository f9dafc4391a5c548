// scansurf: an offscreen picture of the surfaces, rendered on the engine's Vulkan device.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "scansurf/contours.h"

namespace scansurf {

// Where the camera looks from, in the input's axes read as patient axes (x to the left,
// y to the back, z up, as DICOM's LPS): front looks at the face from -y with z up.
enum class ViewPreset { Oblique, Front, Back, Left, Right, Top, Bottom };

// "oblique", "front", "back", "left", "right", "top", "bottom"; nullopt otherwise.
std::optional<ViewPreset> parseViewPreset(std::string_view name);

struct PreviewOptions {
  std::uint32_t width = 960;
  std::uint32_t height = 720;
  ViewPreset view = ViewPreset::Oblique;
  // sRGB colour per feature (Surfaces::features order); missing ones are grey.
  std::vector<Rgb> colors;
  // Opacity per feature in (0, 1]; missing ones are opaque. Translucent features are drawn
  // after the opaque ones, without depth writes, so what they enclose shows through.
  std::vector<float> opacity;
  Rgb background{245, 245, 245};
  // Host memory the rendering may use, in bytes (estimatePreviewBytes); 0 = what the machine
  // has available. A picture that needs more is refused with Errc::ResourceLimit.
  std::uint64_t memoryLimit = 0;
};

// About the host memory a picture of options' size takes to render: it is drawn at twice the
// size, read back, averaged and encoded (a software device's images are host memory too).
std::uint64_t estimatePreviewBytes(const PreviewOptions& options);

// An 8-bit sRGB RGBA picture, rows top to bottom.
struct PreviewImage {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<std::uint8_t> rgba;
};

}  // namespace scansurf
