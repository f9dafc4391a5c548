// Shared by GLSL (classify.comp) and C++ (passes/classification.cpp).
#ifndef SCANSURF_SHARED_CLASSIFY_PUSH_H
#define SCANSURF_SHARED_CLASSIFY_PUSH_H

#ifdef __cplusplus
#include <cstdint>
namespace scansurf::shared {
struct ClassifyPush {
  std::uint32_t nx, ny;          // voxels per row and column of the whole volume
  std::uint32_t cellLayers;      // cell layers in this dispatch (label layers - 1)
  std::uint32_t firstCellLayer;  // global index of the first cell layer of the slab
  std::uint32_t capacity;        // records the output buffer holds
  std::uint32_t labelBits;       // 16: two labels per word; 32: one label per word
  std::uint32_t labelOffset;     // labels before the slab's first in the bound range (alignment)
  std::uint32_t upperIsData;     // 32-bit words whose upper half is other data (clearances)
  std::uint32_t tiled;           // 1: workgroup x + y * kTileRow covers the tile tiles[that] (x | y << 16)
  std::uint32_t tileCount;       // tiles listed
};
inline constexpr std::uint32_t kTileRow = 16384;  // workgroups per row of a tiled dispatch
static_assert(sizeof(ClassifyPush) == 40, "ClassifyPush must match the GLSL push-constant block");
}  // namespace scansurf::shared
#else
layout(push_constant) uniform ClassifyPush {
  uint nx;
  uint ny;
  uint cellLayers;
  uint firstCellLayer;
  uint capacity;
  uint labelBits;
  uint labelOffset;
  uint upperIsData;
  uint tiled;
  uint tileCount;
}
push;
const uint kTileRow = 16384u;
#endif

#endif
