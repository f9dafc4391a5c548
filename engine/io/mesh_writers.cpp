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

Result<void> writeObj(const std::filesystem::path& path, const CompactMesh& mesh, const std::string& name) {
  std::unique_ptr<draco::Mesh> dm = toDracoMesh(mesh);
  dm->SetName(name);
  draco::ObjEncoder encoder;
  draco::EncoderBuffer buffer;
  if (!encoder.EncodeToBuffer(*dm, &buffer))
    return makeError(Errc::Internal, "cannot encode '" + path.string() + "': Draco's OBJ encoder failed");
  return writeFileAtomically(path, buffer.data(), buffer.size());
}

Result<void> writeStl(const std::filesystem::path& path, const CompactMesh& mesh) {
  std::unique_ptr<draco::Mesh> dm = toDracoMesh(mesh);
  draco::StlEncoder encoder;
  draco::EncoderBuffer buffer;
  if (const draco::Status s = encoder.EncodeToBuffer(*dm, &buffer); !s.ok())
    return makeError(Errc::Internal, "cannot encode '" + path.string() + "': " + s.error_msg_string());
  return writeFileAtomically(path, buffer.data(), buffer.size());
}

}  // namespace scansurf
