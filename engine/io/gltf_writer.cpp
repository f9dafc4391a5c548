// Binary glTF through draco::GltfEncoder: a draco::Scene with one mesh group, node and
// material per feature.
#include "io/gltf_writer.h"

#include <draco/io/gltf_encoder.h>
#include <draco/scene/scene.h>

#include <cmath>

#include "io/atomic_file.h"

namespace scansurf {

double srgbToLinear(std::uint8_t c) {
  const double v = c / 255.0;
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

Result<void> writeGlb(const std::filesystem::path& path, std::span<const GltfFeature> features, const GlbOptions& options) {
  draco::Scene scene;
  int materials = 0;
  for (const GltfFeature& f : features) {
    if (f.mesh == nullptr || f.mesh->triangleCount() == 0) continue;
    std::unique_ptr<draco::Mesh> mesh = toDracoMesh(*f.mesh);
    mesh->SetName(f.name);
    if (options.draco) {
      draco::DracoCompressionOptions compression;
      compression.compression_level = options.dracoOptions.compressionLevel;
      compression.quantization_position.SetQuantizationBits(quantizationBitsFor(*f.mesh, options.dracoOptions));
      mesh->SetCompressionEnabled(true);
      mesh->SetCompressionOptions(compression);
    }
    const draco::MeshIndex meshIndex = scene.AddMesh(std::move(mesh));

    draco::Material* material = scene.GetMaterialLibrary().MutableMaterial(materials);
    material->SetName(f.name);
    material->SetColorFactor(draco::Vector4f(static_cast<float>(srgbToLinear(f.color[0])),
                                             static_cast<float>(srgbToLinear(f.color[1])),
                                             static_cast<float>(srgbToLinear(f.color[2])), 1.0f));
    material->SetMetallicFactor(0.0f);
    material->SetRoughnessFactor(0.7f);

    const draco::MeshGroupIndex group = scene.AddMeshGroup();
    scene.GetMeshGroup(group)->SetName(f.name);
    scene.GetMeshGroup(group)->AddMeshInstance({meshIndex, materials});
    const draco::SceneNodeIndex node = scene.AddNode();
    scene.GetNode(node)->SetName(f.name);
    scene.GetNode(node)->SetMeshGroupIndex(group);
    scene.AddRootNodeIndex(node);
    ++materials;
  }

  draco::GltfEncoder encoder;
  draco::EncoderBuffer buffer;
  if (const draco::Status s = encoder.EncodeToBuffer(scene, &buffer); !s.ok())
    return makeError(Errc::Internal, "cannot encode '" + path.string() + "': Draco glTF encoder: " + s.error_msg_string());
  return writeFileAtomically(path, buffer.data(), buffer.size());
}

}  // namespace scansurf
