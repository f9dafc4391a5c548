// scansurf: VTK's own XML formats (VTK File Formats, "XML File Formats": PolyData .vtp and
// MultiBlock .vtm), read by VTK, ParaView, pyvista and 3D Slicer: one feature's surface with
// its normals and name, the multi-label mesh with its label pair per face, and 3D Slicer's
// closed-surface segmentation (.seg.vtm: one .vtp per segment whose field data carry the
// attributes vtkMRMLSegmentationStorageNode reads).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "geometry/mesh/compact_mesh.h"
#include "io/slicer_terminology.h"
#include "scansurf/contours.h"
#include "scansurf/result.h"
#include "scansurf/surfaces.h"

namespace scansurf {

// One feature's surface: points (float32, input units), triangles wound outward, area-weighted
// point normals ("Normals"), and field data "Name" (string), "Label" (int32, the feature's
// label) and "Units" (string). Replaced atomically; errors: Errc::Io naming the path.
Result<void> writeFeatureVtp(const std::filesystem::path& path, const CompactMesh& mesh, const std::string& name, int label,
                             const std::string& units);

// The multi-label mesh: shared points, every triangle once, cell data "label_inside" and
// "label_outside" (uint16; the normal points from inside's region into outside's).
Result<void> writeMultiLabelVtp(const std::filesystem::path& path, const MultiLabelMesh& mesh, const std::string& units);

// One segment of a Slicer closed-surface segmentation.
struct SlicerSegment {
  std::string id;    // unique within the segmentation, e.g. "Segment_1"
  std::string name;  // shown in Slicer
  Rgb color{};
  std::string terminology;            // Slicer's TerminologyEntry (7 '~'-separated fields)
  const CompactMesh* mesh = nullptr;  // not empty
};

// 3D Slicer's closed-surface segmentation: `path` (NAME.seg.vtm) lists one block per segment,
// each NAME.seg_<k>.vtp beside it in Slicer's own frame (RAS: the input's LPS x and y negated,
// a rotation, so windings stay outward), with the field data Slicer's storage node reads
// (Segmentation_MasterRepresentation "Closed surface", Segment_ID, _Name, _Color, _Tags ...).
// Returns the .vtp paths, which the caller stages with the .vtm (see stageSegVtm in outputs).
std::filesystem::path slicerSegmentPath(const std::filesystem::path& vtm, std::size_t index);
Result<void> writeSlicerSegmentVtp(const std::filesystem::path& path, const SlicerSegment& segment);
// The .vtm listing the segments' files (names relative to the .vtm's folder), in order.
Result<void> writeSlicerSegmentationVtm(const std::filesystem::path& path, const std::vector<std::string>& blockFiles);

}  // namespace scansurf
