// scansurf: the run report (scansurf/report.h).
#include "scansurf/report.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <set>

#include "io/atomic_file.h"
#include "io/file_hash.h"
#include "io/length_units.h"
#include "scansurf/palette.h"
#include "scansurf/version.h"

namespace scansurf {

namespace fs = std::filesystem;

namespace {

// Per feature, the names of the features on the other side of its separating surfaces.
std::vector<std::vector<std::string>> surfaceNeighbours(const ContourSet& contours, const MultiLabelMesh& mesh) {
  std::set<std::pair<Label, Label>> pairs;
  for (std::size_t t = 0; t + 1 < mesh.labels.size(); t += 2)
    if (mesh.labels[t] != kBackground && mesh.labels[t + 1] != kBackground) pairs.emplace(mesh.labels[t], mesh.labels[t + 1]);
  std::vector<std::vector<std::string>> out(contours.features.size());
  const auto name = [&](Label l) { return contours.features[static_cast<std::size_t>(featureOfLabel(l))].name; };
  for (auto [a, b] : pairs) {
    if (static_cast<std::size_t>(featureOfLabel(b)) >= out.size()) continue;
    out[static_cast<std::size_t>(featureOfLabel(a))].push_back(name(b));
    out[static_cast<std::size_t>(featureOfLabel(b))].push_back(name(a));
  }
  return out;
}

void addOverlapFacts(RunReport& r, const ContourSet& contours, const OverlapReport& overlaps, const Grid& grid) {
  r.overlapMode = overlapModeName(overlaps.mode);
  r.layers = overlaps.layers;
  r.maskLayers = overlaps.maskLayers;
  r.overlapTolerance = overlaps.tolerance;
  r.overlapDepthLimit = incidentalDepthLimit(overlaps.tolerance, grid);
  const auto percent = [](double part, double whole) { return whole > 0 ? 100.0 * part / whole : 0.0; };
  for (const SharedVolume& s : overlaps.partialOverlaps()) {
    const FeatureVolumes &a = overlaps.features[static_cast<std::size_t>(s.a)],
                         &b = overlaps.features[static_cast<std::size_t>(s.b)];
    r.partialOverlaps.push_back(
        {contours.features[static_cast<std::size_t>(s.a)].name, contours.features[static_cast<std::size_t>(s.b)].name, s.volume,
         percent(s.volume, std::min(a.ownVolume, b.ownVolume)), s.depth, s.depthMeasured, s.regions, s.incidental, s.givenUpByA,
         s.givenUpByB, percent(s.givenUpByA, a.contour), percent(s.givenUpByB, b.contour)});
  }
  for (const VolumeLoss& l : overlaps.losses) {
    const double contour = overlaps.features[static_cast<std::size_t>(l.feature)].contour;
    r.losses.push_back({contours.features[static_cast<std::size_t>(l.feature)].name,
                        l.to >= 0 ? contours.features[static_cast<std::size_t>(l.to)].name : std::string("background"), l.volume,
                        contour > 0 ? 100.0 * l.volume / contour : 0.0, l.nested});
  }
}

}  // namespace

std::string utcTimestamp() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

Result<VolumeUnit> volumeUnitFor(const std::string& choice, const std::string& inputUnits) {
  static constexpr struct {
    const char* choice;
    const char* name;
    double metres;  // the unit's length
  } units[] = {{"mm3", "mm^3", 1e-3}, {"cm3", "cm^3", 1e-2}, {"cc", "cm^3", 1e-2},
               {"ml", "cm^3", 1e-2},  {"um3", "um^3", 1e-6}, {"nm3", "nm^3", 1e-9}};
  if (choice == "input") return VolumeUnit{};
  for (const auto& u : units) {
    if (choice != u.choice) continue;
    const double metres = metresPerUnit(inputUnits);
    if (metres <= 0)
      return makeError(Errc::InvalidArgument, "volume unit " + choice + ": the input's unit '" + inputUnits +
                                                  "' has no known length; use the input's own (\"input\")");
    const double ratio = metres / u.metres;
    return VolumeUnit{u.name, ratio * ratio * ratio};
  }
  return makeError(Errc::InvalidArgument, "unknown volume unit '" + choice + "': choose input, mm3, cm3 (cc, ml), um3 or nm3");
}

namespace {

InputFile hashedFile(const std::string& path) {
  InputFile file{path, {}, 0};
  std::error_code ec;
  file.bytes = std::filesystem::file_size(path, ec);
  if (ec) file.bytes = 0;
  if (auto digest = sha256OfFile(path)) file.sha256 = std::move(*digest);
  return file;
}

// Every volume of the report in the chosen unit (areas and lengths stay in the input's).
void scaleVolumes(RunReport& r, double scale) {
  if (scale == 1) return;
  for (ReportFeature& f : r.features) {
    f.volumes.contour *= scale, f.volumes.ownVolume *= scale, f.stats.volume *= scale;
    for (auto& o : f.overlaps) o.second *= scale;
  }
  for (RunReport::Loss& l : r.losses) l.volume *= scale;
  for (RunReport::Overlap& o : r.partialOverlaps) o.volume *= scale, o.givenUpByA *= scale, o.givenUpByB *= scale;
}

}  // namespace

RunReport makeReport(const ContourSet& contours, const BuildResult& built, const DeviceInfo& device, ReportContext context,
                     std::vector<MeshStats> stats) {
  RunReport r;
  r.generator = std::string("scansurf ") + version();
  r.input = std::move(context.input);
  r.commandLine = std::move(context.commandLine);
  r.started = std::move(context.started);
  r.units = contours.units;
  r.volumeUnit = context.volumeUnit.name.empty() ? contours.units + "^3" : context.volumeUnit.name;
  for (const std::string& file : contours.files) r.inputFiles.push_back(hashedFile(file));
  r.frameOfReferenceUid = contours.frameOfReferenceUid;
  r.reference = contours.reference;
  r.parameters = std::move(context.parameters);
  r.deviceName = device.name, r.deviceType = device.type, r.driver = device.driver;
  r.grid = built.volume.grid;
  for (int f : built.nesting.order) r.nestingOrder.push_back(contours.features[static_cast<std::size_t>(f)].name);
  r.userOrder = built.nesting.userOrder;
  r.meshVertices = built.surfaces.mesh.vertexCount();
  r.meshTriangles = built.surfaces.mesh.triangleCount();
  if (const std::size_t n = built.surfaces.features.size(); stats.size() != n)
    stats = built.audit.stats.size() == n ? built.audit.stats : computeFeatureStats(built.surfaces);
  const std::vector<Rgb> colors = featureColors(contours);
  const std::vector<std::vector<std::string>> neighbours = surfaceNeighbours(contours, built.surfaces.mesh);
  for (std::size_t f = 0; f < contours.features.size() && f < stats.size(); ++f) {
    ReportFeature rf{
        contours.features[f].name, labelOfFeature(static_cast<int>(f)), colors[f], stats[f], {}, {}, neighbours[f], {}};
    rf.sourceNumber = contours.features[f].sourceNumber;
    rf.interpretedType = contours.features[f].interpretedType;
    if (f < context.files.size())
      for (const fs::path& p : context.files[f]) rf.files.push_back(p.string());
    if (f < built.overlaps.features.size()) rf.volumes = built.overlaps.features[f];
    for (const SharedVolume& s : built.overlaps.partialOverlaps())
      if (s.a == static_cast<int>(f) || s.b == static_cast<int>(f))
        rf.overlaps.emplace_back(contours.features[static_cast<std::size_t>(s.a == static_cast<int>(f) ? s.b : s.a)].name,
                                 s.volume);
    r.features.push_back(std::move(rf));
  }
  addOverlapFacts(r, contours, built.overlaps, built.volume.grid);
  r.estimatedMemory = built.estimatedMemory;
  r.memoryLimit = built.memoryLimit;
  r.interpolation = built.interpolation;
  scaleVolumes(r, context.volumeUnit.scale);
  for (const StageTime& t : context.timings) r.timings.emplace_back(t.stage, t.seconds);
  r.remeshing = built.surfaces.remeshing;
  r.simplification = built.surfaces.simplification;
  r.triangleShape = built.surfaces.triangleShape;
  for (const fs::path& p : context.outputs) r.outputs.push_back(p.string());
  r.warnings = contours.warnings;  // every warning of the run: reading's, then the build's
  r.warnings.insert(r.warnings.end(), built.warnings.begin(), built.warnings.end());
  return r;
}

namespace {

nlohmann::ordered_json anglesJson(const AngleFigures& a) { return {{"min", a.min}, {"p5", a.p5}, {"mean", a.mean}}; }

// Remeshing's figures: triangle counts, the smallest angle of each triangle (degrees: least,
// 5th percentile, mean) before and after, and the largest distance from the smoothed surface.
nlohmann::ordered_json remeshingJson(const RemeshReport& r) {
  return {{"edge_length", r.edgeLength},
          {"triangles_before", r.trianglesBefore},
          {"triangles_after", r.trianglesAfter},
          {"smallest_angle_before", anglesJson(r.anglesBefore)},
          {"smallest_angle_after", anglesJson(r.anglesAfter)},
          {"max_distance", r.maxDistance},
          {"chunks", r.chunks},
          {"bands", r.bands},
          {"operations",
           {{"splits", r.splits}, {"collapses", r.collapses}, {"flips", r.flips}, {"moves", r.moves}, {"refused", r.rejected}}}};
}

// Simplification's figures: triangle counts and smallest angles before and after, and the
// patches put back as smoothed by their own checks or the crossing test.
nlohmann::ordered_json simplificationJson(const SimplificationReport& r) {
  return {{"triangles_before", r.trianglesBefore},
          {"triangles_after", r.trianglesAfter},
          {"smallest_angle_before", anglesJson(r.anglesBefore)},
          {"smallest_angle_after", anglesJson(r.anglesAfter)},
          {"patches", r.patches},
          {"refused", r.refused},
          {"crossing", r.crossing}};
}

// Snapping's figures: the voxel centres that became vertices, what vanished, the quads flipped.
nlohmann::ordered_json triangleShapeJson(const TriangleShapeReport& r) {
  return {{"fraction", r.fraction},
          {"candidates", r.candidates},
          {"points", r.points},
          {"merged_vertices", r.mergedVertices},
          {"removed_triangles", r.removedTriangles},
          {"quads_flipped", r.quadsFlipped},
          {"cube_fans", r.cubeFans},
          {"fan_vertices_removed", r.fanVerticesRemoved},
          {"seconds", r.seconds}};
}

nlohmann::ordered_json overlapsJson(const std::vector<std::pair<std::string, double>>& overlaps) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const auto& [name, volume] : overlaps) out.push_back({{"with", name}, {"shared_volume", volume}});
  return out;
}

nlohmann::ordered_json gridJson(const Grid& g) {
  return {{"size", {g.nx, g.ny, g.nz}},
          {"origin", {g.originX, g.originY, g.layerZ.empty() ? 0.0 : g.layerZ.front()}},
          {"spacing_xy", {g.spacingX, g.spacingY}},
          {"layer_z", g.layerZ}};
}

nlohmann::ordered_json interpolationJson(const InterpolationSummary& in) {
  return {{"used", in.used()},
          {"plane_layers", in.planeLayers},
          {"surfaced_layers", in.surfacedLayers},
          {"layers_per_gap", {in.minFactor, in.maxFactor}},
          {"caps", in.caps == CapShape::Flat ? "flat" : "round"}};
}

nlohmann::ordered_json inputFilesJson(const std::vector<InputFile>& files) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const InputFile& f : files)
    out.push_back({{"path", f.path},
                   {"sha256", f.sha256.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(f.sha256)},
                   {"bytes", f.bytes}});
  return out;
}

// The CT lattice: pixel (i, j) of slice k is centred at (origin + (i, j) * spacing, slice_z[k]).
nlohmann::ordered_json referenceJson(const GridReference& g) {
  return {{"size", {g.nx, g.ny, g.sliceZ.size()}},
          {"origin", {g.originX, g.originY}},
          {"spacing", {g.spacingX, g.spacingY}},
          {"slice_z", g.sliceZ}};
}

nlohmann::ordered_json featuresJson(const RunReport& report) {
  using nlohmann::ordered_json;
  ordered_json features = ordered_json::array();
  for (const ReportFeature& f : report.features) {
    const MeshStats& s = f.stats;
    features.push_back({{"name", f.name},
                        {"label", f.label},
                        {"source_number", f.sourceNumber > 0 ? ordered_json(f.sourceNumber) : ordered_json()},
                        {"interpreted_type", f.interpretedType.empty() ? ordered_json() : ordered_json(f.interpretedType)},
                        {"color", {f.color[0], f.color[1], f.color[2]}},
                        {"triangles", s.triangles},
                        {"vertices", s.vertices},
                        {"area", s.area},
                        {"components", s.components},
                        {"genus", s.genus},
                        {"closed", s.closed},
                        {"manifold", s.manifold},
                        {"oriented", s.oriented},
                        {"contour_volume", f.volumes.contour},
                        {"labelled_volume", f.volumes.ownVolume},
                        {"labelled_voxels", f.volumes.ownVoxels},
                        {"surface_volume", s.volume},
                        {"layer", f.volumes.layer},
                        {"mask_layer", f.volumes.maskLayer},
                        {"shares_surface_with", f.sharesSurfaceWith},
                        {"overlaps", overlapsJson(f.overlaps)},
                        {"files", f.files}});
  }
  return features;
}

nlohmann::ordered_json overlapsSectionJson(const RunReport& report) {
  using nlohmann::ordered_json;
  ordered_json j = {{"mode", report.overlapMode}, {"layers", report.layers}, {"mask_layers", report.maskLayers}};
  ordered_json losses = ordered_json::array();
  for (const RunReport::Loss& l : report.losses)
    losses.push_back({{"feature", l.feature},
                      {"to", l.to},
                      {"volume", l.volume},
                      {"percent_of_contour_volume", l.percentOfContour},
                      {"nested", l.nested}});
  j["losses"] = losses;
  const OverlapTolerance& t = report.overlapTolerance;
  j["tolerance"] = {{"enabled", t.enabled},
                    {"depth", report.overlapDepthLimit},
                    {"depth_automatic", t.depth <= 0},
                    {"percent_of_smaller", t.percent}};
  ordered_json pairs = ordered_json::array();
  for (const RunReport::Overlap& o : report.partialOverlaps)
    pairs.push_back({{"a", o.a},
                     {"b", o.b},
                     {"shared_volume", o.volume},
                     {"percent_of_smaller", o.percentOfSmaller},
                     {"depth", o.depthMeasured ? ordered_json(o.depth) : ordered_json(nullptr)},
                     {"regions", o.regions},
                     {"verdict", o.incidental ? "incidental" : "real"},
                     {"given_up", {{"a", o.givenUpByA}, {"b", o.givenUpByB}}},
                     {"given_up_percent_of_contour_volume", {{"a", o.givenUpPercentA}, {"b", o.givenUpPercentB}}}});
  j["partial"] = pairs;
  return j;
}

nlohmann::ordered_json timingsJson(const RunReport& report, double& total) {
  nlohmann::ordered_json timings = nlohmann::ordered_json::array();
  total = 0;
  for (const auto& [stage, seconds] : report.timings) {
    timings.push_back({{"stage", stage}, {"seconds", seconds}});
    total += seconds;
  }
  return timings;
}

}  // namespace

std::string reportJson(const RunReport& report) {
  using nlohmann::ordered_json;
  ordered_json j;
  j["format"] = "scansurf-report";
  j["version"] = 1;
  j["generator"] = report.generator.empty() ? std::string("scansurf ") + version() : report.generator;
  j["input"] = report.input;
  if (!report.commandLine.empty()) j["command_line"] = report.commandLine;
  if (!report.started.empty()) j["started"] = report.started;
  j["input_files"] = inputFilesJson(report.inputFiles);
  j["frame_of_reference_uid"] = report.frameOfReferenceUid.empty() ? ordered_json() : ordered_json(report.frameOfReferenceUid);
  j["reference_grid"] = report.reference ? referenceJson(*report.reference) : ordered_json();
  j["units"] = report.units;
  j["length_unit"] = report.units;
  j["area_unit"] = report.units + "^2";
  j["volume_unit"] = report.volumeUnit;
  ordered_json params = ordered_json::object();
  for (const auto& parameter : report.parameters)
    std::visit([&](const auto& v) { params[parameter.first] = v; }, parameter.second);
  j["parameters"] = params;
  j["device"] = {{"name", report.deviceName}, {"type", report.deviceType}, {"driver", report.driver}};
  j["grid"] = gridJson(report.grid);
  j["nesting"] = {{"order", report.nestingOrder}, {"from_input", report.userOrder}};
  j["memory"] = {{"estimated_bytes", report.estimatedMemory}, {"limit_bytes", report.memoryLimit}};
  j["interpolation"] = interpolationJson(report.interpolation);
  j["multilabel_mesh"] = {{"vertices", report.meshVertices}, {"triangles", report.meshTriangles}};
  j["features"] = featuresJson(report);
  j["overlaps"] = overlapsSectionJson(report);
  if (report.triangleShape.ran) j["triangle_shape"] = triangleShapeJson(report.triangleShape);
  if (report.simplification.ran) j["simplification"] = simplificationJson(report.simplification);
  if (report.remeshing.ran) j["remeshing"] = remeshingJson(report.remeshing);
  double total = 0;
  j["timings"] = timingsJson(report, total);
  j["total_seconds"] = total;
  j["warnings"] = report.warnings;
  j["outputs"] = report.outputs;
  // Names are bytes from the input (an ROI name may be Latin-1): invalid UTF-8 is replaced.
  return j.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
}

Result<void> writeReport(const std::filesystem::path& path, const RunReport& report) {
  const std::string text = reportJson(report);
  return writeFileAtomically(path, text.data(), text.size());
}

}  // namespace scansurf
