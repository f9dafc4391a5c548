#include "scansurf/engine.h"

#include <chrono>

#include "geometry/assembly.h"
#include "geometry/coverage.h"
#include "geometry/feature_surfaces.h"
#include "geometry/validate.h"
#include "geometry/smoothing.h"
#include "gpu/context.h"
#include "passes/classification.h"
#include "passes/preview.h"
#include "passes/scan_conversion.h"
#include "scansurf/vulkan_interop.h"

namespace scansurf {

struct Engine::Impl {
  std::unique_ptr<gpu::Context> context;
  std::unique_ptr<passes::ScanConverter> scanConverter;  // created on first use
  std::unique_ptr<passes::Classifier> classifier;
  std::unique_ptr<passes::PreviewRenderer> previewRenderer;
};

namespace {

class StageClock {
 public:
  StageClock(std::vector<StageTime>& out, const BuildOptions& options)
      : out_(out), options_(options), start_(std::chrono::steady_clock::now()) {}
  void lap(const char* stage) {
    const auto now = std::chrono::steady_clock::now();
    out_.push_back({stage, std::chrono::duration<double>(now - start_).count()});
    if (options_.onStage) options_.onStage(out_.back().stage, out_.back().seconds);
    start_ = now;
  }

 private:
  std::vector<StageTime>& out_;
  const BuildOptions& options_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace

Engine::Engine(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Engine::Engine(Engine&&) noexcept = default;
Engine& Engine::operator=(Engine&&) noexcept = default;
Engine::~Engine() = default;

Result<Engine> Engine::create(const EngineOptions& options) {
  auto impl = std::make_unique<Impl>();
  SCANSURF_ASSIGN_OR_RETURN(impl->context, gpu::Context::create(options));
  return Engine(std::move(impl));
}

Result<Engine> Engine::adopt(const ExternalVulkan& vulkan, const EngineOptions& options) {
  auto impl = std::make_unique<Impl>();
  SCANSURF_ASSIGN_OR_RETURN(impl->context, gpu::Context::adopt(vulkan, options));
  return Engine(std::move(impl));
}

const DeviceInfo& Engine::device() const { return impl_->context->info(); }
std::uint64_t Engine::validationMessageCount() const { return impl_->context->validationMessageCount(); }

Result<LabelVolume> Engine::scanConvert(const ContourSet& contours, const Grid& grid, const std::vector<int>& order) {
  if (!impl_->scanConverter) {
    SCANSURF_ASSIGN_OR_RETURN(impl_->scanConverter, passes::ScanConverter::create(*impl_->context));
  }
  return impl_->scanConverter->run(contours, grid, order);
}

Result<ClassifiedCells> Engine::classify(const LabelVolume& volume) {
  if (!impl_->classifier) {
    SCANSURF_ASSIGN_OR_RETURN(impl_->classifier, passes::Classifier::create(*impl_->context));
  }
  SCANSURF_ASSIGN_OR_RETURN(std::vector<CellCase> records, impl_->classifier->run(volume));
  return ClassifiedCells{std::move(records)};
}

Result<Surfaces> Engine::extract(const LabelVolume& volume, const Nesting& nesting, int featureCount,
                                 SurfaceConvention convention, int threads) {
  SCANSURF_ASSIGN_OR_RETURN(ClassifiedCells cells, classify(volume));
  Surfaces surfaces;
  surfaces.convention = convention;
  surfaces.mesh = assembleMesh(volume.grid, cells.records, threads);
  surfaces.features = extractFeatureSurfaces(surfaces.mesh, featureCount, nesting, convention);
  return surfaces;
}

Result<PreviewImage> Engine::renderPreview(const Surfaces& surfaces, const PreviewOptions& options) {
  if (!impl_->previewRenderer) {
    SCANSURF_ASSIGN_OR_RETURN(impl_->previewRenderer, passes::PreviewRenderer::create(*impl_->context));
  }
  return impl_->previewRenderer->render(surfaces, options);
}

Result<BuildResult> Engine::build(const ContourSet& contours, const BuildOptions& options) {
  BuildResult out;
  StageClock clock(out.timings, options);
  out.nesting = computeNesting(contours);
  clock.lap("nesting");
  SCANSURF_ASSIGN_OR_RETURN(const Grid grid, makeGrid(contours, options.grid));
  out.warnings = findUncoveredContours(contours, grid);
  clock.lap("grid");
  SCANSURF_ASSIGN_OR_RETURN(out.volume, scanConvert(contours, grid, out.nesting.order));
  clock.lap("scan conversion");
  SCANSURF_ASSIGN_OR_RETURN(ClassifiedCells cells, classify(out.volume));
  clock.lap("classification");
  out.surfaces.convention = options.convention;
  out.surfaces.mesh = assembleMesh(grid, cells.records, options.threads);
  cells.records = {};
  clock.lap("assembly");
  if (options.smoothing.enabled) {
    smoothMesh(out.surfaces.mesh, grid, &contours, options.smoothing, options.threads, options.grid.sliceTolerance);
    clock.lap("smoothing");
  }
  out.surfaces.features = extractFeatureSurfaces(out.surfaces.mesh, static_cast<int>(contours.features.size()), out.nesting,
                                                 options.convention);
  clock.lap("feature surfaces");
  // A feature without a surface deserves a word: it has no slices, is too small for the grid,
  // or (partition convention) features of higher priority cover all of it.
  for (std::size_t f = 0; f < out.surfaces.features.size(); ++f)
    if (out.surfaces.features[f].triangles.empty())
      out.warnings.push_back(describeFeature(contours, static_cast<int>(f)) +
                             ": no surface (no slices, smaller than a pixel, or covered by features of higher priority)");
  return out;
}

}  // namespace scansurf
