// scansurf: options of the constrained smoothing of separating surfaces (paper §3.5 and its
// "future work": smoothing that conforms to the original contours).
#pragma once

namespace scansurf {

// Defaults suit typical CT contours (about 1 mm pixels, 1-3 mm slices); they never need
// touching. Positions change, never the triangles or their labels.
struct SmoothingOptions {
  // Off by default in the library (Engine::build); the command-line tool turns it on.
  bool enabled = false;
  // How much to smooth, in plain Jacobi sweeps of every vertex; the smoother covers them in
  // far fewer sweeps (super-steps: 150 in 35).
  int iterations = 150;
  // Step size of each sweep in (0, 1]: how far a vertex moves toward its relaxed target.
  double strength = 0.8;
  // Junction curves (three or more labels) relax along themselves; off: they stay put.
  bool junctions = true;
  // Vertices on contour planes sit where the original contours cross their grid edges and stay
  // there; off: they relax like the others (still on their plane).
  bool contourFit = true;
  // Afterwards each feature's volume is restored to its slab volume (the contours' areas times
  // their slabs; enclosing convention): relaxation shrinks small convex structures and swells
  // thin ones. Only vertices off the contour planes that bound one feature move, each inside
  // its own lattice simplex (docs/method.md, "Smoothing"). Off: as relaxed.
  bool keepVolumes = true;
};

}  // namespace scansurf
