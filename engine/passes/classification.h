// scansurf passes: tetrahedral classification on the GPU (Nielson & Franke 1997). A compute
// shader visits every cell of the label volume and appends a compact CellCase record for
// each cell that holds a separating surface. The volume is processed in batches of layers so
// no buffer exceeds maxStorageBufferRange (128 MiB on lavapipe), whatever the volume's size.
#pragma once

#include <memory>
#include <vector>

#include "geometry/extraction/cell_cases.h"
#include "geometry/grid/content_tiles.h"
#include "gpu/context.h"
#include "scansurf/label_volume.h"
#include "scansurf/vulkan_interop.h"

namespace scansurf::gpu {
class Buffer;
}  // namespace scansurf::gpu

namespace scansurf::passes {

class Classifier {
 public:
  static Result<std::unique_ptr<Classifier>> create(const gpu::Context& ctx);
  ~Classifier();

  // Records of every cell holding a surface, sorted by cell index; identical to
  // classifyCellsReference(volume).
  Result<std::vector<CellCase>> run(const LabelVolume& volume);
  // The same from labels already in a buffer on this device (16- or 32-bit, x fastest; see
  // DeviceLabelVolume in scansurf/vulkan_interop.h): each batch is copied on the device, never
  // through the host. A 32-bit label above 65535 is Errc::InvalidInput.
  Result<std::vector<CellCase>> run(const DeviceLabelVolume& volume);
  // The same with the buffer's size known (scansurf's own buffers): each batch's labels are
  // bound in place, with no copy and no batch buffer. upperIsData: 32-bit words whose upper
  // 16 bits are other data (the interpolation's words, label | clearance << 16).
  // content (geometry/grid/content_tiles.h), when given, says where the labels can be other
  // than background: only the cells of columns near a marked tile are visited, with the same
  // records as a visit of every cell when the marks hold.
  Result<std::vector<CellCase>> runInPlace(const DeviceLabelVolume& volume, VkDeviceSize bufferSize, bool upperIsData = false,
                                           const ContentTiles* content = nullptr);

  // Bytes of labels one batch may upload; smaller forces more batches (tests use it).
  void setBatchBudget(std::size_t bytes);
  int lastBatchCount() const;

  struct State;
  struct Source;

 private:
  Result<std::vector<CellCase>> classify(const Source& source);
  // Records one batch's pass: its labels into place, the counter cleared, the dispatch.
  // tiles: the batch's tiles of cell columns (none: every column).
  void recordBatch(VkCommandBuffer cmd, const Source& source, const gpu::Buffer& labels, const gpu::Buffer& counter, int first,
                   int layers, std::size_t capacity, std::uint32_t labelOffset, std::uint32_t tiles) const;
  Result<Source> deviceSource(const DeviceLabelVolume& volume) const;
  explicit Classifier(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace scansurf::passes
