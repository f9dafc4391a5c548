// scansurf CLI: what a run tells the user on stdout (see summary.h).
#include "summary.h"

#include "safe_text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace fs = std::filesystem;

namespace scansurf::cli {

const char* conventionName(SurfaceConvention c) { return c == SurfaceConvention::Enclosing ? "enclosing" : "partition"; }

namespace {

std::vector<std::string> printableNames(const ContourSet& set) {
  std::vector<std::string> names;
  for (const Feature& f : set.features) names.push_back(printable(f.name));
  return names;
}

// One decimal for mm-scale volumes; four significant digits for small ones (µm³ of EM data).
std::string formatVolume(double volume) {
  char text[32];
  std::snprintf(text, sizeof text, std::abs(volume) >= 100 ? "%.1f" : "%.4g", volume);
  return text;
}

// " (surface volume differs from the contour volume by X %)" when it does by more than 1 %.
std::string volumeFlag(double surface, double contour) {
  if (contour <= 0 || std::abs(surface - contour) <= 0.01 * contour) return {};
  char text[96];
  std::snprintf(text, sizeof text, "  (surface volume %+.1f %% from the contour volume)", 100.0 * (surface - contour) / contour);
  return text;
}

// "; in 6 chunks and 5 bands" when remeshing split the work, else nothing.
std::string chunksNote(const RemeshReport& r) {
  if (r.bands == 0) return "";  // remeshed whole (each layer, with overlaps as layers)
  char note[64];
  std::snprintf(note, sizeof note, "; in %zu chunks and %zu bands", r.chunks, r.bands);
  return note;
}

// The shared volume in percent of the smaller structure's own volume.
double percentOfSmaller(const OverlapReport& report, const SharedVolume& s) {
  const double smaller = std::min(report.features[static_cast<std::size_t>(s.a)].ownVolume,
                                  report.features[static_cast<std::size_t>(s.b)].ownVolume);
  return smaller > 0 ? 100.0 * s.volume / smaller : 0.0;
}

// "0.09 % of rectum": the shared volume against the smaller structure's own volume.
std::string shareOfSmaller(const OverlapReport& report, const SharedVolume& s, const std::vector<std::string>& names) {
  const bool aSmaller =
      report.features[static_cast<std::size_t>(s.a)].ownVolume <= report.features[static_cast<std::size_t>(s.b)].ownVolume;
  char text[160];
  std::snprintf(text, sizeof text, "%.2f %% of %s", percentOfSmaller(report, s),
                names[static_cast<std::size_t>(aSmaller ? s.a : s.b)].c_str());
  return text;
}

// What the overlap rule made of a pair, and why.
std::string verdictOf(const OverlapReport& report, const SharedVolume& s) {
  if (s.nested) return "nested: one holds the other";
  if (!report.tolerance.enabled) return "real: separate layers (tolerance off)";
  if (s.incidental) return "incidental: one layer, shared voxels split";
  if (percentOfSmaller(report, s) > report.tolerance.percent) return "real: separate layers (too large)";
  return "real: separate layers (too deep)";
}

// "mm3" for the input's unit cubed, else the chosen unit ("cm^3" printed "cm3").
std::string volumeUnitText(const ContourSet& set, const VolumeUnit& unit) {
  if (unit.name.empty()) return printable(set.units) + "3";
  std::string text = unit.name;
  std::erase(text, '^');
  return text;
}

void printOverlaps(const ContourSet& set, const OverlapReport& report, const VolumeUnit& unit) {
  const std::vector<std::string> names = printableNames(set);
  const auto name = [&](int f) { return names[static_cast<std::size_t>(f)].c_str(); };
  const std::string unitText = printable(set.units), volumeText = volumeUnitText(set, unit);
  const char* units = volumeText.c_str();
  const auto volume = [&](double v) { return formatVolume(v * unit.scale); };
  for (const SharedVolume& s : report.partialOverlaps()) {
    const std::string share = shareOfSmaller(report, s, names);
    const std::string depth = s.depthMeasured
                                  ? "at most " + formatVolume(s.depth) + " " + unitText + " deep"
                                  : "deeper, in regions of at most " + formatVolume(report.tolerance.percent / 2) + " %";
    if (s.incidental && report.mode == OverlapMode::Layers)
      std::printf("overlap: %s and %s share %s %s (%s, %s): incidental, split between them (%s gave up %s %s, %s %s %s)\n",
                  name(s.a), name(s.b), volume(s.volume).c_str(), units, share.c_str(), depth.c_str(), name(s.a),
                  volume(s.givenUpByA).c_str(), units, name(s.b), volume(s.givenUpByB).c_str(), units);
    else
      std::printf("overlap: %s and %s share %s %s (%s): %s\n", name(s.a), name(s.b), volume(s.volume).c_str(), units,
                  share.c_str(),
                  report.mode == OverlapMode::Layers ? "surfaced in separate layers" : "the partition gives it to one");
  }
  for (const VolumeLoss& l : report.losses) {
    if (l.nested) continue;  // a container's shell around what it holds: the convention, not a loss
    const double contour = report.features[static_cast<std::size_t>(l.feature)].contour;
    std::printf("partition: %s lost %s %s (%.2f %% of its contour volume) to %s\n", name(l.feature), volume(l.volume).c_str(),
                units, contour > 0 ? 100.0 * l.volume / contour : 0.0, l.to >= 0 ? name(l.to) : "background");
  }
}

}  // namespace

void printOverlapList(const ContourSet& set, const OverlapReport& report, double depthLimit) {
  const std::vector<std::string> names = printableNames(set);
  const std::string units = printable(set.units);
  if (report.tolerance.enabled)
    std::printf(
        "%s: %zu features; a partial overlap is incidental when it is at most %s %% of the smaller feature and "
        "each connected region of it lies within %s %s of the nearer outline or is at most %s %%\n",
        printable(set.source).c_str(), set.features.size(), formatVolume(report.tolerance.percent).c_str(),
        formatVolume(depthLimit).c_str(), units.c_str(), formatVolume(report.tolerance.percent / 2).c_str());
  else
    std::printf("%s: %zu features; overlap tolerance off: every partial overlap is real\n", printable(set.source).c_str(),
                set.features.size());
  std::printf("  %-20s %-20s %14s %24s %12s %7s  %s\n", "feature", "with", ("shared " + units + "3").c_str(), "of the smaller",
              ("depth " + units).c_str(), "regions", "verdict");
  for (const SharedVolume& s : report.shared) {
    const std::string depth = s.depthMeasured ? formatVolume(s.depth) : "-";
    const std::string regions = s.nested || !report.tolerance.enabled ? "-" : std::to_string(s.regions);
    std::printf("  %-20s %-20s %14s %24s %12s %7s  %s\n", names[static_cast<std::size_t>(s.a)].c_str(),
                names[static_cast<std::size_t>(s.b)].c_str(), formatVolume(s.volume).c_str(),
                shareOfSmaller(report, s, names).c_str(), depth.c_str(), regions.c_str(), verdictOf(report, s).c_str());
  }
  if (report.shared.empty()) std::printf("  no two features share a voxel\n");
  std::printf("surface layers: %d\n", report.layers);
}

void printSummary(const RunFacts& facts, const std::vector<fs::path>& written, const std::string& outDir) {
  const ContourSet& set = *facts.contours;
  const BuildResult& built = *facts.built;
  const Grid& g = built.volume.grid;
  std::printf("grid: %d x %d x %d voxels (%g x %g %s pixels, %d slices, 1-voxel background border)\n", g.nx, g.ny, g.nz,
              g.spacingX, g.spacingY, printable(set.units).c_str(), g.nz - 2);
  const InterpolationSummary& in = built.interpolation;
  if (in.used())
    std::printf("interpolation: %d layers surfaced (%d to %d per slice gap, %s caps); the contour planes are %d of them\n",
                in.surfacedLayers, in.minFactor, in.maxFactor, in.caps == CapShape::Flat ? "flat" : "round", in.planeLayers);
  std::printf("nesting order (%s, innermost first):", built.nesting.userOrder ? "from input" : "computed");
  for (int f : built.nesting.order) std::printf(" %s", printable(set.features[static_cast<std::size_t>(f)].name).c_str());
  std::printf("\nsurfaces (%s convention, overlaps as %s: %d layer%s): %zu vertices, %zu triangles in the multi-label mesh\n",
              conventionName(facts.convention), overlapModeName(built.overlaps.mode), built.overlaps.layers,
              built.overlaps.layers == 1 ? "" : "s", built.surfaces.mesh.vertexCount(), built.surfaces.mesh.triangleCount());
  const std::string volumeText = volumeUnitText(set, facts.volumeUnit);
  const double scale = facts.volumeUnit.scale;
  std::printf("  %-20s %6s %5s %10s %14s %14s %10s %6s %s\n", "feature", "label", "layer", "triangles",
              ("volume " + volumeText).c_str(), ("contour " + volumeText).c_str(), "components", "genus", "closed");
  for (std::size_t f = 0; f < set.features.size(); ++f) {
    const MeshStats& s = facts.stats[f];
    const FeatureVolumes& v = built.overlaps.features[f];
    std::printf("  %-20s %6d %5d %10zu %14s %14s %10d %6d %s%s\n", printable(set.features[f].name).c_str(),
                labelOfFeature(static_cast<int>(f)), v.layer, s.triangles, formatVolume(s.volume * scale).c_str(),
                formatVolume(v.contour * scale).c_str(), s.components, s.genus,
                s.closed && s.manifold && s.oriented ? "yes" : "NO", volumeFlag(s.volume, v.contour).c_str());
  }
  std::size_t empty = 0;
  for (const MeshStats& s : facts.stats) empty += s.triangles == 0;
  if (empty > 0)
    std::printf(
        "%zu of %zu features have no surface: they cover no voxel centre of this grid (%g %s pixels); a finer "
        "--voxel-size gives them one\n",
        empty, set.features.size(), g.spacingX, printable(set.units).c_str());
  printOverlaps(set, built.overlaps, facts.volumeUnit);
  if (const TriangleShapeReport& r = built.surfaces.triangleShape; r.ran)
    std::printf(
        "triangle shape: %zu of %zu crowded voxel centres snapped, %zu vertices merged into them, %zu triangles gone; "
        "%zu quads re-split; %zu cubes and blocks re-triangulated from their rims, %zu vertices and %zu triangles fewer "
        "(%.3f s)\n",
        r.points, r.candidates, r.mergedVertices, r.removedTriangles, r.quadsFlipped, r.cubeFans, r.fanVerticesRemoved,
        2 * r.fanVerticesRemoved, r.seconds);
  if (const SimplificationReport& r = built.surfaces.simplification; r.ran)
    std::printf(
        "simplification: %zu -> %zu triangles; smallest angle %.1f -> %.1f deg, 5th percentile %.1f -> %.1f, mean %.1f -> "
        "%.1f; %zu of %zu patches kept as smoothed (%zu by their checks, %zu crossing)\n",
        r.trianglesBefore, r.trianglesAfter, r.anglesBefore.min, r.anglesAfter.min, r.anglesBefore.p5, r.anglesAfter.p5,
        r.anglesBefore.mean, r.anglesAfter.mean, r.refused + r.crossing, r.patches, r.refused, r.crossing);
  if (const RemeshReport& r = built.surfaces.remeshing; r.ran)
    std::printf(
        "remeshing (edge length %g %s): %zu -> %zu triangles; smallest angle %.1f -> %.1f deg, 5th percentile %.1f -> "
        "%.1f, mean %.1f -> %.1f; at most %.3g %s from the smoothed surface%s\n",
        r.edgeLength, printable(set.units).c_str(), r.trianglesBefore, r.trianglesAfter, r.anglesBefore.min, r.anglesAfter.min,
        r.anglesBefore.p5, r.anglesAfter.p5, r.anglesBefore.mean, r.anglesAfter.mean, r.maxDistance, printable(set.units).c_str(),
        chunksNote(r).c_str());
  double total = 0;
  std::printf("time:");
  for (const StageTime& t : facts.timings) {
    std::printf(" %s %.3f s;", t.stage.c_str(), t.seconds);
    total += t.seconds;
  }
  std::printf(" total %.3f s\nwrote %zu files", total, written.size());
  if (written.size() <= 4)  // e.g. -o x.glb --preview x.png: name them
    for (const fs::path& p : written) std::printf(" %s", p.c_str());
  else
    std::printf(" to %s", outDir.c_str());
  std::printf("\n");
}

}  // namespace scansurf::cli
