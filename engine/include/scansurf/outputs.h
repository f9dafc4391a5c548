// scansurf: writing surfaces, scenes, label volumes and pictures, one file at a time or every
// output of a run at once (all or nothing).
#pragma once

#include <array>
#include <filesystem>
#include <functional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "scansurf/build_result.h"
#include "scansurf/contours.h"
#include "scansurf/label_volume.h"
#include "scansurf/preview.h"
#include "scansurf/result.h"
#include "scansurf/surfaces.h"

namespace scansurf {

// Per-feature surface formats (one file per feature: PLY, Draco, OBJ, STL, VTK PolyData) and
// the scenes of every feature (GLB; 3D Slicer's closed-surface segmentation, .seg.vtm with one
// .vtp per segment beside it).
enum class MeshFormat { Ply, Drc, Obj, Stl, Glb, Vtp, SegVtm };

// "ply", "drc", "obj", "stl", "glb", "vtp", "seg.vtm" (case-insensitive, a leading '.'
// allowed); else an Errc::InvalidArgument error naming the known formats.
Result<MeshFormat> parseMeshFormat(std::string_view name);
const char* extensionOf(MeshFormat format);  // ".ply", ...

struct DracoOptions {
  // Position quantization bits (1..30); 0 = the fewest bits whose error stays below maxError.
  int quantizationBits = 0;
  // Largest allowed position error per axis, input units; used when quantizationBits is 0.
  // 0 = Draco's default of 11 bits.
  double maxError = 0;
  int compressionLevel = 7;  // 0 (fastest) .. 10 (smallest)
};

// The default Draco error bound for a grid: 1/25 of its smallest voxel edge, so no two
// surface vertices (at least 1/12 voxel apart) quantize to one point.
double defaultQuantizationError(const Grid& grid);

// How the scene's coordinates relate to glTF's (y up, metres).
enum class SceneFrame {
  // Default: a root node turns patient LPS (x left, y posterior, z superior) in the input's
  // units into glTF's y-up metres (x stays left, superior becomes +y, anterior +z), so viewers
  // show the patient upright at true size. The vertices keep the input's values.
  Gltf,
  // No root transform: raw input coordinates, read as metres by glTF viewers.
  Patient,
};

struct SceneOptions {
  bool draco = true;  // KHR_draco_mesh_compression; false: plain float32 accessors
  DracoOptions dracoOptions;
  SceneFrame frame = SceneFrame::Gltf;
  // Opacity per feature in (0, 1] (below 1: alpha-blended). Empty: features that enclose
  // others (computeNesting) are drawn at 0.3, so the organs inside BODY show; the rest opaque.
  std::vector<float> opacity;
};

// Every single-file writer below stages its file beside the target and renames it into place,
// so a failure never leaves a partial file; errors are Errc::Io naming the path (Errc::Internal
// when an encoder refuses the mesh).

// One feature's closed surface in `format` (not a scene). Positions in input units; PLY exact
// floats, Draco quantized by `draco`, OBJ with 6 decimals, STL float32 with unit normals, VTP
// float32 with point normals and the feature's name and label as field data. Draco, OBJ, STL
// and VTP refuse an empty surface (Errc::InvalidArgument); PLY writes it empty.
Result<void> writeSurface(const std::filesystem::path& path, const Surfaces& surfaces, int feature, MeshFormat format,
                          const ContourSet& contours, const DracoOptions& draco = {});
// Every separating surface in one binary PLY, each face with label_inside / label_outside.
Result<void> writeMultiLabelMesh(const std::filesystem::path& path, const Surfaces& surfaces);
// One binary glTF scene (.glb): a named, coloured node per feature with a surface.
Result<void> writeScene(const std::filesystem::path& path, const ContourSet& contours, const Surfaces& surfaces,
                        const SceneOptions& options = {});
// Label volume formats, chosen by the file name (case-insensitive).
enum class VolumeFormat {
  Nrrd,   // F.nrrd, F.seg.nrrd: gzip NRRD, LPS, with the label table F.ctbl (3D Slicer colour table)
  Nifti,  // F.nii, F.nii.gz: NIfTI-1 (gzip for .nii.gz), RAS, with the label table F.label.txt (ITK-SNAP)
};
// The format of a label volume path; else an Errc::InvalidArgument error naming the known
// extensions (.nrrd, .seg.nrrd, .nii, .nii.gz).
Result<VolumeFormat> volumeFormatOf(const std::filesystem::path& path);
// The label table written beside a label volume: F.ctbl for F.nrrd (F.seg.ctbl for
// F.seg.nrrd), F.label.txt for F.nii and F.nii.gz.
std::filesystem::path labelTablePathFor(const std::filesystem::path& labelVolume, VolumeFormat format);

// The label volume (label = feature index + 1, 0 = background) in the format of `path`'s
// extension, plus its label table beside it (labelTablePathFor). Unevenly spaced layers are
// resampled along z onto even planes first (nearest layer; docs/outputs.md, "Uneven slices").
// - NRRD: gzip, `space: left-posterior-superior`, 3D Slicer segment keys (*.seg.nrrd opens as a
//   named, coloured segmentation), the table in Slicer's colour-table format.
// - NIfTI-1 through the NIfTI reference library: uint8 (uint16 when a label exceeds 255),
//   intent LABEL; qform and sform map voxels to RAS mm, i.e. scansurf's LPS x and y negated, so
//   the volume overlays the surfaces in RAS tools (ITK-SNAP, FSL, nibabel, 3D Slicer); the
//   table in ITK-SNAP's label description format.
// Errors: Errc::InvalidArgument for an unknown extension; Errc::Io naming the path.
Result<void> writeLabelVolume(const std::filesystem::path& path, const ContourSet& contours, const LabelVolume& volume);

// The label volume of a run (Engine::build), as writeLabelVolume above but from each feature's
// own region, rasterized exactly as the device did:
// - NRRD / seg.nrrd: every feature's own mask, the region its contours enclose alone; features
//   that share voxels (nested or overlapping) go to different layers: a 4-D volume with the list
//   axis first when there is more than one layer (3D Slicer's seg.nrrd convention, with
//   Segment{i}_Layer, _LabelValue and _Extent), 3-D otherwise.
// - NIfTI: the single partition (one label per voxel, inner features first), what label-map
//   tools expect.
// With a reference series (ContourSet::reference) and a grid built on it, the file lies exactly
// on its lattice: same size, origin, spacing and slices (unevenly spaced CT slices are
// resampled as above); voxels beyond it are dropped, and `warnings` (when given) names each
// feature that lost some and how many. A grid of its own (voxel size, pixel counts) is written
// as it is, with a warning.
Result<void> writeLabelVolume(const std::filesystem::path& path, const ContourSet& contours, const BuildResult& built,
                              std::vector<std::string>* warnings = nullptr);

// A run's label volume in memory, as the NIfTI output holds it: one label per voxel (label =
// feature index + 1, inner features first where they share voxels, 0 = background) on a
// regular lattice: the reference CT's when the grid lies on it, else the grid's (unevenly
// spaced layers resampled along z, as writeLabelVolume does).
struct LabelImage {
  int nx = 0, ny = 0, nz = 0;
  std::vector<Label> labels;                    // x fastest, then y, then z
  std::array<double, 3> origin{};               // centre of voxel (0, 0, 0), input units (LPS)
  std::array<std::array<double, 3>, 3> axes{};  // the step along i, j and k
  bool resampled = false;                       // layers were resampled onto even planes
  std::vector<std::string> warnings;            // voxels beyond the reference CT
};
Result<LabelImage> labelImage(const ContourSet& contours, const BuildResult& built);

// What writeDicomSeg wrote.
struct DicomSegSummary {
  int segments = 0;                   // one per feature with a voxel inside the CT
  int frames = 0;                     // one per segment and CT slice that holds part of it
  std::vector<std::string> warnings;  // features left out; voxels beyond the CT's field of view
};
// The label volume as a DICOM Segmentation (BINARY, one segment per feature that has voxels;
// the segments do not overlap, as in the label volume) on the grid of the CT series in
// `referenceSeriesDir`: the CT's rows, columns, pixel spacing and slice positions, referencing
// its images (Referenced Series, Derivation Image and Source Image Sequences), with its
// patient, study and frame of reference. `volume` must lie on that CT's lattice, as build()
// puts it when the contours were read with ReadOptions::referenceSeries and the grid options
// set no voxel size or counts. Details: docs/formats.md, "DICOM SEG".
// Errors: Errc::InvalidArgument (the volume is not on the CT lattice), Errc::InvalidInput (the
// series cannot be read, or no feature has a voxel on it), Errc::Io naming the path,
// Errc::Internal (DCMTK refused the object).
Result<DicomSegSummary> writeDicomSeg(const std::filesystem::path& path, const ContourSet& contours, const LabelVolume& volume,
                                      const std::filesystem::path& referenceSeriesDir);
// The same for a run: each segment is its feature's own region (segments overlap where the
// structures do).
Result<DicomSegSummary> writeDicomSeg(const std::filesystem::path& path, const ContourSet& contours, const BuildResult& built,
                                      const std::filesystem::path& referenceSeriesDir);
// An RGBA picture as PNG.
Result<void> writePreview(const std::filesystem::path& path, const PreviewImage& image);

// Everything a run writes. Paths are final destinations.
struct OutputPlan {
  std::filesystem::path dir;        // per-feature files and multilabel.ply; empty = none
  std::vector<MeshFormat> formats;  // in dir: Glb = one scene dir/<sceneName>.glb, others per feature
  std::string sceneName = "surfaces";
  std::filesystem::path glbFile;  // a scene at this exact path; empty = none
  // Every structure in this one file, by its extension: .ply and .vtp the multi-label mesh (every
  // separating surface once, each face with its two labels); .stl, .obj and .drc each feature's
  // closed surface, all in one mesh. Empty = none.
  std::filesystem::path meshFile;
  bool multilabel = true;                 // dir/multilabel.ply when Ply is among the formats
  SceneOptions scene;                     // GLB (dracoOptions also for .drc; maxError from the grid when 0)
  std::filesystem::path labelVolume;      // .nrrd/.seg.nrrd/.nii/.nii.gz (+ its label table); empty = none
  std::filesystem::path dicomSeg;         // .dcm DICOM Segmentation on referenceSeries' grid; empty = none
  std::filesystem::path referenceSeries;  // the CT folder the label volume lies on (for dicomSeg)
  std::filesystem::path report;           // .json; empty = none
  std::filesystem::path preview;          // .png; empty = none
};

// Every directory the plan writes into (for OutputStaging::lock), each once.
std::vector<std::filesystem::path> outputDirectories(const OutputPlan& plan);

// Checks, before any work, that every output of the plan can be written: directories exist or
// can be created and accept files, extensions are known, no two outputs share a path, a DICOM
// SEG has its reference series.
// Errors: Errc::InvalidArgument (unknown extension, clash, DICOM SEG without referenceSeries),
// Errc::Io naming the path.
Result<void> checkOutputs(const OutputPlan& plan);

// Files written into staging folders beside their destinations (one per directory) and moved
// into place by commit(), so a failed run leaves nothing partial and replaces no existing
// file. Destroyed without commit(), it removes everything staged.
class OutputStaging {
 public:
  OutputStaging() = default;
  OutputStaging(const OutputStaging&) = delete;
  OutputStaging& operator=(const OutputStaging&) = delete;
  ~OutputStaging();

  // Calls write(stagedPath) for the file that will end up at `target`; an error from it names
  // `target`, not the staging path. Errors: Errc::InvalidArgument when `target` was already
  // staged, Errc::Io, or write's error.
  Result<void> stage(const std::filesystem::path& target,
                     const std::function<Result<void>(const std::filesystem::path& staged)>& write);
  // Moves every staged file into place; returns the final paths in staging order. A target
  // that is a directory is found before anything moves (Errc::Io, nothing replaced).
  Result<std::vector<std::filesystem::path>> commit();
  // The final paths staged so far.
  std::vector<std::filesystem::path> targets() const;
  // Removes everything staged now, and the run locks' files (as the destructor does); for an
  // interrupted run.
  void discard() noexcept;
  // Holds `directory`'s run lock (an flock on directory/.scansurf.lock, released when this
  // object dies, also when the process is killed) so that two runs into one place cannot
  // interleave their files. stage() takes it for every directory it writes into; take it
  // before the work to fail early. Errors: Errc::Io naming the directory and, when another
  // run holds it, that run's pid.
  Result<void> lock(const std::filesystem::path& directory);

 private:
  Result<std::filesystem::path> reserve(const std::filesystem::path& target);
  std::vector<std::filesystem::path> dirs_;
  std::vector<std::pair<std::filesystem::path, int>> locks_;                    // directory, open lock file
  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> files_;  // staged, target
  std::set<std::filesystem::path> targets_;                                     // the targets of files_, to find a clash at once
  unsigned long id_ = 0;  // names this staging's folders: .scansurf-staging-<pid>-<id>
};

struct SurfaceOutputs {
  std::vector<std::vector<std::filesystem::path>> files;  // per feature: final paths holding its surface
  std::vector<std::string> warnings;                      // e.g. a feature without a surface
};

// Stages the surfaces, scene, label volume and DICOM SEG of the plan (not its report or
// preview). A feature with no triangles gets only its (empty) PLY, with a warning; the DICOM
// SEG's warnings (writeDicomSeg) join them.
Result<SurfaceOutputs> stageSurfaceOutputs(OutputStaging& staging, const OutputPlan& plan, const ContourSet& contours,
                                           const BuildResult& built);

// A file name from a feature name: letters, digits, '.', '-' and '_' kept, the rest '_'; over
// kMaxFileStem bytes, cut and ended with a hash of the whole name (every file system takes the
// result with any extension, staging and temporary suffix); made unique against `used`
// ignoring case ("Body" and "BODY" become Body and BODY_2, which case-insensitive file
// systems keep apart), and added to it.
inline constexpr std::size_t kMaxFileStem = 160;
std::string fileStem(const std::string& name, std::vector<std::string>& used);

}  // namespace scansurf
