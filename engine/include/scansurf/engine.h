// scansurf: the engine. Scan converts contour sets on a Vulkan device and extracts separating
// surfaces (Lee et al., "Scanline Surfacing"; Nielson & Franke 1997).
//
//   auto engine = scansurf::Engine::create({});
//   auto built = engine->build(contours, {});      // nesting, grid, scan conversion, surfaces
//
// The same, stage by stage (exactly what build() gives, smoothing included, when no features
// partly overlap and every feature is drawn on every plane between its first and last; with
// partial overlaps build() runs the stages once per layer):
//   auto nesting = scansurf::computeNesting(contours, options.grid.sliceTolerance);
//   auto grid = scansurf::makeGrid(contours, options.grid);
//   auto volume = engine->scanConvert(contours, nesting, *grid, options);
//   auto surfaces = engine->extract(*volume, nesting, options, &contours);
//
// Threads: an Engine is used by one thread at a time (calls on one Engine are not
// synchronized); distinct Engines may run concurrently, also on one borrowed device as long
// as the application gives each its own queue. Free functions are thread-safe.
// Errors: every call returns Result<T>; nothing throws across this API.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "scansurf/audit.h"
#include "scansurf/build_result.h"
#include "scansurf/contours.h"
#include "scansurf/device.h"
#include "scansurf/grid.h"
#include "scansurf/interpolation.h"
#include "scansurf/label_volume.h"
#include "scansurf/nesting.h"
#include "scansurf/overlaps.h"
#include "scansurf/preview.h"
#include "scansurf/remesh.h"
#include "scansurf/result.h"
#include "scansurf/simplification.h"
#include "scansurf/smoothing.h"
#include "scansurf/surfaces.h"

namespace scansurf {

struct ExternalVulkan;     // scansurf/vulkan_interop.h
struct DeviceLabelVolume;  // scansurf/vulkan_interop.h

// Everything that shapes a run, for build() and for each stage call alike. An option out of
// its range is refused (Errc::InvalidArgument, naming it), never clamped.
struct BuildOptions {
  // The voxel grid (makeGrid); grid.sliceTolerance also decides which slices are one plane in
  // nesting, scan conversion and smoothing. When grid sets no voxel size, counts or reference,
  // the contour set's own reference lattice (ContourSet::reference, e.g. its CT) is used.
  GridOptions grid;
  SurfaceConvention convention = SurfaceConvention::Enclosing;
  // Layers (default): partly overlapping features are surfaced in separate layers, each
  // feature enclosing its own contours' region. Partition: one label per voxel, as the seed.
  OverlapMode overlaps = OverlapMode::Layers;
  // Layers mode: which partial overlaps are incidental slivers between neighbours (one layer,
  // the shared voxels split between them) rather than overlaps by design. build() refuses a
  // negative or non-finite depth and a percentage outside [0, 100] (Errc::InvalidArgument).
  OverlapTolerance overlapTolerance;
  int threads = 0;                           // CPU threads for the CPU stages; 0 = all (or SCANSURF_THREADS)
  static constexpr int kMostThreads = 1024;  // build() refuses more; more than the cores only costs
  // Host memory build() may use, in bytes; 0 = what the machine has available when the build
  // starts (MemAvailable, lowered by a cgroup limit and rlimits). Before anything large is
  // allocated, build() estimates the label volume, mesh and device needs from the contours and
  // the grid, and refuses with Errc::ResourceLimit when they exceed this or the device's memory.
  std::uint64_t memoryLimit = 0;
  // Host memory the caller needs beside the build within memoryLimit (a preview it will render,
  // estimatePreviewBytes): counted in the build's estimate, so that a run is refused before it
  // starts rather than at the end.
  std::uint64_t reservedMemory = 0;
  // Interpolated layers between the contour planes (stage "interpolation"); off unless set.
  InterpolationOptions interpolation;
  // Constrained smoothing after assembly (stage "smoothing"); off unless enabled.
  SmoothingOptions smoothing;
  // Verified simplification after smoothing (stage "simplification"); off unless enabled
  // (recommended() enables it).
  SimplificationOptions simplification;
  // Isotropic remeshing after smoothing and simplification (stage "remeshing"); off unless enabled.
  RemeshOptions remeshing;
  // BuildResult::volume's labels. true: the scan-converted labels are read back to the host.
  // false: they stay on the device from scan conversion to classification (no readback and no
  // upload again: two copies of the whole volume, over PCIe on a discrete GPU), and
  // BuildResult::volume holds only its grid. The command-line tool's label-volume and DICOM SEG
  // outputs rasterize their own volumes, so it passes false. Interpolation and the partition
  // mode's volume losses read the labels on the host, so they are kept there anyway.
  bool keepLabelVolume = true;
  // The check of every surface against its contours after the build (scansurf/audit.h).
  AuditOptions audit;
  // Called as each stage begins and when it is done, on the calling thread: every stage begins
  // and ends once per surface layer, labelled with its layer when the build has several.
  struct StageEvent {
    std::string stage;
    bool done = false;
    double seconds = 0;  // when done: the stage's time
    int layer = -1;      // the surface layer, or -1 when the build has one
    int layers = 1;
  };
  std::function<void(const StageEvent& event)> onStageEvent;

  // What scansurf recommends and its command-line tool and Python package start from:
  // smoothing and simplification on, interpolation kAuto with round caps, everything else as
  // declared above (the library's own defaults leave those three off).
  static BuildOptions recommended() {
    BuildOptions options;
    options.smoothing.enabled = true;
    options.simplification.enabled = true;
    options.interpolation.factor = InterpolationOptions::kAuto;
    return options;
  }
};

class Engine {
 public:
  // Creates a Vulkan instance and device of its own. Errors: Errc::NoDevice (no usable device,
  // each rejected device listed with the reason), Errc::Vulkan.
  static Result<Engine> create(const EngineOptions& options);
  // Borrows the application's device (see vulkan_interop.h for the requirements, which are
  // checked: Errc::NoDevice says what is missing). scansurf never waits on the device as a
  // whole, only on its own fences.
  static Result<Engine> adopt(const ExternalVulkan& vulkan, const EngineOptions& options = {});

  Engine(Engine&&) noexcept;
  Engine& operator=(Engine&&) noexcept;
  ~Engine();

  const DeviceInfo& device() const;
  // Validation messages received so far (0 when validation is off).
  std::uint64_t validationMessageCount() const;

  // The whole method: nesting, grid, overlap analysis, then for each layer (one, or the single
  // partition) scan conversion, interpolation (when options.interpolation says so),
  // classification, assembly, smoothing (when
  // options.smoothing.enabled) and the feature surfaces. `contours` must be validated
  // (readContours does it). Coordinates and volumes in the contours' units.
  Result<BuildResult> build(const ContourSet& contours, const BuildOptions& options);
  // build()'s overlap analysis alone (grid, nesting, each feature's region as this device
  // rasterizes it, shared and touching pairs, verdicts and layers), without surfacing: what
  // build() would do with each pair. The incidental pairs' given-up volumes are computed too.
  Result<OverlapReport> analyzeOverlaps(const ContourSet& contours, const BuildOptions& options);

  // The stage calls surface one label volume: the whole set when nothing partly overlaps (or
  // in Partition mode), else one layer at a time (a ContourSet holding that layer's features).
  // They do not split incidental overlaps (scan conversion gives shared voxels by priority)
  // nor give a feature its own slabs on other features' planes: build() does both.
  // Stage 1 on the device: scan converts every slice of a validated contour set into a label
  // volume on `grid` (makeGrid(contours, options.grid)), inner features first by
  // nesting.order. Label of feature i = i + 1; padding layers stay background.
  Result<LabelVolume> scanConvert(const ContourSet& contours, const Nesting& nesting, const Grid& grid,
                                  const BuildOptions& options);
  // Stage 2: interpolation between the volume's layers (options.interpolation) and
  // classification on the device, then assembly, smoothing (options.smoothing) and the
  // feature surfaces on the CPU. nesting.parent.size() is the number of features. `contours`
  // (the set scan converted into `volume`, or null) enables contour fitting and places the
  // interpolated boundaries where the contours cross the grid (without: mid-edge).
  Result<Surfaces> extract(const LabelVolume& volume, const Nesting& nesting, const BuildOptions& options,
                           const ContourSet* contours = nullptr);
  // Stage 2 from labels the application already holds in a VkBuffer on the adopted device
  // (vulkan_interop.h): no readback, no upload. Same result as the host overload without
  // interpolation (these labels are surfaced as they are).
  Result<Surfaces> extract(const DeviceLabelVolume& volume, const Nesting& nesting, const BuildOptions& options,
                           const ContourSet* contours = nullptr);

  // Renders the feature surfaces offscreen on this device: shaded, each feature in
  // options.colors, an orthographic camera fitted to them from options.view.
  Result<PreviewImage> renderPreview(const Surfaces& surfaces, const PreviewOptions& options);

 private:
  struct Impl;
  explicit Engine(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace scansurf
