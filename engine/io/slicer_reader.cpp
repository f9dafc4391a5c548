// scansurf: 3D Slicer planar-contour segmentations (see slicer_reader.h), parsed with pugixml.
#include "io/slicer_reader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <pugixml.hpp>
#include <string>
#include <vector>

#include "geometry/contours/validate.h"
#include "io/vtk_xml_arrays.h"

namespace scansurf {
namespace {

namespace fs = std::filesystem;

Unexpected bad(const std::string& what) { return makeError(Errc::InvalidInput, what); }

Result<pugi::xml_node> openVtkFile(pugi::xml_document& doc, const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return makeError(Errc::Io, path.string() + ": cannot open the file");
  const pugi::xml_parse_result parsed = doc.load(in);
  if (!parsed)
    return bad(path.string() + ": not well-formed XML (" + parsed.description() + " at byte " + std::to_string(parsed.offset) +
               ")");
  pugi::xml_node root = doc.child("VTKFile");
  if (!root) return bad(path.string() + ": not a VTK XML file (no VTKFile element)");
  return root;
}

// The string of a field-data array (VTK stores each string with a terminating NUL); empty
// when the file has no such array.
Result<std::string> fieldString(const pugi::xml_node& fieldData, const char* name, const VtkXmlEncoding& e,
                                const std::string& where) {
  const pugi::xml_node array = fieldData.find_child_by_attribute("Name", name);
  if (!array) return std::string();
  SCANSURF_ASSIGN_OR_RETURN(std::string s, vtkBytes(array, e, where + ", field " + name));
  if (const auto nul = s.find('\0'); nul != std::string::npos) s.resize(nul);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
  return s;
}

Result<std::optional<Rgb>> fieldColor(const pugi::xml_node& fieldData, const VtkXmlEncoding& e, const std::string& where) {
  const pugi::xml_node array = fieldData.find_child_by_attribute("Name", "Segment_DefaultColor");
  if (!array) return std::optional<Rgb>{};
  SCANSURF_ASSIGN_OR_RETURN(const std::vector<double> v, vtkNumbers(array, e, where + ", field Segment_DefaultColor"));
  if (v.size() < 3) return bad(where + ": Segment_DefaultColor with fewer than 3 values");
  const auto channel = [](double c) { return static_cast<std::uint8_t>(std::lround(std::clamp(c, 0.0, 1.0) * 255)); };
  return std::optional<Rgb>{Rgb{channel(v[0]), channel(v[1]), channel(v[2])}};
}

// Cell k's point indices [begin, end) from VTK's connectivity and offsets (old files: one end
// per cell; VTK 9's: a leading 0 and one end per cell).
struct Cells {
  std::vector<double> connectivity, offsets;
  std::size_t count() const { return offsets.size() - (leadingZero() ? 1 : 0); }
  bool leadingZero() const { return !offsets.empty() && offsets.front() == 0; }
  std::size_t begin(std::size_t k) const {
    return leadingZero() ? static_cast<std::size_t>(offsets[k]) : k == 0 ? 0 : static_cast<std::size_t>(offsets[k - 1]);
  }
  std::size_t end(std::size_t k) const { return static_cast<std::size_t>(offsets[leadingZero() ? k + 1 : k]); }
};

Result<Cells> cellsOf(const pugi::xml_node& piece, const char* kind, const VtkXmlEncoding& e, const std::string& where) {
  Cells cells;
  const pugi::xml_node node = piece.child(kind);
  if (!node) return cells;
  for (const char* name : {"connectivity", "offsets"}) {
    const pugi::xml_node array = node.find_child_by_attribute("Name", name);
    if (!array) return bad(where + ": " + kind + " without " + name);
    SCANSURF_ASSIGN_OR_RETURN(std::vector<double> v, vtkNumbers(array, e, where + ", " + kind + " " + name));
    (std::string(name) == "connectivity" ? cells.connectivity : cells.offsets) = std::move(v);
  }
  for (std::size_t k = 0; k < cells.count(); ++k)
    if (cells.begin(k) > cells.end(k) || cells.end(k) > cells.connectivity.size())
      return bad(where + ": " + kind + " offsets out of order or beyond the connectivity");
  return cells;
}

// One closed polyline into a slice of the feature, LPS; its points on one plane.
Result<void> addPolyline(const std::vector<double>& points, const Cells& cells, std::size_t k, Feature& feature,
                         const std::string& where) {
  const std::string line = where + ", polyline " + std::to_string(k);
  Contour contour;
  double z = 0;
  for (std::size_t i = cells.begin(k); i < cells.end(k); ++i) {
    const auto p = static_cast<std::size_t>(cells.connectivity[i]);
    if (p * 3 + 2 >= points.size()) return bad(line + ": a point index beyond the points");
    const double x = points[3 * p], y = points[3 * p + 1], pz = points[3 * p + 2];
    if (i == cells.begin(k)) z = pz;
    if (std::abs(pz - z) > 1e-3 * (1 + std::abs(z)))
      return bad(line + ": its points do not lie on one plane (z " + formatNumber(z) + " and " + formatNumber(pz) + ")");
    contour.points.push_back({-x, -y});  // RAS to LPS
  }
  if (contour.points.size() < 3) return bad(line + ": fewer than 3 points");
  feature.slices.push_back({z, {std::move(contour)}});
  return {};
}

Result<Feature> readSegment(const fs::path& path, int index) {
  pugi::xml_document doc;
  SCANSURF_ASSIGN_OR_RETURN(const pugi::xml_node root, openVtkFile(doc, path));
  const std::string where = path.string();
  if (std::string(root.attribute("type").as_string()) != "PolyData") return bad(where + ": not a VTK PolyData file");
  SCANSURF_ASSIGN_OR_RETURN(const VtkXmlEncoding e, vtkXmlEncoding(root, where));
  const pugi::xml_node polyData = root.child("PolyData");
  const pugi::xml_node fields = polyData.child("FieldData");
  Feature feature;
  SCANSURF_ASSIGN_OR_RETURN(feature.name, fieldString(fields, "Segment_Name", e, where));
  if (feature.name.empty()) feature.name = "segment " + std::to_string(index);
  SCANSURF_ASSIGN_OR_RETURN(feature.color, fieldColor(fields, e, where));
  const std::string segment = where + ", segment \"" + feature.name + "\"";
  for (pugi::xml_node piece = polyData.child("Piece"); piece; piece = piece.next_sibling("Piece")) {
    const pugi::xml_node pointsArray = piece.child("Points").child("DataArray");
    if (!pointsArray) continue;
    SCANSURF_ASSIGN_OR_RETURN(const std::vector<double> points, vtkNumbers(pointsArray, e, segment + ", points"));
    for (const char* kind : {"Lines", "Polys"}) {
      SCANSURF_ASSIGN_OR_RETURN(const Cells cells, cellsOf(piece, kind, e, segment));
      for (std::size_t k = 0; k < cells.count(); ++k) SCANSURF_TRY(addPolyline(points, cells, k, feature, segment));
    }
  }
  std::stable_sort(feature.slices.begin(), feature.slices.end(), [](const auto& a, const auto& b) { return a.z < b.z; });
  return feature;
}

// The block files a multiblock file names, in order (blocks may nest).
void blockFiles(const pugi::xml_node& node, const fs::path& dir, std::vector<fs::path>& out) {
  for (const pugi::xml_node child : node.children()) {
    if (const char* file = child.attribute("file").as_string(nullptr); file && *file) out.push_back(dir / file);
    blockFiles(child, dir, out);
  }
}

}  // namespace

bool looksLikeVtkXml(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(512, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  return head.find("<VTKFile") != std::string::npos;
}

Result<ContourSet> readSlicerSegmentation(const fs::path& path) {
  pugi::xml_document doc;
  SCANSURF_ASSIGN_OR_RETURN(const pugi::xml_node root, openVtkFile(doc, path));
  ContourSet contours;
  contours.source = path.string();
  contours.units = "mm";
  const std::string type = root.attribute("type").as_string();
  std::vector<fs::path> files;
  if (type == "vtkMultiBlockDataSet")
    blockFiles(root.child("vtkMultiBlockDataSet"), path.parent_path(), files);
  else if (type == "PolyData")
    files.push_back(path);
  else
    return bad(path.string() + ": a VTK " + type + " file, not a segmentation (vtkMultiBlockDataSet or PolyData)");
  if (files.empty()) return bad(path.string() + ": the multiblock file names no block file");
  for (std::size_t i = 0; i < files.size(); ++i) {
    std::error_code ec;
    if (!fs::is_regular_file(files[i], ec))
      return makeError(Errc::Io,
                       path.string() + ": block " + std::to_string(i) + " names " + files[i].string() + ", which is not there");
    SCANSURF_ASSIGN_OR_RETURN(Feature feature, readSegment(files[i], static_cast<int>(i)));
    contours.files.push_back(files[i].string());
    if (!feature.slices.empty())
      contours.features.push_back(std::move(feature));
    else
      contours.warnings.push_back(files[i].string() + ": segment \"" + feature.name + "\" has no contours (skipped)");
  }
  contours.files.insert(contours.files.begin(), path.string());
  SCANSURF_TRY(validateAndNormalize(contours));
  contours.notes.push_back("3D Slicer segmentation: " + std::to_string(contours.features.size()) +
                           " segments with planar contours (RAS turned to patient LPS, mm)");
  return contours;
}

}  // namespace scansurf
