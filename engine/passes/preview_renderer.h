// scansurf passes: an offscreen preview of the surfaces. Each feature's triangles are drawn
// in its colour with an orthographic camera fitted to the surfaces, opaque features first
// (depth-tested), translucent ones blended over them; the image is rendered at twice the
// size and averaged down 2x2 on the CPU (supersampling), then read back.
#pragma once

#include <memory>

#include "gpu/context.h"
#include "scansurf/preview.h"
#include "scansurf/surfaces.h"

namespace scansurf::passes {

class PreviewRenderer {
 public:
  static Result<std::unique_ptr<PreviewRenderer>> create(const gpu::Context& ctx);
  ~PreviewRenderer();

  // Renders every feature surface of `surfaces`. Errors: InvalidArgument for a zero or
  // oversized picture; Vulkan failures.
  Result<PreviewImage> render(const Surfaces& surfaces, const PreviewOptions& options);

  struct State;

 private:
  explicit PreviewRenderer(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace scansurf::passes
