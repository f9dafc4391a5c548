#include "outputs.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>

#include "io/atomic_file.h"
#include "io/gltf_writer.h"
#include "io/mesh_writers.h"
#include "io/nrrd_writer.h"
#include "io/ply_writer.h"
#include "scansurf/palette.h"

namespace fs = std::filesystem;

namespace scansurf::cli {

std::string fileStem(const std::string& name, std::vector<std::string>& used) {
  std::string stem;
  for (unsigned char c : name) stem += (std::isalnum(c) || c == '-' || c == '_' || c == '.') ? static_cast<char>(c) : '_';
  if (stem.empty() || stem.front() == '.') stem = "feature" + stem;
  std::string unique = stem;
  for (int n = 2; std::find(used.begin(), used.end(), unique) != used.end(); ++n) unique = stem + "_" + std::to_string(n);
  used.push_back(unique);
  return unique;
}

Result<MeshFormat> parseMeshFormat(const std::string& name) {
  std::string n;
  for (unsigned char c : name) n += static_cast<char>(std::tolower(c));
  if (!n.empty() && n.front() == '.') n.erase(0, 1);
  for (MeshFormat f : {MeshFormat::Ply, MeshFormat::Drc, MeshFormat::Obj, MeshFormat::Stl, MeshFormat::Glb})
    if ("." + n == extensionOf(f)) return f;
  return makeError(Errc::InvalidArgument, "unknown output format \"" + name + "\" (known: ply, drc, obj, stl, glb)");
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

bool hasExtension(const fs::path& path, const std::string& ext) {
  std::string e = path.extension().string();
  for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e == ext;
}

Result<void> checkFile(const fs::path& path, const char* what, const std::string& ext, std::vector<fs::path>& seen) {
  if (path.empty()) return {};
  if (!hasExtension(path, ext))
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

Result<void> checkOutputs(const OutputPlan& plan) {
  std::vector<fs::path> seen;
  if (!plan.dir.empty()) SCANSURF_TRY(ensureWritableDirectory(plan.dir));
  SCANSURF_TRY(checkFile(plan.glbFile, "GLB output", ".glb", seen));
  SCANSURF_TRY(checkFile(plan.labelVolume, "label volume", ".nrrd", seen));
  SCANSURF_TRY(checkFile(plan.report, "report", ".json", seen));
  SCANSURF_TRY(checkFile(plan.preview, "preview", ".png", seen));
  return {};
}

Staging::~Staging() {
  std::error_code ignored;
  for (const fs::path& dir : dirs_) fs::remove_all(dir, ignored);
}

Result<fs::path> Staging::path(const fs::path& target) {
  for (const auto& [staged, t] : files_)
    if (t == target) return makeError(Errc::InvalidArgument, "two outputs would be written to '" + target.string() + "'");
  const fs::path parent = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const fs::path dir = parent / (".scansurf-staging-" + std::to_string(::getpid()));
  if (std::find(dirs_.begin(), dirs_.end(), dir) == dirs_.end()) {
    std::error_code ec;
    fs::remove_all(dir, ec);
    if (!fs::create_directory(dir, ec)) return makeError(Errc::Io, "cannot create " + dir.string() + ": " + ec.message());
    dirs_.push_back(dir);
  }
  fs::path staged = dir / (std::to_string(files_.size()) + "-" + target.filename().string());
  files_.emplace_back(staged, target);
  return staged;
}

std::vector<fs::path> Staging::targets() const {
  std::vector<fs::path> out;
  for (const auto& f : files_) out.push_back(f.second);
  return out;
}

Result<std::vector<fs::path>> Staging::commit() {
  std::vector<fs::path> written;
  std::error_code ec;
  for (const auto& [staged, target] : files_) {
    fs::rename(staged, target, ec);
    if (ec) return makeError(Errc::Io, "cannot move " + target.filename().string() + " into place at '" + target.string() + "': " + ec.message());
    written.push_back(target);
  }
  return written;
}

Result<void> named(Result<void> r, const fs::path& staged, const fs::path& target) {
  if (r) return r;
  std::string message = r.error().message;
  for (std::size_t at; (at = message.find(staged.string())) != std::string::npos;)
    message.replace(at, staged.string().size(), target.string());
  return makeError(r.error().code, message);
}

Result<SurfaceOutputs> writeSurfaceOutputs(Staging& staging, const OutputPlan& plan, const ContourSet& contours,
                                           const Surfaces& surfaces, const LabelVolume& volume) {
  const std::size_t featureCount = contours.features.size();
  SurfaceOutputs out;
  out.files.resize(featureCount);
  std::vector<std::vector<fs::path>>& perFeature = out.files;
  const std::vector<Rgb> colors = featureColors(contours);
  DracoOptions draco = plan.dracoOptions;
  if (draco.quantizationBits == 0 && draco.maxError <= 0) draco.maxError = defaultQuantizationError(volume.grid);

  const bool wantsGlb = !plan.glbFile.empty() || std::find(plan.formats.begin(), plan.formats.end(), MeshFormat::Glb) != plan.formats.end();
  const bool wantsPly = !plan.dir.empty() && std::find(plan.formats.begin(), plan.formats.end(), MeshFormat::Ply) != plan.formats.end();
  std::vector<CompactMesh> compact;  // kept for the GLB scene
  SurfaceCompactor compactor(surfaces.mesh);
  std::vector<std::string> used{"multilabel", plan.sceneName};
  for (std::size_t f = 0; f < featureCount; ++f) {
    const FeatureSurface& surface = surfaces.features[f];
    const std::string stem = fileStem(contours.features[f].name, used);
    SCANSURF_ASSIGN_OR_RETURN(CompactMesh mesh, compactor.compact(surface));
    if (!plan.dir.empty()) {
      for (MeshFormat format : plan.formats) {
        if (format == MeshFormat::Glb) continue;
        if (format != MeshFormat::Ply && surface.triangles.empty()) {
          out.warnings.push_back("feature \"" + contours.features[f].name + "\" has no surface: no " + extensionOf(format) +
                                 " written for it");
          continue;
        }
        const fs::path target = plan.dir / (stem + extensionOf(format));
        SCANSURF_ASSIGN_OR_RETURN(const fs::path staged, staging.path(target));
        switch (format) {
          case MeshFormat::Ply: SCANSURF_TRY(named(writeSurfacePly(staged, mesh, static_cast<int>(f)), staged, target)); break;
          case MeshFormat::Drc: SCANSURF_TRY(named(writeDrc(staged, mesh, draco), staged, target)); break;
          case MeshFormat::Obj: SCANSURF_TRY(named(writeObj(staged, mesh, contours.features[f].name), staged, target)); break;
          case MeshFormat::Stl: SCANSURF_TRY(named(writeStl(staged, mesh), staged, target)); break;
          case MeshFormat::Glb: break;
        }
        perFeature[f].push_back(target);
      }
    }
    if (wantsGlb) compact.push_back(std::move(mesh));
  }
  if (wantsPly && plan.multilabel) {
    SCANSURF_ASSIGN_OR_RETURN(const fs::path staged, staging.path(plan.dir / "multilabel.ply"));
    SCANSURF_TRY(named(writeMultiLabelPly(staged, surfaces.mesh), staged, plan.dir / "multilabel.ply"));
  }
  if (wantsGlb) {
    std::vector<GltfFeature> scene;
    for (std::size_t f = 0; f < featureCount; ++f) scene.push_back({contours.features[f].name, colors[f], &compact[f]});
    GlbOptions options;
    options.draco = plan.draco;
    options.dracoOptions = draco;
    std::vector<fs::path> targets;
    if (!plan.glbFile.empty()) targets.push_back(plan.glbFile);
    if (!plan.dir.empty() && std::find(plan.formats.begin(), plan.formats.end(), MeshFormat::Glb) != plan.formats.end())
      targets.push_back(plan.dir / (plan.sceneName + ".glb"));
    for (const fs::path& target : targets) {
      SCANSURF_ASSIGN_OR_RETURN(const fs::path staged, staging.path(target));
      SCANSURF_TRY(named(writeGlb(staged, scene, options), staged, target));
      for (std::size_t f = 0; f < featureCount; ++f)
        if (surfaces.features[f].triangleCount() > 0) perFeature[f].push_back(target);
    }
  }
  if (!plan.labelVolume.empty()) {
    std::vector<LabelEntry> table;
    for (std::size_t f = 0; f < featureCount; ++f)
      table.push_back({labelOfFeature(static_cast<int>(f)), contours.features[f].name, colors[f]});
    SCANSURF_ASSIGN_OR_RETURN(const fs::path staged, staging.path(plan.labelVolume));
    SCANSURF_TRY(named(writeNrrd(staged, regularize(volume), table), staged, plan.labelVolume));
    fs::path tablePath = plan.labelVolume;
    tablePath.replace_extension(".ctbl");
    SCANSURF_ASSIGN_OR_RETURN(const fs::path stagedTable, staging.path(tablePath));
    SCANSURF_TRY(named(writeLabelTable(stagedTable, table), stagedTable, tablePath));
  }
  return out;
}

}  // namespace scansurf::cli
