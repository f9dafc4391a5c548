// OBJ and binary STL through Draco's ObjEncoder and StlEncoder (no hand-written formats),
// buffered in memory and written through an AtomicFile.
#include "io/mesh_writers.h"

#include <draco/io/obj_encoder.h>
#include <draco/io/stl_encoder.h>
#include <draco/mesh/mesh.h>

#include <limits>

#include "io/atomic_file.h"
#include "io/draco_writer.h"

namespace scansurf {
namespace {

Result<void> writeBuffer(const std::filesystem::path& path, const draco::EncoderBuffer& buffer) {
  SCANSURF_ASSIGN_OR_RETURN(AtomicFile file, AtomicFile::create(path));
  SCANSURF_TRY(file.write(buffer.data(), buffer.size()));
  return file.commit();
}

}  // namespace

Result<CompactMesh> compactSurface(const MultiLabelMesh& mesh, const FeatureSurface& surface) {
  constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> remap(mesh.vertexCount(), kUnused);
  for (std::uint32_t v : surface.triangles) {
    if (v >= remap.size())
      return makeError(Errc::Internal, "surface of feature " + std::to_string(surface.feature) + " indexes vertex " +
                                           std::to_string(v) + " beyond the mesh's " + std::to_string(remap.size()));
    remap[v] = 0;
  }
  CompactMesh out;
  std::uint32_t used = 0;
  for (std::size_t v = 0; v < remap.size(); ++v) {
    if (remap[v] == kUnused) continue;
    remap[v] = used++;
    out.positions.insert(out.positions.end(), mesh.positions.begin() + static_cast<std::ptrdiff_t>(3 * v),
                         mesh.positions.begin() + static_cast<std::ptrdiff_t>(3 * v + 3));
  }
  out.triangles.reserve(surface.triangles.size());
  for (std::uint32_t v : surface.triangles) out.triangles.push_back(remap[v]);
  return out;
}

Result<void> writeObj(const std::filesystem::path& path, const CompactMesh& mesh, const std::string& name) {
  std::unique_ptr<draco::Mesh> dm = toDracoMesh(mesh);
  dm->SetName(name);
  draco::ObjEncoder encoder;
  draco::EncoderBuffer buffer;
  if (!encoder.EncodeToBuffer(*dm, &buffer))
    return makeError(Errc::Internal, "cannot encode '" + path.string() + "': Draco's OBJ encoder failed");
  return writeBuffer(path, buffer);
}

Result<void> writeStl(const std::filesystem::path& path, const CompactMesh& mesh) {
  std::unique_ptr<draco::Mesh> dm = toDracoMesh(mesh);
  draco::StlEncoder encoder;
  draco::EncoderBuffer buffer;
  if (const draco::Status s = encoder.EncodeToBuffer(*dm, &buffer); !s.ok())
    return makeError(Errc::Internal, "cannot encode '" + path.string() + "': " + s.error_msg_string());
  return writeBuffer(path, buffer);
}

}  // namespace scansurf
