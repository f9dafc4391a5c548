// scansurf: the binary glTF container (glTF 2.0 §4.4; see glb_container.h).
#include "io/glb_container.h"

#include <cstring>

namespace scansurf {
namespace {

constexpr std::uint32_t kMagic = 0x46546C67;      // "glTF"
constexpr std::uint32_t kJsonChunk = 0x4E4F534A;  // "JSON"
constexpr std::uint32_t kBinChunk = 0x004E4942;   // "BIN\0"

std::uint32_t readU32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 | static_cast<std::uint32_t>(p[2]) << 16 |
         static_cast<std::uint32_t>(p[3]) << 24;
}

void appendU32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int b = 0; b < 4; ++b) out.push_back(static_cast<std::uint8_t>(v >> (8 * b)));
}

void appendChunk(std::vector<std::uint8_t>& out, std::uint32_t type, const std::uint8_t* data, std::size_t size,
                 std::uint8_t pad) {
  const std::size_t padded = (size + 3) / 4 * 4;
  appendU32(out, static_cast<std::uint32_t>(padded));
  appendU32(out, type);
  out.insert(out.end(), data, data + size);
  out.insert(out.end(), padded - size, pad);
}

}  // namespace

Result<GlbContainer> parseGlb(const std::uint8_t* data, std::size_t size) {
  if (size < 20 || readU32(data) != kMagic || readU32(data + 4) != 2 || readU32(data + 8) != size)
    return makeError(Errc::Internal, "not a glTF 2.0 binary container");
  GlbContainer glb;
  for (std::size_t at = 12; at + 8 <= size;) {
    const std::uint32_t length = readU32(data + at), type = readU32(data + at + 4);
    if (at + 8 + length > size) return makeError(Errc::Internal, "glTF binary container: a chunk runs past the end");
    const std::uint8_t* chunk = data + at + 8;
    if (type == kJsonChunk) glb.json.assign(reinterpret_cast<const char*>(chunk), length);
    if (type == kBinChunk) glb.bin.assign(chunk, chunk + length);
    at += 8 + length;
  }
  if (glb.json.empty()) return makeError(Errc::Internal, "glTF binary container without a JSON chunk");
  return glb;
}

std::vector<std::uint8_t> serializeGlb(const GlbContainer& glb) {
  std::vector<std::uint8_t> out;
  appendU32(out, kMagic);
  appendU32(out, 2);
  appendU32(out, 0);  // total length, set below
  appendChunk(out, kJsonChunk, reinterpret_cast<const std::uint8_t*>(glb.json.data()), glb.json.size(), ' ');
  if (!glb.bin.empty()) appendChunk(out, kBinChunk, glb.bin.data(), glb.bin.size(), 0);
  const auto total = static_cast<std::uint32_t>(out.size());
  for (int b = 0; b < 4; ++b) out[8 + static_cast<std::size_t>(b)] = static_cast<std::uint8_t>(total >> (8 * b));
  return out;
}

}  // namespace scansurf
