// scansurf: the engine, the one pipeline path behind build() and the stage calls
// (Lee et al., "Scanline Surfacing"; Nielson & Franke 1997).
#include "scansurf/engine.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>

#include "core/guard.h"
#include "core/memory.h"
#include "core/parallel.h"
#include "geometry/audit/surface_audit.h"
#include "geometry/contours/validate.h"
#include "geometry/extraction/assembly.h"
#include "geometry/extraction/edge_crossings.h"
#include "geometry/extraction/feature_surfaces.h"
#include "geometry/grid/content_tiles.h"
#include "geometry/grid/contour_layers.h"
#include "geometry/grid/coverage.h"
#include "geometry/grid/footprint.h"
#include "geometry/interpolation/interpolated_volume.h"
#include "geometry/interpolation/interpolation_plan.h"
#include "geometry/overlaps/overlap_analysis.h"
#include "geometry/overlaps/overlap_split.h"
#include "geometry/overlaps/own_slabs.h"
#include "geometry/remesh/remesh_mesh.h"
#include "geometry/shape/snapping.h"
#include "geometry/shape/triangle_shape.h"
#include "geometry/shape/volume_restoration.h"
#include "geometry/simplification/simplify_mesh.h"
#include "geometry/smoothing/smooth_mesh.h"
#include "gpu/commands.h"
#include "gpu/context.h"
#include "gpu/resources.h"
#include "passes/classification.h"
#include "passes/interpolator.h"
#include "passes/preview_renderer.h"
#include "passes/scan_conversion.h"
#include "run_checks.h"
#include "scansurf/input.h"
#include "scansurf/vulkan_interop.h"
#include "surface_layers.h"

namespace scansurf {

// The device and the passes made on it (each on first use): the engine's whole state. The
// getters name the pass they give (made when first asked for).
struct EngineState {
  std::unique_ptr<gpu::Context> context;
  std::unique_ptr<passes::ScanConverter> scanConverter;  // created on first use
  std::unique_ptr<passes::Classifier> classifier;
  std::unique_ptr<passes::Interpolator> interpolator;
  std::unique_ptr<passes::PreviewRenderer> previewRenderer;

  Result<passes::ScanConverter*> scanConverterPass() {
    if (!scanConverter) {
      SCANSURF_ASSIGN_OR_RETURN(scanConverter, passes::ScanConverter::create(*context));
    }
    return scanConverter.get();
  }
  Result<passes::Interpolator*> interpolatorPass() {
    if (!interpolator) {
      SCANSURF_ASSIGN_OR_RETURN(interpolator, passes::Interpolator::create(*context));
    }
    return interpolator.get();
  }
  Result<passes::Classifier*> classifierPass() {
    if (!classifier) {
      SCANSURF_ASSIGN_OR_RETURN(classifier, passes::Classifier::create(*context));
    }
    return classifier.get();
  }
  Result<passes::PreviewRenderer*> previewPass() {
    if (!previewRenderer) {
      SCANSURF_ASSIGN_OR_RETURN(previewRenderer, passes::PreviewRenderer::create(*context));
    }
    return previewRenderer.get();
  }
};

struct Engine::Impl : EngineState {};

namespace {

// Times each stage into `out` and reports it through options.onStageEvent: begin
// announces a stage, lap ends it (stages follow each other: a stage's time runs from the
// previous lap).
class StageClock {
 public:
  StageClock(std::vector<StageTime>& out, const BuildOptions& options)
      : out_(out), options_(options), start_(std::chrono::steady_clock::now()) {}
  void begin(const char* stage) {
    if (options_.onStageEvent) options_.onStageEvent({stage, false, 0, layer_, layers_});
  }
  void lap(const char* stage) {
    const auto now = std::chrono::steady_clock::now();
    out_.push_back({stage, std::chrono::duration<double>(now - start_).count()});
    if (options_.onStageEvent) options_.onStageEvent({stage, true, out_.back().seconds, layer_, layers_});
    start_ = now;
  }
  void setLayer(int layer, int layers) { layer_ = layer, layers_ = layers; }

 private:
  std::vector<StageTime>& out_;
  const BuildOptions& options_;
  std::chrono::steady_clock::time_point start_;
  int layer_ = -1, layers_ = 1;
};

Result<void> checkNesting(const Nesting& nesting) {
  if (nesting.parent.empty())
    return makeError(Errc::InvalidArgument, "extract: the nesting names no feature (Nesting::parent is empty)");
  if (nesting.parent.size() > static_cast<std::size_t>(kMaxFeatures))
    return makeError(Errc::InvalidArgument, "extract: more than " + std::to_string(kMaxFeatures) + " features");
  return {};
}

// What the surfaces are held to beyond the labels: the medial split of incidental pairs, and
// each feature's volume (slabVolumes), which smoothing restores (volume_restoration.h).
struct SurfaceTargets {
  const MedialCrossings* medial = nullptr;
  std::vector<double> volumes;
};

// Per feature, the slab rule's volume of its contours less what it gave up to incidental
// neighbours: what its surface should enclose.
std::vector<double> slabVolumes(const OverlapReport& overlaps) {
  std::vector<double> out;
  for (const FeatureVolumes& f : overlaps.features) out.push_back(f.contour);
  for (const SharedVolume& s : overlaps.shared) {
    out[static_cast<std::size_t>(s.a)] -= s.givenUpByA;
    out[static_cast<std::size_t>(s.b)] -= s.givenUpByB;
  }
  return out;
}

// The stage calls' targets: each feature's slab volume on the grid of its planes (no medial split).
SurfaceTargets slabTargets(const ContourSet* contours, const Grid& grid) {
  SurfaceTargets targets;
  if (contours)
    for (const Feature& f : contours->features) targets.volumes.push_back(slabVolume(f, grid));
  return targets;
}

// What every stage of one surfacing pass reads: the engine, the contours (null for a bare
// label volume), the nesting, the options, the clock and what the surfaces are held to.
struct SurfacingRun {
  EngineState& impl;
  const ContourSet* contours;
  const Nesting& nesting;
  const BuildOptions& options;
  StageClock& clock;
  SurfaceTargets targets;
};

// Classification records to feature surfaces: assembly, smoothing, triangle shape,
// simplification, remeshing, feature extraction.
Surfaces surfacesFromCells(const SurfacingRun& run, std::vector<CellCase> cells, const Grid& grid,
                           std::span<const std::uint16_t> clearance = {}) {
  const BuildOptions& options = run.options;
  const ContourSet* contours = run.contours;
  const Nesting& nesting = run.nesting;
  const SurfaceTargets& targets = run.targets;
  StageClock& clock = run.clock;
  Surfaces surfaces;
  surfaces.convention = options.convention;
  clock.begin("assembly");
  surfaces.mesh = assembleMesh(grid, cells, options.threads);
  cells = {};
  clock.lap("assembly");
  const std::vector<bool> planes = contourLayers(grid, contours);
  if (options.smoothing.enabled) {
    clock.begin("smoothing");
    SmoothingReport smoothed =
        smoothMesh(surfaces.mesh, grid, contours, options.smoothing, options.threads, clearance, targets.medial);
    clock.lap("smoothing");
    clock.begin("triangle shape");
    // Simplification, when asked, starts from the fans' triangles: it merges the vertices the
    // boxes' rims keep (docs/method.md, "Simplification").
    const double snap = snapFractionFor(grid, planes, options.smoothing.snap);
    const ShapedTriangles shaped = shapeTriangles(surfaces.mesh, grid, snap, smoothed.onSheet, true, options.threads);
    surfaces.triangleShape = shaped.report;
    if (options.smoothing.keepVolumes && options.convention == SurfaceConvention::Enclosing && !targets.volumes.empty())
      restoreVolumes(surfaces.mesh, grid, nesting, targets.volumes, smoothed.onSheet, planes, options.smoothing.minAngle,
                     options.threads, &shaped.disks, smoothed.betweenPlanes);
    clock.lap("triangle shape");
  }
  if (options.simplification.enabled) {
    clock.begin("simplification");
    surfaces.simplification = simplifyMesh(surfaces.mesh, grid, planes, options.simplification, options.threads);
    clock.lap("simplification");
  }
  if (options.remeshing.enabled) {
    clock.begin("remeshing");
    surfaces.remeshing = remeshMesh(surfaces.mesh, grid, contours, nesting, options.remeshing, options.threads);
    clock.lap("remeshing");
  }
  clock.begin("feature surfaces");
  surfaces.features = extractFeatureSurfaces(surfaces.mesh, static_cast<int>(nesting.parent.size()), nesting, options.convention);
  clock.lap("feature surfaces");
  return surfaces;
}

// A long gap in a feature's planes is said: capped on each side, or (no layer of the grid
// between the planes to cap on) bridged as before.
void warnAboutLongGaps(const ContourSet& contours, const Grid& grid, double gapFactor, std::vector<std::string>& warnings) {
  const auto text = [](double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.6g", v);
    return std::string(buffer);
  };
  for (const LongGap& g : longGaps(contours, grid, gapFactor))
    warnings.push_back(describeFeature(contours, g.feature) + ": its planes z=" + text(g.below) + " and z=" + text(g.above) +
                       " are " + text(g.above - g.below) + " apart, more than " + text(gapFactor) +
                       " times its usual spacing of " + text(g.usual) +
                       (g.capped ? ": each side is capped on its own, not bridged"
                                 : ": no other plane lies between them, so the slab rule bridges them") +
                       " (GridOptions::gapFactor)");
}

// A feature without a surface deserves a word: it has no slices, is too small for the grid,
// or (partition convention) features of higher priority cover all of it.
void warnAboutEmptySurfaces(const ContourSet& contours, const Surfaces& surfaces, std::vector<std::string>& warnings) {
  for (std::size_t f = 0; f < surfaces.features.size(); ++f)
    if (surfaces.features[f].triangles.empty())
      warnings.push_back(describeFeature(contours, static_cast<int>(f)) +
                         ": no surface (no slices, smaller than a pixel, or covered by features of higher priority)");
}

// Classification and the CPU stages for one label volume, on the host (LabelVolume) or
// already on the device (DeviceLabelVolume).
template <typename Volume>
Result<Surfaces> surfacesOfVolume(const SurfacingRun& run, const Volume& volume) {
  run.clock.begin("classification");
  SCANSURF_ASSIGN_OR_RETURN(passes::Classifier * classifier, run.impl.classifierPass());
  SCANSURF_ASSIGN_OR_RETURN(std::vector<CellCase> cells, classifier->run(volume));
  run.clock.lap("classification");
  return surfacesFromCells(run, std::move(cells), volume.grid);
}

// Classification of labels in one of scansurf's own device buffers, bound in place; the buffer
// is released once classified: the CPU stages' peak memory need not hold it.
// upperIsData: 32-bit label | clearance words (interpolation).
// content: where the labels can be other than background (ContentTiles; empty: anywhere).
Result<std::vector<CellCase>> classifyOwnBuffer(EngineState& impl, gpu::Buffer buffer, const Grid& grid, std::uint32_t bits,
                                                bool upperIsData, const ContentTiles& content, StageClock& clock) {
  clock.begin("classification");
  SCANSURF_ASSIGN_OR_RETURN(passes::Classifier * classifier, impl.classifierPass());
  SCANSURF_ASSIGN_OR_RETURN(std::vector<CellCase> cells, classifier->runInPlace(DeviceLabelVolume{buffer.handle(), 0, bits, grid},
                                                                                buffer.size(), upperIsData, &content));
  buffer = gpu::Buffer{};
  clock.lap("classification");
  return cells;
}

// A layer's part of the whole grid's interpolation factors (interpolationFactors): every layer
// is interpolated alike.
std::vector<int> factorsOf(const Grid& planes, const Grid& grid, const std::vector<int>& gridFactors) {
  const auto first = std::find(grid.layerZ.begin(), grid.layerZ.end(), planes.layerZ.front()) - grid.layerZ.begin();
  return {gridFactors.begin() + first, gridFactors.begin() + first + planes.nz - 1};
}

// containers[label]: the label's feature contains another.
std::vector<bool> containerLabels(const Nesting& nesting) {
  std::vector<bool> containers(nesting.parent.size() + 1, false);
  for (int parent : nesting.parent)
    if (parent >= 0) containers[labelOfFeature(parent)] = true;
  return containers;
}

// Surfaces of contour planes with interpolated layers between them. The planes come to the
// host for their edge crossings (a CPU stage), but the interpolation passes copy them from the
// device labels when there are some; the interpolated labels stay on the device for
// classification (as label | clearance words), and the host gets the clearances, which
// smoothing needs.
Result<Surfaces> interpolatedSurfaces(const SurfacingRun& run, const LabelVolume& planes,
                                      std::optional<passes::ScanConverter::DeviceLabels> device,
                                      const std::vector<int>& factors) {
  EngineState& impl = run.impl;
  const ContourSet* contours = run.contours;
  const BuildOptions& options = run.options;
  StageClock& clock = run.clock;
  clock.begin("interpolation");
  SCANSURF_ASSIGN_OR_RETURN(passes::Interpolator * interpolator, impl.interpolatorPass());
  // Without the contours, every boundary crosses its grid edge in the middle.
  const std::vector<std::uint16_t> crossings =
      contours ? planeEdgeCrossings(planes, *contours, options.threads, run.targets.medial)
               : std::vector<std::uint16_t>(planes.labels.size(), static_cast<std::uint16_t>(kMidEdge | (kMidEdge << 8)));
  const Grid fineGrid = interpolatedGrid(planes.grid, factors);
  // Labels scan converted here from the contours lie near them (not so a caller's own volume).
  const ContentTiles content = device && contours
                                   ? interpolatedContentTiles(contentTilesOf(planes.grid, *contours), factors, kWindowMargin + 1)
                                   : ContentTiles{};
  SCANSURF_ASSIGN_OR_RETURN(
      gpu::Buffer words,
      gpu::Buffer::create(*impl.context, fineGrid.voxelCount() * 4,
                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::MemoryDomain::Device));
  SCANSURF_ASSIGN_OR_RETURN(InterpolatedVolume fine,
                            interpolator->run(planes, crossings, factors, options.interpolation.caps, options.threads,
                                              {device ? &device->buffer : nullptr, &words}, containerLabels(run.nesting)));
  device.reset();
  clock.lap("interpolation");
  SCANSURF_ASSIGN_OR_RETURN(std::vector<CellCase> cells,
                            classifyOwnBuffer(impl, std::move(words), fineGrid, 32, true, content, clock));
  return surfacesFromCells(run, std::move(cells), fineGrid, fine.clearance);
}

// Surfaces of a scan-converted volume of contour planes: interpolated first when asked, else
// classified from the device labels when there are some (bound in place, no upload).
Result<Surfaces> surfacesOfPlanes(const SurfacingRun& run, const LabelVolume& planes,
                                  std::optional<passes::ScanConverter::DeviceLabels> device, const std::vector<int>& factors) {
  if (interpolates(factors)) return interpolatedSurfaces(run, planes, std::move(device), factors);
  if (!device) return surfacesOfVolume(run, planes);
  const ContentTiles content = run.contours ? contentTilesOf(device->grid, *run.contours) : ContentTiles{};
  SCANSURF_ASSIGN_OR_RETURN(std::vector<CellCase> cells,
                            classifyOwnBuffer(run.impl, std::move(device->buffer), device->grid, 16, false, content, run.clock));
  return surfacesFromCells(run, std::move(cells), planes.grid);
}

// Scan conversion for the surfaces: the labels stay on the device for the next GPU pass, and
// come to the host too when `toHost` or when interpolating (the edge crossings of the planes
// are a CPU stage). `planes` always gets the grid.
Result<passes::ScanConverter::DeviceLabels> scanPlanes(passes::ScanConverter& scanner, const ContourSet& contours,
                                                       const Grid& grid, const std::vector<int>& order, bool interpolating,
                                                       bool toHost, LabelVolume& planes) {
  planes.grid = grid;
  return scanner.runOnDevice(contours, grid, order, toHost || interpolating ? &planes : nullptr);
}

// Writes the medial split's labels into the device's labels in place: one 2-byte copy region
// per voxel from a small upload buffer (vkCmdCopyBuffer asks no alignment), so the labels need
// not come to the host and go back.
Result<void> patchDeviceLabels(const gpu::Context& ctx, const gpu::Buffer& labels,
                               const std::vector<std::pair<std::size_t, Label>>& patch) {
  SCANSURF_ASSIGN_OR_RETURN(gpu::Buffer values, gpu::Buffer::create(ctx, patch.size() * sizeof(Label),
                                                                    VK_BUFFER_USAGE_TRANSFER_SRC_BIT, gpu::MemoryDomain::Upload));
  std::vector<VkBufferCopy> regions;
  regions.reserve(patch.size());
  auto* out = static_cast<Label*>(values.mapped());
  for (std::size_t p = 0; p < patch.size(); ++p) {
    out[p] = patch[p].second;
    regions.push_back({p * sizeof(Label), patch[p].first * sizeof(Label), sizeof(Label)});
  }
  SCANSURF_ASSIGN_OR_RETURN(gpu::OneShotCommands commands, gpu::OneShotCommands::begin(ctx));
  vkCmdCopyBuffer(commands.cmd(), values.handle(), labels.handle(), static_cast<std::uint32_t>(regions.size()), regions.data());
  return commands.submitAndWait();
}

// One layer's scan conversion: its contours on its grid (part of the whole grid), in nesting
// order, and the medial split to write in; its labels go to the host when toHost or when
// interpolating.
struct LayerScan {
  const ContourSet& contours;
  const Grid& wholeGrid;
  const Grid& grid;
  const std::vector<int>& order;
  bool interpolating = false;
  bool toHost = false;
  const std::vector<LabelOverride>& split;
};

// Scan conversion of one layer with the medial split of its incidental overlaps written in
// (overlap_split.h), on the device and in the host copy when there is one.
Result<passes::ScanConverter::DeviceLabels> scanAndSplit(EngineState& impl, const LayerScan& scan, LabelVolume& planes) {
  const Grid& grid = scan.grid;
  SCANSURF_ASSIGN_OR_RETURN(passes::ScanConverter * scanner, impl.scanConverterPass());
  SCANSURF_ASSIGN_OR_RETURN(auto device,
                            scanPlanes(*scanner, scan.contours, grid, scan.order, scan.interpolating, scan.toHost, planes));
  if (scan.split.empty()) return device;
  const std::vector<std::pair<std::size_t, Label>> patch = overridesOnGrid(grid, scan.wholeGrid, scan.split);
  if (patch.empty()) return device;
  SCANSURF_TRY(patchDeviceLabels(*impl.context, device.buffer, patch));
  if (!planes.labels.empty())
    for (const auto& [index, label] : patch) planes.labels[index] = label;
  return device;
}

InterpolationSummary summarizeInterpolation(const Grid& grid, const std::vector<int>& factors, CapShape caps) {
  InterpolationSummary s;
  s.planeLayers = grid.nz;
  s.surfacedLayers = fineLayerOfPlane(factors).back() + 1;
  if (!factors.empty()) {
    s.minFactor = *std::min_element(factors.begin(), factors.end());
    s.maxFactor = *std::max_element(factors.begin(), factors.end());
  }
  s.caps = caps;
  return s;
}

// What the build knows once the overlaps are analysed: the contours (own slabs filled), the
// grid and its interpolation factors, each feature's region, each layer's medial split.
struct AnalysedInput {
  const ContourSet& contours;
  const Grid& grid;
  const std::vector<int>& factors;
  const std::vector<FeatureRegion>& regions;
  const std::vector<std::vector<LabelOverride>>& split;
  const MedialCrossings& medial;
};

// Layers mode with partial overlaps: each layer scan converted and surfaced on its own.
Result<void> buildLayers(EngineState& impl, const AnalysedInput& in, const BuildOptions& options, BuildResult& out,
                         StageClock& clock) {
  const ContourSet& contours = in.contours;
  const Grid& grid = in.grid;
  out.surfaces.convention = options.convention;
  out.surfaces.features.resize(contours.features.size());
  for (std::size_t f = 0; f < contours.features.size(); ++f) out.surfaces.features[f].feature = static_cast<int>(f);
  for (int layer = 0; layer < out.overlaps.layers; ++layer) {
    clock.setLayer(layer, out.overlaps.layers);
    clock.begin("scan conversion");
    const ContourSet subset = layerContours(contours, out.overlaps, layer);
    const Grid sub = layerGrid(grid, in.regions, out.overlaps, layer);
    const std::vector<int> subFactors = factorsOf(sub, grid, in.factors);
    LabelVolume volume;
    const LayerScan scan{subset,
                         grid,
                         sub,
                         out.nesting.order,
                         interpolates(subFactors),
                         layer == 0 && options.keepLabelVolume,
                         in.split[static_cast<std::size_t>(layer)]};
    SCANSURF_ASSIGN_OR_RETURN(auto device, scanAndSplit(impl, scan, volume));
    clock.lap("scan conversion");
    const SurfacingRun run{impl, &subset, out.nesting, options, clock, {&in.medial, slabVolumes(out.overlaps)}};
    SCANSURF_ASSIGN_OR_RETURN(Surfaces surfaces, surfacesOfPlanes(run, volume, std::move(device), subFactors));
    appendLayer(out.surfaces, std::move(surfaces), out.overlaps, layer);
    if (layer == 0) out.volume = std::move(volume);
  }
  clock.setLayer(-1, 1);
  return {};
}

// Partition mode: a feature that partly overlaps one of higher priority loses the shared voxels.
void warnAboutLosses(const ContourSet& contours, const OverlapReport& report, std::vector<std::string>& warnings) {
  for (const VolumeLoss& l : report.losses) {
    const double contour = report.features[static_cast<std::size_t>(l.feature)].contour;
    if (l.nested || contour <= 0 || l.volume <= 0.01 * contour) continue;
    const std::string to = l.to >= 0 ? "\"" + contours.features[static_cast<std::size_t>(l.to)].name + "\"" : "background";
    warnings.push_back("feature \"" + contours.features[static_cast<std::size_t>(l.feature)].name + "\" lost " +
                       std::to_string(static_cast<int>(std::lround(100.0 * l.volume / contour))) +
                       " % of its contour volume to " + to + " (overlaps as a partition; as layers, the default, it keeps them)");
  }
}

// Every vertex is finite before anything is written; anything else is a bug of ours.
Result<void> checkFinite(const MultiLabelMesh& mesh) {
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
    if (!std::isfinite(mesh.positions[i]))
      return makeError(Errc::Internal, "vertex " + std::to_string(i / 3) + " of the surfaces is not finite");
  return {};
}

// A voxel of the grid of contour planes, its layers' mean spacing deep: differences in volume
// under it are the grid's, never a finding.
double planeVoxelVolume(const Grid& grid) {
  const double depth = grid.nz > 1 ? (grid.layerZ.back() - grid.layerZ.front()) / (grid.nz - 1) : 0;
  return grid.spacingX * grid.spacingY * depth;
}

// The run's check of its own surfaces (audit.h): its findings become warnings; a defect fails
// the build unless the options keep it. Topology is held to the contours where each feature
// encloses its own region (Layers, Enclosing); volumes where smoothing restores them.
Result<void> auditBuild(const ContourSet& contours, const Grid& grid, std::span<const FeatureRegion> regions,
                        const BuildOptions& options, BuildResult& out) {
  const bool own = options.convention == SurfaceConvention::Enclosing && options.overlaps == OverlapMode::Layers;
  const bool volumes = own && options.smoothing.enabled && options.smoothing.keepVolumes;
  const AuditInputs in{contours,
                       out.surfaces,
                       own ? regions : std::span<const FeatureRegion>{},
                       volumes ? slabVolumes(out.overlaps) : std::vector<double>{},
                       options.audit.volumeTolerance,
                       planeVoxelVolume(grid),
                       options.threads};
  out.audit = auditSurfaces(in);
  std::string defects;
  for (const AuditFinding& f : out.audit.findings)
    if (f.defect && !options.audit.keepDefective)
      defects += (defects.empty() ? "" : "; ") + f.message;
    else
      out.warnings.push_back(f.message);
  if (defects.empty()) return {};
  return makeError(Errc::DefectiveSurface,
                   defects + "; nothing is kept (BuildOptions::audit.keepDefective keeps a defective surface)");
}

// One entry per stage name, the times of every layer added up, in first-seen order.
void mergeStageTimes(std::vector<StageTime>& timings) {
  std::vector<StageTime> merged;
  for (const StageTime& t : timings) {
    auto it = std::find_if(merged.begin(), merged.end(), [&](const StageTime& m) { return m.stage == t.stage; });
    if (it == merged.end())
      merged.push_back(t);
    else
      it->seconds += t.seconds;
  }
  timings = std::move(merged);
}

// Stage 2's frame for the stage calls: errors guarded, the nesting checked, the stages timed.
template <typename Extract>
Result<Surfaces> extractFrom(const Grid& grid, const Nesting& nesting, const BuildOptions& options, const Extract& extract) {
  return guarded("surface extraction on " + describeGrid(grid), [&]() -> Result<Surfaces> {
    SCANSURF_TRY(checkOptions(options));
    SCANSURF_TRY(checkNesting(nesting));
    std::vector<StageTime> timings;
    StageClock clock(timings, options);
    return extract(clock);
  });
}

const std::vector<LabelOverride> kNoSplit;

// The overlap analysis with its verdicts; in Layers mode also the medial split of the
// incidental pairs (per surface layer) and what each side gave up. Partition mode keeps one layer.
OverlapReport overlapAnalysis(const ContourSet& contours, const Grid& grid, const Nesting& nesting,
                              const std::vector<FeatureRegion>& regions, const BuildOptions& options,
                              std::vector<std::vector<LabelOverride>>& split) {
  OverlapReport report = analyzeOverlaps(contours, grid, nesting, regions, options.overlapTolerance);
  report.mode = options.overlaps;
  if (options.overlaps == OverlapMode::Partition) {
    for (FeatureVolumes& f : report.features) f.layer = 0;
    report.layers = 1;
    return report;
  }
  split = splitIncidentalOverlaps(contours, grid, nesting, regions, report);
  return report;
}

// A validated copy of contours not yet validated (readContours and validateContours set
// planeTolerance), so that an application's contours made in memory meet the same checks;
// nothing when they are validated already: the caller's own are used.
Result<std::optional<ContourSet>> validatedCopyIfNeeded(const ContourSet& contours) {
  if (contours.planeTolerance > 0) return std::optional<ContourSet>{};
  std::optional<ContourSet> copy = contours;
  SCANSURF_TRY(validateContours(*copy));
  return copy;
}

}  // namespace

Engine::Engine(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Engine::Engine(Engine&&) noexcept = default;
Engine& Engine::operator=(Engine&&) noexcept = default;
Engine::~Engine() = default;

Result<std::vector<DeviceListing>> listDevices() {
  return guarded("listing the Vulkan devices", [] { return gpu::Context::listDevices(); });
}

Result<Engine> Engine::create(const EngineOptions& options) {
  return guarded("creating the Vulkan device", [&]() -> Result<Engine> {
    auto impl = std::make_unique<Impl>();
    SCANSURF_ASSIGN_OR_RETURN(impl->context, gpu::Context::create(options));
    return Engine(std::move(impl));
  });
}

Result<Engine> Engine::adopt(const ExternalVulkan& vulkan, const EngineOptions& options) {
  return guarded("adopting the application's Vulkan device", [&]() -> Result<Engine> {
    auto impl = std::make_unique<Impl>();
    SCANSURF_ASSIGN_OR_RETURN(impl->context, gpu::Context::adopt(vulkan, options));
    return Engine(std::move(impl));
  });
}

const DeviceInfo& Engine::device() const { return impl_->context->info(); }
std::uint64_t Engine::validationMessageCount() const { return impl_->context->validationMessageCount(); }

Result<LabelVolume> Engine::scanConvert(const ContourSet& contours, const Nesting& nesting, const Grid& grid,
                                        const BuildOptions& options) {
  return guarded("scan conversion on " + describeGrid(grid), [&]() -> Result<LabelVolume> {
    SCANSURF_TRY(checkOptions(options));
    SCANSURF_ASSIGN_OR_RETURN(passes::ScanConverter * scanner, impl_->scanConverterPass());
    return scanner->run(contours, grid, nesting.order);
  });
}

Result<Surfaces> Engine::extract(const LabelVolume& volume, const Nesting& nesting, const BuildOptions& options,
                                 const ContourSet* contours) {
  return extractFrom(volume.grid, nesting, options, [&](StageClock& clock) {
    const SurfacingRun run{*impl_, contours, nesting, options, clock, slabTargets(contours, volume.grid)};
    return surfacesOfPlanes(run, volume, std::nullopt, interpolationFactors(volume.grid, options.interpolation));
  });
}

Result<Surfaces> Engine::extract(const DeviceLabelVolume& volume, const Nesting& nesting, const BuildOptions& options,
                                 const ContourSet* contours) {
  return extractFrom(volume.grid, nesting, options, [&](StageClock& clock) {
    const SurfacingRun run{*impl_, contours, nesting, options, clock, slabTargets(contours, volume.grid)};
    return surfacesOfVolume(run, volume);
  });
}

Result<PreviewImage> Engine::renderPreview(const Surfaces& surfaces, const PreviewOptions& options) {
  return guarded("rendering the preview", [&]() -> Result<PreviewImage> {
    SCANSURF_ASSIGN_OR_RETURN(passes::PreviewRenderer * renderer, impl_->previewPass());
    return renderer->render(surfaces, options);
  });
}

Result<BuildResult> Engine::build(const ContourSet& givenContours, const BuildOptions& options) {
  return guarded("building the surfaces of " + givenContours.source, [&]() -> Result<BuildResult> {
    SCANSURF_TRY(checkOptions(options));
    SCANSURF_ASSIGN_OR_RETURN(const std::optional<ContourSet> copy, validatedCopyIfNeeded(givenContours));
    const ContourSet& input = copy ? *copy : givenContours;
    BuildResult out;
    StageClock clock(out.timings, options);
    clock.begin("grid");
    // The grid and the budget first: a run that cannot fit is refused before any real work.
    SCANSURF_ASSIGN_OR_RETURN(const Grid grid, makeGrid(input, options.grid));
    const std::vector<int> factors = interpolationFactors(grid, options.interpolation);
    out.interpolation = summarizeInterpolation(grid, factors, options.interpolation.caps);
    SCANSURF_TRY(checkEdgeLength(options.remeshing, grid));
    SCANSURF_TRY(checkMemoryBudget(input, grid, out.interpolation.surfacedLayers, options, impl_->context->info(), out));
    out.warnings = findUncoveredContours(input, grid);
    // Every feature holds its own slabs on the other features' planes (own_slabs.h).
    out.gapFactor = options.grid.gapFactor;
    warnAboutLongGaps(input, grid, options.grid.gapFactor, out.warnings);
    const std::optional<ContourSet> filled = withOwnSlabs(input, grid, options.grid.gapFactor);
    const ContourSet& contours = filled ? *filled : input;
    clock.lap("grid");
    clock.begin("nesting");
    out.nesting = computeNesting(contours, options.grid.sliceTolerance);
    clock.lap("nesting");
    clock.begin("overlap analysis");
    SCANSURF_ASSIGN_OR_RETURN(passes::ScanConverter * scanner, impl_->scanConverterPass());
    out.subPixelBits = scanner->subPixelBits();
    out.threads = options.threads > 0 ? options.threads : defaultThreadCount();
    const std::vector<FeatureRegion> regions = rasterizeFeatures(contours, grid, out.subPixelBits, options.threads);
    std::vector<std::vector<LabelOverride>> split;
    out.overlaps = overlapAnalysis(contours, grid, out.nesting, regions, options, split);
    // The partition mode gives shared voxels by priority: its interfaces stay as they were.
    const MedialCrossings medial =
        options.overlaps == OverlapMode::Layers ? MedialCrossings(contours, grid, out.overlaps) : MedialCrossings();
    clock.lap("overlap analysis");
    if (options.overlaps == OverlapMode::Partition || out.overlaps.layers == 1) {
      clock.begin("scan conversion");
      const bool toHost = options.keepLabelVolume || options.overlaps == OverlapMode::Partition;  // losses need them
      const LayerScan scan{
          contours, grid, grid, out.nesting.order, interpolates(factors), toHost, split.empty() ? kNoSplit : split[0]};
      SCANSURF_ASSIGN_OR_RETURN(auto device, scanAndSplit(*impl_, scan, out.volume));
      clock.lap("scan conversion");
      const SurfacingRun run{*impl_, &contours, out.nesting, options, clock, {&medial, slabVolumes(out.overlaps)}};
      SCANSURF_ASSIGN_OR_RETURN(out.surfaces, surfacesOfPlanes(run, out.volume, std::move(device), factors));
      if (options.overlaps == OverlapMode::Partition) {
        out.overlaps.losses = volumeLosses(regions, out.volume, out.nesting);
        warnAboutLosses(contours, out.overlaps, out.warnings);
      }
    } else {
      SCANSURF_TRY(buildLayers(*impl_, {contours, grid, factors, regions, split, medial}, options, out, clock));
    }
    warnAboutEmptySurfaces(contours, out.surfaces, out.warnings);
    SCANSURF_TRY(checkFinite(out.surfaces.mesh));
    clock.begin("audit");
    SCANSURF_TRY(auditBuild(contours, grid, regions, options, out));
    clock.lap("audit");
    mergeStageTimes(out.timings);
    return out;
  });
}

Result<OverlapReport> Engine::analyzeOverlaps(const ContourSet& givenContours, const BuildOptions& options) {
  return guarded("analyzing the overlaps of " + givenContours.source, [&]() -> Result<OverlapReport> {
    SCANSURF_TRY(checkOptions(options));
    SCANSURF_ASSIGN_OR_RETURN(const std::optional<ContourSet> copy, validatedCopyIfNeeded(givenContours));
    const ContourSet& input = copy ? *copy : givenContours;
    SCANSURF_ASSIGN_OR_RETURN(const Grid grid, makeGrid(input, options.grid));
    const std::optional<ContourSet> filled = withOwnSlabs(input, grid, options.grid.gapFactor);
    const ContourSet& contours = filled ? *filled : input;
    const Nesting nesting = computeNesting(contours, options.grid.sliceTolerance);
    SCANSURF_ASSIGN_OR_RETURN(passes::ScanConverter * scanner, impl_->scanConverterPass());
    const std::vector<FeatureRegion> regions = rasterizeFeatures(contours, grid, scanner->subPixelBits(), options.threads);
    std::vector<std::vector<LabelOverride>> split;
    return overlapAnalysis(contours, grid, nesting, regions, options, split);
  });
}

}  // namespace scansurf
