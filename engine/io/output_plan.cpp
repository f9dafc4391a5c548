// scansurf: what a run's outputs are called and whether they can be written, checked before
// the work (scansurf/outputs.h: fileStem, the formats by name, checkOutputs).
#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <string_view>

#include "io/atomic_file.h"
#include "io/nifti_writer.h"
#include "io/nrrd_writer.h"
#include "io/output_names.h"
#include "scansurf/outputs.h"

namespace fs = std::filesystem;

namespace scansurf {

std::string lowerName(const fs::path& path) {
  std::string name = path.filename().string();
  for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return name;
}

bool hasExtension(const fs::path& path, const std::string& ext) {
  const std::string name = lowerName(path);
  return name.size() > ext.size() && name.compare(name.size() - ext.size(), ext.size(), ext) == 0;
}

std::string sanitized(const std::string& name) {
  std::string stem;
  for (unsigned char c : name) stem += (std::isalnum(c) || c == '-' || c == '_' || c == '.') ? static_cast<char>(c) : '_';
  return stem;
}

namespace {

bool equalIgnoringCase(const std::string& a, const std::string& b) {
  return std::equal(a.begin(), a.end(), b.begin(), b.end(),
                    [](unsigned char x, unsigned char y) { return std::tolower(x) == std::tolower(y); });
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
  for (MeshFormat f :
       {MeshFormat::Ply, MeshFormat::Drc, MeshFormat::Obj, MeshFormat::Stl, MeshFormat::Glb, MeshFormat::Vtp, MeshFormat::SegVtm})
    if ("." + n == extensionOf(f)) return f;
  return makeError(Errc::InvalidArgument,
                   "unknown output format \"" + std::string(name) + "\" (known: ply, drc, obj, stl, glb, vtp, seg.vtm)");
}

const char* extensionOf(MeshFormat format) {
  switch (format) {
    case MeshFormat::Ply: return ".ply";
    case MeshFormat::Drc: return ".drc";
    case MeshFormat::Obj: return ".obj";
    case MeshFormat::Stl: return ".stl";
    case MeshFormat::Glb: return ".glb";
    case MeshFormat::Vtp: return ".vtp";
    case MeshFormat::SegVtm: return ".seg.vtm";
  }
  return "";
}

namespace {

// ext empty: the caller checked the format.
Result<void> checkFile(const fs::path& path, const char* what, const std::string& ext, std::vector<fs::path>& seen) {
  if (path.empty()) return {};
  if (!ext.empty() && !hasExtension(path, ext))
    return makeError(Errc::InvalidArgument,
                     std::string(what) + " '" + path.string() + "': unknown format (expected a " + ext + " file)");
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
  for (const fs::path* file : {&plan.glbFile, &plan.meshFile, &plan.labelVolume, &plan.dicomSeg, &plan.report, &plan.preview})
    if (!file->empty()) add(file->parent_path());
  return dirs;
}

Result<void> checkOutputs(const OutputPlan& plan) {
  std::vector<fs::path> seen;
  if (!plan.dir.empty()) SCANSURF_TRY(ensureWritableDirectory(plan.dir));
  SCANSURF_TRY(checkFile(plan.glbFile, "GLB output", ".glb", seen));
  if (!plan.meshFile.empty()) {
    const auto format = parseMeshFormat(plan.meshFile.extension().string());
    if (!format || *format == MeshFormat::Glb || *format == MeshFormat::SegVtm)
      return makeError(Errc::InvalidArgument, "mesh output '" + plan.meshFile.string() +
                                                  "': unknown format (expected a .ply, .vtp, .stl, .obj or .drc file)");
    SCANSURF_TRY(checkFile(plan.meshFile, "mesh output", "", seen));
  }
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

}  // namespace scansurf
