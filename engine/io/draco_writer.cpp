// Draco (google/draco) edgebreaker compression of feature surfaces.
#include "io/draco_writer.h"

#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "io/atomic_file.h"

namespace scansurf {

double defaultQuantizationError(const Grid& grid) {
  double edge = std::min(grid.spacingX, grid.spacingY);
  for (std::size_t k = 1; k < grid.layerZ.size(); ++k) edge = std::min(edge, grid.layerZ[k] - grid.layerZ[k - 1]);
  return edge / 25.0;
}

namespace {

double largestExtent(const CompactMesh& mesh) {
  if (mesh.positions.empty()) return 0;
  double extent = 0;
  for (int a = 0; a < 3; ++a) {
    float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
    for (std::size_t i = static_cast<std::size_t>(a); i < mesh.positions.size(); i += 3)
      lo = std::min(lo, mesh.positions[i]), hi = std::max(hi, mesh.positions[i]);
    extent = std::max(extent, static_cast<double>(hi) - static_cast<double>(lo));
  }
  return extent;
}

}  // namespace

double quantizationError(const CompactMesh& mesh, int bits) {
  return largestExtent(mesh) / (2.0 * (std::ldexp(1.0, bits) - 1.0));
}

int quantizationBitsFor(const CompactMesh& mesh, const DracoOptions& options) {
  if (options.quantizationBits > 0) return std::clamp(options.quantizationBits, 1, 30);
  if (options.maxError <= 0) return 11;
  // Draco stores dequantized float32, so aim 1 % under the bound to absorb its rounding.
  int bits = 1;
  while (bits < 30 && quantizationError(mesh, bits) > 0.99 * options.maxError) ++bits;
  return bits;
}

std::unique_ptr<draco::Mesh> toDracoMesh(const CompactMesh& mesh) {
  auto out = std::make_unique<draco::Mesh>();
  const auto vertices = static_cast<std::uint32_t>(mesh.vertexCount());
  out->set_num_points(vertices);
  draco::GeometryAttribute position;
  position.Init(draco::GeometryAttribute::POSITION, nullptr, 3, draco::DT_FLOAT32, false, sizeof(float) * 3, 0);
  const int id = out->AddAttribute(position, true, vertices);
  draco::PointAttribute* attribute = out->attribute(id);
  for (std::uint32_t v = 0; v < vertices; ++v)
    attribute->SetAttributeValue(draco::AttributeValueIndex(v), &mesh.positions[3 * static_cast<std::size_t>(v)]);
  out->SetNumFaces(mesh.triangleCount());
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
    out->SetFace(draco::FaceIndex(static_cast<std::uint32_t>(t)),
                 {draco::PointIndex(mesh.triangles[3 * t]), draco::PointIndex(mesh.triangles[3 * t + 1]),
                  draco::PointIndex(mesh.triangles[3 * t + 2])});
  return out;
}

Result<void> writeDrc(const std::filesystem::path& path, const CompactMesh& mesh, const DracoOptions& options) {
  std::unique_ptr<draco::Mesh> dm = toDracoMesh(mesh);
  draco::Encoder encoder;
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, quantizationBitsFor(mesh, options));
  const int speed = 10 - std::clamp(options.compressionLevel, 0, 10);
  encoder.SetSpeedOptions(speed, speed);
  draco::EncoderBuffer buffer;
  if (const draco::Status s = encoder.EncodeMeshToBuffer(*dm, &buffer); !s.ok())
    return makeError(Errc::Internal, "cannot encode '" + path.string() + "': Draco: " + s.error_msg_string());
  return writeFileAtomically(path, buffer.data(), buffer.size());
}

}  // namespace scansurf
