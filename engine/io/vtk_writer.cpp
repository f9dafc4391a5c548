// scansurf: VTK XML PolyData and MultiBlock files (VTK File Formats, "XML File Formats");
// 3D Slicer's closed-surface segmentation after vtkMRMLSegmentationStorageNode's keys
// (see vtk_writer.h). Arrays are inline binary (base64 of a UInt32 byte count and the
// little-endian values); strings are ASCII byte codes, each ended by 0, as VTK writes them.
#include "io/vtk_writer.h"

#include <cstdint>
#include <cstring>
#include <sstream>

#include "core/text_fields.h"
#include "io/atomic_file.h"
#include "scansurf/version.h"

namespace scansurf {
namespace {

std::string base64(const std::vector<std::uint8_t>& bytes) {
  static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t n = static_cast<std::uint32_t>(bytes[i]) << 16 |
                            (i + 1 < bytes.size() ? static_cast<std::uint32_t>(bytes[i + 1]) << 8 : 0u) |
                            (i + 2 < bytes.size() ? bytes[i + 2] : 0u);
    out += kDigits[(n >> 18) & 63];
    out += kDigits[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? kDigits[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kDigits[n & 63] : '=';
  }
  return out;
}

// A binary DataArray: the values behind a UInt32 byte count (header_type UInt32).
template <typename T>
std::string dataArray(const char* type, const std::string& name, int components, const std::vector<T>& values) {
  const auto bytes = static_cast<std::uint32_t>(values.size() * sizeof(T));
  std::vector<std::uint8_t> block(sizeof bytes + bytes);
  std::memcpy(block.data(), &bytes, sizeof bytes);
  if (bytes) std::memcpy(block.data() + sizeof bytes, values.data(), bytes);
  std::ostringstream out;
  out << "<DataArray type=\"" << type << "\" Name=\"" << name << "\" NumberOfComponents=\"" << components
      << "\" NumberOfTuples=\"" << values.size() / static_cast<std::size_t>(components) << "\" format=\"binary\">"
      << base64(block) << "</DataArray>\n";
  return out.str();
}

// A one-value string array in field data: the bytes as decimal codes, ended by 0.
std::string stringArray(const std::string& name, const std::string& value) {
  std::ostringstream out;
  out << "<Array type=\"String\" Name=\"" << name << "\" NumberOfTuples=\"1\" format=\"ascii\">";
  for (unsigned char c : value) out << static_cast<int>(c) << ' ';
  out << "0</Array>\n";
  return out.str();
}

// Names and values in attributes: XML's five characters escaped, controls dropped.
std::string attribute(const std::string& text) {
  std::string out;
  for (unsigned char c : text) {
    if (c < 0x20) continue;
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += static_cast<char>(c);
    }
  }
  return out;
}

// The points and triangles of a PolyData piece, with what goes inside it (point, cell data).
std::string piece(const std::vector<float>& positions, const std::vector<std::uint32_t>& triangles, const std::string& inner) {
  std::vector<std::int64_t> connectivity(triangles.begin(), triangles.end()), offsets(triangles.size() / 3);
  for (std::size_t t = 0; t < offsets.size(); ++t) offsets[t] = static_cast<std::int64_t>(3 * (t + 1));
  std::ostringstream out;
  out << "<Piece NumberOfPoints=\"" << positions.size() / 3 << "\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" "
      << "NumberOfPolys=\"" << triangles.size() / 3 << "\">\n"
      << inner << "<Points>\n"
      << dataArray("Float32", "Points", 3, positions) << "</Points>\n<Polys>\n"
      << dataArray("Int64", "connectivity", 1, connectivity) << dataArray("Int64", "offsets", 1, offsets)
      << "</Polys>\n</Piece>\n";
  return out.str();
}

std::string polyDataFile(const std::string& fieldData, const std::string& pieceXml) {
  return "<?xml version=\"1.0\"?>\n<!-- " + oneLineText(std::string("scansurf ") + SCANSURF_VERSION_STRING) +
         " -->\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt32\">\n<PolyData>\n"
         "<FieldData>\n" +
         fieldData + "</FieldData>\n" + pieceXml + "</PolyData>\n</VTKFile>\n";
}

Result<void> writeText(const std::filesystem::path& path, const std::string& text) {
  return writeFileAtomically(path, text.data(), text.size());
}

std::string intArray(const std::string& name, std::int32_t value) {
  return dataArray("Int32", name, 1, std::vector<std::int32_t>{value});
}

}  // namespace

Result<void> writeFeatureVtp(const std::filesystem::path& path, const CompactMesh& mesh, const std::string& name, int label,
                             const std::string& units) {
  const std::string fields = stringArray("Name", name) + intArray("Label", label) + stringArray("Units", units);
  const std::string normals =
      "<PointData Normals=\"Normals\">\n" + dataArray("Float32", "Normals", 3, vertexNormals(mesh)) + "</PointData>\n";
  return writeText(path, polyDataFile(fields, piece(mesh.positions, mesh.triangles, normals)));
}

Result<void> writeMultiLabelVtp(const std::filesystem::path& path, const MultiLabelMesh& mesh, const std::string& units) {
  std::vector<std::uint16_t> inside(mesh.triangleCount()), outside(mesh.triangleCount());
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) inside[t] = mesh.labels[2 * t], outside[t] = mesh.labels[2 * t + 1];
  const std::string cells = "<CellData Scalars=\"label_inside\">\n" + dataArray("UInt16", "label_inside", 1, inside) +
                            dataArray("UInt16", "label_outside", 1, outside) + "</CellData>\n";
  const std::string fields =
      stringArray("Units", units) + stringArray("Labels",
                                                "label L = feature L-1, 0 = background; normals point from "
                                                "label_inside's region into label_outside's");
  return writeText(path, polyDataFile(fields, piece(mesh.positions, mesh.triangles, cells)));
}

std::filesystem::path slicerSegmentPath(const std::filesystem::path& vtm, std::size_t index) {
  std::string stem = vtm.filename().string();
  if (stem.size() > 4 && stem.compare(stem.size() - 4, 4, ".vtm") == 0) stem.resize(stem.size() - 4);
  return vtm.parent_path() / (stem + "_" + std::to_string(index) + ".vtp");
}

Result<void> writeSlicerSegmentVtp(const std::filesystem::path& path, const SlicerSegment& segment) {
  const CompactMesh& mesh = *segment.mesh;
  // LPS -> RAS: x and y negated, a half turn about z, so the normals turn with the points
  // (exactly: negation is exact) and the windings stay outward.
  std::vector<float> ras = mesh.positions, normals = vertexNormals(mesh);
  for (std::vector<float>* a : {&ras, &normals})
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) (*a)[3 * v] = -(*a)[3 * v], (*a)[3 * v + 1] = -(*a)[3 * v + 1];
  const std::vector<double> color = {segment.color[0] / 255.0, segment.color[1] / 255.0, segment.color[2] / 255.0};
  std::ostringstream colorArray;
  colorArray << "<DataArray type=\"Float64\" Name=\"Segment_Color\" NumberOfComponents=\"3\" NumberOfTuples=\"1\" "
                "format=\"ascii\">"
             << color[0] << ' ' << color[1] << ' ' << color[2] << "</DataArray>\n";
  const std::string fields = stringArray("Segmentation_MasterRepresentation", "Closed surface") +
                             stringArray("Segment_ID", segment.id) + stringArray("Segment_Name", segment.name) +
                             colorArray.str() + stringArray("Segment_Tags", slicerTags(segment.terminology)) +
                             stringArray("Segment_NameAutoGenerated", "0") + stringArray("Segment_ColorAutoGenerated", "0") +
                             stringArray("Segmentation_ConversionParameters", "") +
                             stringArray("Segmentation_ContainedRepresentationNames", "Closed surface|");
  const std::string pointData =
      "<PointData Normals=\"Normals\">\n" + dataArray("Float32", "Normals", 3, normals) + "</PointData>\n";
  return writeText(path, polyDataFile(fields, piece(ras, mesh.triangles, pointData)));
}

Result<void> writeSlicerSegmentationVtm(const std::filesystem::path& path, const std::vector<std::string>& blockFiles) {
  std::string text =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"vtkMultiBlockDataSet\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt32\">\n<vtkMultiBlockDataSet>\n";
  for (std::size_t k = 0; k < blockFiles.size(); ++k)
    text += "<DataSet index=\"" + std::to_string(k) + "\" file=\"" + attribute(blockFiles[k]) + "\"/>\n";
  text += "</vtkMultiBlockDataSet>\n</VTKFile>\n";
  return writeText(path, text);
}

}  // namespace scansurf
