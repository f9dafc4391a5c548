// scansurf tests: the CPU pipeline (makeGrid -> referenceScanConvert -> classifyCellsReference
// -> assembleMesh) and the measures the smoothing and remeshing tests share.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "geometry/smoothing/smooth_mesh.h"
#include "scansurf/contours.h"
#include "scansurf/grid.h"
#include "scansurf/nesting.h"
#include "scansurf/surfaces.h"

namespace scansurf::test {

struct Built {
  ContourSet set;
  Grid grid;
  Nesting nesting;
  MultiLabelMesh mesh;
  std::vector<FeatureSurface> features;  // Enclosing
};

// The raw (unsmoothed) separating surfaces of `set` at this in-plane voxel size, slices as layers.
Built buildCpu(const ContourSet& set, double voxelSize);
// Recomputes b.features (Enclosing) after the mesh changed.
void refreshFeatures(Built& b);
// Smooths b.mesh with SmoothingOptions' defaults, smoothing on (relaxation alone: no snapping).
SmoothingReport smoothWithDefaults(Built& b, int threads = 0);

// Per feature surface of one convention, its statistics.
std::vector<MeshStats> surfaceStats(const Built& b, SurfaceConvention convention);
// Both conventions' statistics, taken before a change to the mesh.
struct SurfaceSnapshot {
  std::vector<MeshStats> enclosing, partition;
};
SurfaceSnapshot snapshotSurfaces(const Built& b);
// What no longer holds of `before` after the change, one line per fault (naming the convention
// and feature): a surface lost or made, not a closed oriented manifold, another genus or
// components, or a volume off by more than volumeTolerance (relative). Empty: all kept.
std::vector<std::string> surfacesLost(const Built& b, const SurfaceSnapshot& before, double volumeTolerance);

struct Angles {
  double min = 180, p5 = 180;
};
// Smallest and 5th percentile of every triangle's smallest angle, degrees.
Angles minAngles(const MultiLabelMesh& m);

using Distance = std::function<double(double, double, double)>;
struct Accuracy {
  double mean = 0, max = 0, volume = 0;
};
// Area-weighted mean and max distance of feature 0's surface to the analytic surface over 7
// samples per triangle (those whose centroid lies in [zLow, zHigh]), and its whole volume.
Accuracy accuracy(const Built& b, const Distance& distance, double zLow = -1e300, double zHigh = 1e300);

// Area-weighted mean and 95th percentile of the angle, degrees, between each face's normal
// (turned by `facing`: -1 where the faces' normals point inward) and the direction from the
// origin to its centroid: how far the faces lie from a sphere's about the origin. Over the
// faces whose centroid z lies in [zLow, zHigh); degenerate faces are left out.
struct NormalErrors {
  double mean = 0, p95 = 0;
};
NormalErrors sphereNormalErrors(std::span<const float> positions, std::span<const std::uint32_t> triangles, double facing = 1,
                                double zLow = -1e300, double zHigh = 1e300);

// Mean distance, in pixels, from feature 0's cross-sections at the contour planes (every mesh
// edge with both ends at a slice's z, sampled at 5 points, weighted by length) to the
// original contours.
double crossSectionError(const Built& b);

// Distance in the plane from (x, y) to the nearest contour of the slice.
double distanceToContours(const FeatureSlice& slice, double x, double y);

// The interface of two abutting features: the triangles between labels la and lb, and how
// many of their vertex uses lie on only one of the two surfaces a and b (0: they share it).
struct InterfaceUse {
  std::size_t triangles = 0, unshared = 0;
};
InterfaceUse interfaceUse(const MultiLabelMesh& mesh, const FeatureSurface& a, const FeatureSurface& b, Label la, Label lb);

}  // namespace scansurf::test
