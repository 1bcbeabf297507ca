#include "engine/ref/reference_scene.hpp"

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "engine/anim/instances.hpp"
#include "engine/anim/skinning.hpp"
#include "engine/core/error.hpp"
#include "engine/scene/asset_instances.hpp"
#include "engine/scene/systems.hpp"

namespace bounce::ref {
namespace {

RefLight makeLight(RefLightType type, glm::vec3 color, float intensity, float range, float inner, float outer,
                   const glm::mat4& world) {
  RefLight l;
  l.type = type;
  l.position = glm::vec3(world[3]);
  l.direction = glm::normalize(glm::vec3(world * glm::vec4(0, 0, -1, 0)));
  l.radiance = color * intensity;
  l.range = range;
  l.cosOuter = std::cos(outer);
  l.cosInner = std::cos(inner);
  return l;
}

RefLightType fromAsset(asset::LightType t) {
  return t == asset::LightType::Point ? RefLightType::Point
         : t == asset::LightType::Spot ? RefLightType::Spot
                                       : RefLightType::Directional;
}

}  // namespace

std::string ReferenceAssets::key(const scene::MeshRef& ref) { return scene::assetKey(ref); }

void ReferenceAssets::load(ecs::Registry& registry, const std::filesystem::path& cookCache) {
  registry.view<scene::MeshRef>().each([&](ecs::Entity, scene::MeshRef& ref) {
    const std::string k = key(ref);
    if (entries_.count(k)) return;
    Entry e;
    e.options = scene::cookOptionsForRef(ref, cookCache);
    e.cpu = scene::cookForRef(ref, cookCache);
    e.contentKey = asset::cacheKey(ref.asset, e.options);
    e.firstTexture = static_cast<std::uint32_t>(textures_.size());
    for (const auto& t : e.cpu.textures) textures_.push_back(makeTexture(t.width, t.height, t.pixels, t.srgb));
    entries_.emplace(k, std::move(e));
  });
}

const ReferenceAssets::Entry& ReferenceAssets::get(const scene::MeshRef& ref) const {
  auto it = entries_.find(key(ref));
  if (it == entries_.end()) throw InternalError("ref::ReferenceAssets: " + ref.asset.string() + " was not loaded");
  return it->second;
}

SceneDesc extractScene(ecs::Registry& registry, const scene::Level& level, const ReferenceAssets& assets,
                       bool withTextures) {
  SceneDesc out;
  if (withTextures) out.textures = assets.textures();
  out.background = level.background;

  registry.view<scene::MeshRef, scene::WorldTransform>().each(
      [&](ecs::Entity e, scene::MeshRef& ref, scene::WorldTransform& world) {
        const ReferenceAssets::Entry& a = assets.get(ref);
        const auto* over = registry.tryGet<scene::MaterialOverride>(e);
        auto texture = [&](const asset::TextureRef& t) {
          return t.texture >= 0 && std::size_t(t.texture) < a.cpu.textures.size() ? int(a.firstTexture) + t.texture : -1;
        };
        const anim::Pose* pose = registry.tryGet<anim::Pose>(e);
        const glm::mat4 skinFrame = pose ? anim::skinFrame(a.cpu, ref, world.matrix, *pose) : world.matrix;
        scene::forEachInstancedNode(a.cpu, ref, world.matrix, [&](int n, const glm::mat4& nodeWorld) {
          const asset::Node& node = a.cpu.nodes[n];
          glm::mat4 m = nodeWorld;
          if (node.light >= 0) {
            const asset::Light& L = a.cpu.lights[node.light];
            out.lights.push_back(makeLight(fromAsset(L.type), L.color, L.intensity, L.range, L.innerConeAngle,
                                           L.outerConeAngle, nodeWorld));
          }
          if (node.mesh < 0 || node.vlm.present) return;  // extras.bounce_vlm: virtual light, not real geometry
          const bool deformed = pose && anim::isDeformed(a.cpu, n);
          std::vector<glm::vec3> posedP, posedN;
          for (std::size_t pi = 0; pi < a.cpu.meshes[node.mesh].primitives.size(); ++pi) {
            const asset::Primitive& p = a.cpu.meshes[node.mesh].primitives[pi];
            // The same CPU evaluation the renderer draws (engine/anim): morphed, then skinned into
            // asset space and placed by the skin frame.
            if (deformed) m = anim::posePrimitive(a.cpu, n, pi, pose, posedP, posedN) ? skinFrame : nodeWorld;
            const std::vector<glm::vec3>& srcP = deformed ? posedP : p.positions;
            const std::vector<glm::vec3>& srcN = deformed ? posedN : p.normals;
            const glm::mat3 normalMatrix = glm::inverseTranspose(glm::mat3(m));
            RefMaterial mat;  // the default material (white, no emission) when the primitive has none
            if (p.material >= 0 && std::size_t(p.material) < a.cpu.materials.size()) {
              const asset::Material& src = a.cpu.materials[p.material];
              mat.albedo = glm::vec3(src.baseColorFactor);
              mat.albedoTexture = texture(src.baseColorTexture);
              mat.emissive = src.emissiveFactor;
              mat.emissiveTexture = texture(src.emissiveTexture);
            }
            if (over && over->albedo) mat.albedo = *over->albedo;
            if (over && over->emissive) mat.emissive = *over->emissive;
            RefMesh mesh;
            mesh.material = static_cast<std::uint32_t>(out.materials.size());
            out.materials.push_back(mat);
            mesh.positions.reserve(p.positions.size());
            mesh.normals.reserve(p.positions.size());
            for (std::size_t v = 0; v < p.positions.size(); ++v) {
              mesh.positions.push_back(glm::vec3(m * glm::vec4(srcP[v], 1.0f)));
              // Not renormalised: mesh.vert passes normalMatrix·n on and the fragment normalises
              // after interpolation, so the interpolation weights match.
              mesh.normals.push_back(normalMatrix * srcN[v]);
            }
            if (p.uv0.size() == p.positions.size()) mesh.uvs = p.uv0;
            else if (!p.uv0.empty()) {  // GpuScene zero-fills missing UVs; do the same
              mesh.uvs.assign(p.positions.size(), glm::vec2(0.0f));
              std::copy_n(p.uv0.begin(), std::min(p.uv0.size(), p.positions.size()), mesh.uvs.begin());
            }
            mesh.indices = p.indices;
            out.meshes.push_back(std::move(mesh));
          }
        }, pose ? &pose->local : nullptr);
      });

  registry.view<scene::Light, scene::WorldTransform>().each(
      [&](ecs::Entity, scene::Light& L, scene::WorldTransform& world) {
        const RefLightType type = L.type == scene::LightType::Point  ? RefLightType::Point
                                  : L.type == scene::LightType::Spot ? RefLightType::Spot
                                                                     : RefLightType::Directional;
        out.lights.push_back(makeLight(type, L.color, L.intensity, L.range.value_or(0.0f), L.innerConeRad,
                                       L.outerConeRad, world.matrix));
        if (type != RefLightType::Directional) out.lights.back().radius = L.radius;
      });

  // Camera: the active camera's world transform with its scale removed, as GpuScene::extract.
  glm::mat4 camWorld(1.0f);
  scene::Camera cam;
  if (ecs::Entity c = scene::activeCamera(registry); !c.isNull()) {
    camWorld = registry.get<scene::WorldTransform>(c).matrix;
    cam = registry.get<scene::Camera>(c);
  }
  for (int i = 0; i < 3; ++i) camWorld[i] = glm::vec4(glm::normalize(glm::vec3(camWorld[i])), 0.0f);
  out.camera = {camWorld, cam.yfovRad, cam.near, cam.far};
  return out;
}

}  // namespace bounce::ref
