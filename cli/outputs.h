// scansurf CLI: writing every output of a run, all or nothing.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "io/draco_writer.h"
#include "scansurf/contours.h"
#include "scansurf/label_volume.h"
#include "scansurf/result.h"
#include "scansurf/surfaces.h"

namespace scansurf::cli {

// Per-feature surface formats (one file per feature in the output directory) and the scene.
enum class MeshFormat { Ply, Drc, Obj, Stl, Glb };

// "ply", "drc", "obj", "stl", "glb" (case-insensitive, a leading '.' allowed); else an
// Errc::InvalidArgument error naming the known formats.
Result<MeshFormat> parseMeshFormat(const std::string& name);
const char* extensionOf(MeshFormat format);  // ".ply", ...

// Everything a run writes. Paths are final destinations.
struct OutputPlan {
  std::filesystem::path dir;        // per-feature files and multilabel.ply; empty = none
  std::vector<MeshFormat> formats;  // in dir: Glb = one scene dir/<sceneName>.glb, others per feature
  std::string sceneName = "surfaces";
  std::filesystem::path glbFile;    // a scene at this exact path (-o x.glb); empty = none
  bool multilabel = true;           // dir/multilabel.ply when Ply is among the formats
  bool draco = true;                // GLB with KHR_draco_mesh_compression
  DracoOptions dracoOptions;        // .drc and Draco GLB (maxError filled in from the grid)
  std::filesystem::path labelVolume;  // .nrrd (+ .ctbl label table beside it); empty = none
  std::filesystem::path report;       // .json; empty = none
  std::filesystem::path preview;      // .png; empty = none
};

// Checks, before any work, that every output can be written: the directories exist or can be
// created and accept files, extensions are known, no two outputs share a path. Errors:
// Errc::InvalidArgument (unknown extension), Errc::Io naming the path.
Result<void> checkOutputs(const OutputPlan& plan);

// Outputs written into staging folders (one per destination directory, created on demand)
// and moved into place by commit(), so a failed run leaves nothing partial and replaces no
// existing file. Destroyed without commit(), it removes everything staged.
class Staging {
 public:
  Staging() = default;
  Staging(const Staging&) = delete;
  Staging& operator=(const Staging&) = delete;
  ~Staging();

  // Where to write the file that will end up at `target`. Errors: Errc::Io, or
  // Errc::InvalidArgument when `target` was already staged.
  Result<std::filesystem::path> path(const std::filesystem::path& target);
  // Moves every staged file into place; returns the final paths in staging order.
  Result<std::vector<std::filesystem::path>> commit();
  // The final paths staged so far.
  std::vector<std::filesystem::path> targets() const;

 private:
  std::vector<std::filesystem::path> dirs_;
  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> files_;  // staged, target
};

// r, with any mention of the staged path replaced by the target's, so errors name the file the
// user asked for.
Result<void> named(Result<void> r, const std::filesystem::path& staged, const std::filesystem::path& target);

struct SurfaceOutputs {
  std::vector<std::vector<std::filesystem::path>> files;  // per feature: final paths holding its surface
  std::vector<std::string> warnings;                      // e.g. a feature without a surface
};

// Writes the surfaces and the label volume of the plan into `staging`. A feature with no
// triangles (contours too small for the grid) gets only its (empty) PLY: Draco, OBJ and STL
// encoders refuse empty meshes; a warning says so. Errors name the final path.
Result<SurfaceOutputs> writeSurfaceOutputs(Staging& staging, const OutputPlan& plan, const ContourSet& contours,
                                           const Surfaces& surfaces, const LabelVolume& volume);

// A file name from a feature name: letters, digits, '.', '-' and '_' kept, the rest '_';
// made unique against `used` (and added to it).
std::string fileStem(const std::string& name, std::vector<std::string>& used);

}  // namespace scansurf::cli
