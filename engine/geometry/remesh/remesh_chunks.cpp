// Chunks and bands of the parallel remeshing (remesh_chunks.h): planning, cutting out, merging.
#include "geometry/remesh/remesh_chunks.h"

#include <algorithm>
#include <cmath>

namespace scansurf::remesh {
namespace {

// Band half-width around a cut: three target lengths beyond the tallest input triangle, so the
// band frees every triangle phase 0 pinned on the cut and a few rows of the ones it had to
// shape around them.
constexpr double kBandLengths = 3.0;
// Chunks at least this many band half-widths thick: the bands' regions (four half-widths) stay
// apart.
constexpr double kChunkBands = 5.0;

float zOf(const MultiLabelMesh& mesh, std::uint32_t v) { return mesh.positions[3 * v + 2]; }

void zRange(const MultiLabelMesh& mesh, std::size_t t, float& lo, float& hi) {
  lo = hi = zOf(mesh, mesh.triangles[3 * t]);
  for (int c = 1; c < 3; ++c) {
    const float z = zOf(mesh, mesh.triangles[3 * t + c]);
    lo = std::min(lo, z), hi = std::max(hi, z);
  }
}

}  // namespace

ChunkPlan planChunks(const MultiLabelMesh& mesh, double edgeLength, std::size_t trianglesPerChunk) {
  ChunkPlan plan;
  plan.phases[0].push_back(WorkUnit{});
  plan.phases[0][0].triangles = mesh.triangleCount();
  const std::size_t n = mesh.triangleCount(), chunks = trianglesPerChunk ? n / trianglesPerChunk : 0;
  if (chunks < 2) return plan;
  std::vector<float> centre(n);
  float tallest = 0;
  for (std::size_t t = 0; t < n; ++t) {
    float lo = 0, hi = 0;
    zRange(mesh, t, lo, hi);
    centre[t] = 0.5f * (lo + hi);
    tallest = std::max(tallest, hi - lo);
  }
  std::sort(centre.begin(), centre.end());
  const double band = kBandLengths * edgeLength + tallest, thickness = kChunkBands * band;
  // As many chunks as fit `thickness` apart, cut at triangle-count quantiles, each moved into
  // the range that leaves the chunks before and after it their thickness.
  const auto count = std::min<std::size_t>(chunks, static_cast<std::size_t>((centre.back() - centre.front()) / thickness));
  std::vector<double> cuts;
  for (std::size_t s = 1; s < count; ++s) {
    const double earliest = (cuts.empty() ? centre.front() : cuts.back()) + thickness;
    const double latest = centre.back() - static_cast<double>(count - s) * thickness;
    cuts.push_back(std::clamp<double>(centre[s * n / count], earliest, std::max(earliest, latest)));
  }
  if (cuts.empty()) return plan;
  plan.phases[0].clear();
  for (std::size_t i = 0; i <= cuts.size(); ++i) {
    WorkUnit u;
    if (i > 0) u.lo = u.freeLo = cuts[i - 1];
    if (i < cuts.size()) u.hi = u.freeHi = cuts[i];
    plan.phases[0].push_back(u);
  }
  for (double c : cuts) plan.phases[1].push_back({c - 2 * band, c + 2 * band, c - band, c + band});
  for (auto& phase : plan.phases)
    for (WorkUnit& u : phase)
      u.triangles = static_cast<std::size_t>(std::lower_bound(centre.begin(), centre.end(), u.freeHi) -
                                             std::lower_bound(centre.begin(), centre.end(), u.freeLo));
  return plan;
}

std::vector<std::uint32_t> vertexValence(const MultiLabelMesh& mesh) {
  std::vector<std::uint32_t> valence(mesh.vertexCount(), 0);
  for (std::uint32_t v : mesh.triangles) ++valence[v];
  return valence;
}

SubMesh extractUnit(const MultiLabelMesh& mesh, const std::vector<std::uint32_t>& valence, const std::vector<char>& settled,
                    const WorkUnit& unit) {
  SubMesh sub;
  const std::size_t n = mesh.triangleCount();
  std::vector<std::uint32_t> localOf(mesh.vertexCount(), UINT32_MAX);
  std::vector<std::uint32_t> taken;
  std::vector<char> pinnedGlobal(mesh.vertexCount(), 0);
  for (std::size_t t = 0; t < n; ++t) {
    float lo = 0, hi = 0;
    zRange(mesh, t, lo, hi);
    if (hi < unit.lo || lo > unit.hi) continue;
    taken.push_back(static_cast<std::uint32_t>(t));
    const bool inside = lo > unit.lo && hi < unit.hi;
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t v = mesh.triangles[3 * t + c];
      localOf[v] = 0;
      const double z = zOf(mesh, v);
      if (!inside || !(z > unit.freeLo && z < unit.freeHi)) pinnedGlobal[v] = 1;
    }
  }
  // Local ids in the whole mesh's vertex order: the remesher visits edges in that order.
  std::vector<std::uint32_t> uses(mesh.vertexCount(), 0);
  for (std::uint32_t t : taken)
    for (int c = 0; c < 3; ++c) ++uses[mesh.triangles[3 * t + c]];
  for (std::uint32_t v = 0; v < mesh.vertexCount(); ++v) {
    if (localOf[v] == UINT32_MAX) continue;
    localOf[v] = static_cast<std::uint32_t>(sub.globalVertex.size());
    sub.globalVertex.push_back(v);
    sub.pinned.push_back(pinnedGlobal[v]);
    sub.rim.push_back(uses[v] != valence[v]);
    sub.settled.push_back(v < settled.size() && settled[v]);
    for (int k = 0; k < 3; ++k) sub.mesh.positions.push_back(mesh.positions[3 * v + k]);
  }
  for (std::uint32_t t : taken) {
    std::array<std::uint32_t, 4> key{};
    bool editable = false;
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t v = mesh.triangles[3 * t + c];
      key[c] = localOf[v];
      sub.mesh.triangles.push_back(localOf[v]);
      editable |= !pinnedGlobal[v];
    }
    sub.mesh.labels.push_back(mesh.labels[2 * t]);
    sub.mesh.labels.push_back(mesh.labels[2 * t + 1]);
    if (editable) {
      sub.editable.push_back(t);
      continue;
    }
    std::sort(key.begin(), key.begin() + 3);
    key[3] = labelPairKey(mesh.labels[2 * t], mesh.labels[2 * t + 1]);
    sub.fixed.push_back(key);
  }
  std::sort(sub.fixed.begin(), sub.fixed.end());
  return sub;
}

void mergeUnits(MultiLabelMesh& mesh, const std::vector<SubMesh>& subs, const std::vector<UnitResult>& results,
                std::vector<char>& settled) {
  std::vector<char> replaced(mesh.triangleCount(), 0);
  for (const SubMesh& s : subs)
    for (std::uint32_t t : s.editable) replaced[t] = 1;
  MultiLabelMesh out;
  out.positions = std::move(mesh.positions);
  for (std::size_t t = 0; t < replaced.size(); ++t) {
    if (replaced[t]) continue;
    for (int c = 0; c < 3; ++c) out.triangles.push_back(mesh.triangles[3 * t + c]);
    out.labels.push_back(mesh.labels[2 * t]);
    out.labels.push_back(mesh.labels[2 * t + 1]);
  }
  for (std::size_t u = 0; u < subs.size(); ++u) {
    const SubMesh& s = subs[u];
    const UnitResult& r = results[u];
    std::vector<std::uint32_t> globalOf(r.positions.size());
    for (std::size_t v = 0; v < r.positions.size(); ++v) {
      if (v < s.globalVertex.size()) {
        globalOf[v] = s.globalVertex[v];
        if (s.pinned[v]) continue;  // as it was, and maybe another unit's
      } else {
        globalOf[v] = static_cast<std::uint32_t>(out.positions.size() / 3);
        out.positions.resize(out.positions.size() + 3);
      }
      for (int k = 0; k < 3; ++k) out.positions[3 * globalOf[v] + k] = static_cast<float>(r.positions[v][k]);
      if (settled.size() <= globalOf[v]) settled.resize(out.positions.size() / 3, 0);
      settled[globalOf[v]] = 1;
    }
    for (std::size_t t = 0; t < r.triangles.size(); ++t) {
      for (std::uint32_t v : r.triangles[t]) out.triangles.push_back(globalOf[v]);
      out.labels.push_back(static_cast<Label>(r.pairs[t] & 0xffff));
      out.labels.push_back(static_cast<Label>(r.pairs[t] >> 16));
    }
  }
  mesh = std::move(out);
}

void compactVertices(MultiLabelMesh& mesh) {
  std::vector<std::uint32_t> remap(mesh.vertexCount(), UINT32_MAX);
  for (std::uint32_t v : mesh.triangles) remap[v] = 0;
  std::uint32_t next = 0;
  for (std::size_t v = 0; v < remap.size(); ++v) {
    if (remap[v] == UINT32_MAX) continue;
    remap[v] = next;
    for (int k = 0; k < 3; ++k) mesh.positions[3 * next + k] = mesh.positions[3 * v + k];
    ++next;
  }
  mesh.positions.resize(3 * static_cast<std::size_t>(next));
  for (std::uint32_t& v : mesh.triangles) v = remap[v];
}

}  // namespace scansurf::remesh
