// scansurf passes: tetrahedral classification on the GPU (Nielson & Franke 1997). A compute
// shader visits every cell of the label volume and appends a compact CellCase record for
// each cell that holds a separating surface. The volume is processed in slabs of layers so
// no buffer exceeds maxStorageBufferRange (128 MiB on lavapipe), whatever the volume's size.
#pragma once

#include <memory>
#include <vector>

#include "geometry/cell_cases.h"
#include "gpu/context.h"

namespace scansurf::passes {

class Classifier {
 public:
  static Result<std::unique_ptr<Classifier>> create(const gpu::Context& ctx);
  ~Classifier();

  // Records of every cell holding a surface, sorted by cell index; identical to
  // classifyCellsReference(volume).
  Result<std::vector<CellCase>> run(const LabelVolume& volume);

  // Bytes of labels one slab may upload; smaller forces more slabs (tests use it).
  void setSlabBudget(std::size_t bytes);
  int lastSlabCount() const;

  struct State;

 private:
  explicit Classifier(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace scansurf::passes
