// OBJ and binary STL through Draco's ObjEncoder and StlEncoder (no hand-written formats),
// buffered in memory and written through an AtomicFile.
#include "io/mesh_writers.h"

#include <draco/io/obj_encoder.h>
#include <draco/io/stl_encoder.h>
#include <draco/mesh/mesh.h>

#include <algorithm>
#include <limits>
#include <vector>

#include "core/text_fields.h"
#include "io/atomic_file.h"
#include "io/draco_writer.h"
#include "scansurf/version.h"

namespace scansurf {

Result<void> writeObj(const std::filesystem::path& path, const CompactMesh& mesh, const std::string& name,
                      const std::string& units) {
  std::unique_ptr<draco::Mesh> dm = toDracoMesh(mesh);
  dm->SetName(name);
  draco::ObjEncoder encoder;
  draco::EncoderBuffer buffer;
  if (!encoder.EncodeToBuffer(*dm, &buffer))
    return makeError(Errc::Internal, "cannot encode '" + path.string() + "': Draco's OBJ encoder failed");
  const std::string comment = std::string("# scansurf ") + version() + ": surface of \"" + oneLineText(name, "\"") +
                              "\", coordinates in " + (units.empty() ? std::string("the input's units") : oneLineText(units)) +
                              "\n";
  return writeFileAtomically(path, [&](AtomicFile& file) -> Result<void> {
    SCANSURF_TRY(file.write(comment.data(), comment.size()));
    return file.write(buffer.data(), buffer.size());
  });
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
