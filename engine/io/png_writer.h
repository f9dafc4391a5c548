// scansurf: PNG images through libpng.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>

#include "scansurf/result.h"

namespace scansurf {

// Writes an 8-bit RGBA image (rows top to bottom, 4 bytes per pixel, sRGB) as PNG.
// Replaced atomically. Errors: Errc::InvalidArgument when the sizes disagree, Errc::Io naming
// the path.
Result<void> writePng(const std::filesystem::path& path, std::uint32_t width, std::uint32_t height,
                      std::span<const std::uint8_t> rgba);

}  // namespace scansurf
