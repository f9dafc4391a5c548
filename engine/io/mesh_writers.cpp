// OBJ and binary STL through Draco's ObjEncoder and StlEncoder (no hand-written formats),
// buffered in memory and written through an AtomicFile.
#include "io/mesh_writers.h"

#include <draco/io/obj_encoder.h>

#include <draco/io/stl_encoder.h>
#include <draco/mesh/mesh.h>
#include <cstdio>

#include <algorithm>
#include <limits>
#include <vector>

#include "core/text_fields.h"
#include "io/atomic_file.h"
#include "io/draco_writer.h"
#include "scansurf/version.h"

namespace scansurf {

// The surface with its vertex normals, for Draco's OBJ encoder to write as `vn`.
std::unique_ptr<draco::Mesh> withNormals(const CompactMesh& mesh) {
  std::unique_ptr<draco::Mesh> dm = toDracoMesh(mesh);
  const std::vector<float> normals = vertexNormals(mesh);
  draco::GeometryAttribute normal;
  normal.Init(draco::GeometryAttribute::NORMAL, nullptr, 3, draco::DT_FLOAT32, false, sizeof(float) * 3, 0);
  const auto vertices = static_cast<std::uint32_t>(mesh.vertexCount());
  draco::PointAttribute* attribute = dm->attribute(dm->AddAttribute(normal, true, vertices));
  for (std::uint32_t v = 0; v < vertices; ++v)
    attribute->SetAttributeValue(draco::AttributeValueIndex(v), &normals[3 * static_cast<std::size_t>(v)]);
  return dm;
}

Result<void> writeObj(const std::filesystem::path& path, const CompactMesh& mesh, const std::string& name,
                      const std::string& units, const ObjMaterial* material) {
  std::unique_ptr<draco::Mesh> dm = withNormals(mesh);
  dm->SetName(name);
  draco::ObjEncoder encoder;
  draco::EncoderBuffer buffer;
  if (!encoder.EncodeToBuffer(*dm, &buffer))
    return makeError(Errc::Internal, "cannot encode '" + path.string() + "': Draco's OBJ encoder failed");
  const std::string comment = std::string("# scansurf ") + version() + ": surface of \"" + oneLineText(name, "\"") +
                              "\", coordinates in " + (units.empty() ? std::string("the input's units") : oneLineText(units)) +
                              "\n" +
                              (material ? "mtllib " + material->library + "\nusemtl " + material->name + "\n" : std::string());
  return writeFileAtomically(path, [&](AtomicFile& file) -> Result<void> {
    SCANSURF_TRY(file.write(comment.data(), comment.size()));
    return file.write(buffer.data(), buffer.size());
  });
}

Result<void> writeMtl(const std::filesystem::path& path, const ObjMaterial& material) {
  char kd[64];
  std::snprintf(kd, sizeof kd, "Kd %.6f %.6f %.6f\n", material.color[0] / 255.0, material.color[1] / 255.0,
                material.color[2] / 255.0);
  const std::string text = std::string("# scansurf ") + version() + "\nnewmtl " + material.name + "\nKa 0 0 0\n" + kd +
                           "Ks 0.2 0.2 0.2\nNs 20\nd 1\nillum 2\n";
  return writeFileAtomically(path, text.data(), text.size());
}

Result<void> writeStl(const std::filesystem::path& path, const CompactMesh& mesh, const std::string& units) {
  std::unique_ptr<draco::Mesh> dm = toDracoMesh(mesh);
  draco::StlEncoder encoder;
  draco::EncoderBuffer buffer;
  if (const draco::Status s = encoder.EncodeToBuffer(*dm, &buffer); !s.ok())
    return makeError(Errc::Internal, "cannot encode '" + path.string() + "': " + s.error_msg_string());
  // The 80-byte header names the generator (never starting with "solid", which marks ASCII STL).
  std::vector<char> bytes(buffer.data(), buffer.data() + buffer.size());
  const std::string header =
      std::string("scansurf ") + version() + " binary STL, " + (units.empty() ? std::string("input units") : oneLineText(units));
  if (bytes.size() >= 80) {
    std::fill(bytes.begin(), bytes.begin() + 80, ' ');
    std::copy_n(header.begin(), std::min<std::size_t>(header.size(), 80), bytes.begin());
  }
  return writeFileAtomically(path, bytes.data(), bytes.size());
}

}  // namespace scansurf
