// scansurf: the smoothed surface network that remeshing stays on: nearest points on its
// sheets (by label pair), on its junction curves (by the labels that meet there) and on its
// contour-plane cross-sections (by plane and label pair).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/remesh/remesh_network.h"

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
  // cells of the given size; built on up to `threads` threads, the same for any count.
  ReferenceSurface(const Network& net, double cell, int threads = 1);
  // Nearest point of the feature within `radius` of p.
  Nearest nearest(const Vec3& p, const FeatureKey& key, double radius) const;
  // The same, searching within a tenth of `radius` first (most queries are that close).
  Nearest nearestNear(const Vec3& p, const FeatureKey& key, double radius) const;
  // Whether some point of the feature lies within `radius` of p.
  bool within(const Vec3& p, const FeatureKey& key, double radius) const;

 private:
  // A triangle or segment of the network's vertices (points_), 24 bytes: millions of them.
  struct Primitive {
    std::uint64_t keyValue;  // its feature (cells are hashed with it: this weeds out collisions)
    std::array<std::uint32_t, 3> corners;
    std::uint8_t count;  // 3: triangle, 2: segment
    FeatureKey::Kind keyKind;
    bool is(const FeatureKey& key) const { return keyKind == key.kind && keyValue == key.value; }
  };
  // Calls f(primitive) for the feature's primitives in the cells within radius of p whose
  // box lies within sqrt(limit2) of p, until f returns false; f may lower limit2.
  template <typename F>
  void visit(const Vec3& p, const FeatureKey& key, double radius, const double& limit2, F f) const;
  // A primitive in a cell, with its box widened to floats: a cell's run is scanned in one
  // stream, and only the primitives near enough are looked up.
  struct CellEntry {
    std::array<float, 3> lo, hi;
    std::uint32_t primitive;
  };
  // Read-only after construction: an open-addressing table from a (cell, feature) key to its
  // run of entries in one array, each run by ascending primitive (compressed rows).
  struct CellTable {
    static constexpr std::uint64_t kEmpty = ~0ull;
    std::vector<std::uint64_t> keys;    // per slot, kEmpty when free
    std::vector<std::uint32_t> runs;    // per slot, its run's index
    std::vector<std::uint32_t> starts;  // run r is entries[starts[r], starts[r + 1])
    std::vector<CellEntry> entries;
    int shift = 64;
    std::size_t slotOf(std::uint64_t key) const { return static_cast<std::size_t>((key * 0x9e3779b97f4a7c15ull) >> shift); }
    std::span<const CellEntry> find(std::uint64_t key) const;
  };
  void addPrimitives(const Network& net, int threads);
  void bucket(int threads);
  std::uint64_t cellKey(std::int64_t x, std::int64_t y, std::int64_t z, const FeatureKey& key) const;
  // Calls f(cell key) for every cell that [lo, hi] touches, z-major.
  template <typename F>
  void forCells(const Vec3& lo, const Vec3& hi, const FeatureKey& key, F f) const;

  void boxOf(const Primitive& q, Vec3& lo, Vec3& hi) const;
  Vec3 nearestOn(const Primitive& q, const Vec3& p) const;  // the primitive's point nearest p

  double cell_;
  std::vector<Vec3> points_;  // the network's vertex positions
  std::vector<Primitive> primitives_;
  CellTable cells_;
};

// The point of triangle abc nearest p (Ericson, "Real-Time Collision Detection", 5.1.5).
Vec3 nearestOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);
Vec3 nearestOnSegment(const Vec3& p, const Vec3& a, const Vec3& b);

}  // namespace scansurf::remesh
