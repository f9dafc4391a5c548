// scansurf: moves that keep triangles well shaped (see angle_guard.h). The rule is monotone (a
// triangle may lose angle only while it stays above the limit), so a mesh that starts above
// the limit stays above it through every placement, sweep and restoration round, and one that
// starts below it (thick slices without interpolation) never gets worse there.
#include "geometry/smoothing/angle_guard.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/parallel.h"

namespace scansurf {
namespace {

constexpr int kPulls = 20;                   // pulls back before a move is given up
constexpr float kKeep = 0.8f;                // what each pull keeps of the move
constexpr std::size_t kSerialBelow = 16384;  // candidate triangles worth a fork-join

struct Edges {
  float ab[3], bc[3], ca[3];
  float lab, lbc, lca;  // squared lengths
};

float dot(const float* u, const float* v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; }

Edges edgesOf(const float* p, const std::uint32_t* tri, int stride) {
  const float* a = p + static_cast<std::size_t>(tri[0]) * stride;
  const float* b = p + static_cast<std::size_t>(tri[1]) * stride;
  const float* c = p + static_cast<std::size_t>(tri[2]) * stride;
  Edges e;
  for (int k = 0; k < 3; ++k) e.ab[k] = b[k] - a[k], e.bc[k] = c[k] - b[k], e.ca[k] = a[k] - c[k];
  e.lab = dot(e.ab, e.ab), e.lbc = dot(e.bc, e.bc), e.lca = dot(e.ca, e.ca);
  return e;
}

// Whether a corner's cosine exceeds `limit` > 0, without a root: cos = d / sqrt(l1 l2) > limit.
bool sharperThan(float d, float l1, float l2, float limit) { return d > 0 && d * d > limit * limit * l1 * l2; }

// Whether some corner is sharper than the limit (or the triangle is degenerate).
bool anyCornerSharper(const Edges& e, float limit) {
  if (!(e.lab > 0 && e.lbc > 0 && e.lca > 0)) return true;
  return sharperThan(-dot(e.ab, e.ca), e.lab, e.lca, limit) || sharperThan(-dot(e.ab, e.bc), e.lab, e.lbc, limit) ||
         sharperThan(-dot(e.bc, e.ca), e.lbc, e.lca, limit);
}

// The largest cosine of the triangle's three corners, 1 where it is degenerate: its smallest
// angle is the arc cosine of that.
float sharpestCosine(const Edges& e) {
  if (!(e.lab > 0 && e.lbc > 0 && e.lca > 0)) return 1;
  return std::max({-dot(e.ab, e.ca) / std::sqrt(e.lab * e.lca), -dot(e.ab, e.bc) / std::sqrt(e.lab * e.lbc),
                   -dot(e.bc, e.ca) / std::sqrt(e.lbc * e.lca)});
}

bool moved(const float* before, const float* after, std::size_t v, int stride) {
  for (int k = 0; k < stride; ++k)
    if (before[v * stride + k] != after[v * stride + k]) return true;
  return false;
}

}  // namespace

AngleGuard::AngleGuard(const MultiLabelMesh& mesh, double limitDegrees, int threads, const IncidentTriangles* incident)
    : mesh_(mesh),
      vertexCount_(mesh.vertexCount()),
      limitCosine_(limitDegrees > 0 ? static_cast<float>(std::cos(limitDegrees * std::numbers::pi / 180)) : 1.0f),
      threads_(threads),
      ownIncident_(enabled() && !incident ? incidentTriangles(mesh) : IncidentTriangles{}),
      incident_(incident ? *incident : ownIncident_) {}

std::vector<std::uint32_t> AngleGuard::trianglesAround(std::span<const std::uint32_t> vertices) const {
  std::vector<std::uint8_t> seen(mesh_.triangleCount(), 0);
  std::vector<std::uint32_t> triangles;
  appendTrianglesAround(vertices, seen, triangles);
  std::sort(triangles.begin(), triangles.end());
  return triangles;
}

// Appends the triangles of these vertices not yet `seen` (and marks them).
void AngleGuard::appendTrianglesAround(std::span<const std::uint32_t> vertices, std::vector<std::uint8_t>& seen,
                                       std::vector<std::uint32_t>& out) const {
  for (std::uint32_t v : vertices)
    for (std::uint32_t i = incident_.start[v]; i < incident_.start[v + 1]; ++i) {
      const std::uint32_t t = incident_.list[i];
      if (!seen[t]) seen[t] = 1, out.push_back(t);
    }
}

// The candidates (all: every triangle) that are too sharp, in per-chunk lists. Small lists run
// on the calling thread: a round after the first touches a few hundred triangles.
void AngleGuard::findSharp(const float* before, const float* after, int stride, std::span<const std::uint32_t> candidates,
                           bool all, std::vector<std::vector<std::uint32_t>>& sharp) const {
  const std::size_t count = all ? mesh_.triangleCount() : candidates.size();
  const int threads = count < kSerialBelow ? 1 : threads_;
  sharp.resize(static_cast<std::size_t>(chunkCount(count, threads)));
  parallelChunks(count, threads, [&](int chunk, std::size_t begin, std::size_t end) {
    std::vector<std::uint32_t>& out = sharp[static_cast<std::size_t>(chunk)];
    out.clear();
    for (std::size_t i = begin; i < end; ++i) {
      const std::uint32_t t = all ? static_cast<std::uint32_t>(i) : candidates[i];
      const std::uint32_t* tri = &mesh_.triangles[3 * static_cast<std::size_t>(t)];
      const Edges now = edgesOf(after, tri, stride);
      if (anyCornerSharper(now, limitCosine_) && sharpestCosine(now) > sharpestCosine(edgesOf(before, tri, stride)))
        out.push_back(t);
    }
  });
}

std::size_t AngleGuard::apply(const float* before, float* after, int stride, const std::vector<std::uint32_t>* watched) {
  if (!enabled()) return 0;
  // Scratch kept between calls (zero outside a call): pulls so far per vertex, whether a
  // vertex is in this round's list, whether a triangle is in the next round's candidates.
  pulls_.resize(vertexCount_, 0), inRound_.resize(vertexCount_, 0), seen_.resize(mesh_.triangleCount(), 0);
  std::vector<std::uint8_t>&pulls = pulls_, &inRound = inRound_, &seen = seen_;
  std::vector<std::vector<std::uint32_t>> sharp;
  std::vector<std::uint32_t> candidates, pulled, everPulled;
  // The watched triangles first (null: every one), then those around the vertices just pulled back.
  findSharp(before, after, stride, watched ? std::span<const std::uint32_t>(*watched) : std::span<const std::uint32_t>(),
            !watched, sharp);
  for (;;) {
    pulled.clear();
    for (const std::vector<std::uint32_t>& list : sharp)
      for (std::uint32_t t : list)
        for (int k = 0; k < 3; ++k) {
          const std::uint32_t v = mesh_.triangles[3 * static_cast<std::size_t>(t) + k];
          if (!inRound[v] && moved(before, after, v, stride)) inRound[v] = 1, pulled.push_back(v);
        }
    if (pulled.empty()) break;
    for (std::uint32_t v : pulled) {
      inRound[v] = 0;
      if (pulls[v] == 0) everPulled.push_back(v);
      const bool giveUp = ++pulls[v] > kPulls;
      for (int k = 0; k < stride; ++k) {
        const std::size_t i = static_cast<std::size_t>(v) * stride + k;
        after[i] = giveUp ? before[i] : before[i] + kKeep * (after[i] - before[i]);
      }
    }
    candidates.clear();
    appendTrianglesAround(pulled, seen, candidates);
    for (std::uint32_t t : candidates) seen[t] = 0;
    findSharp(before, after, stride, candidates, false, sharp);
  }
  for (std::uint32_t v : everPulled) pulls[v] = 0;
  return everPulled.size();
}

}  // namespace scansurf
