// scansurf: where a label volume can hold anything but background, known from the contours
// before the volume is drawn, so that classification visits the cells near the structures and
// not the empty margin (the scanline surfacing paper, §3.5, classifies every cell).
#pragma once

#include <cstdint>
#include <vector>

#include "scansurf/contours.h"
#include "scansurf/grid.h"
#include "scansurf/label_volume.h"

namespace scansurf {

// Per layer of a grid, a mark per tile of kTile x kTile voxel columns: 1 where a voxel of the
// tile may hold a label other than background. Every unmarked tile's voxels are background.
struct ContentTiles {
  static constexpr int kTile = 8;
  int tilesX = 0, tilesY = 0, layers = 0;
  std::vector<std::uint8_t> marks;  // layer by layer, tilesX * tilesY each, x fastest

  bool empty() const { return marks.empty(); }
  bool marked(int layer, int tx, int ty) const {
    return tx < tilesX && ty < tilesY && marks[(static_cast<std::size_t>(layer) * tilesY + ty) * tilesX + tx] != 0;
  }
};

// The tiles that scan conversion of `contours` on `grid` can draw into: every contour's
// bounding box in pixels, a pixel wider on each side, on the layer its slice lies on
// (Grid::layerOfPlane), as scan conversion places it.
ContentTiles contentTilesOf(const Grid& grid, const ContourSet& contours);

// Exactly the tiles of `volume` that hold a voxel other than background.
ContentTiles contentTilesOf(const LabelVolume& volume);

// The same for the volume that interpolation makes of those planes with `factors`
// (interpolationFactors): a plane's layer keeps its tiles; a layer between planes A and B gets
// the tiles of A, B and their other neighbours (a structure's window on a plane spans its
// pixels on the planes beside it) widened by `reach` pixels, the farthest a window reaches
// beyond those pixels (interpolation_plan.h, kWindowMargin).
ContentTiles interpolatedContentTiles(const ContentTiles& planes, const std::vector<int>& factors, int reach);

}  // namespace scansurf
