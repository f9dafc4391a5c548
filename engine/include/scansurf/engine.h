// scansurf: the engine. Scan converts contour sets on a Vulkan device and extracts separating
// surfaces (Lee et al., "Scanline Surfacing"; Nielson & Franke 1997).
//
//   auto engine = scansurf::Engine::create({});
//   auto built = engine->build(contours, {});      // nesting, scan conversion, surfaces
//
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "cell_case.h"  // shaders/shared, also compiled as GLSL
#include "scansurf/contours.h"
#include "scansurf/grid.h"
#include "scansurf/label_volume.h"
#include "scansurf/nesting.h"
#include "scansurf/preview.h"
#include "scansurf/result.h"
#include "scansurf/smoothing.h"
#include "scansurf/surfaces.h"

namespace scansurf {

struct ExternalVulkan;  // scansurf/vulkan_interop.h

struct EngineOptions {
  // Which device: an index into the list of devices, or part of its name (case-insensitive).
  // Empty: the SCANSURF_DEVICE environment variable, else the best device
  // (discrete > integrated > virtual > CPU).
  std::string device;
  // Enable VK_LAYER_KHRONOS_validation. Also on when SCANSURF_VALIDATION=1.
  bool validation = false;
  // Receives every validation message; default: printed to stderr.
  std::function<void(std::string_view)> onValidationMessage;
};

struct DeviceInfo {
  std::string name;
  std::string type;  // "discrete", "integrated", "virtual", "cpu" or "other"
  std::string driver;
  std::uint32_t apiVersion = 0;
  bool borrowed = false;  // the application's device (Engine::adopt)
};

// The time one stage took.
struct StageTime {
  std::string stage;
  double seconds = 0;
};

struct BuildOptions {
  GridOptions grid;
  SurfaceConvention convention = SurfaceConvention::Enclosing;
  int threads = 0;  // CPU threads for assembly and smoothing; 0 = all
  // Constrained smoothing after assembly (stage "smoothing"); off unless enabled.
  SmoothingOptions smoothing;
  // Called after each stage of build() with its name and time (progress reports).
  std::function<void(const std::string& stage, double seconds)> onStage;
};

struct BuildResult {
  Nesting nesting;
  LabelVolume volume;
  Surfaces surfaces;
  std::vector<std::string> warnings;  // e.g. contours too small to cover a pixel centre
  std::vector<StageTime> timings;
};

// Per-cell case data of the tetrahedral classification (CellCase: shaders/shared/cell_case.h).
struct ClassifiedCells {
  std::vector<CellCase> records;  // sorted by cell
};

class Engine {
 public:
  // Creates an instance and device of its own.
  static Result<Engine> create(const EngineOptions& options);
  // Borrows the application's device (see vulkan_interop.h).
  static Result<Engine> adopt(const ExternalVulkan& vulkan, const EngineOptions& options = {});

  Engine(Engine&&) noexcept;
  Engine& operator=(Engine&&) noexcept;
  ~Engine();

  const DeviceInfo& device() const;
  // Validation messages received so far (0 when validation is off).
  std::uint64_t validationMessageCount() const;

  // Scan converts every slice of a validated contour set into a label volume on `grid`;
  // order is the nesting order (innermost first; Nesting::order). Label of feature i = i+1.
  Result<LabelVolume> scanConvert(const ContourSet& contours, const Grid& grid, const std::vector<int>& order);
  // Classifies every tetrahedron of the volume on the GPU: case data of occupied cells.
  Result<ClassifiedCells> classify(const LabelVolume& volume);
  // Classification, then CPU assembly of the multi-label mesh and the feature surfaces.
  Result<Surfaces> extract(const LabelVolume& volume, const Nesting& nesting, int featureCount,
                           SurfaceConvention convention, int threads = 0);
  // The whole method: nesting, grid, scan conversion, classification, assembly.
  Result<BuildResult> build(const ContourSet& contours, const BuildOptions& options);
  // Renders the feature surfaces offscreen on this device (passes/preview.h): shaded, each
  // feature in options.colors, an orthographic camera fitted to them from options.view.
  Result<PreviewImage> renderPreview(const Surfaces& surfaces, const PreviewOptions& options);

  struct Impl;

 private:
  explicit Engine(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace scansurf
