// scansurf: the smoothed surface network that remeshing stays on: nearest points on its
// sheets (by label pair), on its junction curves (by the labels that meet there) and on its
// contour-plane cross-sections (by plane and label pair).
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "geometry/remesh_network.h"

namespace scansurf::remesh {

// The nearest point found and its distance; found = false when nothing lay within the radius.
struct Nearest {
  bool found = false;
  Vec3 point{};
  double distance = 0;
};

// Which reference feature a point belongs to: a sheet (label pair), a junction curve (the
// sorted set of labels around it, hashed) or a plane cross-section (plane and pair).
struct FeatureKey {
  enum class Kind : std::uint8_t { Sheet, Curve, Plane } kind = Kind::Sheet;
  std::uint64_t value = 0;
};
FeatureKey sheetKey(std::uint32_t pair);
FeatureKey planeKey(int plane, std::uint32_t pair);
// The labels of an edge's triangles, as a curve key.
FeatureKey curveKey(const Network& net, const std::vector<std::uint32_t>& edgeTris);

class ReferenceSurface {
 public:
  // A copy of the network as it is now (sheets, junction edges, in-plane edges), bucketed in
  // cells of the given size.
  ReferenceSurface(const Network& net, double cell);
  // Nearest point of the feature within `radius` of p.
  Nearest nearest(const Vec3& p, const FeatureKey& key, double radius) const;
  // The same, searching within a tenth of `radius` first (most queries are that close).
  Nearest nearestNear(const Vec3& p, const FeatureKey& key, double radius) const;
  // Whether some point of the feature lies within `radius` of p.
  bool within(const Vec3& p, const FeatureKey& key, double radius) const;

 private:
  struct Primitive {
    std::uint32_t first;  // into points_
    std::uint8_t count;   // 3: triangle, 2: segment
    FeatureKey key;       // cells are hashed with the key: this weeds out collisions
    Vec3 lo, hi;          // bounding box
  };
  // Calls f(primitive) for the feature's primitives in the cells within radius of p until f
  // returns false.
  template <typename F>
  void visit(const Vec3& p, const FeatureKey& key, double radius, F f) const;
  using Bucket = std::unordered_map<std::uint64_t, std::vector<std::uint32_t>>;  // cell -> primitives
  void add(const FeatureKey& key, const Vec3* corners, int count);
  std::uint64_t cellKey(std::int64_t x, std::int64_t y, std::int64_t z, const FeatureKey& key) const;

  double cell_;
  std::vector<Vec3> points_;
  std::vector<Primitive> primitives_;
  Bucket cells_;  // (cell, feature) -> primitives
};

// The point of triangle abc nearest p (Ericson, "Real-Time Collision Detection", 5.1.5).
Vec3 nearestOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);
Vec3 nearestOnSegment(const Vec3& p, const Vec3& a, const Vec3& b);

}  // namespace scansurf::remesh
