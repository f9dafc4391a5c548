// scansurf passes: slice scan conversion (Lee et al., "Scanline Surfacing", §3.4) with Vulkan
// graphics pipelines. Each feature's contours on a slice are drawn as triangle fans that
// toggle one stencil bit (even-odd parity: holes and concave shapes fill right); a quad over
// the feature's bounding box then writes the feature's label where the bit is set, with the
// feature's nesting rank as depth so inner features win, and clears the bit for the next
// feature. Many slices are recorded into one command buffer (a batch), one submit per batch.
#pragma once

#include <memory>
#include <vector>

#include "gpu/context.h"
#include "gpu/resources.h"
#include "scansurf/contours.h"
#include "scansurf/label_volume.h"

namespace scansurf::passes {

class ScanConverter {
 public:
  static Result<std::unique_ptr<ScanConverter>> create(const gpu::Context& ctx);
  ~ScanConverter();

  // Rasterizes a validated contour set on `grid` (made by makeGrid for it) into a label
  // volume; order is the nesting order, innermost first. Padding layers stay background.
  // Slices go to the layer whose plane holds them (Grid::layerOfPlane).
  Result<LabelVolume> run(const ContourSet& contours, const Grid& grid, const std::vector<int>& order);

  // The same labels left on the device for classification (no readback and upload
  // again between GPU passes): a buffer of 16-bit labels in LabelVolume's layout, usable as
  // a DeviceLabelVolume (storage and transfer usage; classified in place by
  // Classifier::runInPlace). `host`, when given, also receives them (its labels are filled).
  struct DeviceLabels {
    gpu::Buffer buffer;
    Grid grid;
  };
  Result<DeviceLabels> runOnDevice(const ContourSet& contours, const Grid& grid, const std::vector<int>& order,
                                   LabelVolume* host);

  int subPixelBits() const;
  // Batches used by the last run (for reports and tests).
  int lastBatchCount() const;

  // Bytes of label image one batch may use; smaller forces more batches (tests use it).
  void setBatchBudget(std::size_t bytes);

  struct State;

 private:
  explicit ScanConverter(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace scansurf::passes
