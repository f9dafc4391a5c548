// Binary glTF through draco::GltfEncoder: a draco::Scene with one mesh group, node and
// material per feature; then the scene description is adjusted in the container (glTF 2.0
// §3.5.3 node matrices, §3.9.4 alpha modes, §3.2 asset): the root transform into glTF's
// frame, blending for translucent features, the generator and the original frame in extras.
#include "io/gltf_writer.h"

#include <draco/io/gltf_encoder.h>
#include <draco/scene/scene.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <string_view>

#include "core/utf8.h"
#include "io/atomic_file.h"
#include "io/glb_container.h"
#include "io/length_units.h"
#include "scansurf/version.h"

namespace scansurf {
namespace {

void addNormals(draco::Mesh& mesh, const std::vector<float>& normals) {
  const auto vertices = static_cast<std::uint32_t>(normals.size() / 3);
  draco::GeometryAttribute normal;
  normal.Init(draco::GeometryAttribute::NORMAL, nullptr, 3, draco::DT_FLOAT32, false, sizeof(float) * 3, 0);
  draco::PointAttribute* attribute = mesh.attribute(mesh.AddAttribute(normal, true, vertices));
  for (std::uint32_t v = 0; v < vertices; ++v)
    attribute->SetAttributeValue(draco::AttributeValueIndex(v), &normals[3 * std::size_t{v}]);
}

std::unique_ptr<draco::Mesh> sceneMesh(const GltfFeature& f, const GlbOptions& options) {
  std::unique_ptr<draco::Mesh> mesh = toDracoMesh(*f.mesh);
  addNormals(*mesh, vertexNormals(*f.mesh));
  if (options.draco) {
    draco::DracoCompressionOptions compression;
    compression.compression_level = options.dracoOptions.compressionLevel;
    compression.quantization_position.SetQuantizationBits(quantizationBitsFor(*f.mesh, options.dracoOptions));
    compression.quantization_bits_normal = 10;  // directions to a fraction of a degree: shading looks smooth
    mesh->SetCompressionEnabled(true);
    mesh->SetCompressionOptions(compression);
  }
  return mesh;
}

// Draco's glTF encoder writes names into its JSON unescaped (a quote, backslash or control
// character in a name made it unreadable), so it gets a placeholder per feature, and the JSON
// library writes the real names afterwards (realNames).
constexpr std::string_view kPlaceholder = "scansurf-feature-";
std::string placeholderName(int material) { return std::string(kPlaceholder) + std::to_string(material); }

void addFeature(draco::Scene& scene, const GltfFeature& f, const GlbOptions& options, int material) {
  const std::string name = placeholderName(material);
  const draco::MeshIndex meshIndex = scene.AddMesh(sceneMesh(f, options));
  scene.GetMesh(meshIndex).SetName(name);
  draco::Material* m = scene.GetMaterialLibrary().MutableMaterial(material);
  m->SetName(name);
  m->SetColorFactor(draco::Vector4f(static_cast<float>(srgbToLinear(f.color[0])), static_cast<float>(srgbToLinear(f.color[1])),
                                    static_cast<float>(srgbToLinear(f.color[2])), std::clamp(f.opacity, 0.0f, 1.0f)));
  m->SetMetallicFactor(0.0f);
  m->SetRoughnessFactor(0.7f);
  if (f.opacity < 1) m->SetTransparencyMode(draco::Material::TRANSPARENCY_BLEND);
  const draco::MeshGroupIndex group = scene.AddMeshGroup();
  scene.GetMeshGroup(group)->SetName(name);
  scene.GetMeshGroup(group)->AddMeshInstance({meshIndex, material});
  const draco::SceneNodeIndex node = scene.AddNode();
  scene.GetNode(node)->SetName(name);
  scene.GetNode(node)->SetMeshGroupIndex(group);
  scene.AddRootNodeIndex(node);
}

// Every node, mesh and material name that is a placeholder becomes its feature's name, valid
// UTF-8 (glTF's JSON is UTF-8; ROI names may be Latin-1), escaped by the JSON library.
void realNames(nlohmann::json& gltf, const std::vector<std::string>& names) {
  for (const char* kind : {"nodes", "meshes", "materials"}) {
    if (!gltf.contains(kind)) continue;
    for (nlohmann::json& item : gltf[kind]) {
      if (!item.contains("name") || !item["name"].is_string()) continue;
      const std::string placeholder = item["name"].get<std::string>();
      if (placeholder.rfind(kPlaceholder, 0) != 0) continue;
      const std::size_t i = std::strtoul(placeholder.c_str() + kPlaceholder.size(), nullptr, 10);
      if (i < names.size() && placeholder == placeholderName(static_cast<int>(i))) item["name"] = validUtf8(names[i]);
    }
  }
}

// Without Draco the vertex attributes and indices lie in plain buffer views, which glTF asks
// to name their target (ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER; the validator hints otherwise).
void markBufferViewTargets(nlohmann::json& gltf) {
  if (!gltf.contains("meshes") || !gltf.contains("accessors") || !gltf.contains("bufferViews")) return;
  const auto mark = [&](const nlohmann::json& accessor, int target) {
    if (!accessor.is_number_unsigned() || accessor.get<std::size_t>() >= gltf["accessors"].size()) return;
    const nlohmann::json& a = gltf["accessors"][accessor.get<std::size_t>()];
    if (!a.contains("bufferView") || a["bufferView"].get<std::size_t>() >= gltf["bufferViews"].size()) return;
    gltf["bufferViews"][a["bufferView"].get<std::size_t>()]["target"] = target;
  };
  const nlohmann::json meshes = gltf["meshes"];  // a copy: mark() writes into gltf
  for (const nlohmann::json& mesh : meshes) {
    if (!mesh.contains("primitives")) continue;
    for (const nlohmann::json& primitive : mesh["primitives"]) {
      if (primitive.contains("attributes"))
        for (const nlohmann::json& accessor : primitive["attributes"]) mark(accessor, 34962);
      if (primitive.contains("indices")) mark(primitive["indices"], 34963);
    }
  }
}

// Patient LPS in `units` to glTF's y-up metres, column-major: x -> x, z (superior) -> y,
// y (posterior) -> -z (anterior toward the viewer). A specimen's sections stack up the same way.
nlohmann::json rootMatrix(double scale) {
  return nlohmann::json::array({scale, 0, 0, 0, 0, 0, -scale, 0, 0, scale, 0, 0, 0, 0, 0, 1});
}

// The root node, the generator and the record of the original frame.
void adjustScene(nlohmann::json& gltf, const GlbOptions& options) {
  const double metres = metresPerUnit(options.units);
  const bool patient = options.coordinates == CoordinateFrame::PatientLps;
  const std::string from = patient ? "patient LPS" : "the specimen frame (z across the sections)";
  nlohmann::json frame = {{"coordinates", patient ? "patient LPS (x left, y posterior, z superior)"
                                                  : "specimen (x, y in the section plane, z across the sections)"},
                          {"unit", options.units}};
  if (options.frame == SceneFrame::Gltf && gltf.contains("scenes") && !gltf["scenes"].empty()) {
    nlohmann::json& scene = gltf["scenes"][0];
    nlohmann::json root = {{"name", patient ? "scansurf patient frame" : "scansurf specimen frame"},
                           {"matrix", rootMatrix(metres > 0 ? metres : 1.0)}};
    root["children"] = scene.value("nodes", nlohmann::json::array());
    gltf["nodes"].push_back(root);
    scene["nodes"] = nlohmann::json::array({gltf["nodes"].size() - 1});
    frame["root_node"] = metres > 0 ? "turns " + from + " into glTF y-up and scales " + options.units + " to metres"
                                    : "turns " + from + " into glTF y-up; unit '" + options.units + "' not scaled";
  } else {
    frame["root_node"] = std::string("none: vertices are raw ") + (patient ? "patient" : "specimen") +
                         " coordinates (--gltf-frame patient asked for the input's own frame)";
  }
  gltf["asset"]["generator"] = std::string("scansurf ") + version();
  gltf["asset"]["extras"]["scansurf"] = frame;
}

}  // namespace

double srgbToLinear(std::uint8_t c) {
  const double v = c / 255.0;
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

Result<void> writeGlb(const std::filesystem::path& path, std::span<const GltfFeature> features, const GlbOptions& options) {
  draco::Scene scene;
  std::vector<std::string> names;  // by material (one per feature with a surface)
  for (const GltfFeature& f : features)
    if (f.mesh != nullptr && f.mesh->triangleCount() > 0) {
      addFeature(scene, f, options, static_cast<int>(names.size()));
      names.push_back(f.name);
    }

  draco::GltfEncoder encoder;
  draco::EncoderBuffer buffer;
  if (const draco::Status s = encoder.EncodeToBuffer(scene, &buffer); !s.ok())
    return makeError(Errc::Internal, "cannot encode '" + path.string() + "': Draco glTF encoder: " + s.error_msg_string());
  SCANSURF_ASSIGN_OR_RETURN(GlbContainer glb, parseGlb(reinterpret_cast<const std::uint8_t*>(buffer.data()), buffer.size()));
  nlohmann::json gltf = nlohmann::json::parse(glb.json, nullptr, false);
  if (gltf.is_discarded())
    return makeError(Errc::Internal, "cannot encode '" + path.string() + "': unreadable glTF JSON from Draco");
  realNames(gltf, names);
  if (!options.draco) markBufferViewTargets(gltf);
  adjustScene(gltf, options);
  glb.json = gltf.dump();
  const std::vector<std::uint8_t> bytes = serializeGlb(glb);
  return writeFileAtomically(path, bytes.data(), bytes.size());
}

}  // namespace scansurf
