// Binary little-endian PLY (Turk, "The PLY polygon file format", 1994), written through a
// buffer into an AtomicFile.
#include "io/ply_writer.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "core/text_fields.h"
#include "geometry/mesh/compact_mesh.h"
#include "io/atomic_file.h"
#include "scansurf/version.h"

namespace scansurf {
namespace {

// Serializes little-endian values into a buffer flushed to the file in large writes.
class LittleEndianWriter {
 public:
  explicit LittleEndianWriter(AtomicFile& file) : file_(file) { buffer_.reserve(kFlushSize + 64); }

  void bytes(const void* data, std::size_t size) {
    const auto* p = static_cast<const char*>(data);
    buffer_.insert(buffer_.end(), p, p + size);
  }
  template <typename T>
  void value(T v) {
    std::array<char, sizeof(T)> raw{};
    std::memcpy(raw.data(), &v, sizeof(T));
    if constexpr (std::endian::native == std::endian::big) std::reverse(raw.begin(), raw.end());
    bytes(raw.data(), raw.size());
  }
  // Writes the buffer out once it is large; call after each record.
  Result<void> maybeFlush() { return buffer_.size() >= kFlushSize ? flush() : Result<void>{}; }
  Result<void> flush() {
    Result<void> r = file_.write(buffer_.data(), buffer_.size());
    buffer_.clear();
    return r;
  }

 private:
  static constexpr std::size_t kFlushSize = 1 << 20;
  AtomicFile& file_;
  std::vector<char> buffer_;
};

Result<void> checkIndexRange(const std::filesystem::path& path, std::size_t vertices) {
  if (vertices > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    return makeError(Errc::Io, "cannot write '" + path.string() + "': more vertices than PLY int indices hold");
  return {};
}

// The unit every coordinate is in: the contour set's (mm for DICOM), else "the input's".
std::string unitsComment(const std::string& units) {
  return "comment units: " + (units.empty() ? std::string("the input contours' units") : oneLineText(units)) +
         " (x, y in-plane, z along the slices)\n";
}

// Which program and version made the file.
std::string generatorComment() { return std::string("comment generator: scansurf ") + version() + "\n"; }

}  // namespace

Result<void> writeSurfacePly(const std::filesystem::path& path, const MultiLabelMesh& mesh, const FeatureSurface& surface,
                             const std::string& units) {
  SCANSURF_ASSIGN_OR_RETURN(const CompactMesh compact, compactSurface(mesh, surface));
  return writeSurfacePly(path, compact, surface.feature, units);
}

Result<void> writeSurfacePly(const std::filesystem::path& path, const CompactMesh& compact, int feature,
                             const std::string& units) {
  const std::size_t used = compact.vertexCount();
  SCANSURF_TRY(checkIndexRange(path, used));

  return writeFileAtomically(path, [&](AtomicFile& file) -> Result<void> {
    LittleEndianWriter out(file);
    const std::string header = "ply\nformat binary_little_endian 1.0\ncomment scansurf separating surface of feature " +
                               std::to_string(feature) + " (label " + std::to_string(feature + 1) +
                               "), faces wound counter-clockwise seen from outside\n" + generatorComment() + unitsComment(units) +
                               "element vertex " + std::to_string(used) +
                               "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                               std::to_string(compact.triangleCount()) + "\nproperty list uchar int vertex_indices\nend_header\n";
    out.bytes(header.data(), header.size());
    for (float x : compact.positions) {
      out.value(x);
      SCANSURF_TRY(out.maybeFlush());
    }
    for (std::size_t t = 0; t < compact.triangleCount(); ++t) {
      out.value(std::uint8_t{3});
      for (int c = 0; c < 3; ++c) out.value(static_cast<std::int32_t>(compact.triangles[3 * t + c]));
      SCANSURF_TRY(out.maybeFlush());
    }
    return out.flush();
  });
}

Result<void> writeMultiLabelPly(const std::filesystem::path& path, const MultiLabelMesh& mesh, const std::string& units) {
  SCANSURF_TRY(checkIndexRange(path, mesh.vertexCount()));
  return writeFileAtomically(path, [&](AtomicFile& file) -> Result<void> {
    LittleEndianWriter out(file);
    const std::string header =
        "ply\nformat binary_little_endian 1.0\n"
        "comment scansurf multi-label separating surfaces; label 0 = background, label L = feature L-1\n"
        "comment label_inside < label_outside; each face's normal (counter-clockwise) points from "
        "label_inside's region into label_outside's\n" +
        generatorComment() + unitsComment(units) + "element vertex " + std::to_string(mesh.vertexCount()) +
        "\nproperty float x\nproperty float y\nproperty float z\nelement face " + std::to_string(mesh.triangleCount()) +
        "\nproperty list uchar int vertex_indices\nproperty ushort label_inside\nproperty ushort label_outside\n"
        "end_header\n";
    out.bytes(header.data(), header.size());
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
      for (int a = 0; a < 3; ++a) out.value(mesh.positions[3 * v + a]);
      SCANSURF_TRY(out.maybeFlush());
    }
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
      out.value(std::uint8_t{3});
      for (int c = 0; c < 3; ++c) out.value(static_cast<std::int32_t>(mesh.triangles[3 * t + c]));
      out.value(static_cast<std::uint16_t>(mesh.labels[2 * t]));
      out.value(static_cast<std::uint16_t>(mesh.labels[2 * t + 1]));
      SCANSURF_TRY(out.maybeFlush());
    }
    return out.flush();
  });
}

}  // namespace scansurf
