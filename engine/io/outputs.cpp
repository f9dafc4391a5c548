// scansurf: every output of a run by format: the writers behind scansurf/outputs.h and the
// staging of a whole run's surface files (names: output_plan.cpp; all or nothing: output_staging.cpp).
#include "scansurf/outputs.h"

#include <algorithm>
#include <optional>

#include "geometry/mesh/compact_mesh.h"
#include "io/atomic_file.h"
#include "io/ct_series.h"
#include "io/dicom_seg_writer.h"
#include "io/draco_writer.h"
#include "io/gltf_writer.h"
#include "io/mesh_writers.h"
#include "io/nifti_writer.h"
#include "io/nrrd_writer.h"
#include "io/output_names.h"
#include "io/ply_writer.h"
#include "io/png_writer.h"
#include "io/run_volumes.h"
#include "io/slicer_terminology.h"
#include "io/vtk_writer.h"
#include "scansurf/nesting.h"
#include "scansurf/palette.h"

namespace fs = std::filesystem;

namespace scansurf {

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
  glb.coordinates = contours.frame;
  return glb;
}

std::vector<LabelEntry> labelTable(const ContourSet& contours) {
  const std::vector<Rgb> colors = featureColors(contours);
  std::vector<LabelEntry> table;
  for (std::size_t f = 0; f < contours.features.size(); ++f)
    table.push_back({labelOfFeature(static_cast<int>(f)), contours.features[f].name, colors[f],
                     slicerTerminology(terminologyOf(contours.features[f].interpretedType))});
  return table;
}

Result<void> writeCompact(const fs::path& path, const CompactMesh& mesh, int feature, MeshFormat format, const std::string& name,
                          const std::string& units, const DracoOptions& draco) {
  if (format != MeshFormat::Ply && mesh.triangles.empty())
    return makeError(Errc::InvalidArgument, "feature \"" + name + "\" has no surface: " + extensionOf(format) +
                                                " cannot hold an empty mesh (" + path.string() + ")");
  switch (format) {
    case MeshFormat::Ply: return writeSurfacePly(path, mesh, feature, units);
    case MeshFormat::Drc: return writeDrc(path, mesh, draco);
    case MeshFormat::Obj: return writeObj(path, mesh, name, units);
    case MeshFormat::Stl: return writeStl(path, mesh, units);
    case MeshFormat::Vtp: return writeFeatureVtp(path, mesh, name, labelOfFeature(feature), units);
    case MeshFormat::Glb:
    case MeshFormat::SegVtm: break;
  }
  return makeError(Errc::InvalidArgument,
                   "writeSurface writes one feature; a scene (GLB, .seg.vtm) is not one (" + path.string() + ")");
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

// An OBJ with its colour in a material file beside it.
Result<void> stageObj(OutputStaging& staging, const fs::path& target, const CompactMesh& mesh, const std::string& name,
                      const ObjMaterial& material, const std::string& units) {
  SCANSURF_TRY(staging.stage(target.parent_path() / material.library, [&](const fs::path& p) { return writeMtl(p, material); }));
  return staging.stage(target, [&](const fs::path& p) { return writeObj(p, mesh, name, units, &material); });
}

// The per-feature files of one feature in the plan's directory.
Result<void> stageFeatureFiles(OutputStaging& staging, const OutputPlan& plan, const CompactMesh& mesh, int feature,
                               const std::string& name, const std::string& stem, const Rgb& color, const std::string& units,
                               const DracoOptions& draco, SurfaceOutputs& out) {
  for (MeshFormat format : plan.formats) {
    if (format == MeshFormat::Glb || format == MeshFormat::SegVtm) continue;
    if (format != MeshFormat::Ply && mesh.triangles.empty()) {
      out.warnings.push_back("feature \"" + name + "\" has no surface: no " + extensionOf(format) + " written for it");
      continue;
    }
    const fs::path target = plan.dir / (stem + extensionOf(format));
    if (format == MeshFormat::Obj) {
      SCANSURF_TRY(stageObj(staging, target, mesh, name, {stem + ".mtl", stem, color}, units));
      out.files[static_cast<std::size_t>(feature)].push_back(plan.dir / (stem + ".mtl"));
    } else {
      SCANSURF_TRY(
          staging.stage(target, [&](const fs::path& p) { return writeCompact(p, mesh, feature, format, name, units, draco); }));
    }
    out.files[static_cast<std::size_t>(feature)].push_back(target);
  }
  return {};
}

// 3D Slicer's closed-surface segmentation: one segment per feature with a surface (VTK drops
// empty blocks, so an empty feature is left out, with a warning), its .vtp files and the .vtm.
Result<void> stageSlicerSegmentation(OutputStaging& staging, const fs::path& vtm, const ContourSet& contours,
                                     const std::vector<CompactMesh>& meshes, SurfaceOutputs& out) {
  const std::vector<Rgb> colors = featureColors(contours);
  std::vector<std::string> blocks;
  for (std::size_t f = 0; f < meshes.size(); ++f) {
    const std::string& name = contours.features[f].name;
    if (meshes[f].triangles.empty()) {
      out.warnings.push_back("feature \"" + name + "\" has no surface: no segment for it in " + vtm.filename().string());
      continue;
    }
    const SlicerSegment segment{"Segment_" + std::to_string(f + 1), name, colors[f],
                                slicerTerminology(terminologyOf(contours.features[f].interpretedType)), &meshes[f]};
    const fs::path target = slicerSegmentPath(vtm, blocks.size());
    blocks.push_back(target.filename().string());
    SCANSURF_TRY(staging.stage(target, [&](const fs::path& p) { return writeSlicerSegmentVtp(p, segment); }));
    out.files[f].push_back(target);
    out.files[f].push_back(vtm);
  }
  return staging.stage(vtm, [&](const fs::path& p) { return writeSlicerSegmentationVtm(p, blocks); });
}

// Every feature's closed surface in one mesh, one after another.
CompactMesh mergedSurfaces(const std::vector<CompactMesh>& meshes) {
  CompactMesh merged;
  for (const CompactMesh& m : meshes) {
    const auto first = static_cast<std::uint32_t>(merged.vertexCount());
    merged.positions.insert(merged.positions.end(), m.positions.begin(), m.positions.end());
    for (std::uint32_t v : m.triangles) merged.triangles.push_back(first + v);
  }
  return merged;
}

// Every structure in one file (OutputPlan::meshFile).
Result<void> stageMeshFile(OutputStaging& staging, const fs::path& target, const ContourSet& contours, const Surfaces& surfaces,
                           const std::vector<CompactMesh>& meshes, const DracoOptions& draco, SurfaceOutputs& out) {
  SCANSURF_ASSIGN_OR_RETURN(const MeshFormat format, parseMeshFormat(target.extension().string()));
  const std::string& units = contours.units;
  const auto write = [&](const fs::path& p) -> Result<void> {
    if (format == MeshFormat::Ply) return writeMultiLabelPly(p, surfaces.mesh, units);
    if (format == MeshFormat::Vtp) return writeMultiLabelVtp(p, surfaces.mesh, units);
    const CompactMesh merged = mergedSurfaces(meshes);
    if (merged.triangles.empty())
      return makeError(Errc::InvalidArgument, "no feature has a surface: " + target.string() + " cannot hold an empty mesh");
    if (format == MeshFormat::Obj) return writeObj(p, merged, target.stem().string(), units);
    return writeCompact(p, merged, 0, format, target.stem().string(), units, draco);
  };
  SCANSURF_TRY(staging.stage(target, write));
  for (std::size_t f = 0; f < meshes.size(); ++f)
    if (!meshes[f].triangles.empty()) out.files[f].push_back(target);
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
  return writeCompact(path, mesh, feature, format, contours.features[static_cast<std::size_t>(feature)].name, contours.units,
                      draco);
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
// system, one that names the multi-label mesh's or the scene's files (the input's name), or one
// that differs from another only in case or in characters a file name cannot hold.
void warnAboutFileStem(const std::string& name, const std::string& stem, const std::string& sceneName,
                       std::vector<std::string>& warnings) {
  const std::string plain = sanitized(name);
  const auto same = [](const std::string& a, const std::string& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(),
                      [](unsigned char x, unsigned char y) { return std::tolower(x) == std::tolower(y); });
  };
  if (plain.size() > kMaxFileStem)
    warnings.push_back("feature \"" + name.substr(0, 40) + "...\": its name is too long for a file name; its files are " + stem +
                       ".* (the report keeps the whole name)");
  else if (stem != plain && (same(plain, "multilabel") || same(plain, sceneName)))
    warnings.push_back("feature \"" + name + "\": its name is that of the " +
                       (same(plain, "multilabel") ? std::string("multi-label mesh's files (multilabel.*)")
                                                  : "scene files, named after the input (" + sceneName + ".glb, .seg.vtm)") +
                       "; its files are " + stem + ".*");
  else if (stem != plain && plain.size() > sceneName.size() + 5 &&
           same(plain.substr(0, sceneName.size() + 5), sceneName + ".seg_"))
    warnings.push_back("feature \"" + name + "\": its name is that of a block of the Slicer segmentation (" + sceneName +
                       ".seg_N.vtp); its files are " + stem + ".*");
  else if (stem != plain && stem.rfind(plain + "_", 0) == 0)
    warnings.push_back("feature \"" + name +
                       "\": another feature's file name differs only in case or in characters a file name "
                       "cannot hold; its files are " +
                       stem + ".*");
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
  // The Slicer segmentation's blocks (slicerSegmentPath) are taken too: a feature named like
  // one gets another file name (with fileStem's warning) instead of a clash found after the build.
  if (!plan.dir.empty() && has(plan.formats, MeshFormat::SegVtm))
    for (std::size_t b = 0; b < featureCount; ++b)
      used.push_back(slicerSegmentPath(plan.dir / (plan.sceneName + ".seg.vtm"), b).stem().string());
  const std::vector<Rgb> colors = featureColors(contours);
  for (std::size_t f = 0; f < featureCount; ++f) {
    const std::string& name = contours.features[f].name;
    SCANSURF_ASSIGN_OR_RETURN(CompactMesh mesh, compactor.compact(surfaces.features[f]));
    if (!plan.dir.empty()) {
      const std::string stem = fileStem(name, used);
      warnAboutFileStem(name, stem, plan.sceneName, out.warnings);
      SCANSURF_TRY(
          stageFeatureFiles(staging, plan, mesh, static_cast<int>(f), name, stem, colors[f], contours.units, draco, out));
    }
    if (!scenes.empty() || has(plan.formats, MeshFormat::SegVtm) || !plan.meshFile.empty()) compact.push_back(std::move(mesh));
  }
  if (!plan.meshFile.empty()) SCANSURF_TRY(stageMeshFile(staging, plan.meshFile, contours, surfaces, compact, draco, out));
  if (!plan.dir.empty() && has(plan.formats, MeshFormat::SegVtm))
    SCANSURF_TRY(stageSlicerSegmentation(staging, plan.dir / (plan.sceneName + ".seg.vtm"), contours, compact, out));
  if (!plan.dir.empty() && has(plan.formats, MeshFormat::Ply) && plan.multilabel)
    SCANSURF_TRY(staging.stage(plan.dir / "multilabel.ply",
                               [&](const fs::path& p) { return writeMultiLabelPly(p, surfaces.mesh, contours.units); }));
  if (!plan.dir.empty() && has(plan.formats, MeshFormat::Vtp) && plan.multilabel)
    SCANSURF_TRY(staging.stage(plan.dir / "multilabel.vtp",
                               [&](const fs::path& p) { return writeMultiLabelVtp(p, surfaces.mesh, contours.units); }));
  const GlbOptions glb = glbOptions(plan.scene, draco, contours);
  const std::vector<float> opacity = scenes.empty() ? std::vector<float>{} : sceneOpacity(contours, plan.scene);
  for (const fs::path& target : scenes) {
    SCANSURF_TRY(
        staging.stage(target, [&](const fs::path& p) { return writeGlb(p, sceneFeatures(contours, compact, opacity), glb); }));
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
    SCANSURF_TRY(
        staging.stage(plan.labelVolume, [&](const fs::path& p) { return writeRunVolume(p, format, contours, *volumes, table); }));
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
