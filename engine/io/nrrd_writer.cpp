// NRRD writer (format 4: teem.sourceforge.net/nrrd/format.html): a text header, a blank line,
// then the voxels gzip-compressed by zlib.
#include "io/nrrd_writer.h"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "core/text_fields.h"
#include "io/atomic_file.h"
#include "io/slicer_terminology.h"

namespace scansurf {
namespace {

std::string vec(const std::array<double, 3>& v) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "(%.17g,%.17g,%.17g)", v[0], v[1], v[2]);
  return buf;
}

// Segment names and values must stay on one header line (and start no key of their own).
std::string oneLine(const std::string& s) { return oneLineText(s); }

Result<std::vector<unsigned char>> gzip(const void* data, std::size_t size, const std::filesystem::path& path) {
  z_stream z{};
  // windowBits 15 + 16: a gzip wrapper, which NRRD's "encoding: gzip" expects.
  if (deflateInit2(&z, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK)
    return makeError(Errc::Internal, "cannot write '" + path.string() + "': zlib initialisation failed");
  // zlib counts in 32 bits: feed and drain it in chunks so volumes over 4 GiB compress whole.
  constexpr std::size_t kChunk = std::size_t{1} << 30;
  std::vector<unsigned char> out;
  std::vector<unsigned char> buffer(std::size_t{1} << 20);
  const auto* in = static_cast<const unsigned char*>(data);
  std::size_t left = size;
  int rc = Z_OK;
  while (rc != Z_STREAM_END) {
    if (z.avail_in == 0 && left > 0) {
      const std::size_t take = std::min(left, kChunk);
      z.next_in = const_cast<Bytef*>(in);
      z.avail_in = static_cast<uInt>(take);
      in += take, left -= take;
    }
    z.next_out = buffer.data();
    z.avail_out = static_cast<uInt>(buffer.size());
    rc = deflate(&z, left == 0 ? Z_FINISH : Z_NO_FLUSH);
    if (rc == Z_STREAM_ERROR) break;
    out.insert(out.end(), buffer.data(), buffer.data() + (buffer.size() - z.avail_out));
  }
  deflateEnd(&z);
  if (rc != Z_STREAM_END) return makeError(Errc::Internal, "cannot write '" + path.string() + "': zlib compression failed");
  return out;
}

}  // namespace

RegularLabelVolume regularize(const LabelVolume& volume) {
  const Grid& g = volume.grid;
  RegularLabelVolume out;
  out.nx = g.nx, out.ny = g.ny;
  out.geometry.origin = {g.originX, g.originY, g.layerZ.empty() ? 0.0 : g.layerZ.front()};
  out.geometry.axes[0] = {g.spacingX, 0, 0};
  out.geometry.axes[1] = {0, g.spacingY, 0};
  if (g.nz < 2) {
    out.nz = g.nz;
    out.labels = volume.labels;
    out.geometry.axes[2] = {0, 0, 1};
    return out;
  }
  const double first = g.layerZ.front(), last = g.layerZ.back();
  const double mean = (last - first) / (g.nz - 1);
  double minGap = mean;
  bool even = true;
  for (int k = 1; k < g.nz; ++k) {
    const double gap = g.layerZ[static_cast<std::size_t>(k)] - g.layerZ[static_cast<std::size_t>(k - 1)];
    minGap = std::min(minGap, gap);
    even = even && std::abs(gap - mean) <= 1e-4 * mean;
  }
  if (even) {
    out.nz = g.nz;
    out.labels = volume.labels;
    out.geometry.axes[2] = {0, 0, mean};
    return out;
  }
  out.resampled = true;
  // Planes at the smallest gap, but never more than kMaxResampling times the layers: one odd
  // slice 0.01 mm from its neighbour must not ask for thousands of planes.
  constexpr double kMaxResampling = 8;
  const double planes = std::floor((last - first) / minGap + 1e-6) + 1;
  out.nz = static_cast<int>(std::min(planes, kMaxResampling * g.nz));
  const double step = (last - first) / (out.nz - 1);
  out.geometry.axes[2] = {0, 0, step};
  const std::size_t plane = static_cast<std::size_t>(g.nx) * static_cast<std::size_t>(g.ny);
  out.labels.resize(plane * static_cast<std::size_t>(out.nz));
  std::size_t layer = 0;
  for (int k = 0; k < out.nz; ++k) {
    const double z = first + k * step;
    while (layer + 1 < g.layerZ.size() && std::abs(g.layerZ[layer + 1] - z) < std::abs(g.layerZ[layer] - z)) ++layer;
    std::copy_n(volume.labels.begin() + static_cast<std::ptrdiff_t>(layer * plane), plane,
                out.labels.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(k) * plane));
  }
  return out;
}

namespace {

// Per label, "i0 i1 j0 j1 k0 k1" of its voxels in one layer, in one pass over the layer.
std::map<Label, std::string> extentsOf(const RegularLabelVolume& v) {
  std::map<Label, std::array<int, 6>> boxes;
  std::size_t n = 0;
  for (int k = 0; k < v.nz; ++k)
    for (int j = 0; j < v.ny; ++j)
      for (int i = 0; i < v.nx; ++i, ++n) {
        const Label l = v.labels[n];
        if (l == kBackground) continue;
        auto [it, fresh] = boxes.try_emplace(l, std::array<int, 6>{i, i, j, j, k, k});
        if (fresh) continue;
        std::array<int, 6>& b = it->second;
        b[0] = std::min(b[0], i), b[1] = std::max(b[1], i), b[2] = std::min(b[2], j), b[3] = std::max(b[3], j);
        b[4] = std::min(b[4], k), b[5] = std::max(b[5], k);
      }
  std::map<Label, std::string> out;
  for (const auto& [label, b] : boxes)
    out[label] = std::to_string(b[0]) + " " + std::to_string(b[1]) + " " + std::to_string(b[2]) + " " + std::to_string(b[3]) +
                 " " + std::to_string(b[4]) + " " + std::to_string(b[5]);
  return out;
}

std::string segmentationHeader(const std::vector<RegularLabelVolume>& layers, const std::vector<LabelEntry>& table,
                               const std::vector<int>& layerOf, bool bytes) {
  const RegularLabelVolume& first = layers.front();
  const bool list = layers.size() > 1;
  std::ostringstream h;
  h << "NRRD0004\n# scansurf label volume: every feature's own mask (label = feature index + 1, 0 = background)";
  h << (list ? "; features that share voxels are in different layers (the list axis)\n" : "\n");
  h << "type: " << (bytes ? "unsigned char" : "unsigned short") << "\ndimension: " << (list ? 4 : 3)
    << "\nspace: " << first.geometry.space << "\n";
  h << "sizes: " << (list ? std::to_string(layers.size()) + " " : "") << first.nx << " " << first.ny << " " << first.nz << "\n";
  h << "space directions: " << (list ? "none " : "") << vec(first.geometry.axes[0]) << " " << vec(first.geometry.axes[1]) << " "
    << vec(first.geometry.axes[2]) << "\n";
  h << "kinds: " << (list ? "list " : "") << "domain domain domain\nendian: little\nencoding: gzip\n";
  h << "space origin: " << vec(first.geometry.origin) << "\n";
  h << "Segmentation_MasterRepresentation:=Binary labelmap\nSegmentation_SourceRepresentation:=Binary labelmap\n";
  h << "Segmentation_ContainedRepresentationNames:=Binary labelmap|\n";
  h << "Segmentation_ReferenceImageExtentOffset:=0 0 0\n";
  std::vector<std::map<Label, std::string>> extents;
  for (const RegularLabelVolume& layer : layers) extents.push_back(extentsOf(layer));
  for (std::size_t s = 0; s < table.size(); ++s) {
    const LabelEntry& e = table[s];
    const int layer = s < layerOf.size() ? layerOf[s] : 0;
    char color[64];
    std::snprintf(color, sizeof color, "%.6g %.6g %.6g", e.color[0] / 255.0, e.color[1] / 255.0, e.color[2] / 255.0);
    const std::string p = "Segment" + std::to_string(s) + "_";
    const auto extent = extents[static_cast<std::size_t>(layer)].find(e.label);
    // IDs must be unique where names need not be.
    h << p << "ID:=Segment_" << e.label << "\n"
      << p << "Name:=" << oneLine(e.name) << "\n"
      << p << "NameAutoGenerated:=0\n"
      << p << "Color:=" << color << "\n"
      << p << "ColorAutoGenerated:=0\n"
      << p << "LabelValue:=" << e.label << "\n"
      << p << "Layer:=" << layer << "\n"
      << p
      << "Extent:=" << (extent == extents[static_cast<std::size_t>(layer)].end() ? std::string("0 -1 0 -1 0 -1") : extent->second)
      << "\n"
      << p << "Tags:=" << slicerTags(e.terminology.empty() ? slicerTerminology(terminologyOf({})) : e.terminology) << "\n";
  }
  h << "\n";
  return h.str();
}

// The voxels, the list axis fastest when there are layers.
std::vector<unsigned char> interleave(const std::vector<RegularLabelVolume>& layers, bool bytes) {
  const std::size_t voxels = layers.front().labels.size(), count = layers.size();
  std::vector<unsigned char> raw;
  raw.reserve(voxels * count * (bytes ? 1 : 2));
  for (std::size_t n = 0; n < voxels; ++n)
    for (std::size_t l = 0; l < count; ++l) {
      const Label v = layers[l].labels[n];
      raw.push_back(static_cast<unsigned char>(v & 0xFF));
      if (!bytes) raw.push_back(static_cast<unsigned char>(v >> 8));
    }
  return raw;
}

}  // namespace

Result<void> writeSegmentationNrrd(const std::filesystem::path& path, const std::vector<RegularLabelVolume>& layers,
                                   const std::vector<LabelEntry>& table, const std::vector<int>& layerOf) {
  if (layers.empty()) return makeError(Errc::InvalidArgument, "cannot write '" + path.string() + "': no label volume");
  Label maxLabel = 0;
  for (const RegularLabelVolume& l : layers)
    if (!l.labels.empty()) maxLabel = std::max(maxLabel, *std::max_element(l.labels.begin(), l.labels.end()));
  const bool bytes = maxLabel < 256;
  const std::string header = segmentationHeader(layers, table, layerOf, bytes);
  const std::vector<unsigned char> raw = interleave(layers, bytes);
  SCANSURF_ASSIGN_OR_RETURN(std::vector<unsigned char> packed, gzip(raw.data(), raw.size(), path));
  return writeFileAtomically(path, [&](AtomicFile& file) -> Result<void> {
    SCANSURF_TRY(file.write(header.data(), header.size()));
    return file.write(packed.data(), packed.size());
  });
}

Result<void> writeNrrd(const std::filesystem::path& path, const RegularLabelVolume& volume,
                       const std::vector<LabelEntry>& table) {
  return writeSegmentationNrrd(path, {volume}, table, std::vector<int>(table.size(), 0));
}

Result<void> writeLabelTable(const std::filesystem::path& path, const std::vector<LabelEntry>& table) {
  std::ostringstream t;
  t << "# scansurf label table (3D Slicer colour table): label name R G B A\n0 background 0 0 0 0\n";
  for (const LabelEntry& e : table) {
    std::string name = oneLine(e.name);
    std::replace(name.begin(), name.end(), ' ', '_');  // one token per field
    t << e.label << " " << name << " " << int{e.color[0]} << " " << int{e.color[1]} << " " << int{e.color[2]} << " 255\n";
  }
  const std::string text = t.str();
  return writeFileAtomically(path, text.data(), text.size());
}

}  // namespace scansurf
