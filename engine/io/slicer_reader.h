// scansurf: 3D Slicer's planar-contour segmentations, as SlicerRT saves them: a multiblock
// file NAME.seg.vtm naming one PolyData file (.vtp) per segment, or one such .vtp alone. Each
// .vtp holds the segment's contours as closed polylines (the closing point repeated) in RAS
// coordinates, millimetres, and in its field data the segment's name (Segment_Name) and colour
// (Segment_DefaultColor, 0..1). Points become LPS (x and y negated), as DICOM and the other
// readers have them; one feature per segment, its slices the polylines' planes.
#pragma once

#include <filesystem>

#include "scansurf/contours.h"
#include "scansurf/result.h"

namespace scansurf {

// Whether the file is a VTK XML file (its first element VTKFile), by content.
bool looksLikeVtkXml(const std::filesystem::path& path);

// Errors (Errc::InvalidInput) name the file, the segment and the polyline at fault: not a
// multiblock or PolyData file, a block file that cannot be read, a polyline off its plane or
// of fewer than 3 points, arrays that do not decode; then the checks every reader's contours
// meet (validate.h).
Result<ContourSet> readSlicerSegmentation(const std::filesystem::path& path);

}  // namespace scansurf
