// scansurf passes: the SPIR-V embedded at build time (cmake/Shaders.cmake generates the
// definition from shaders/*).
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

namespace scansurf::shaders {

// The SPIR-V of the shader file `name` (e.g. "classify.comp"); throws std::logic_error for a
// name that is not embedded (a build error, not a user error).
std::span<const std::uint32_t> spirv(std::string_view name);

}  // namespace scansurf::shaders
