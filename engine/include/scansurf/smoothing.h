// scansurf: options of the constrained smoothing of separating surfaces (paper §3.5 and its
// "future work": smoothing that conforms to the original contours).
#pragma once

#include <cstddef>

namespace scansurf {

// Defaults suit typical CT contours (about 1 mm pixels, 1-3 mm slices); they never need
// touching. Positions change, never the triangles or their labels.
struct SmoothingOptions {
  // Off by default in the library (Engine::build); the command-line tool turns it on.
  bool enabled = false;
  // How much to smooth, in plain Jacobi sweeps of every vertex; the smoother covers them in
  // far fewer sweeps (super-steps: 150 in 35).
  int iterations = 150;
  static constexpr int kMostIterations = 100000;  // build() refuses more (or fewer than 1)
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
  // Smallest angle, degrees, that placing, relaxing and restoring may leave in a triangle: a move
  // that would make a triangle sharper than this (and sharper than it was) is shortened, still
  // inside the vertex's simplex (geometry/smoothing/angle_guard.h). Off by default: shortening alone costs
  // accuracy (3 degrees: up to 8 % more mean distance; 15: up to twice; docs/method.md,
  // "Triangle shape"). 0: off.
  double minAngle = 0;
  // Vertices crowding a voxel centre merge into it after relaxation, before the volumes are
  // restored (Raman & Wenger's snapping; geometry/shape/snapping.h): every voxel centre that a vertex
  // on one of its lattice edges lies within this fraction of the edge from becomes a vertex,
  // where one label pair meets around it. Removes the slivers that sliding vertices make near
  // voxel centres, and their triangles. In [0, 0.45]; 0: off. Where the contour planes lie
  // closer than two pixels it is used scaled down in proportion (else it would cost more than a
  // tenth of the surfaces' accuracy there); TriangleShapeReport::fraction says what was used.
  double snap = 0.05;
};

// What snapping, the quads' diagonals and the cubes' fans did (docs/method.md, "Triangle
// shape"); ran = false
// when smoothing did not run. With several layers, the layers' sums.
struct TriangleShapeReport {
  bool ran = false;
  double fraction = 0;                 // the fraction used (SmoothingOptions::snap, scaled for thin slices)
  std::size_t candidates = 0;          // voxel centres some vertex came within the fraction of
  std::size_t points = 0;              // of them, snapped: now vertices
  std::size_t mergedVertices = 0;      // vertices merged into them
  std::size_t removedTriangles = 0;    // triangles that vanished
  std::size_t quadsFlipped = 0;        // quads split along their other diagonal
  std::size_t cubeFans = 0;            // cubes and boxes (up to 2 x 2 x 2) whose surface became its rim's triangles
  std::size_t fanVerticesRemoved = 0;  // the vertices they lost (and twice as many triangles)
  double seconds = 0;                  // the three steps, inside the smoothing stage
};

}  // namespace scansurf
