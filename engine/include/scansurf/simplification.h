// scansurf: options and figures of the verified simplification of the smoothed
// separating-surface network (quadric-error edge collapses, Garland & Heckbert 1997).
#pragma once

#include <cstddef>

#include "scansurf/remesh.h"  // AngleFigures

namespace scansurf {

struct SimplificationOptions {
  // Off in the library's own defaults, on in BuildOptions::recommended() (what the command-line
  // tool and the Python package start from): it merges the cubes' fans' triangles into fewer,
  // better-shaped ones (docs/method.md, "Simplification" has the figures). Runs after
  // smoothing, before remeshing.
  bool enabled = false;
  // How far a collapse may move the surface, in in-plane voxels (the quadric error bound).
  double tolerance = 0.05;
  // Collapses stop once a patch is down to triangles of about this edge length, in in-plane
  // voxels: flat parts become triangles of about two voxels, not long slivers (docs/method.md
  // gives the counts and the analytic sphere's normals at this length).
  double edgeLength = 2.5;
  // New triangles keep at least the lesser of this smallest angle (degrees) and the one of the
  // triangles they replace: collapses never make triangles sharper below it.
  double minAngle = 15;
  // A set tolerance or edgeLength outside these (in-plane voxels) is refused (Errc::InvalidArgument).
  static constexpr double kMostTolerance = 0.5, kLeastEdge = 0.5, kMostEdge = 8;
};

// What simplification did; ran = false when it did not run.
struct SimplificationReport {
  bool ran = false;
  std::size_t trianglesBefore = 0, trianglesAfter = 0;
  AngleFigures anglesBefore, anglesAfter;  // every triangle's smallest angle
  std::size_t patches = 0;                 // one label pair in one tile between two cuts (contour planes, tier bounds)
  // Patches whose simplified triangles failed a check and were put back as smoothed: by the
  // patch's own checks (topology, border, cross-sections, turned triangles), then by the exact
  // crossing test against every triangle near them, or for sharing an edge with more than one
  // other triangle of a label (another patch joined the same two vertices).
  std::size_t refused = 0, crossing = 0;
};

}  // namespace scansurf
