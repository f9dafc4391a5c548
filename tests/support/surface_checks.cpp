// scansurf tests: the CPU pipeline and shared surface measures (see surface_checks.h).
#include "support/surface_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <set>

#include "geometry/extraction/assembly.h"
#include "geometry/extraction/cell_cases.h"
#include "geometry/extraction/feature_surfaces.h"
#include "geometry/smoothing/smooth_mesh.h"
#include "support/reference_rasterizer.h"

namespace scansurf::test {

Built buildCpu(const ContourSet& set, double voxelSize) {
  Built b;
  b.set = set;
  GridOptions options;
  options.voxelSize = voxelSize;
  auto grid = makeGrid(set, options);
  if (!grid) {
    std::fprintf(stderr, "%s: %s\n", set.source.c_str(), grid.error().message.c_str());
    std::abort();
  }
  b.grid = *grid;
  b.nesting = computeNesting(set);
  const LabelVolume volume = referenceScanConvert(set, b.grid, b.nesting.order, 8);
  b.mesh = assembleMesh(b.grid, classifyCellsReference(volume));
  refreshFeatures(b);
  return b;
}

void refreshFeatures(Built& b) {
  b.features = extractFeatureSurfaces(b.mesh, static_cast<int>(b.set.features.size()), b.nesting, SurfaceConvention::Enclosing);
}

Angles minAngles(const MultiLabelMesh& m) {
  std::vector<double> mins;
  for (std::size_t t = 0; t < m.triangleCount(); ++t) {
    double best = 180;
    for (int c = 0; c < 3; ++c) {
      const float* o = &m.positions[3 * m.triangles[3 * t + c]];
      const float* p = &m.positions[3 * m.triangles[3 * t + (c + 1) % 3]];
      const float* q = &m.positions[3 * m.triangles[3 * t + (c + 2) % 3]];
      double u[3], v[3];
      for (int k = 0; k < 3; ++k) u[k] = p[k] - o[k], v[k] = q[k] - o[k];
      const double d = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
      const double nu = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]),
                   nv = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      best = std::min(best, std::acos(std::clamp(d / (nu * nv), -1.0, 1.0)) * 180 / std::numbers::pi);
    }
    mins.push_back(best);
  }
  std::sort(mins.begin(), mins.end());
  return {mins.front(), mins[mins.size() / 20]};
}

Accuracy accuracy(const Built& b, const Distance& distance, double zLow, double zHigh) {
  const std::vector<std::uint32_t>& tris = b.features[0].triangles;
  double sum = 0, area = 0, worst = 0;
  for (std::size_t t = 0; t < tris.size() / 3; ++t) {
    double p[3][3];
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) p[c][k] = b.mesh.positions[3 * tris[3 * t + c] + k];
    const double zc = (p[0][2] + p[1][2] + p[2][2]) / 3;
    if (zc < zLow || zc > zHigh) continue;
    double u[3], v[3];
    for (int k = 0; k < 3; ++k) u[k] = p[1][k] - p[0][k], v[k] = p[2][k] - p[0][k];
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double a = 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    static constexpr double kBary[7][3] = {
        {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {.5, .5, 0}, {0, .5, .5}, {.5, 0, .5}, {1. / 3, 1. / 3, 1. / 3}};
    double local = 0;
    for (const auto& w : kBary) {
      double q[3];
      for (int k = 0; k < 3; ++k) q[k] = w[0] * p[0][k] + w[1] * p[1][k] + w[2] * p[2][k];
      const double d = std::abs(distance(q[0], q[1], q[2]));
      local += d / 7;
      worst = std::max(worst, d);
    }
    sum += local * a;
    area += a;
  }
  return {sum / area, worst, computeMeshStats(b.mesh.positions, tris).volume};
}

NormalErrors sphereNormalErrors(std::span<const float> positions, std::span<const std::uint32_t> triangles, double facing,
                                double zLow, double zHigh) {
  std::vector<std::pair<double, double>> angleArea;
  double total = 0, sum = 0;
  for (std::size_t t = 0; t + 2 < triangles.size(); t += 3) {
    double p[3][3];
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k)
        p[c][k] = positions[3 * std::size_t{triangles[t + static_cast<std::size_t>(c)]} + static_cast<std::size_t>(k)];
    const double u[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
    const double v[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double c[3] = {(p[0][0] + p[1][0] + p[2][0]) / 3, (p[0][1] + p[1][1] + p[2][1]) / 3, (p[0][2] + p[1][2] + p[2][2]) / 3};
    if (c[2] < zLow || c[2] >= zHigh) continue;
    const double ln = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), lc = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    if (ln == 0 || lc == 0) continue;
    const double cosine = std::clamp(facing * (n[0] * c[0] + n[1] * c[1] + n[2] * c[2]) / (ln * lc), -1.0, 1.0);
    const double angle = std::acos(cosine) * 180 / std::numbers::pi, area = ln / 2;
    angleArea.push_back({angle, area});
    total += area, sum += angle * area;
  }
  std::sort(angleArea.begin(), angleArea.end());
  double seen = 0, p95 = 0;
  for (const auto& [angle, area] : angleArea)
    if ((seen += area) >= 0.95 * total) {
      p95 = angle;
      break;
    }
  return {total > 0 ? sum / total : 0, p95};
}

double distanceToContours(const FeatureSlice& slice, double x, double y) {
  double best = 1e300;
  for (const Contour& contour : slice.contours)
    for (std::size_t j = 0; j < contour.points.size(); ++j) {
      const Point2 u = contour.points[j], w = contour.points[(j + 1) % contour.points.size()];
      const double dx = w.x - u.x, dy = w.y - u.y;
      const double h = std::clamp(((x - u.x) * dx + (y - u.y) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
      best = std::min(best, std::hypot(x - u.x - h * dx, y - u.y - h * dy));
    }
  return best;
}

double crossSectionError(const Built& b) {
  // The slice of feature 0 whose z the vertex has (within the default slice tolerance).
  const auto sliceOf = [&](std::uint32_t v) -> const FeatureSlice* {
    const double z = b.mesh.positions[3 * v + 2];
    for (const FeatureSlice& s : b.set.features[0].slices)
      if (std::abs(s.z - z) <= kDefaultSliceTolerance) return &s;
    return nullptr;
  };
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
  const std::vector<std::uint32_t>& tris = b.features[0].triangles;
  for (std::size_t t = 0; t < tris.size() / 3; ++t)
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t p = tris[3 * t + c], q = tris[3 * t + (c + 1) % 3];
      if (sliceOf(p) && sliceOf(p) == sliceOf(q)) edges.insert({std::min(p, q), std::max(p, q)});
    }
  double sum = 0, length = 0;
  for (const auto& [p, q] : edges) {
    const FeatureSlice* slice = sliceOf(p);
    const float* a = &b.mesh.positions[3 * p];
    const float* c = &b.mesh.positions[3 * q];
    const double len = std::hypot(c[0] - a[0], c[1] - a[1]);
    for (int i = 0; i < 5; ++i) {
      const double s = i / 4.0;
      sum += distanceToContours(*slice, a[0] + s * (c[0] - a[0]), a[1] + s * (c[1] - a[1])) * len / 5;
    }
    length += len;
  }
  return length > 0 ? sum / length / b.grid.spacingX : 0;
}

InterfaceUse interfaceUse(const MultiLabelMesh& mesh, const FeatureSurface& a, const FeatureSurface& b, Label la, Label lb) {
  const std::set<std::uint32_t> onA(a.triangles.begin(), a.triangles.end()), onB(b.triangles.begin(), b.triangles.end());
  InterfaceUse use;
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    if (mesh.labels[2 * t] != la || mesh.labels[2 * t + 1] != lb) continue;
    ++use.triangles;
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t v = mesh.triangles[3 * t + static_cast<std::size_t>(c)];
      use.unshared += !onA.count(v) || !onB.count(v);
    }
  }
  return use;
}

SmoothingReport smoothWithDefaults(Built& b, int threads) {
  SmoothingOptions o;
  o.enabled = true;
  return smoothMesh(b.mesh, b.grid, &b.set, o, threads);
}

std::vector<MeshStats> surfaceStats(const Built& b, SurfaceConvention convention) {
  std::vector<MeshStats> out;
  for (const FeatureSurface& s : extractFeatureSurfaces(b.mesh, static_cast<int>(b.set.features.size()), b.nesting, convention))
    out.push_back(computeMeshStats(b.mesh.positions, s.triangles));
  return out;
}

SurfaceSnapshot snapshotSurfaces(const Built& b) {
  return {surfaceStats(b, SurfaceConvention::Enclosing), surfaceStats(b, SurfaceConvention::Partition)};
}

std::vector<std::string> surfacesLost(const Built& b, const SurfaceSnapshot& before, double volumeTolerance) {
  std::vector<std::string> lost;
  for (const auto& [convention, was] :
       {std::pair{SurfaceConvention::Enclosing, &before.enclosing}, std::pair{SurfaceConvention::Partition, &before.partition}}) {
    const std::vector<MeshStats> now = surfaceStats(b, convention);
    for (std::size_t f = 0; f < now.size(); ++f) {
      const MeshStats &s = now[f], &o = (*was)[f];
      const std::string at = std::string(convention == SurfaceConvention::Enclosing ? "enclosing" : "partition") + " feature " +
                             std::to_string(f) + ": ";
      if ((s.triangles == 0) != (o.triangles == 0)) lost.push_back(at + "surface lost or made");
      if (o.triangles == 0 || s.triangles == 0) continue;
      if (!(s.closed && s.manifold && s.oriented)) lost.push_back(at + "not a closed oriented manifold");
      if (s.genus != o.genus) lost.push_back(at + "genus " + std::to_string(o.genus) + " -> " + std::to_string(s.genus));
      if (s.components != o.components)
        lost.push_back(at + "components " + std::to_string(o.components) + " -> " + std::to_string(s.components));
      if (std::abs(s.volume - o.volume) > volumeTolerance * std::abs(o.volume))
        lost.push_back(at + "volume " + std::to_string(o.volume) + " -> " + std::to_string(s.volume));
    }
  }
  return lost;
}

}  // namespace scansurf::test
