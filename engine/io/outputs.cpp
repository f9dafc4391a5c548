// scansurf: every output of a run, one file at a time or all or nothing (scansurf/outputs.h).
#include "scansurf/outputs.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <string_view>

#include <algorithm>
#include <atomic>
#include <optional>
#include <cctype>

#include "geometry/compact_mesh.h"
#include "io/atomic_file.h"
#include "io/ct_series.h"
#include "io/dicom_seg_writer.h"
#include "io/draco_writer.h"
#include "io/run_volumes.h"
#include "io/gltf_writer.h"
#include "io/mesh_writers.h"
#include "io/nifti_writer.h"
#include "io/nrrd_writer.h"
#include "io/ply_writer.h"
#include "io/png_writer.h"
#include "scansurf/nesting.h"
#include "scansurf/palette.h"

namespace fs = std::filesystem;

namespace scansurf {
namespace {

std::string lowerName(const fs::path& path) {
  std::string name = path.filename().string();
  for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return name;
}

bool hasExtension(const fs::path& path, const std::string& ext) {
  const std::string name = lowerName(path);
  return name.size() > ext.size() && name.compare(name.size() - ext.size(), ext.size(), ext) == 0;
}

}  // namespace

namespace {

// Letters, digits, '.', '-' and '_' kept, every other byte '_'.
std::string sanitized(const std::string& name) {
  std::string stem;
  for (unsigned char c : name) stem += (std::isalnum(c) || c == '-' || c == '_' || c == '.') ? static_cast<char>(c) : '_';
  return stem;
}

bool equalIgnoringCase(const std::string& a, const std::string& b) {
  return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](unsigned char x, unsigned char y) { return std::tolower(x) == std::tolower(y); });
}

// FNV-1a, 32 bits, as 8 hex digits: tells cut names apart.
std::string nameHash(const std::string& name) {
  std::uint32_t h = 2166136261u;
  for (unsigned char c : name) h = (h ^ c) * 16777619u;
  char text[9];
  std::snprintf(text, sizeof text, "%08x", h);
  return text;
}

}  // namespace

std::string fileStem(const std::string& name, std::vector<std::string>& used) {
  std::string stem = sanitized(name);
  if (stem.empty() || stem.front() == '.') stem = "feature" + stem;
  if (stem.size() > kMaxFileStem) stem = stem.substr(0, kMaxFileStem - 9) + "_" + nameHash(name);
  auto taken = [&](const std::string& candidate) {
    return std::any_of(used.begin(), used.end(), [&](const std::string& u) { return equalIgnoringCase(u, candidate); });
  };
  std::string unique = stem;
  for (int n = 2; taken(unique); ++n) unique = stem + "_" + std::to_string(n);
  used.push_back(unique);
  return unique;
}

Result<VolumeFormat> volumeFormatOf(const fs::path& path) {
  for (const char* ext : {".nrrd"})
    if (hasExtension(path, ext)) return VolumeFormat::Nrrd;
  for (const char* ext : {".nii", ".nii.gz"})
    if (hasExtension(path, ext)) return VolumeFormat::Nifti;
  std::string message = "'";  // not "'" + path.string(): GCC 12 warns -Wrestrict in error (GCC bug 105329)
  message += path.string();
  message += "': unknown format (known: .nrrd, .seg.nrrd, .nii, .nii.gz)";
  return makeError(Errc::InvalidArgument, message);
}

fs::path labelTablePathFor(const fs::path& labelVolume, VolumeFormat format) {
  if (format == VolumeFormat::Nifti) return itkSnapLabelPathFor(labelVolume);
  fs::path table = labelVolume;
  return table.replace_extension(".ctbl");
}

Result<MeshFormat> parseMeshFormat(std::string_view name) {
  std::string n;
  for (unsigned char c : name) n += static_cast<char>(std::tolower(c));
  if (!n.empty() && n.front() == '.') n.erase(0, 1);
  for (MeshFormat f : {MeshFormat::Ply, MeshFormat::Drc, MeshFormat::Obj, MeshFormat::Stl, MeshFormat::Glb})
    if ("." + n == extensionOf(f)) return f;
  return makeError(Errc::InvalidArgument, "unknown output format \"" + std::string(name) + "\" (known: ply, drc, obj, stl, glb)");
}

const char* extensionOf(MeshFormat format) {
  switch (format) {
    case MeshFormat::Ply: return ".ply";
    case MeshFormat::Drc: return ".drc";
    case MeshFormat::Obj: return ".obj";
    case MeshFormat::Stl: return ".stl";
    case MeshFormat::Glb: return ".glb";
  }
  return "";
}

namespace {

// ext empty: the caller checked the format.
Result<void> checkFile(const fs::path& path, const char* what, const std::string& ext, std::vector<fs::path>& seen) {
  if (path.empty()) return {};
  if (!ext.empty() && !hasExtension(path, ext))
    return makeError(Errc::InvalidArgument, std::string(what) + " '" + path.string() + "': unknown format (expected a " + ext +
                                                " file)");
  const fs::path full = fs::absolute(path).lexically_normal();
  if (std::find(seen.begin(), seen.end(), full) != seen.end())
    return makeError(Errc::InvalidArgument, "two outputs would be written to '" + path.string() + "'");
  seen.push_back(full);
  if (fs::is_directory(path)) return makeError(Errc::Io, std::string(what) + " '" + path.string() + "' is a directory");
  return ensureWritableDirectory(path.has_parent_path() ? path.parent_path() : fs::path("."));
}

}  // namespace

std::vector<fs::path> outputDirectories(const OutputPlan& plan) {
  std::vector<fs::path> dirs;
  auto add = [&](const fs::path& dir) {
    const fs::path d = dir.empty() ? fs::path(".") : dir;
    if (std::find(dirs.begin(), dirs.end(), d) == dirs.end()) dirs.push_back(d);
  };
  if (!plan.dir.empty()) add(plan.dir);
  for (const fs::path* file : {&plan.glbFile, &plan.labelVolume, &plan.dicomSeg, &plan.report, &plan.preview})
    if (!file->empty()) add(file->parent_path());
  return dirs;
}

Result<void> checkOutputs(const OutputPlan& plan) {
  std::vector<fs::path> seen;
  if (!plan.dir.empty()) SCANSURF_TRY(ensureWritableDirectory(plan.dir));
  SCANSURF_TRY(checkFile(plan.glbFile, "GLB output", ".glb", seen));
  if (!plan.labelVolume.empty()) {
    auto format = volumeFormatOf(plan.labelVolume);
    if (!format) return makeError(Errc::InvalidArgument, "label volume " + format.error().message);
    SCANSURF_TRY(checkFile(plan.labelVolume, "label volume", "", seen));
    SCANSURF_TRY(checkFile(labelTablePathFor(plan.labelVolume, *format), "label table", "", seen));
  }
  SCANSURF_TRY(checkFile(plan.dicomSeg, "DICOM SEG output", ".dcm", seen));
  if (!plan.dicomSeg.empty() && plan.referenceSeries.empty())
    return makeError(Errc::InvalidArgument, "DICOM SEG output '" + plan.dicomSeg.string() +
                                                "' needs the CT series the label volume lies on (a reference series)");
  SCANSURF_TRY(checkFile(plan.report, "report", ".json", seen));
  SCANSURF_TRY(checkFile(plan.preview, "preview", ".png", seen));
  return {};
}

namespace {
unsigned long nextStagingId() {
  static std::atomic<unsigned long> next{1};
  return next.fetch_add(1);
}
}  // namespace

// Staging folders of processes that died (killed during their write stage) are removed by
// the next run into the same place: the pid in the name is no longer alive.
void removeStaleStaging(const fs::path& parent) {
  constexpr std::string_view kPrefix = ".scansurf-staging-";
  std::error_code ec;
  for (fs::directory_iterator it(parent, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(kPrefix, 0) != 0) continue;
    const std::string rest = name.substr(kPrefix.size());
    const long pid = std::strtol(rest.c_str(), nullptr, 10);
    if (pid <= 0 || pid == ::getpid()) continue;
    if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) {
      std::error_code ignored;
      fs::remove_all(it->path(), ignored);
    }
  }
}

constexpr const char* kLockName = ".scansurf.lock";

// Removes the lock file's name if it still is the file `fd` locked (a later run may have made a
// new one after an earlier removal).
void unlinkOwnLock(const fs::path& dir, int fd) {
  const fs::path file = dir / kLockName;
  struct stat held {}, named {};
  if (::fstat(fd, &held) == 0 && ::lstat(file.c_str(), &named) == 0 && held.st_ino == named.st_ino && held.st_dev == named.st_dev)
    ::unlink(file.c_str());
}

// Opens (or creates) the lock file itself, never what a link of that name points to: a link
// planted there must not let a run empty, overwrite or create a file elsewhere.
Result<int> openLockFile(const fs::path& file) {
  const int fd = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
  if (fd < 0 && errno == ELOOP)
    return makeError(Errc::Io, "the run lock '" + file.string() + "' is a symbolic link; scansurf never follows one there (remove it)");
  if (fd < 0) return makeError(Errc::Io, "cannot open the run lock '" + file.string() + "': " + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    return makeError(Errc::Io, "the run lock '" + file.string() + "' is not a regular file (remove it)");
  }
  return fd;
}

OutputStaging::~OutputStaging() {
  discard();
  for (const auto& [dir, fd] : locks_) ::close(fd);  // releases the flock
}

Result<void> OutputStaging::lock(const fs::path& directory) {
  const fs::path dir = directory.empty() ? fs::path(".") : directory;
  for (const auto& held : locks_)
    if (held.first == dir) return {};
  const fs::path file = dir / kLockName;
  int fd = -1;
  bool busy = false;
  for (int attempt = 0; fd < 0 && attempt < 100; ++attempt) {
    SCANSURF_ASSIGN_OR_RETURN(fd, openLockFile(file));
    busy = ::flock(fd, LOCK_EX | LOCK_NB) != 0;
    struct stat held {}, named {};
    if (busy || (::fstat(fd, &held) == 0 && ::lstat(file.c_str(), &named) == 0 && held.st_ino == named.st_ino &&
                 held.st_dev == named.st_dev))
      break;  // held by another run, or locked and still the file of that name
    ::close(fd);  // its last holder unlinked it meanwhile: lock the new one
    fd = -1;
  }
  if (fd < 0) return makeError(Errc::Io, "cannot take the run lock '" + file.string() + "'");
  if (busy) {
    char pid[32] = {};
    const ssize_t n = ::pread(fd, pid, sizeof pid - 1, 0);
    ::close(fd);
    const std::string holder = n > 0 ? " (pid " + std::string(pid, static_cast<std::size_t>(n)) + ")" : "";
    return makeError(Errc::Io, "another scansurf run" + holder + " is writing into '" + dir.string() +
                                   "'; wait for it to finish or choose another output location");
  }
  const std::string self = std::to_string(::getpid());
  if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, self.data(), self.size(), 0) < 0) {
    // The pid is only a courtesy for the message of a run that waits; the lock holds without it.
  }
  locks_.emplace_back(dir, fd);
  return {};
}

void OutputStaging::discard() noexcept {
  std::error_code ignored;
  for (const fs::path& dir : dirs_) fs::remove_all(dir, ignored);
  // Unlinked while still held, so nothing is left behind, also by an interrupted run, and a
  // run that opens the name next makes a fresh file (lock() checks it locked the named one).
  for (const auto& [dir, fd] : locks_) unlinkOwnLock(dir, fd);
}

namespace {

// A staged file is named by its index and the target's extensions (writers read ".nii.gz" and
// ".seg.nrrd" off the name), never its whole name: a 250-character file name plus a prefix
// was more than a file name may be.
std::string stagedSuffix(const fs::path& target) {
  const std::string last = target.extension().string();
  const std::string before = target.stem().extension().string();
  std::string suffix = (before.size() > 1 && before.size() <= 8 ? before : std::string()) + last;
  if (suffix.size() > 24) suffix.clear();
  return suffix;
}

}  // namespace

Result<fs::path> OutputStaging::reserve(const fs::path& target) {
  if (!targets_.insert(target).second)
    return makeError(Errc::InvalidArgument, "two outputs would be written to '" + target.string() + "'");
  const fs::path parent = target.has_parent_path() ? target.parent_path() : fs::path(".");
  // One folder per OutputStaging (pid and a process-wide count): two runs in one process
  // writing to one directory never share or remove each other's staged files.
  if (id_ == 0) id_ = nextStagingId();
  const fs::path dir = parent / (".scansurf-staging-" + std::to_string(::getpid()) + "-" + std::to_string(id_));
  if (std::find(dirs_.begin(), dirs_.end(), dir) == dirs_.end()) {
    SCANSURF_TRY(lock(parent));
    removeStaleStaging(parent);
    std::error_code ec;
    fs::remove_all(dir, ec);
    if (!fs::create_directory(dir, ec)) return makeError(Errc::Io, "cannot create " + dir.string() + ": " + ec.message());
    dirs_.push_back(dir);
  }
  fs::path staged = dir / (std::to_string(files_.size()) + stagedSuffix(target));
  files_.emplace_back(staged, target);
  return staged;
}

Result<void> OutputStaging::stage(const fs::path& target, const std::function<Result<void>(const fs::path& staged)>& write) {
  SCANSURF_ASSIGN_OR_RETURN(const fs::path staged, reserve(target));
  const DeferredSync oneSyncAtCommit;
  Result<void> written = write(staged);
  if (written) return written;
  // Name the file the user asked for, not the staging path.
  std::string message = written.error().message;
  for (std::size_t at; (at = message.find(staged.string())) != std::string::npos;)
    message.replace(at, staged.string().size(), target.string());
  return makeError(written.error().code, message);
}

std::vector<fs::path> OutputStaging::targets() const {
  std::vector<fs::path> out;
  for (const auto& f : files_) out.push_back(f.second);
  return out;
}

Result<std::vector<fs::path>> OutputStaging::commit() {
  std::vector<fs::path> written;
  std::error_code ec;
  // A target that is a directory would stop the moves half way: find it before any move.
  for (const auto& [staged, target] : files_)
    if (fs::is_directory(target, ec))
      return makeError(Errc::Io, "cannot write '" + target.string() + "': a directory is in the way; nothing was replaced");
  // Everything staged reaches the disk before the first move (one sync, not one per file).
  for (const fs::path& dir : dirs_) SCANSURF_TRY(syncFileSystemOf(dir));
  // All or nothing: every old file is moved aside into the staging folder first (same
  // directory, so a rename), then the new ones into place; a move that fails (an immutable
  // file, a mount point) puts back everything moved so far.
  std::vector<std::pair<fs::path, fs::path>> asideOf;  // target, where its old file went
  const auto undo = [&](std::size_t placed) {
    std::error_code ignored;
    for (std::size_t i = 0; i < placed; ++i) fs::rename(files_[i].second, files_[i].first, ignored);
    for (const auto& [target, aside] : asideOf) fs::rename(aside, target, ignored);
  };
  for (std::size_t i = 0; i < files_.size(); ++i) {
    const fs::path& target = files_[i].second;
    if (!fs::exists(fs::symlink_status(target, ec))) continue;
    const fs::path aside = files_[i].first.parent_path() / ("old-" + std::to_string(i));
    fs::rename(target, aside, ec);
    if (ec) {
      undo(0);
      return makeError(Errc::Io, "cannot replace '" + target.string() + "': " + ec.message() + "; nothing was replaced");
    }
    asideOf.emplace_back(target, aside);
  }
  for (std::size_t i = 0; i < files_.size(); ++i) {
    const auto& [staged, target] = files_[i];
    fs::rename(staged, target, ec);
    if (ec) {
      undo(i);
      return makeError(Errc::Io, "cannot move " + target.filename().string() + " into place at '" + target.string() + "': " +
                                     ec.message() + "; nothing was replaced");
    }
    written.push_back(target);
  }
  // The moves themselves: each destination directory's entries.
  for (const fs::path& dir : dirs_) SCANSURF_TRY(syncFileSystemOf(dir.parent_path()));
  return written;
}

namespace {

// Features that enclose others are see-through (as in the preview), unless the options say.
std::vector<float> sceneOpacity(const ContourSet& contours, const SceneOptions& options) {
  return options.opacity.empty() ? displayOpacity(computeNesting(contours)) : options.opacity;
}

std::vector<GltfFeature> sceneFeatures(const ContourSet& contours, const std::vector<CompactMesh>& meshes,
                                       const std::vector<float>& opacity) {
  const std::vector<Rgb> colors = featureColors(contours);
  std::vector<GltfFeature> scene;
  for (std::size_t f = 0; f < meshes.size(); ++f)
    scene.push_back({contours.features[f].name, colors[f], &meshes[f], f < opacity.size() ? opacity[f] : 1.0f});
  return scene;
}

GlbOptions glbOptions(const SceneOptions& options, const DracoOptions& draco, const ContourSet& contours) {
  GlbOptions glb;
  glb.draco = options.draco;
  glb.dracoOptions = draco;
  glb.frame = options.frame;
  glb.units = contours.units;
  return glb;
}

std::vector<LabelEntry> labelTable(const ContourSet& contours) {
  const std::vector<Rgb> colors = featureColors(contours);
  std::vector<LabelEntry> table;
  for (std::size_t f = 0; f < contours.features.size(); ++f)
    table.push_back({labelOfFeature(static_cast<int>(f)), contours.features[f].name, colors[f]});
  return table;
}

Result<void> writeCompact(const fs::path& path, const CompactMesh& mesh, int feature, MeshFormat format,
                          const std::string& name, const DracoOptions& draco) {
  if (format != MeshFormat::Ply && mesh.triangles.empty())
    return makeError(Errc::InvalidArgument, "feature \"" + name + "\" has no surface: " + extensionOf(format) +
                                                " cannot hold an empty mesh (" + path.string() + ")");
  switch (format) {
    case MeshFormat::Ply: return writeSurfacePly(path, mesh, feature);
    case MeshFormat::Drc: return writeDrc(path, mesh, draco);
    case MeshFormat::Obj: return writeObj(path, mesh, name);
    case MeshFormat::Stl: return writeStl(path, mesh);
    case MeshFormat::Glb: break;
  }
  return makeError(Errc::InvalidArgument, "writeSurface writes one feature; a GLB scene is writeScene's (" + path.string() + ")");
}

DracoOptions dracoFor(const DracoOptions& options, const Grid& grid) {
  DracoOptions draco = options;
  if (draco.quantizationBits == 0 && draco.maxError <= 0) draco.maxError = defaultQuantizationError(grid);
  return draco;
}

Result<void> writeVolumeFile(const fs::path& path, VolumeFormat format, const ContourSet& contours,
                             const RegularLabelVolume& volume, const std::vector<LabelEntry>& table) {
  if (format == VolumeFormat::Nifti) return writeNifti(path, volume, contours.units);
  return writeNrrd(path, volume, table);
}

Result<void> writeTableFile(const fs::path& path, VolumeFormat format, const std::vector<LabelEntry>& table) {
  if (format == VolumeFormat::Nifti) return writeItkSnapLabels(path, table);
  return writeLabelTable(path, table);
}

// A run's label volume: masks in layers for NRRD, the partition for NIfTI.
Result<void> writeRunVolume(const fs::path& path, VolumeFormat format, const ContourSet& contours, const RunVolumes& volumes,
                            const std::vector<LabelEntry>& table) {
  if (format == VolumeFormat::Nifti) return writeNifti(path, volumes.partition, contours.units);
  std::vector<int> layerOf;
  for (const LabelEntry& e : table) layerOf.push_back(volumes.maskLayerOf[static_cast<std::size_t>(featureOfLabel(e.label))]);
  return writeSegmentationNrrd(path, volumes.masks, table, layerOf);
}

bool has(const std::vector<MeshFormat>& formats, MeshFormat f) {
  return std::find(formats.begin(), formats.end(), f) != formats.end();
}

// The per-feature files of one feature in the plan's directory.
Result<void> stageFeatureFiles(OutputStaging& staging, const OutputPlan& plan, const CompactMesh& mesh, int feature,
                               const std::string& name, const std::string& stem, const DracoOptions& draco,
                               SurfaceOutputs& out) {
  for (MeshFormat format : plan.formats) {
    if (format == MeshFormat::Glb) continue;
    if (format != MeshFormat::Ply && mesh.triangles.empty()) {
      out.warnings.push_back("feature \"" + name + "\" has no surface: no " + extensionOf(format) + " written for it");
      continue;
    }
    const fs::path target = plan.dir / (stem + extensionOf(format));
    SCANSURF_TRY(staging.stage(target, [&](const fs::path& p) { return writeCompact(p, mesh, feature, format, name, draco); }));
    out.files[static_cast<std::size_t>(feature)].push_back(target);
  }
  return {};
}

std::vector<fs::path> sceneTargets(const OutputPlan& plan) {
  std::vector<fs::path> targets;
  if (!plan.glbFile.empty()) targets.push_back(plan.glbFile);
  if (!plan.dir.empty() && has(plan.formats, MeshFormat::Glb)) targets.push_back(plan.dir / (plan.sceneName + ".glb"));
  return targets;
}

}  // namespace

Result<void> writeSurface(const fs::path& path, const Surfaces& surfaces, int feature, MeshFormat format,
                          const ContourSet& contours, const DracoOptions& draco) {
  if (feature < 0 || static_cast<std::size_t>(feature) >= surfaces.features.size() ||
      surfaces.features.size() != contours.features.size())
    return makeError(Errc::InvalidArgument, "writeSurface: feature " + std::to_string(feature) + " is not one of the " +
                                                std::to_string(surfaces.features.size()) + " surfaces of the contour set");
  SurfaceCompactor compactor(surfaces.mesh);
  SCANSURF_ASSIGN_OR_RETURN(const CompactMesh mesh, compactor.compact(surfaces.features[static_cast<std::size_t>(feature)]));
  return writeCompact(path, mesh, feature, format, contours.features[static_cast<std::size_t>(feature)].name, draco);
}

Result<void> writeMultiLabelMesh(const fs::path& path, const Surfaces& surfaces) {
  return writeMultiLabelPly(path, surfaces.mesh);
}

Result<void> writeScene(const fs::path& path, const ContourSet& contours, const Surfaces& surfaces, const SceneOptions& options) {
  if (surfaces.features.size() != contours.features.size())
    return makeError(Errc::InvalidArgument, "writeScene: the surfaces are not those of the contour set");
  SurfaceCompactor compactor(surfaces.mesh);
  std::vector<CompactMesh> meshes;
  for (const FeatureSurface& surface : surfaces.features) {
    SCANSURF_ASSIGN_OR_RETURN(CompactMesh mesh, compactor.compact(surface));
    meshes.push_back(std::move(mesh));
  }
  return writeGlb(path, sceneFeatures(contours, meshes, sceneOpacity(contours, options)),
                  glbOptions(options, options.dracoOptions, contours));
}

Result<void> writeLabelVolume(const fs::path& path, const ContourSet& contours, const LabelVolume& volume) {
  SCANSURF_ASSIGN_OR_RETURN(const VolumeFormat format, volumeFormatOf(path));
  const std::vector<LabelEntry> table = labelTable(contours);
  SCANSURF_TRY(writeVolumeFile(path, format, contours, regularize(volume), table));
  return writeTableFile(labelTablePathFor(path, format), format, table);
}

Result<void> writeLabelVolume(const fs::path& path, const ContourSet& contours, const BuildResult& built,
                              std::vector<std::string>* warnings) {
  SCANSURF_ASSIGN_OR_RETURN(const VolumeFormat format, volumeFormatOf(path));
  SCANSURF_ASSIGN_OR_RETURN(const RunVolumes volumes, runVolumes(contours, built, format == VolumeFormat::Nifti));
  if (warnings) warnings->insert(warnings->end(), volumes.warnings.begin(), volumes.warnings.end());
  const std::vector<LabelEntry> table = labelTable(contours);
  SCANSURF_TRY(writeRunVolume(path, format, contours, volumes, table));
  return writeTableFile(labelTablePathFor(path, format), format, table);
}

Result<DicomSegSummary> writeDicomSeg(const fs::path& path, const ContourSet& contours, const LabelVolume& volume,
                                      const fs::path& referenceSeriesDir) {
  SCANSURF_ASSIGN_OR_RETURN(const CtSeries ct, readCtSeries(referenceSeriesDir));
  return writeDicomSegmentation(path, contours, {volume}, ct);
}

Result<DicomSegSummary> writeDicomSeg(const fs::path& path, const ContourSet& contours, const BuildResult& built,
                                      const fs::path& referenceSeriesDir) {
  SCANSURF_ASSIGN_OR_RETURN(const CtSeries ct, readCtSeries(referenceSeriesDir));
  SCANSURF_ASSIGN_OR_RETURN(const RunVolumes volumes, runVolumes(contours, built, false));
  return writeDicomSegmentation(path, contours, volumes.masksOnGrid, ct);
}

Result<void> writePreview(const fs::path& path, const PreviewImage& image) {
  return writePng(path, image.width, image.height, image.rgba);
}

namespace {

// A feature whose files are not named after it as such says so: a name too long for a file
// system, or one that differs from another only in case or in characters a file name cannot hold.
void warnAboutFileStem(const std::string& name, const std::string& stem, std::vector<std::string>& warnings) {
  const std::string plain = sanitized(name);
  if (plain.size() > kMaxFileStem)
    warnings.push_back("feature \"" + name.substr(0, 40) + "...\": its name is too long for a file name; its files are " + stem +
                       ".* (the report keeps the whole name)");
  else if (stem != plain && stem.rfind(plain + "_", 0) == 0)
    warnings.push_back("feature \"" + name + "\": another feature's file name differs only in case or in characters a file name "
                       "cannot hold; its files are " + stem + ".*");
}

}  // namespace

Result<SurfaceOutputs> stageSurfaceOutputs(OutputStaging& staging, const OutputPlan& plan, const ContourSet& contours,
                                           const BuildResult& built) {
  const Surfaces& surfaces = built.surfaces;
  const LabelVolume& volume = built.volume;
  if (surfaces.features.size() != contours.features.size())
    return makeError(Errc::InvalidArgument, "stageSurfaceOutputs: the build result is not that of the contour set");
  const std::size_t featureCount = contours.features.size();
  SurfaceOutputs out;
  out.files.resize(featureCount);
  const DracoOptions draco = dracoFor(plan.scene.dracoOptions, volume.grid);
  const std::vector<fs::path> scenes = sceneTargets(plan);
  std::vector<CompactMesh> compact;  // kept for the GLB scene
  SurfaceCompactor compactor(surfaces.mesh);
  std::vector<std::string> used{"multilabel", plan.sceneName};
  for (std::size_t f = 0; f < featureCount; ++f) {
    const std::string& name = contours.features[f].name;
    SCANSURF_ASSIGN_OR_RETURN(CompactMesh mesh, compactor.compact(surfaces.features[f]));
    if (!plan.dir.empty()) {
      const std::string stem = fileStem(name, used);
      warnAboutFileStem(name, stem, out.warnings);
      SCANSURF_TRY(stageFeatureFiles(staging, plan, mesh, static_cast<int>(f), name, stem, draco, out));
    }
    if (!scenes.empty()) compact.push_back(std::move(mesh));
  }
  if (!plan.dir.empty() && has(plan.formats, MeshFormat::Ply) && plan.multilabel)
    SCANSURF_TRY(staging.stage(plan.dir / "multilabel.ply", [&](const fs::path& p) { return writeMultiLabelPly(p, surfaces.mesh); }));
  const GlbOptions glb = glbOptions(plan.scene, draco, contours);
  const std::vector<float> opacity = scenes.empty() ? std::vector<float>{} : sceneOpacity(contours, plan.scene);
  for (const fs::path& target : scenes) {
    SCANSURF_TRY(staging.stage(target, [&](const fs::path& p) { return writeGlb(p, sceneFeatures(contours, compact, opacity), glb); }));
    for (std::size_t f = 0; f < featureCount; ++f)
      if (surfaces.features[f].triangleCount() > 0) out.files[f].push_back(target);
  }
  std::optional<RunVolumes> volumes;
  if (!plan.labelVolume.empty() || !plan.dicomSeg.empty()) {
    const auto format = plan.labelVolume.empty() ? Result<VolumeFormat>(VolumeFormat::Nrrd) : volumeFormatOf(plan.labelVolume);
    SCANSURF_ASSIGN_OR_RETURN(volumes, runVolumes(contours, built, format && *format == VolumeFormat::Nifti));
    if (!plan.labelVolume.empty()) out.warnings.insert(out.warnings.end(), volumes->warnings.begin(), volumes->warnings.end());
  }
  if (!plan.labelVolume.empty()) {
    SCANSURF_ASSIGN_OR_RETURN(const VolumeFormat format, volumeFormatOf(plan.labelVolume));
    const std::vector<LabelEntry> table = labelTable(contours);
    SCANSURF_TRY(staging.stage(plan.labelVolume,
                               [&](const fs::path& p) { return writeRunVolume(p, format, contours, *volumes, table); }));
    SCANSURF_TRY(staging.stage(labelTablePathFor(plan.labelVolume, format),
                               [&](const fs::path& p) { return writeTableFile(p, format, table); }));
  }
  if (!plan.dicomSeg.empty()) {
    if (plan.referenceSeries.empty())
      return makeError(Errc::InvalidArgument, "DICOM SEG output '" + plan.dicomSeg.string() + "' needs a reference series");
    SCANSURF_ASSIGN_OR_RETURN(const CtSeries ct, readCtSeries(plan.referenceSeries));
    SCANSURF_TRY(staging.stage(plan.dicomSeg, [&](const fs::path& p) -> Result<void> {
      SCANSURF_ASSIGN_OR_RETURN(DicomSegSummary seg, writeDicomSegmentation(p, contours, volumes->masksOnGrid, ct));
      out.warnings.insert(out.warnings.end(), seg.warnings.begin(), seg.warnings.end());
      return {};
    }));
  }
  return out;
}

}  // namespace scansurf
