// scansurf passes: the SPIR-V embedded at build time (cmake/Shaders.cmake generates the
// definition from shaders/*).
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

namespace scansurf::shaders {

// The SPIR-V of the shader file `name` (e.g. "classify.comp"); empty for a name that is not
// embedded (a build error: gpu::createShaderModule then returns Errc::Internal). Never throws.
std::span<const std::uint32_t> spirv(std::string_view name) noexcept;

}  // namespace scansurf::shaders
