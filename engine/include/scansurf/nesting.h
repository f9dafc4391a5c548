// scansurf: the nesting order of features (paper §3.3).
#pragma once

#include <vector>

#include "scansurf/contours.h"

namespace scansurf {

struct Nesting {
  // Feature indices, innermost first: a feature inside another comes before it and so wins
  // where they overlap. Siblings keep their input order.
  std::vector<int> order;
  // parent[f]: the smallest feature that contains feature f, or -1. A feature is contained in
  // another when, on every slice it appears in, the other appears too and every one of its
  // contour points lies inside the other's region (even-odd) on that slice.
  std::vector<int> parent;
  bool userOrder = false;  // order came from the input's "order"
};

// Computes containment and the nesting order of a validated contour set; slices closer than
// sliceTolerance (input units) are one plane. The order is acyclic and deterministic;
// contours.order, when not empty, is used as the order instead.
Nesting computeNesting(const ContourSet& contours, double sliceTolerance = 0);

// The nesting of `featureCount` features none of which contains another, in index order: for
// label volumes made elsewhere (Engine::extract) where containment is not known.
Nesting flatNesting(int featureCount);

// True when feature `inner` is contained in `outer` (directly or through parents).
bool isInside(const Nesting& nesting, int inner, int outer);

}  // namespace scansurf
