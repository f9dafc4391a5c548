// scansurf: volume restoration after smoothing (see volume_restoration.h). A feature f with
// volume V and target T moves each of its movable vertices v by the same distance s along its
// volume gradient g_v (dV/dx_v: a sixth of the cross products of its fan) within its carrier
// (projected onto the carrier's edge or face), so V changes by s * sum |g_v| to first order:
// s = (T - V) / sum |g_v|, at most a quarter voxel a round,
// then each vertex is projected back into its carrier; a few rounds absorb the projection's
// clamping and the second-order terms.
#include "geometry/shape/volume_restoration.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "core/parallel.h"
#include "geometry/extraction/assembly.h"
#include "geometry/mesh/incident_triangles.h"
#include "geometry/mesh/vertex_roles.h"
#include "geometry/shape/cube_fans.h"
#include "geometry/smoothing/angle_guard.h"
#include "geometry/smoothing/carrier_projection.h"

namespace scansurf {
namespace {

constexpr int kRounds = 8;               // a step is at most kLargestStep: thin features need several
constexpr double kClose = 1e-4;          // every feature this close to its target: done
constexpr std::size_t kBlock = 1 << 16;  // triangles summed together
constexpr double kLargestStep = 0.25;    // of the smallest voxel spacing, per round

// Whether the vertex lies in the plane of a contour layer (its carrier's corners all on it).
bool onContourPlane(std::uint64_t key, const std::vector<bool>& contourLayers) {
  const std::uint64_t z = (key >> (2 * kKeyBits)) & kKeyMask;  // twelfths of a layer
  return z % 12 == 0 && z / 12 < contourLayers.size() && contourLayers[z / 12];
}

struct Bound {
  int feature = 0;
  int sign = 1;  // +1: the triangle's normal points out of the feature
};

// Which features' enclosing regions a triangle between labels a and b bounds, with its sign.
class FeatureBounds {
 public:
  FeatureBounds(const Nesting& nesting, const MultiLabelMesh& mesh) : parent_(nesting.parent), present_(parent_.size(), 0) {
    for (Label l : mesh.labels)
      if (l != kBackground && l <= present_.size()) present_[l - 1] = 1;
  }

  const std::vector<Bound>& of(Label a, Label b) {
    auto [it, fresh] = cache_.try_emplace(labelPairKey(a, b));
    if (fresh) {
      const std::vector<int> pa = path(a), pb = path(b);
      for (int f : pa)
        if (std::find(pb.begin(), pb.end(), f) == pb.end()) it->second.push_back({f, +1});
      for (int f : pb)
        if (std::find(pa.begin(), pa.end(), f) == pa.end()) it->second.push_back({f, -1});
    }
    return it->second;
  }

 private:
  // The label's feature and its ancestors that have labels in the mesh.
  std::vector<int> path(Label l) const {
    std::vector<int> out;
    for (int f = l == kBackground ? -1 : l - 1; f >= 0 && static_cast<std::size_t>(f) < parent_.size();
         f = parent_[static_cast<std::size_t>(f)])
      if (present_[static_cast<std::size_t>(f)]) out.push_back(f);
    return out;
  }

  const std::vector<int>& parent_;
  std::vector<char> present_;
  std::unordered_map<std::uint32_t, std::vector<Bound>> cache_;
};

Vec3 position(const MultiLabelMesh& mesh, std::uint32_t v) {
  return {mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]};
}

class Restorer {
 public:
  Restorer(MultiLabelMesh& mesh, const Grid& grid, const Nesting& nesting, const std::vector<bool>& onSheet,
           const std::vector<bool>& contourLayers, std::span<const std::uint64_t> held)
      : mesh_(mesh), grid_(grid), bounds_(nesting, mesh), triangleBounds_(mesh.triangleCount()) {
    std::uint32_t last = UINT32_MAX;  // triangles of one pair mostly come together
    const std::vector<Bound>* bounds = nullptr;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
      const std::uint32_t pair = labelPairKey(mesh.labels[2 * t], mesh.labels[2 * t + 1]);
      if (pair != last) bounds = &bounds_.of(mesh.labels[2 * t], mesh.labels[2 * t + 1]), last = pair;
      triangleBounds_[t] = bounds;
    }
    findMovable(onSheet, contourLayers, nesting.parent.size());
    held_.resize(movable_.size());
    for (std::size_t i = 0; i < movable_.size(); ++i)
      held_[i] = std::binary_search(held.begin(), held.end(), mesh.keys[movable_[i]]);
  }
  bool holdsAny() const { return std::find(held_.begin(), held_.end(), 1) != held_.end(); }

  // Per feature, its enclosed volume: sums over fixed blocks of triangles added in block
  // order, so the same for any thread count.
  std::vector<double> volumes(int threads) const {
    const std::size_t n = mesh_.triangleCount(), blocks = (n + kBlock - 1) / kBlock;
    std::vector<std::vector<double>> partial(blocks, std::vector<double>(featureCount_, 0.0));
    parallelChunks(blocks, threads, [&](int, std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k)
        for (std::size_t t = k * kBlock; t < std::min(n, (k + 1) * kBlock); ++t) {
          const std::uint32_t* tri = &mesh_.triangles[3 * t];
          const double six = glm::dot(position(mesh_, tri[0]), glm::cross(position(mesh_, tri[1]), position(mesh_, tri[2])));
          for (const Bound& b : *triangleBounds_[t]) partial[k][static_cast<std::size_t>(b.feature)] += b.sign * six / 6;
        }
    });
    std::vector<double> v(featureCount_, 0.0);
    for (const std::vector<double>& p : partial)
      for (std::size_t f = 0; f < p.size(); ++f) v[f] += p[f];
    return v;
  }

  // One round: every movable vertex of a feature with a deficit (non-zero) along its gradient,
  // the held ones too when asked.
  void round(const std::vector<double>& deficit, bool withHeld, int threads) {
    std::vector<Vec3> gradient(movable_.size());
    std::vector<double> sum(featureCount_, 0.0);
    const auto active = [&](std::size_t i) {
      return deficit[static_cast<std::size_t>(featureOf_[i])] != 0 && (withHeld || !held_[i]);
    };
    parallelChunks(movable_.size(), threads, [&](int, std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i)
        if (active(i)) gradient[i] = alongCarrier(carrierOfKey(mesh_.keys[movable_[i]]), gradientOf(movable_[i]));
    });
    for (std::size_t i = 0; i < movable_.size(); ++i) sum[static_cast<std::size_t>(featureOf_[i])] += glm::length(gradient[i]);
    const double largest = kLargestStep * std::min({grid_.spacingX, grid_.spacingY, smallestGap()});
    std::vector<double> step(featureCount_, 0.0);
    for (std::size_t f = 0; f < featureCount_; ++f)
      if (sum[f] > 0) step[f] = std::clamp(deficit[f] / sum[f], -largest, largest);
    parallelChunks(movable_.size(), threads, [&](int, std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i)
        if (active(i)) move(i, gradient[i], step[static_cast<std::size_t>(featureOf_[i])]);
    });
  }

  std::size_t movableCount() const { return movable_.size(); }
  const IncidentTriangles& incident() const { return incident_; }
  bool movesFeature(std::size_t f) const { return moves_[f] != 0; }

 private:
  // Sheet vertices off the contour planes all of whose triangles bound the same features, all
  // on one side: a feature's own surface, which may also bound the features that enclose it by
  // the nesting (a structure reaching out of its container). Each moves for the innermost of
  // them (a bound list starts with it); the others' volumes follow, and their own vertices take
  // up the change in the next round. An interface between siblings (bounds on both sides) stays.
  void findMovable(const std::vector<bool>& onSheet, const std::vector<bool>& contourLayers, std::size_t features) {
    featureCount_ = features;
    const std::size_t n = mesh_.vertexCount();
    constexpr const std::vector<Bound>* kNone = nullptr;
    const std::vector<Bound> mixed;  // a vertex whose triangles bound different features
    std::vector<const std::vector<Bound>*> only(n, kNone);
    const auto same = [](const std::vector<Bound>& a, const std::vector<Bound>& b) {
      return std::equal(a.begin(), a.end(), b.begin(), b.end(),
                        [](const Bound& x, const Bound& y) { return x.feature == y.feature && x.sign == y.sign; });
    };
    for (std::size_t t = 0; t < mesh_.triangleCount(); ++t) {
      const std::vector<Bound>* b = triangleBounds_[t];
      const bool oneSide =
          !b->empty() && std::all_of(b->begin(), b->end(), [&](const Bound& x) { return x.sign == b->front().sign; });
      for (int k = 0; k < 3; ++k) {
        const std::vector<Bound>*& o = only[mesh_.triangles[3 * t + k]];
        if (!oneSide || (o != kNone && o != b && !same(*o, *b)))
          o = &mixed;
        else if (o == kNone)
          o = b;
      }
    }
    incident_ = incidentTriangles(mesh_);
    moves_.assign(features, 0);
    for (std::size_t v = 0; v < n; ++v)
      if (v < onSheet.size() && onSheet[v] && only[v] != kNone && only[v] != &mixed &&
          !onContourPlane(mesh_.keys[v], contourLayers)) {
        const int feature = only[v]->front().feature;
        movable_.push_back(static_cast<std::uint32_t>(v)), featureOf_.push_back(feature);
        moves_[static_cast<std::size_t>(feature)] = 1;
      }
  }

  // dV/dx_v of v's feature: over its fan, relative to v (the fan is closed: exact).
  Vec3 gradientOf(std::uint32_t v) const {
    const Vec3 origin = position(mesh_, v);
    Vec3 g{0, 0, 0};
    for (std::size_t i = incident_.start[v]; i < incident_.start[v + 1]; ++i) {
      const std::uint32_t t = incident_.list[i];
      const std::uint32_t* tri = &mesh_.triangles[3 * t];
      const int k = tri[0] == v ? 0 : tri[1] == v ? 1 : 2;
      const Vec3 p1 = position(mesh_, mesh_.triangles[3 * t + (k + 1) % 3]) - origin;
      const Vec3 p2 = position(mesh_, mesh_.triangles[3 * t + (k + 2) % 3]) - origin;
      g += static_cast<double>((*triangleBounds_[t])[0].sign) * glm::cross(p1, p2) / 6.0;
    }
    return g;
  }

  // g projected onto the carrier's affine span (its edge's line, its face's plane): the part of
  // a move the carrier keeps, so that the first-order volume change is what the step asks for.
  Vec3 alongCarrier(const Carrier& c, const Vec3& g) const {
    if (c.count == 2) {
      const Vec3 e = cornerPosition(grid_, c.corners[1]) - cornerPosition(grid_, c.corners[0]);
      return e * (glm::dot(g, e) / glm::dot(e, e));
    }
    if (c.count == 3) {
      const Vec3 o = cornerPosition(grid_, c.corners[0]);
      const Vec3 n = glm::cross(cornerPosition(grid_, c.corners[1]) - o, cornerPosition(grid_, c.corners[2]) - o);
      return g - n * (glm::dot(g, n) / glm::dot(n, n));
    }
    return g;
  }

  void move(std::size_t i, const Vec3& gradient, double step) {
    const double length = glm::length(gradient);
    if (step == 0 || length == 0) return;
    const std::uint32_t v = movable_[i];
    const Vec3 p = projectIntoCarrier(grid_, carrierOfKey(mesh_.keys[v]), position(mesh_, v) + gradient * (step / length));
    for (int a = 0; a < 3; ++a) mesh_.positions[3 * v + a] = static_cast<float>(p[a]);
  }

  double smallestGap() const {
    double gap = grid_.spacingX;
    for (std::size_t k = 0; k + 1 < grid_.layerZ.size(); ++k) gap = std::min(gap, grid_.layerZ[k + 1] - grid_.layerZ[k]);
    return gap;
  }

  MultiLabelMesh& mesh_;
  const Grid& grid_;
  FeatureBounds bounds_;
  std::vector<const std::vector<Bound>*> triangleBounds_;
  std::size_t featureCount_ = 0;
  IncidentTriangles incident_;
  std::vector<std::uint32_t> movable_;
  std::vector<int> featureOf_;
  std::vector<char> held_;   // per movable vertex: it moves only with the held ones (round)
  std::vector<char> moves_;  // per feature: it has movable vertices
};

double worstError(const std::vector<double>& volumes, std::span<const double> targets, const std::vector<char>& restored) {
  double worst = 0;
  for (std::size_t f = 0; f < restored.size(); ++f)
    if (restored[f]) worst = std::max(worst, std::abs(volumes[f] - targets[f]) / targets[f]);
  return worst;
}

}  // namespace

VolumeRestorationReport restoreVolumes(MultiLabelMesh& mesh, const Grid& grid, const Nesting& nesting,
                                       std::span<const double> targets, const std::vector<bool>& onSheet,
                                       const std::vector<bool>& contourLayers, double minAngle, int threads,
                                       const CubeDisks* disks, std::span<const std::uint64_t> held) {
  VolumeRestorationReport report;
  if (mesh.keys.size() != mesh.vertexCount() || mesh.triangleCount() == 0) return report;
  Restorer restorer(mesh, grid, nesting, onSheet, contourLayers, held);
  std::vector<char> restored(nesting.parent.size(), 0);
  for (std::size_t f = 0; f < restored.size(); ++f) {
    restored[f] = f < targets.size() && targets[f] > 0 && restorer.movesFeature(f);
    report.features += restored[f];
  }
  if (report.features == 0) return report;
  AngleGuard guard(mesh, minAngle, threads, &restorer.incident());
  std::vector<float> before;
  if (disks && disks->count() == 0) disks = nullptr;  // nothing to keep unfolded: no copy of the positions a round
  std::vector<double> volumes = restorer.volumes(threads);
  report.worstBefore = worstError(volumes, targets, restored);
  for (const bool withHeld : {false, true}) {
    if (!withHeld && !restorer.holdsAny()) continue;  // one pass, every vertex
    for (int r = 0; r < kRounds && worstError(volumes, targets, restored) > kClose; ++r) {
      std::vector<double> deficit(restored.size(), 0.0);
      for (std::size_t f = 0; f < restored.size(); ++f)
        if (restored[f] && std::abs(volumes[f] - targets[f]) > kClose * targets[f]) deficit[f] = targets[f] - volumes[f];
      if (guard.enabled() || disks) before = mesh.positions;
      restorer.round(deficit, withHeld, threads);
      guard.apply(before.data(), mesh.positions.data(), 3);
      if (disks) report.heldBack += keepDisksEmbedded(*disks, mesh, before, threads);
      volumes = restorer.volumes(threads);
    }
  }
  report.worstAfter = worstError(volumes, targets, restored);
  report.movedVertices = restorer.movableCount();
  return report;
}

}  // namespace scansurf
