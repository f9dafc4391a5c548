// scansurf: the audit of every feature's surface (surface_audit.h). The statistics come from
// computeFeatureStats; the expected topology from the slab volume of the feature's own region
// (contour_topology.h), features in parallel.
#include "geometry/audit/surface_audit.h"

#include <atomic>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/parallel.h"
#include "geometry/audit/contour_topology.h"
#include "geometry/contours/validate.h"

namespace scansurf {
namespace {

std::string range(int lo, int hi) { return lo == hi ? std::to_string(lo) : std::to_string(lo) + " to " + std::to_string(hi); }

// The nearer end of [lo, hi] to `value`.
int nearer(int lo, int hi, int value) { return value < lo ? lo : hi; }

void addDefects(const ContourSet& contours, int f, const MeshStats& s, std::vector<AuditFinding>& out) {
  const std::string who = describeFeature(contours, f);
  if (!s.closed)
    out.push_back({f, AuditCheck::Open, true, 0, 1, who + ": its surface is open (an edge with other than two triangles)"});
  else if (!s.manifold)
    out.push_back({f, AuditCheck::NotManifold, true, 0, 1,
                   who + ": its surface is not manifold (a vertex whose triangles form more than one fan)"});
  if (s.closed && !s.oriented)
    out.push_back({f, AuditCheck::NotOriented, true, 0, 1, who + ": its surface is not consistently oriented"});
}

void addTopology(const ContourSet& contours, int f, const MeshStats& s, const ExpectedTopology& e,
                 std::vector<AuditFinding>& out) {
  const std::string who = describeFeature(contours, f);
  if (s.components < e.minComponents || s.components > e.maxComponents)
    out.push_back({f, AuditCheck::Components, false, static_cast<double>(nearer(e.minComponents, e.maxComponents, s.components)),
                   static_cast<double>(s.components),
                   who + ": " + std::to_string(s.components) + " surface components where its contours imply " +
                       range(e.minComponents, e.maxComponents)});
  if (s.genus < e.minGenus || s.genus > e.maxGenus)
    out.push_back(
        {f, AuditCheck::Genus, false, static_cast<double>(nearer(e.minGenus, e.maxGenus, s.genus)), static_cast<double>(s.genus),
         who + ": surface genus " + std::to_string(s.genus) + " where its contours imply " + range(e.minGenus, e.maxGenus)});
}

void addVolume(const ContourSet& contours, int f, double found, double target, const AuditInputs& in,
               std::vector<AuditFinding>& out) {
  const double off = found - target;
  if (target <= 0 || std::abs(off) <= in.volumeFloor || std::abs(off) <= in.volumeTolerance * target) return;
  char text[160];
  std::snprintf(text, sizeof text, ": surface volume %.6g where its contours' slab volume is %.6g (%+.1f %%)", found, target,
                100.0 * off / target);
  out.push_back({f, AuditCheck::Volume, false, target, found, describeFeature(contours, f) + text});
}

std::vector<ExpectedTopology> expectedTopologies(std::span<const FeatureRegion> regions, int threads) {
  std::vector<ExpectedTopology> out(regions.size());
  std::atomic<std::size_t> next{0};
  const int workers = chunkCount(regions.size(), threads);
  parallelChunks(static_cast<std::size_t>(workers), workers, [&](int, std::size_t, std::size_t) {
    for (std::size_t i = next++; i < regions.size(); i = next++) {
      const TopologyRange r = contourTopology(regions[i]);
      out[i] = {r.minComponents, r.maxComponents, r.minGenus, r.maxGenus, !r.empty()};
    }
  });
  return out;
}

}  // namespace

const char* auditCheckName(AuditCheck check) noexcept {
  switch (check) {
    case AuditCheck::Open: return "open";
    case AuditCheck::NotManifold: return "not manifold";
    case AuditCheck::NotOriented: return "not oriented";
    case AuditCheck::Components: return "components";
    case AuditCheck::Genus: return "genus";
    case AuditCheck::Volume: return "volume";
  }
  return "check";
}

SurfaceAudit auditSurfaces(const AuditInputs& in) {
  SurfaceAudit audit;
  audit.stats = computeFeatureStats(in.surfaces, in.threads);
  audit.expected =
      in.regions.empty() ? std::vector<ExpectedTopology>(audit.stats.size()) : expectedTopologies(in.regions, in.threads);
  audit.targetVolumes = in.targetVolumes;
  audit.volumeTolerance = in.volumeTolerance;
  for (std::size_t i = 0; i < audit.stats.size(); ++i) {
    const MeshStats& s = audit.stats[i];
    const int f = static_cast<int>(i);
    if (s.triangles == 0) continue;  // no surface: warned about already
    addDefects(in.contours, f, s, audit.findings);
    if (!s.closed || !s.manifold) continue;
    if (i < audit.expected.size() && audit.expected[i].checked) addTopology(in.contours, f, s, audit.expected[i], audit.findings);
    if (i < in.targetVolumes.size()) addVolume(in.contours, f, s.volume, in.targetVolumes[i], in, audit.findings);
  }
  return audit;
}

}  // namespace scansurf
