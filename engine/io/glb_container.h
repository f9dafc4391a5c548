// scansurf: the binary glTF container (glTF 2.0 §4.4 "GLB File Format Specification"): a
// 12-byte header, a JSON chunk and an optional BIN chunk, each 4-byte aligned. Used to adjust
// the scene description that Draco's glTF encoder writes, keeping its binary data as is.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scansurf/result.h"

namespace scansurf {

struct GlbContainer {
  std::string json;               // the JSON chunk, without padding
  std::vector<std::uint8_t> bin;  // the BIN chunk, without padding; empty = none
};

// Splits a GLB file's bytes into its chunks. Errors: Errc::Internal for a malformed container
// (our own encoder's output is never malformed; the check guards the assumption).
Result<GlbContainer> parseGlb(const std::uint8_t* data, std::size_t size);

// The GLB bytes of a container: the JSON chunk padded with spaces, the BIN chunk with zeros.
std::vector<std::uint8_t> serializeGlb(const GlbContainer& glb);

}  // namespace scansurf
