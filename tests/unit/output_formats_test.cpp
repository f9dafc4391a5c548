// Round trips of every output format: each file is read back (Draco's decoders for .drc and
// GLB, small readers of our own for OBJ, STL, NRRD, PNG) and compared with what was written.
#include <draco/compression/decode.h>
#include <draco/io/scene_io.h>
#include <draco/scene/scene.h>
#include <gtest/gtest.h>
#include <png.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <zlib.h>
#include <pugixml.hpp>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/extraction/assembly.h"
#include "geometry/extraction/cell_cases.h"
#include "geometry/extraction/feature_surfaces.h"
#include "io/draco_writer.h"
#include "io/gltf_writer.h"
#include "io/mesh_writers.h"
#include "io/nrrd_writer.h"
#include "io/png_writer.h"
#include "scansurf/nesting.h"
#include "scansurf/outputs.h"
#include "scansurf/palette.h"
#include "scansurf/report.h"
#include "scansurf/version.h"
#include "support/nrrd_reader.h"
#include "support/reference_rasterizer.h"
#include "support/scratch_dir_test.h"
#include "support/shapes.h"

namespace scansurf {
namespace {

namespace fs = std::filesystem;

struct Built {
  ContourSet set;
  LabelVolume volume;
  Surfaces surfaces;
  std::vector<CompactMesh> meshes;
};

// The whole method on the CPU: reference scan conversion and classification.
Built buildOnCpu(ContourSet set, double voxelSize) {
  Built b;
  b.set = std::move(set);
  const Nesting nesting = computeNesting(b.set);
  GridOptions options;
  options.voxelSize = voxelSize;
  auto grid = makeGrid(b.set, options);
  EXPECT_TRUE(grid) << grid.error().message;
  b.volume = test::referenceScanConvert(b.set, *grid, nesting.order, 8);
  const std::vector<CellCase> cells = classifyCellsReference(b.volume);
  b.surfaces.mesh = assembleMesh(*grid, cells, 1);
  b.surfaces.features =
      extractFeatureSurfaces(b.surfaces.mesh, static_cast<int>(b.set.features.size()), nesting, SurfaceConvention::Enclosing);
  for (const FeatureSurface& f : b.surfaces.features) {
    auto m = compactSurface(b.surfaces.mesh, f);
    EXPECT_TRUE(m);
    b.meshes.push_back(*m);
  }
  return b;
}

const Built& nested() {
  static const Built b = buildOnCpu(nestedSpheresContours(12, 5, 1.5), 1.0);  // "outer", "inner"
  return b;
}

using OutputFormatsTest = test::ScratchDirTest;

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

CompactMesh fromDraco(const draco::Mesh& m) {
  CompactMesh out;
  const draco::PointAttribute* pos = m.GetNamedAttribute(draco::GeometryAttribute::POSITION);
  for (draco::PointIndex p(0); p < m.num_points(); ++p) {
    float v[3];
    pos->GetMappedValue(p, v);
    out.positions.insert(out.positions.end(), v, v + 3);
  }
  for (draco::FaceIndex f(0); f < m.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) out.triangles.push_back(m.face(f)[c].value());
  return out;
}

// Same topology, and every vertex within `bound` (per axis) of a vertex of the original.
void expectSameSurface(const CompactMesh& original, const CompactMesh& read, double bound) {
  const MeshStats a = computeMeshStats(original.positions, original.triangles);
  const MeshStats b = computeMeshStats(read.positions, read.triangles);
  EXPECT_EQ(b.triangles, a.triangles);
  EXPECT_EQ(b.vertices, a.vertices);
  EXPECT_EQ(b.components, a.components);
  EXPECT_EQ(b.genus, a.genus);
  EXPECT_EQ(b.closed, a.closed);
  EXPECT_EQ(b.manifold, a.manifold);
  EXPECT_EQ(b.oriented, a.oriented);
  // Moving every vertex by at most `bound` per axis changes the volume by at most area * |d|.
  EXPECT_NEAR(b.volume, a.volume, a.area * bound * std::sqrt(3.0) + 1e-6 * std::abs(a.volume));
  // Nearest original vertex, searched in x order.
  std::vector<std::array<float, 3>> sorted;
  for (std::size_t v = 0; v < original.vertexCount(); ++v)
    sorted.push_back({original.positions[3 * v], original.positions[3 * v + 1], original.positions[3 * v + 2]});
  std::sort(sorted.begin(), sorted.end());
  double worst = 0;
  for (std::size_t v = 0; v < read.vertexCount(); ++v) {
    const float* p = &read.positions[3 * v];
    auto it =
        std::lower_bound(sorted.begin(), sorted.end(), std::array<float, 3>{static_cast<float>(p[0] - bound), -1e30f, -1e30f});
    double best = 1e30;
    for (; it != sorted.end() && (*it)[0] <= p[0] + bound; ++it) {
      double d = 0;
      for (int a2 = 0; a2 < 3; ++a2) d = std::max(d, std::abs(static_cast<double>((*it)[static_cast<std::size_t>(a2)]) - p[a2]));
      best = std::min(best, d);
    }
    worst = std::max(worst, best);
  }
  EXPECT_LE(worst, bound);
}

TEST_F(OutputFormatsTest, DefaultQuantizationStaysBelowATenthOfAVoxelAndKeepsVerticesApart) {
  const Built& b = nested();
  const double bound = defaultQuantizationError(b.volume.grid);
  EXPECT_NEAR(bound, 1.0 / 25.0, 1e-12);  // 1 mm pixels, 1.5 mm slices
  DracoOptions options;
  options.maxError = bound;
  for (const CompactMesh& m : b.meshes) {
    const int bits = quantizationBitsFor(m, options);
    EXPECT_LE(quantizationError(m, bits), bound);
    EXPECT_GT(quantizationError(m, bits - 1), 0.99 * bound) << "the fewest bits";
  }
  options.quantizationBits = 14;
  EXPECT_EQ(quantizationBitsFor(b.meshes[0], options), 14);
}

TEST_F(OutputFormatsTest, DrcRoundTripKeepsTopologyAndPositionsWithinTheBound) {
  const Built& b = nested();
  DracoOptions options;
  options.maxError = defaultQuantizationError(b.volume.grid);
  for (const CompactMesh& m : b.meshes) {
    const fs::path path = dir_ / "surface.drc";
    ASSERT_TRUE(writeDrc(path, m, options));
    const std::string bytes = readFile(path);
    draco::DecoderBuffer buffer;
    buffer.Init(bytes.data(), bytes.size());
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    ASSERT_TRUE(decoded.ok()) << decoded.status().error_msg_string();
    expectSameSurface(m, fromDraco(*decoded.value()), options.maxError * 1.0001);
  }
  EXPECT_EQ(fileCount(), 1u) << "no temporary files left";
}

// The GLB container (glTF 2.0 §"Binary glTF Layout"): header, JSON chunk, BIN chunk.
struct Glb {
  nlohmann::json json;
  std::string bin;
};
Glb parseGlb(const std::string& bytes) {
  auto u32 = [&](std::size_t at) {
    std::uint32_t v;
    std::memcpy(&v, bytes.data() + at, 4);
    return v;
  };
  Glb out;
  EXPECT_GE(bytes.size(), 20u);
  EXPECT_EQ(bytes.substr(0, 4), "glTF");
  EXPECT_EQ(u32(4), 2u);
  EXPECT_EQ(u32(8), bytes.size());
  const std::uint32_t jsonLength = u32(12);
  EXPECT_EQ(u32(16), 0x4E4F534Au);  // "JSON"
  out.json = nlohmann::json::parse(bytes.substr(20, jsonLength));
  const std::size_t binAt = 20 + jsonLength;
  if (binAt < bytes.size()) {
    EXPECT_EQ(u32(binAt + 4), 0x004E4942u);  // "BIN"
    out.bin = bytes.substr(binAt + 8, u32(binAt));
  }
  return out;
}

// Structural checks: accessors and buffer views stay inside the BIN chunk, every primitive's
// POSITION accessor holds `vertices` VEC3 floats, Draco extension declared when used.
void checkGltfStructure(const Glb& glb, bool draco, const std::vector<std::size_t>& vertices,
                        const std::vector<std::size_t>& triangles) {
  const nlohmann::json& j = glb.json;
  ASSERT_EQ(j["asset"]["version"], "2.0");
  const auto has = [&](const char* list) {
    if (!j.contains(list)) return false;
    for (const auto& e : j[list])
      if (e == "KHR_draco_mesh_compression") return true;
    return false;
  };
  EXPECT_EQ(has("extensionsUsed"), draco);
  EXPECT_EQ(has("extensionsRequired"), draco);
  ASSERT_EQ(j["buffers"].size(), 1u);
  EXPECT_EQ(j["buffers"][0]["byteLength"].get<std::size_t>(),
            glb.bin.size() - (glb.bin.size() - j["buffers"][0]["byteLength"].get<std::size_t>()));
  EXPECT_LE(j["buffers"][0]["byteLength"].get<std::size_t>(), glb.bin.size());
  for (const auto& view : j["bufferViews"])
    EXPECT_LE(view.value("byteOffset", std::size_t{0}) + view["byteLength"].get<std::size_t>(),
              j["buffers"][0]["byteLength"].get<std::size_t>());
  ASSERT_EQ(j["meshes"].size(), vertices.size());
  for (std::size_t m = 0; m < vertices.size(); ++m) {
    ASSERT_EQ(j["meshes"][m]["primitives"].size(), 1u);
    const auto& prim = j["meshes"][m]["primitives"][0];
    const auto& pos = j["accessors"][prim["attributes"]["POSITION"].get<std::size_t>()];
    EXPECT_EQ(pos["type"], "VEC3");
    EXPECT_EQ(pos["componentType"], 5126);
    EXPECT_EQ(pos["count"].get<std::size_t>(), vertices[m]);
    EXPECT_EQ(pos["min"].size(), 3u);
    const auto& idx = j["accessors"][prim["indices"].get<std::size_t>()];
    EXPECT_EQ(idx["count"].get<std::size_t>(), 3 * triangles[m]);
    EXPECT_EQ(prim.contains("extensions") && prim["extensions"].contains("KHR_draco_mesh_compression"), draco);
    if (draco) {
      EXPECT_FALSE(pos.contains("bufferView")) << "Draco accessors carry no buffer view";
      EXPECT_LT(prim["extensions"]["KHR_draco_mesh_compression"]["bufferView"].get<std::size_t>(), j["bufferViews"].size());
    }
  }
}

TEST_F(OutputFormatsTest, GlbSceneWithAndWithoutDracoValidatesAndDecodes) {
  const Built& b = nested();
  const std::vector<Rgb> colors = featureColors(b.set);
  std::vector<GltfFeature> features;
  std::vector<std::size_t> vertices, triangles;
  for (std::size_t f = 0; f < b.meshes.size(); ++f) {
    features.push_back({b.set.features[f].name, colors[f], &b.meshes[f]});
    vertices.push_back(b.meshes[f].vertexCount());
    triangles.push_back(b.meshes[f].triangleCount());
  }
  for (bool draco : {true, false}) {
    SCOPED_TRACE(draco ? "draco" : "plain");
    GlbOptions options;
    options.draco = draco;
    options.dracoOptions.maxError = defaultQuantizationError(b.volume.grid);
    const fs::path path = dir_ / (draco ? "draco.glb" : "plain.glb");
    ASSERT_TRUE(writeGlb(path, features, options));
    const Glb glb = parseGlb(readFile(path));
    checkGltfStructure(glb, draco, vertices, triangles);
    if (!draco)  // plain buffer views name their target: vertex attributes, then indices
      for (const auto& mesh : glb.json["meshes"]) {
        const auto& primitive = mesh["primitives"][0];
        const auto viewOf = [&](const nlohmann::json& accessor) {
          return glb.json["bufferViews"][glb.json["accessors"][accessor.get<std::size_t>()]["bufferView"].get<std::size_t>()];
        };
        EXPECT_EQ(viewOf(primitive["attributes"]["POSITION"]).value("target", 0), 34962);
        EXPECT_EQ(viewOf(primitive["indices"]).value("target", 0), 34963);
      }
    // Names and colours.
    for (std::size_t f = 0; f < features.size(); ++f) {
      const auto& mesh = glb.json["meshes"][f];
      EXPECT_EQ(mesh["name"], features[f].name);
      const auto& material = glb.json["materials"][mesh["primitives"][0]["material"].get<std::size_t>()];
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(material["pbrMetallicRoughness"]["baseColorFactor"][static_cast<std::size_t>(c)].get<double>(),
                    srgbToLinear(colors[f][static_cast<std::size_t>(c)]), 1e-5);
    }
    bool named = false;
    for (const auto& node : glb.json["nodes"]) named = named || node.value("name", "") == "inner";
    EXPECT_TRUE(named);
    // Draco's own scene reader decodes it back.
    auto scene = draco::ReadSceneFromFile(path.string());
    ASSERT_TRUE(scene.ok()) << scene.status().error_msg_string();
    ASSERT_EQ(scene.value()->NumMeshes(), static_cast<int>(features.size()));
    for (int m = 0; m < scene.value()->NumMeshes(); ++m)
      expectSameSurface(b.meshes[static_cast<std::size_t>(m)], fromDraco(scene.value()->GetMesh(draco::MeshIndex(m))),
                        draco ? options.dracoOptions.maxError * 1.0001 : 0.0);
  }
}

// What a viewer needs (issue 14): smooth outward normals, the enclosing feature translucent so
// the one inside shows, a root node into glTF's y-up metres, the generator and the frame.
TEST_F(OutputFormatsTest, GlbSceneShowsRightInAViewer) {
  const Built& b = nested();
  for (SceneFrame frame : {SceneFrame::Gltf, SceneFrame::Patient}) {
    SCOPED_TRACE(frame == SceneFrame::Gltf ? "gltf frame" : "patient frame");
    SceneOptions options;
    options.frame = frame;
    const fs::path path = dir_ / "viewer.glb";
    ASSERT_TRUE(writeScene(path, b.set, b.surfaces, options));
    const Glb glb = parseGlb(readFile(path));
    const nlohmann::json& j = glb.json;
    EXPECT_EQ(j["asset"]["generator"], std::string("scansurf ") + version());
    EXPECT_EQ(j["asset"]["extras"]["scansurf"]["unit"], "mm");
    EXPECT_EQ(j["asset"]["extras"]["scansurf"]["coordinates"], "patient LPS (x left, y posterior, z superior)");
    const auto& roots = j["scenes"][0]["nodes"];
    if (frame == SceneFrame::Gltf) {
      ASSERT_EQ(roots.size(), 1u);
      const auto& root = j["nodes"][roots[0].get<std::size_t>()];
      const std::vector<double> expected{1e-3, 0, 0, 0, 0, 0, -1e-3, 0, 0, 1e-3, 0, 0, 0, 0, 0, 1};
      EXPECT_EQ(root["matrix"].get<std::vector<double>>(), expected);
      EXPECT_EQ(root["children"].size(), b.set.features.size());
    } else {
      EXPECT_EQ(roots.size(), b.set.features.size()) << "no root transform";
      for (const auto& node : j["nodes"]) EXPECT_FALSE(node.contains("matrix"));
    }
    for (std::size_t f = 0; f < b.set.features.size(); ++f) {
      const auto& primitive = j["meshes"][f]["primitives"][0];
      EXPECT_TRUE(primitive["attributes"].contains("NORMAL"));
      const auto& material = j["materials"][primitive["material"].get<std::size_t>()];
      const bool encloses = b.set.features[f].name == "outer";
      EXPECT_EQ(material.value("alphaMode", "OPAQUE"), encloses ? "BLEND" : "OPAQUE") << b.set.features[f].name;
      EXPECT_NEAR(material["pbrMetallicRoughness"]["baseColorFactor"][3].get<double>(), encloses ? 0.3 : 1.0, 1e-6);
    }
    // Draco decodes the normals: unit length, pointing out of the (spherical) surfaces.
    auto scene = draco::ReadSceneFromFile(path.string());
    ASSERT_TRUE(scene.ok()) << scene.status().error_msg_string();
    const draco::Mesh& mesh = scene.value()->GetMesh(draco::MeshIndex(0));
    const draco::PointAttribute* normals = mesh.GetNamedAttribute(draco::GeometryAttribute::NORMAL);
    const draco::PointAttribute* positions = mesh.GetNamedAttribute(draco::GeometryAttribute::POSITION);
    ASSERT_NE(normals, nullptr);
    double centre[3] = {0, 0, 0};
    for (draco::PointIndex p(0); p < mesh.num_points(); ++p) {
      float v[3];
      positions->GetMappedValue(p, v);
      for (int a = 0; a < 3; ++a) centre[a] += v[a] / static_cast<double>(mesh.num_points());
    }
    std::size_t outward = 0;
    for (draco::PointIndex p(0); p < mesh.num_points(); ++p) {
      float n[3], v[3];
      normals->GetMappedValue(p, n);
      positions->GetMappedValue(p, v);
      EXPECT_NEAR(std::hypot(n[0], n[1], n[2]), 1.0, 0.01);
      outward += (n[0] * (v[0] - centre[0]) + n[1] * (v[1] - centre[1]) + n[2] * (v[2] - centre[2])) > 0;
    }
    EXPECT_EQ(outward, mesh.num_points());
  }
}

// Names are bytes from the input: a Latin-1 ROI name (R, 0xFC, ckenmark) must not break the
// UTF-8 formats; the invalid byte becomes U+FFFD in the GLB and the report.
TEST_F(OutputFormatsTest, NamesThatAreNotUtf8StillWrite) {
  Built b = nested();
  b.set.features[0].name =
      "R\xFC"
      "ckenmark";
  ASSERT_TRUE(writeScene(dir_ / "latin1.glb", b.set, b.surfaces));
  const Glb glb = parseGlb(readFile(dir_ / "latin1.glb"));
  EXPECT_EQ(glb.json["meshes"][0]["name"],
            "R\xEF\xBF\xBD"
            "ckenmark");
  RunReport r;
  r.features.push_back({b.set.features[0].name, 1, {1, 2, 3}, {}, {}});
  ASSERT_TRUE(writeReport(dir_ / "latin1.json", r));
  EXPECT_EQ(nlohmann::json::parse(readFile(dir_ / "latin1.json"))["features"][0]["name"],
            "R\xEF\xBF\xBD"
            "ckenmark");
}

CompactMesh readObj(const fs::path& path);

// Names with quotes, backslashes and control characters: the GLB keeps them exactly (Draco's
// encoder once wrote them unescaped and the run failed), and in the OBJ a newline cannot start
// a statement of its own (a name with "\nmtllib /etc/passwd\nv 0 0 0" added lines).
TEST_F(OutputFormatsTest, NamesWithQuotesAndControlCharactersStayNames) {
  Built b = nested();
  const std::string hostile = "PTV \"boost\" \\ tab\tline\nmtllib /etc/passwd\nv 0 0 0\x1B[2J";
  b.set.features[0].name = hostile;
  ASSERT_TRUE(writeScene(dir_ / "names.glb", b.set, b.surfaces));
  const Glb glb = parseGlb(readFile(dir_ / "names.glb"));
  EXPECT_EQ(glb.json["meshes"][0]["name"], hostile);
  EXPECT_EQ(glb.json["nodes"][0]["name"], hostile);
  EXPECT_EQ(glb.json["materials"][0]["name"], hostile);
  ASSERT_TRUE(writeObj(dir_ / "names.obj", b.meshes[0], hostile));
  const std::string obj = readFile(dir_ / "names.obj");
  EXPECT_EQ(obj.find("\nmtllib"), std::string::npos);
  EXPECT_EQ(obj.find("\nv 0 0 0"), std::string::npos);
  EXPECT_EQ(obj.find('\x1B'), std::string::npos);
  EXPECT_EQ(readObj(dir_ / "names.obj").positions.size(), b.meshes[0].positions.size()) << "no vertex added";
}

// Every file records which scansurf made it.
TEST_F(OutputFormatsTest, EveryFormatNamesItsGenerator) {
  const Built& b = nested();
  const std::string generator = std::string("scansurf ") + version();
  ASSERT_TRUE(writeSurface(dir_ / "s.ply", b.surfaces, 0, MeshFormat::Ply, b.set));
  ASSERT_TRUE(writeSurface(dir_ / "s.obj", b.surfaces, 0, MeshFormat::Obj, b.set));
  ASSERT_TRUE(writeSurface(dir_ / "s.stl", b.surfaces, 0, MeshFormat::Stl, b.set));
  ASSERT_TRUE(writeMultiLabelMesh(dir_ / "m.ply", b.surfaces));
  EXPECT_NE(readFile(dir_ / "s.ply").find("comment generator: " + generator + "\n"), std::string::npos);
  EXPECT_NE(readFile(dir_ / "m.ply").find("comment generator: " + generator + "\n"), std::string::npos);
  EXPECT_EQ(readFile(dir_ / "s.obj").rfind("# " + generator, 0), 0u);
  EXPECT_EQ(readFile(dir_ / "s.stl").substr(0, generator.size()), generator);
  EXPECT_EQ(readObj(dir_ / "s.obj").triangleCount(), b.meshes[0].triangleCount()) << "the comment keeps the OBJ readable";
}

// Minimal OBJ reader: `v x y z` and `f a b c` (1-based, optionally a/b/c).
CompactMesh readObj(const fs::path& path) {
  CompactMesh m;
  std::istringstream in(readFile(path));
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream l(line);
    std::string tag;
    l >> tag;
    if (tag == "v") {
      float x, y, z;
      l >> x >> y >> z;
      m.positions.insert(m.positions.end(), {x, y, z});
    } else if (tag == "f") {
      std::string c;
      int n = 0;
      while (l >> c) m.triangles.push_back(static_cast<std::uint32_t>(std::stoul(c.substr(0, c.find('/'))) - 1)), ++n;
      EXPECT_EQ(n, 3);
    }
  }
  return m;
}

TEST_F(OutputFormatsTest, ObjRoundTrip) {
  const Built& b = nested();
  for (std::size_t f = 0; f < b.meshes.size(); ++f) {
    const fs::path path = dir_ / "surface.obj";
    ASSERT_TRUE(writeObj(path, b.meshes[f], b.set.features[f].name));
    expectSameSurface(b.meshes[f], readObj(path), 1e-6 * 20);  // 6 decimals
  }
}

TEST_F(OutputFormatsTest, BinaryStlRoundTripWithOutwardNormals) {
  const Built& b = nested();
  const CompactMesh& m = b.meshes[0];
  const fs::path path = dir_ / "surface.stl";
  ASSERT_TRUE(writeStl(path, m));
  const std::string bytes = readFile(path);
  ASSERT_GE(bytes.size(), 84u);
  std::uint32_t count;
  std::memcpy(&count, bytes.data() + 80, 4);
  ASSERT_EQ(count, m.triangleCount());
  ASSERT_EQ(bytes.size(), 84u + 50u * count);
  double volume = 0;
  int outward = 0;
  for (std::uint32_t t = 0; t < count; ++t) {
    float rec[12];
    std::memcpy(rec, bytes.data() + 84 + 50 * t, sizeof rec);
    const float* a = rec + 3;
    const float* b2 = rec + 6;
    const float* c = rec + 9;
    // Exactly the original triangle's corners, in order.
    for (int k = 0; k < 3; ++k)
      for (int ax = 0; ax < 3; ++ax)
        EXPECT_EQ(rec[3 + 3 * k + ax],
                  m.positions[3 * m.triangles[3 * t + static_cast<std::size_t>(k)] + static_cast<std::size_t>(ax)]);
    const double ux = b2[0] - a[0], uy = b2[1] - a[1], uz = b2[2] - a[2];
    const double vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
    const double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    outward += (nx * rec[0] + ny * rec[1] + nz * rec[2]) > 0;
    volume +=
        (a[0] * (b2[1] * c[2] - b2[2] * c[1]) - a[1] * (b2[0] * c[2] - b2[2] * c[0]) + a[2] * (b2[0] * c[1] - b2[1] * c[0])) / 6;
  }
  EXPECT_EQ(outward, static_cast<int>(count)) << "stored normals agree with the winding";
  EXPECT_NEAR(volume, computeMeshStats(m.positions, m.triangles).volume, 1e-6 * volume);
}

using test::Nrrd;
using test::readNrrd;

std::vector<double> numbers(std::string s) {
  for (char& c : s)
    if (c == '(' || c == ')' || c == ',') c = ' ';
  std::istringstream in(s);
  std::vector<double> out;
  double v;
  while (in >> v) out.push_back(v);
  return out;
}

// A voxel whose centre is at a known mm position reads the label of the contour around it.
TEST_F(OutputFormatsTest, NrrdGeometryPutsKnownPointsInTheirFeature) {
  const Built& b = nested();
  std::vector<LabelEntry> table;
  for (std::size_t f = 0; f < b.set.features.size(); ++f)
    table.push_back({labelOfFeature(static_cast<int>(f)), b.set.features[f].name, featureColors(b.set)[f]});
  const RegularLabelVolume regular = regularize(b.volume);
  EXPECT_FALSE(regular.resampled) << "1.5 mm slices are evenly spaced";
  const fs::path path = dir_ / "labels.seg.nrrd";
  ASSERT_TRUE(writeNrrd(path, regular, table));
  const Nrrd n = readNrrd(path);
  EXPECT_EQ(n.fields.at("type"), "unsigned char");
  EXPECT_EQ(n.fields.at("encoding"), "gzip");
  EXPECT_EQ(n.fields.at("space"), "left-posterior-superior");
  EXPECT_EQ(n.fields.at("Segment1_Name"), "inner");
  EXPECT_EQ(n.fields.at("Segment1_LabelValue"), "2");
  // Slicer's terminology tag, the codes the DICOM SEG gives: seven fields, ended by '|'.
  EXPECT_EQ(n.fields.at("Segment1_Tags"),
            "TerminologyEntry:Segmentation category and type - 3D Slicer General Anatomy list~SCT^85756007^Tissue~"
            "SCT^85756007^Tissue~^^~Anatomic codes - DICOM master list~^^~^^|");
  const std::vector<double> sizes = numbers(n.fields.at("sizes"));
  const std::vector<double> dirs = numbers(n.fields.at("space directions"));
  const std::vector<double> origin = numbers(n.fields.at("space origin"));
  ASSERT_EQ(sizes.size(), 3u);
  ASSERT_EQ(dirs.size(), 9u);
  ASSERT_EQ(origin.size(), 3u);
  ASSERT_EQ(n.data.size(), static_cast<std::size_t>(sizes[0] * sizes[1] * sizes[2]));
  // Diagonal directions here; index = (p - origin) / step, rounded.
  auto labelAt = [&](double x, double y, double z) {
    const double p[3] = {x, y, z};
    long idx[3];
    for (int a = 0; a < 3; ++a)
      idx[a] = std::lround((p[a] - origin[static_cast<std::size_t>(a)]) / dirs[static_cast<std::size_t>(4 * a)]);
    return static_cast<int>(static_cast<unsigned char>(n.data[static_cast<std::size_t>(
        idx[0] + static_cast<long>(sizes[0]) * (idx[1] + static_cast<long>(sizes[1]) * idx[2]))]));
  };
  // Spheres centred at the origin, slices at z = ±0.75, ±2.25, ...: inner r = 5, outer r = 12.
  EXPECT_EQ(labelAt(0, 0, 0.75), 2);  // inside "inner"
  EXPECT_EQ(labelAt(8, 0, 0.75), 1);  // between the spheres: "outer"
  EXPECT_EQ(labelAt(0, -9, -2.25), 1);
  EXPECT_EQ(labelAt(14, 0, 0.75), 0);  // outside both
  // The label table beside it.
  ASSERT_TRUE(writeLabelTable(dir_ / "labels.ctbl", table));
  EXPECT_NE(readFile(dir_ / "labels.ctbl").find("\n2 inner "), std::string::npos);
}

TEST_F(OutputFormatsTest, UnevenLayersAreResampledOntoTheSmallestGap) {
  LabelVolume v;
  v.grid.nx = 2, v.grid.ny = 1, v.grid.nz = 4;
  v.grid.originX = 10, v.grid.originY = 20, v.grid.spacingX = 0.5, v.grid.spacingY = 0.5;
  v.grid.layerZ = {0, 1, 3, 4};
  v.labels = {0, 1, 2, 3, 4, 5, 6, 7};
  const RegularLabelVolume r = regularize(v);
  EXPECT_TRUE(r.resampled);
  ASSERT_EQ(r.nz, 5);  // z = 0, 1, 2, 3, 4
  EXPECT_DOUBLE_EQ(r.geometry.axes[2][2], 1.0);
  EXPECT_DOUBLE_EQ(r.geometry.origin[0], 10);
  EXPECT_DOUBLE_EQ(r.geometry.origin[2], 0);
  const std::vector<Label> expected{0, 1, 2, 3, 2, 3, 4, 5, 6, 7};  // z = 2 ties: the lower layer
  EXPECT_EQ(r.labels, expected);
}

// One slice 0.01 mm from its neighbour among 1 mm slices: at most 8 planes per layer.
TEST_F(OutputFormatsTest, AnOddSliceCannotBlowTheResamplingUp) {
  LabelVolume v;
  v.grid.nx = 1, v.grid.ny = 1, v.grid.nz = 301;
  for (int k = 0; k < 300; ++k) v.grid.layerZ.push_back(k);
  v.grid.layerZ.insert(v.grid.layerZ.begin() + 101, 100.01);
  v.labels.assign(301, 1);
  const RegularLabelVolume r = regularize(v);
  EXPECT_TRUE(r.resampled);
  EXPECT_LE(r.nz, 8 * 301);
  EXPECT_NEAR(r.geometry.axes[2][2] * (r.nz - 1), 299.0, 1e-9);
}

TEST_F(OutputFormatsTest, ReportJsonCarriesStatisticsParametersAndTimings) {
  const Built& b = nested();
  RunReport r;
  r.input = "nested.json";
  r.parameters = {{"convention", std::string("enclosing")}, {"voxel_size", 1.0}, {"draco", true}};
  r.deviceName = "test device";
  r.grid = b.volume.grid;
  r.features.push_back({"outer", 1, {1, 2, 3}, computeMeshStats(b.meshes[0].positions, b.meshes[0].triangles), {"x.ply"}});
  r.timings = {{"assembly", 0.25}, {"write", 0.5}};
  const fs::path path = dir_ / "report.json";
  ASSERT_TRUE(writeReport(path, r));
  const nlohmann::json j = nlohmann::json::parse(readFile(path));
  EXPECT_EQ(j["format"], "scansurf-report");
  EXPECT_EQ(j["generator"], std::string("scansurf ") + version());
  EXPECT_EQ(j["parameters"]["convention"], "enclosing");
  EXPECT_EQ(j["parameters"]["draco"], true);
  EXPECT_EQ(j["device"]["name"], "test device");
  const MeshStats& s = r.features[0].stats;
  EXPECT_EQ(j["features"][0]["triangles"].get<std::size_t>(), s.triangles);
  EXPECT_DOUBLE_EQ(j["features"][0]["surface_volume"].get<double>(), s.volume);
  EXPECT_FALSE(j["features"][0].contains("volume")) << "one name for the surface volume";
  EXPECT_DOUBLE_EQ(j["features"][0]["area"].get<double>(), s.area);
  EXPECT_EQ(j["features"][0]["genus"], 0);
  EXPECT_EQ(j["features"][0]["closed"], true);
  EXPECT_DOUBLE_EQ(j["total_seconds"].get<double>(), 0.75);
  EXPECT_EQ(j["grid"]["size"][2].get<int>(), b.volume.grid.nz);
}

TEST_F(OutputFormatsTest, PngRoundTripIsExact) {
  const std::uint32_t w = 7, h = 5;
  std::vector<std::uint8_t> rgba(4 * w * h);
  for (std::size_t i = 0; i < rgba.size(); ++i) rgba[i] = static_cast<std::uint8_t>(i * 37 + 11);
  const fs::path path = dir_ / "p.png";
  ASSERT_TRUE(writePng(path, w, h, rgba));
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  ASSERT_TRUE(png_image_begin_read_from_file(&image, path.c_str()));
  image.format = PNG_FORMAT_RGBA;
  std::vector<std::uint8_t> back(PNG_IMAGE_SIZE(image));
  ASSERT_TRUE(png_image_finish_read(&image, nullptr, back.data(), 0, nullptr));
  EXPECT_EQ(image.width, w);
  EXPECT_EQ(image.height, h);
  EXPECT_EQ(back, rgba);
  EXPECT_FALSE(writePng(path, w, h + 1, rgba)) << "size mismatch is refused";
}

TEST_F(OutputFormatsTest, UnwritablePathsFailNamingThePathAndLeaveNothing) {
  const Built& b = nested();
  const fs::path missing = dir_ / "no-such-dir" / "x.drc";
  auto r = writeDrc(missing, b.meshes[0], {});
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, Errc::Io);
  EXPECT_NE(r.error().message.find("no-such-dir"), std::string::npos) << r.error().message;
  std::ofstream(dir_ / "file") << "x";
  auto g = writeGlb(dir_ / "file" / "scene.glb", {}, {});
  ASSERT_FALSE(g);
  EXPECT_EQ(g.error().code, Errc::Io);
  EXPECT_EQ(fileCount(), 1u);
}

// A directory where an output should go (vertebra.ply/) stops the run before anything is
// replaced: every other target keeps its old contents.
TEST_F(OutputFormatsTest, ADirectoryInTheWayReplacesNothing) {
  std::ofstream(dir_ / "a.ply") << "old a";
  fs::create_directories(dir_ / "b.ply");
  {
    OutputStaging staging;
    const auto write = [](const std::string& text) {
      return [text](const fs::path& p) -> Result<void> {
        std::ofstream(p) << text;
        return {};
      };
    };
    ASSERT_TRUE(staging.stage(dir_ / "a.ply", write("new a")));
    ASSERT_TRUE(staging.stage(dir_ / "b.ply", write("new b")));
    auto committed = staging.commit();
    ASSERT_FALSE(committed);
    EXPECT_EQ(committed.error().code, Errc::Io);
    EXPECT_NE(committed.error().message.find("b.ply"), std::string::npos);
  }
  EXPECT_EQ(readFile(dir_ / "a.ply"), "old a");
  EXPECT_TRUE(fs::is_directory(dir_ / "b.ply"));
  EXPECT_EQ(fileCount(), 2u) << "the staging folder is gone";
}

// A run killed during its write stage leaves its staging folder; the next run into the same
// place removes it (its pid is dead), and leaves a live process's alone.
TEST_F(OutputFormatsTest, StaleStagingOfADeadProcessIsRemoved) {
  pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ASSERT_GT(child, 0);
  ::waitpid(child, nullptr, 0);  // a pid that is certainly dead now
  const fs::path stale = dir_ / (".scansurf-staging-" + std::to_string(child) + "-1");
  const fs::path live = dir_ / (".scansurf-staging-" + std::to_string(::getppid()) + "-1");
  fs::create_directories(stale);
  fs::create_directories(live);
  std::ofstream(stale / "0-big.ply") << "partial";
  OutputStaging staging;
  ASSERT_TRUE(staging.stage(dir_ / "x.ply", [](const fs::path& p) -> Result<void> {
    std::ofstream(p) << "x";
    return {};
  }));
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(fs::exists(live));
  ASSERT_TRUE(staging.commit());
  fs::remove_all(live);
}

// A full disk, simulated with a file-size limit: the write fails, nothing partial remains and
// the previous file is untouched.
TEST_F(OutputFormatsTest, FullDiskLeavesThePreviousFileIntact) {
  const Built& b = nested();
  const fs::path path = dir_ / "scene.glb";
  std::ofstream(path) << "previous";
  std::vector<GltfFeature> features{{"outer", {1, 2, 3}, &b.meshes[0]}};
  GlbOptions options;
  options.draco = false;  // large enough to exceed the limit
  rlimit old{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
  const auto previousHandler = std::signal(SIGXFSZ, SIG_IGN);
  rlimit small = old;
  small.rlim_cur = 4096;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  auto r = writeGlb(path, features, options);
  ::setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, previousHandler);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, Errc::Io);
  EXPECT_EQ(readFile(path), "previous");
  EXPECT_EQ(fileCount(), 1u) << "the temporary file is removed";
}

}  // namespace
}  // namespace scansurf

namespace scansurf {
namespace {

// A small reader of VTK's XML files as VTK reads them: inline binary arrays are base64 of a
// UInt32 byte count and the values; string arrays are decimal byte codes, each ended by 0.
std::vector<std::uint8_t> unbase64(std::string_view text) {
  std::vector<std::uint8_t> out;
  std::uint32_t acc = 0;
  int bits = 0;
  for (char c : text) {
    int v = c >= 'A' && c <= 'Z'   ? c - 'A'
            : c >= 'a' && c <= 'z' ? c - 'a' + 26
            : c >= '0' && c <= '9' ? c - '0' + 52
            : c == '+'             ? 62
            : c == '/'             ? 63
                                   : -1;
    if (v < 0) continue;
    acc = acc << 6 | static_cast<std::uint32_t>(v), bits += 6;
    if (bits >= 8) out.push_back(static_cast<std::uint8_t>(acc >> (bits -= 8)));
  }
  return out;
}

template <typename T>
std::vector<T> binaryArray(const pugi::xml_node& array) {
  const std::vector<std::uint8_t> bytes = unbase64(array.child_value());
  std::uint32_t size = 0;
  std::memcpy(&size, bytes.data(), sizeof size);
  std::vector<T> values(size / sizeof(T));
  std::memcpy(values.data(), bytes.data() + sizeof size, size);
  return values;
}

std::string stringValue(const pugi::xml_node& fields, const char* name) {
  const pugi::xml_node array = fields.find_child_by_attribute("Array", "Name", name);
  std::istringstream codes(array.child_value());
  std::string out;
  for (int code; codes >> code && code != 0;) out += static_cast<char>(code);
  return out;
}

// A build result holding the test build's surfaces and grid, for stageSurfaceOutputs.
BuildResult buildResultOf(const Built& b) {
  BuildResult built;
  built.surfaces = b.surfaces;
  built.volume.grid = b.volume.grid;
  built.overlaps.features.resize(b.set.features.size());
  return built;
}

// VTK PolyData per feature and for the multi-label mesh, and 3D Slicer's closed-surface
// segmentation, read back as VTK reads them: the same points and triangles as the PLY, normals
// per point, the name and label as field data, the label pair per face; the segmentation's
// blocks in order, in RAS, with the keys Slicer's storage node requires.
TEST_F(OutputFormatsTest, VtkFilesCarryTheSurfacesAndWhatTheyAre) {
  const Built& b = nested();
  OutputPlan plan;
  plan.dir = dir_;
  plan.formats = {MeshFormat::Vtp, MeshFormat::SegVtm};
  plan.sceneName = "plan";
  OutputStaging staging;
  const BuildResult built = buildResultOf(b);
  auto staged = stageSurfaceOutputs(staging, plan, b.set, built);
  ASSERT_TRUE(staged) << staged.error().message;
  ASSERT_TRUE(staging.commit());

  const CompactMesh inner = *compactSurface(b.surfaces.mesh, b.surfaces.features[1]);
  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_file((dir_ / "inner.vtp").c_str()));
  const pugi::xml_node poly = doc.child("VTKFile").child("PolyData");
  const pugi::xml_node piece = poly.child("Piece");
  EXPECT_EQ(piece.attribute("NumberOfPoints").as_ullong(), inner.vertexCount());
  EXPECT_EQ(piece.attribute("NumberOfPolys").as_ullong(), inner.triangleCount());
  EXPECT_EQ(binaryArray<float>(piece.child("Points").child("DataArray")), inner.positions);
  const std::vector<std::int64_t> connectivity =
      binaryArray<std::int64_t>(piece.child("Polys").find_child_by_attribute("DataArray", "Name", "connectivity"));
  EXPECT_EQ(std::vector<std::uint32_t>(connectivity.begin(), connectivity.end()), inner.triangles);
  EXPECT_EQ(binaryArray<float>(piece.child("PointData").child("DataArray")).size(), inner.positions.size());
  EXPECT_EQ(stringValue(poly.child("FieldData"), "Name"), "inner");
  EXPECT_EQ(binaryArray<std::int32_t>(poly.child("FieldData").find_child_by_attribute("DataArray", "Name", "Label")),
            std::vector<std::int32_t>{2});

  ASSERT_TRUE(doc.load_file((dir_ / "multilabel.vtp").c_str()));
  const pugi::xml_node cells = doc.child("VTKFile").child("PolyData").child("Piece").child("CellData");
  const std::vector<std::uint16_t> inside =
      binaryArray<std::uint16_t>(cells.find_child_by_attribute("DataArray", "Name", "label_inside"));
  ASSERT_EQ(inside.size(), b.surfaces.mesh.triangleCount());
  for (std::size_t t = 0; t < inside.size(); ++t) ASSERT_EQ(inside[t], b.surfaces.mesh.labels[2 * t]);

  ASSERT_TRUE(doc.load_file((dir_ / "plan.seg.vtm").c_str()));
  std::vector<std::string> blocks;
  for (const pugi::xml_node set : doc.child("VTKFile").child("vtkMultiBlockDataSet").children("DataSet"))
    blocks.push_back(set.attribute("file").value());
  ASSERT_EQ(blocks, (std::vector<std::string>{"plan.seg_0.vtp", "plan.seg_1.vtp"}));
  ASSERT_TRUE(doc.load_file((dir_ / blocks[1]).c_str()));
  const pugi::xml_node segment = doc.child("VTKFile").child("PolyData");
  const pugi::xml_node fields = segment.child("FieldData");
  EXPECT_EQ(stringValue(fields, "Segmentation_MasterRepresentation"), "Closed surface");
  EXPECT_EQ(stringValue(fields, "Segment_Name"), "inner");
  EXPECT_EQ(stringValue(fields, "Segment_ID"), "Segment_2");
  EXPECT_EQ(stringValue(fields, "Segmentation_ContainedRepresentationNames"), "Closed surface|");
  EXPECT_EQ(stringValue(fields, "Segment_Tags").rfind("TerminologyEntry:Segmentation category and type", 0), 0u);
  EXPECT_EQ(std::string(fields.find_child_by_attribute("DataArray", "Name", "Segment_Color").attribute("type").value()),
            "Float64");
  const std::vector<float> ras = binaryArray<float>(segment.child("Piece").child("Points").child("DataArray"));
  ASSERT_EQ(ras.size(), inner.positions.size());
  for (std::size_t v = 0; v < inner.vertexCount(); ++v) {
    ASSERT_EQ(ras[3 * v], -inner.positions[3 * v]) << "x to right-to-left";
    ASSERT_EQ(ras[3 * v + 1], -inner.positions[3 * v + 1]) << "y to posterior-to-anterior";
    ASSERT_EQ(ras[3 * v + 2], inner.positions[3 * v + 2]);
  }
}

}  // namespace
}  // namespace scansurf

namespace scansurf {
namespace {

// The mesh files name the unit their coordinates are in (the contour set's: mm for DICOM, µm
// for an EM series), not "input units".
TEST_F(OutputFormatsTest, MeshHeadersNameTheUnit) {
  Built b = nested();
  b.set.units = "um";
  OutputPlan plan;
  plan.dir = dir_;
  plan.formats = {MeshFormat::Ply, MeshFormat::Obj, MeshFormat::Stl};
  OutputStaging staging;
  const BuildResult built = buildResultOf(b);
  ASSERT_TRUE(stageSurfaceOutputs(staging, plan, b.set, built));
  ASSERT_TRUE(staging.commit());
  EXPECT_NE(readFile(dir_ / "inner.ply").find("comment units: um (x, y in-plane"), std::string::npos);
  EXPECT_NE(readFile(dir_ / "multilabel.ply").find("comment units: um (x, y in-plane"), std::string::npos);
  EXPECT_EQ(readFile(dir_ / "inner.obj").rfind("# scansurf", 0), 0u);
  EXPECT_NE(readFile(dir_ / "inner.obj").find("coordinates in um\n"), std::string::npos);
  EXPECT_EQ(
      readFile(dir_ / "inner.stl").substr(0, 80).rfind(std::string("scansurf ") + SCANSURF_VERSION_STRING + " binary STL, um", 0),
      0u);
}

}  // namespace
}  // namespace scansurf

namespace scansurf {
namespace {

// An EM series' scene calls its frame the specimen's, not a patient's.
TEST_F(OutputFormatsTest, GlbOfASpecimenSaysSo) {
  Built b = nested();
  b.set.frame = CoordinateFrame::Specimen;
  b.set.units = "um";
  const fs::path path = dir_ / "cell.glb";
  ASSERT_TRUE(writeScene(path, b.set, b.surfaces, {}));
  const nlohmann::json j = parseGlb(readFile(path)).json;
  EXPECT_EQ(j["asset"]["extras"]["scansurf"]["coordinates"], "specimen (x, y in the section plane, z across the sections)");
  EXPECT_EQ(j["nodes"][j["scenes"][0]["nodes"][0].get<std::size_t>()]["name"], "scansurf specimen frame");
  EXPECT_EQ(j.dump().find("patient"), std::string::npos);
}

// OBJ as viewers read it: `vn` normals that agree with the faces, and the feature's colour in a
// material file the OBJ names.
TEST_F(OutputFormatsTest, ObjCarriesNormalsAndItsColourInAMaterial) {
  Built b = nested();
  b.set.features[0].color = Rgb{255, 51, 0};
  OutputPlan plan;
  plan.dir = dir_;
  plan.formats = {MeshFormat::Obj};
  OutputStaging staging;
  const BuildResult built = buildResultOf(b);
  auto files = stageSurfaceOutputs(staging, plan, b.set, built);
  ASSERT_TRUE(files);
  ASSERT_TRUE(staging.commit());
  const std::string name = b.set.features[0].name;
  const std::string obj = readFile(dir_ / (name + ".obj"));
  EXPECT_NE(obj.find("\nmtllib " + name + ".mtl\nusemtl " + name + "\n"), std::string::npos);
  const std::string mtl = readFile(dir_ / (name + ".mtl"));
  EXPECT_NE(mtl.find("newmtl " + name + "\n"), std::string::npos);
  EXPECT_NE(mtl.find("Kd 1.000000 0.200000 0.000000\n"), std::string::npos);
  EXPECT_NE(std::find(files->files[0].begin(), files->files[0].end(), dir_ / (name + ".mtl")), files->files[0].end());
  // Every vertex has its normal, every face corner names it (v//vn), and the normals point out.
  std::vector<std::array<float, 3>> normals;
  std::istringstream in(obj);
  std::string line;
  std::size_t corners = 0, sharedIndex = 0;
  while (std::getline(in, line)) {
    std::istringstream l(line);
    std::string tag;
    l >> tag;
    if (tag == "vn") {
      std::array<float, 3> n{};
      l >> n[0] >> n[1] >> n[2];
      normals.push_back(n);
    } else if (tag == "f") {
      std::string c;
      while (l >> c) {
        ++corners;
        const std::size_t slash = c.find("//");
        sharedIndex += slash != std::string::npos && c.substr(0, slash) == c.substr(slash + 2);
      }
    }
  }
  const CompactMesh back = readObj(dir_ / (name + ".obj"));
  ASSERT_EQ(normals.size(), back.vertexCount());
  EXPECT_EQ(sharedIndex, corners);
  const std::vector<float> expected = vertexNormals(back);
  for (std::size_t v = 0; v < normals.size(); ++v)
    EXPECT_GT(normals[v][0] * expected[3 * v] + normals[v][1] * expected[3 * v + 1] + normals[v][2] * expected[3 * v + 2], 0.99f);
}

// A volume unit is the input's length cubed, converted: mm³ to cm³ is a thousandth, µm³ to nm³
// a billion times; an input of unknown length converts to nothing but its own unit.
TEST(VolumeUnits, ConvertFromTheInputsLengthUnit) {
  const auto cc = volumeUnitFor("cc", "mm");
  ASSERT_TRUE(cc);
  EXPECT_EQ(cc->name, "cm^3");
  EXPECT_DOUBLE_EQ(cc->scale, 1e-3);
  const auto nm = volumeUnitFor("nm3", "\xC2\xB5m");
  ASSERT_TRUE(nm);
  EXPECT_NEAR(nm->scale, 1e9, 1e-3);
  const auto own = volumeUnitFor("input", "px");
  ASSERT_TRUE(own);
  EXPECT_TRUE(own->name.empty());
  EXPECT_EQ(own->scale, 1);
  const auto unknownLength = volumeUnitFor("mm3", "px");
  ASSERT_FALSE(unknownLength);
  EXPECT_NE(unknownLength.error().message.find("'px'"), std::string::npos);
  EXPECT_FALSE(volumeUnitFor("litres", "mm"));
}

}  // namespace
}  // namespace scansurf
