#include "engine/render/gpu_scene.hpp"

#include <algorithm>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/quaternion.hpp>

#include "engine/anim/instances.hpp"
#include "engine/anim/pose.hpp"
#include "engine/anim/skinning.hpp"
#include "engine/asset/cook.hpp"
#include "engine/core/log.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/scene/asset_instances.hpp"
#include "engine/scene/components.hpp"
#include "engine/scene/systems.hpp"
#include "engine/scene/transform_math.hpp"

namespace bounce::render {
namespace {

LightGpu makeLight(LightType type, glm::vec3 color, float intensity, float range, float inner, float outer,
                   bool shadows, const glm::mat4& world, float radius = 0.0f) {
  LightGpu l{};
  l.positionType = glm::vec4(glm::vec3(world[3]), static_cast<float>(type));
  const glm::vec3 dir = glm::normalize(glm::vec3(world * glm::vec4(0, 0, -1, 0)));
  l.directionRange = glm::vec4(dir, range);
  l.radiance = glm::vec4(color * intensity, radius);  // w: scene::Light::radius (SL local lights)
  l.cone = glm::vec4(std::cos(outer), std::cos(inner), 0.0f, 0.0f);
  l.shadow = glm::vec4(shadows ? 0.0f : -1.0f, 0.0f, 0.0f, 0.0f);
  return l;
}

}  // namespace

GpuScene::GpuScene(gpu::Context& ctx, const Pipelines& pipelines, gpu::SamplerCache& samplers,
                   std::filesystem::path cookCache)
    : ctx_(ctx), pipelines_(pipelines), samplers_(samplers), cache_(std::move(cookCache)),
      materialDescriptors_(ctx, "materials") {
  gpu::ImageDesc d;
  d.format = VK_FORMAT_R8G8B8A8_UNORM;
  d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  d.name = "white";
  white_ = gpu::Image(ctx_, d);
  const std::uint8_t texel[4] = {255, 255, 255, 255};
  gpu::upload(ctx_, white_, texel);
}

GpuScene::~GpuScene() = default;

std::string GpuScene::key(const scene::MeshRef& ref) { return scene::assetKey(ref); }

void GpuScene::load(ecs::Registry& registry) {
  registry.view<scene::MeshRef>().each([&](ecs::Entity, scene::MeshRef& ref) { upload(ref); });
}

const GpuScene::AssetGpu& GpuScene::upload(const scene::MeshRef& ref) {
  const std::string k = key(ref);
  if (auto it = assets_.find(k); it != assets_.end()) return *it->second;

  auto a = std::make_unique<AssetGpu>();
  a->cpu = scene::cookForRef(ref, cache_);

  for (const auto& mesh : a->cpu.meshes) {
    auto m = std::make_unique<MeshGpu>();
    std::vector<MeshVertex> vertices;
    std::vector<std::uint32_t> indices;
    for (const auto& p : mesh.primitives) {
      MeshGpu::Primitive gp;
      gp.firstIndex = static_cast<std::uint32_t>(indices.size());
      gp.indexCount = static_cast<std::uint32_t>(p.indices.size());
      gp.vertexOffset = static_cast<std::int32_t>(vertices.size());
      gp.material = p.material < 0 ? static_cast<std::uint32_t>(a->cpu.materials.size()) : std::uint32_t(p.material);
      for (std::size_t v = 0; v < p.positions.size(); ++v) {
        MeshVertex mv{};
        std::copy_n(&p.positions[v].x, 3, mv.position);
        std::copy_n(&p.normals[v].x, 3, mv.normal);
        if (v < p.uv0.size()) std::copy_n(&p.uv0[v].x, 2, mv.uv);
        vertices.push_back(mv);
      }
      indices.insert(indices.end(), p.indices.begin(), p.indices.end());
      m->primitives.push_back(gp);
      triangles_ += p.indices.size() / 3;
    }
    if (!vertices.empty()) {
      m->vertices = gpu::Buffer(ctx_, {vertices.size() * sizeof(MeshVertex),
                                       VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                       gpu::MemoryUsage::GpuOnly, mesh.name + ".vertices"});
      gpu::upload(ctx_, m->vertices, gpu::bytesOf(vertices));
    }
    if (!indices.empty()) {
      m->indices = gpu::Buffer(ctx_, {indices.size() * sizeof(std::uint32_t),
                                      VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                      gpu::MemoryUsage::GpuOnly, mesh.name + ".indices"});
      gpu::upload(ctx_, m->indices, gpu::bytesOf(indices));
    }
    m->vertexCount = static_cast<std::uint32_t>(vertices.size());
    a->meshes.push_back(std::move(m));
  }
  uploadSkinVertices(*a);

  for (const auto& t : a->cpu.textures) {
    gpu::ImageDesc d;
    d.format = t.srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;  // sRGB: sampled as linear
    d.width = std::max(1u, t.width);
    d.height = std::max(1u, t.height);
    d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    d.name = t.name.empty() ? "texture" : t.name;
    gpu::Image img(ctx_, d);
    if (t.pixels.size() == std::size_t(d.width) * d.height * 4) {
      gpu::upload(ctx_, img, t.pixels);
    } else {
      std::vector<std::uint8_t> white(std::size_t(d.width) * d.height * 4, 255);
      gpu::upload(ctx_, img, white);
    }
    a->textures.push_back(std::move(img));
  }

  VkSampler sampler = samplers_.get({VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_LINEAR, VK_SAMPLER_ADDRESS_MODE_REPEAT});
  auto textureView = [&](const asset::TextureRef& ref) {
    return ref.texture >= 0 && std::size_t(ref.texture) < a->textures.size() ? a->textures[ref.texture].view()
                                                                              : white_.view();
  };
  for (std::size_t i = 0; i <= a->cpu.materials.size(); ++i) {
    VkDescriptorSet set = materialDescriptors_.allocate(pipelines_.materialLayout);
    gpu::DescriptorWriter w;
    if (i < a->cpu.materials.size()) {
      w.sampledImage(0, textureView(a->cpu.materials[i].baseColorTexture), sampler)
          .sampledImage(1, textureView(a->cpu.materials[i].emissiveTexture), sampler);
    } else {
      w.sampledImage(0, white_.view(), sampler).sampledImage(1, white_.view(), sampler);
    }
    w.update(ctx_, set);
    a->materialSets.push_back(set);
  }
  auto& stored = *(assets_[k] = std::move(a));
  return stored;
}

void GpuScene::uploadSkinVertices(AssetGpu& a) {
  for (std::size_t n = 0; n < a.cpu.nodes.size(); ++n) {
    const asset::Node& node = a.cpu.nodes[n];
    if (node.mesh < 0 || !anim::isDeformed(a.cpu, int(n))) continue;
    // A subdivided deformed mesh is posed as its cage, then refined (uploadStencils).
    const std::int32_t cage = a.cpu.meshes[std::size_t(node.mesh)].cage;
    const std::size_t posed = std::size_t(cage >= 0 ? cage : node.mesh);
    MeshGpu& m = *a.meshes[posed];
    const asset::Mesh& mesh = a.cpu.meshes[posed];
    if (!m.skinVertices && m.vertexCount != 0) {
      // A skinned node's mesh: every primitive weighted (else it is posed on the CPU).
      bool gpu = true;
      if (anim::isSkinned(a.cpu, int(n)))
        for (const auto& p : mesh.primitives) gpu = gpu && !p.weights.empty();
      if (!gpu) continue;
      std::size_t targets = 0;
      for (const auto& p : mesh.primitives) targets = std::max(targets, p.targets.size());
      std::vector<SkinVertex> vs;
      vs.reserve(m.vertexCount);
      std::vector<glm::vec4> deltas(targets * 2 * m.vertexCount, glm::vec4(0.0f));
      m.morphMin.assign(targets, glm::vec3(0.0f));
      m.morphMax.assign(targets, glm::vec3(0.0f));
      for (const auto& p : mesh.primitives) {
        for (std::size_t t = 0; t < p.targets.size(); ++t) {
          const asset::MorphTarget& mt = p.targets[t];
          for (std::size_t v = 0; v < mt.positions.size(); ++v) {
            deltas[2 * (t * m.vertexCount + vs.size() + v)] = glm::vec4(mt.positions[v], 0.0f);
            m.morphMin[t] = glm::min(m.morphMin[t], mt.positions[v]);
            m.morphMax[t] = glm::max(m.morphMax[t], mt.positions[v]);
          }
          for (std::size_t v = 0; v < mt.normals.size(); ++v)
            deltas[2 * (t * m.vertexCount + vs.size() + v) + 1] = glm::vec4(mt.normals[v], 0.0f);
        }
        const bool weighted = !p.weights.empty();
        for (std::size_t v = 0; v < p.positions.size(); ++v) {
          SkinVertex s{};
          const glm::vec2 uv = v < p.uv0.size() ? p.uv0[v] : glm::vec2(0.0f);
          const glm::u16vec4 j1 = p.joints1.empty() ? glm::u16vec4(0) : p.joints1[v];
          const glm::vec4 w1 = p.weights1.empty() ? glm::vec4(0.0f) : p.weights1[v];
          const glm::u16vec4 j0 = weighted ? p.joints[v] : glm::u16vec4(0);
          const glm::vec4 w0 = weighted ? p.weights[v] : glm::vec4(0.0f);
          for (int k = 0; k < 3; ++k) {
            s.positionU[k] = p.positions[v][k];
            s.normalV[k] = p.normals[v][k];
          }
          s.positionU[3] = uv.x;
          s.normalV[3] = uv.y;
          s.joints[0] = std::uint32_t(j0.x) | std::uint32_t(j0.y) << 16;
          s.joints[1] = std::uint32_t(j0.z) | std::uint32_t(j0.w) << 16;
          s.joints[2] = std::uint32_t(j1.x) | std::uint32_t(j1.y) << 16;
          s.joints[3] = std::uint32_t(j1.z) | std::uint32_t(j1.w) << 16;
          for (int k = 0; k < 4; ++k) {
            s.weights0[k] = w0[k];
            s.weights1[k] = w1[k];
          }
          vs.push_back(s);
        }
      }
      const auto storage = [&](gpu::Buffer& b, std::span<const std::uint8_t> bytes, const std::string& name) {
        b = gpu::Buffer(ctx_, {bytes.size(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                               gpu::MemoryUsage::GpuOnly, name});
        gpu::upload(ctx_, b, bytes);
      };
      storage(m.skinVertices, gpu::bytesOf(vs), mesh.name + ".skin");
      if (targets != 0) storage(m.morphDeltas, gpu::bytesOf(deltas), mesh.name + ".morph");
      m.morphTargets = static_cast<std::uint32_t>(targets);
    }
    if (cage >= 0 && m.skinVertices) uploadStencils(a, std::size_t(node.mesh));
  }
}

void GpuScene::uploadStencils(AssetGpu& a, std::size_t meshIndex) {
  MeshGpu& m = *a.meshes[meshIndex];
  if (m.stencilRows) return;
  const asset::Mesh& mesh = a.cpu.meshes[meshIndex];
  const MeshGpu& cage = *a.meshes[std::size_t(mesh.cage)];
  std::vector<StencilRow> rows;
  std::vector<StencilWeight> weights;
  rows.reserve(m.vertexCount);
  for (const auto& p : mesh.primitives) {
    const asset::LimitStencils& st = p.stencils;
    // Stencil indices are per cage primitive; the pass reads the whole cage mesh's posed range.
    const std::uint32_t base = std::uint32_t(cage.primitives[std::size_t(st.cagePrimitive)].vertexOffset);
    for (std::size_t v = 0; v < p.positions.size(); ++v) {
      const glm::vec2 uv = v < p.uv0.size() ? p.uv0[v] : glm::vec2(0.0f);
      rows.push_back({std::uint32_t(weights.size()), st.offsets[v + 1] - st.offsets[v], uv.x, uv.y});
      for (std::uint32_t k = st.offsets[v]; k < st.offsets[v + 1]; ++k)
        weights.push_back({base + st.indices[k], st.weights[k], st.duWeights[k], st.dvWeights[k]});
    }
  }
  if (rows.empty() || weights.empty()) return;
  auto storage = [&](gpu::Buffer& b, std::span<const std::uint8_t> bytes, const std::string& name) {
    b = gpu::Buffer(ctx_, {bytes.size(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                           gpu::MemoryUsage::GpuOnly, name});
    gpu::upload(ctx_, b, bytes);
  };
  storage(m.stencilRows, gpu::bytesOf(rows), mesh.name + ".stencil-rows");
  storage(m.stencilWeights, gpu::bytesOf(weights), mesh.name + ".stencil-weights");
  m.cage = &cage;
}

void GpuScene::extract(ecs::Registry& registry, const scene::Level& level, const ExtractOptions& options,
                       RenderWorld& w) const {
  w = RenderWorld{};
  for (const auto& name : level.effects.names()) w.effects.insert(name);
  w.background = level.background;
  w.sceneMin = glm::vec3(std::numeric_limits<float>::max());
  w.sceneMax = glm::vec3(-std::numeric_limits<float>::max());
  std::vector<std::pair<std::size_t, std::pair<glm::vec3, glm::vec3>>> posedBounds;  // posed draw → world box

  // Meshes: every node of the instanced subtree, composed with the entity's world transform.
  registry.view<scene::MeshRef, scene::WorldTransform>().each(
      [&](ecs::Entity e, scene::MeshRef& ref, scene::WorldTransform& world) {
        const AssetGpu& a = *assets_.at(key(ref));
        const auto* over = registry.tryGet<scene::MaterialOverride>(e);
        const bool dynamic = registry.has<scene::Dynamic>(e);
        const anim::Pose* pose = registry.tryGet<anim::Pose>(e);
        const auto* sl = registry.tryGet<scene::Sl>(e);
        const bool slLocal = sl && sl->localLights && w.has("sl");  // DrawItem::slLocal
        const glm::mat4 skinFrame = pose ? anim::skinFrame(a.cpu, ref, world.matrix, *pose) : world.matrix;
        scene::forEachInstancedNode(a.cpu, ref, world.matrix, [&](int n, const glm::mat4& nodeWorld) {
          glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());  // this node's
          const asset::Node& node = a.cpu.nodes[n];
          if (node.light >= 0) {
            const asset::Light& L = a.cpu.lights[node.light];
            w.lights.push_back(makeLight(static_cast<LightType>(L.type), L.color, L.intensity, L.range,
                                         L.innerConeAngle, L.outerConeAngle, true, nodeWorld));
          }
          if (node.mesh < 0 || node.vlm.present) return;  // extras.bounce_vlm: virtual light, not real geometry
          const auto& meshCpu = a.cpu.meshes[node.mesh];
          // A deformed mesh with a pose: its vertices as posed (engine/anim), skinned ones placed by
          // the skin frame (the spec ignores the skinned node's own transform).
          std::uint32_t posedBase = DrawItem::kNotPosed;
          glm::mat4 m = nodeWorld;
          const MeshGpu& gpuMesh = *a.meshes[node.mesh];
          // A subdivided skinned mesh is skinned as its cage (then refined by the subdivision pass).
          const MeshGpu& skinMesh = gpuMesh.cage ? *gpuMesh.cage : gpuMesh;
          const asset::Mesh& skinCpu = meshCpu.cage >= 0 ? a.cpu.meshes[std::size_t(meshCpu.cage)] : meshCpu;
          if (pose && options.gpuSkinning && skinMesh.skinVertices && (meshCpu.cage < 0 || gpuMesh.cage) &&
              anim::isDeformed(a.cpu, n)) {
            // Posed by the GPU pass: reserve its vertices, queue the job with this instance's joints
            // and morph weights.
            const auto reserve = [&](std::uint32_t vertices) {
              const auto base = static_cast<std::uint32_t>(w.posedVertices.size() / 8);
              w.posedVertices.resize(w.posedVertices.size() + std::size_t(vertices) * 8, 0.0f);
              return base;
            };
            const bool skinned = anim::isSkinned(a.cpu, n);
            const std::uint32_t skinBase = reserve(skinMesh.vertexCount);
            static const std::vector<glm::mat4> kIdentity{glm::mat4(1.0f)};
            const auto& joints = skinned ? pose->joints[std::size_t(node.skin)] : kIdentity;
            // One weight per target: the pose's (or the mesh's defaults), missing ones 0 (MorphJob).
            const std::vector<float>& given = anim::morphWeights(a.cpu, pose, n);
            std::vector<float> weights(skinMesh.morphTargets, 0.0f);
            std::copy_n(given.begin(), std::min(given.size(), weights.size()), weights.begin());
            w.skinJobs.push_back({&skinMesh, skinMesh.vertexCount,
                                  static_cast<std::uint32_t>(skinned ? w.jointMatrices.size() : 0), skinBase,
                                  static_cast<std::uint32_t>(w.morphWeights.size()), skinned});
            if (skinned) w.jointMatrices.insert(w.jointMatrices.end(), joints.begin(), joints.end());
            w.morphWeights.insert(w.morphWeights.end(), weights.begin(), weights.end());
            posedBase = skinBase;
            if (gpuMesh.cage) {  // the refined vertices follow the cage's in the same buffer
              posedBase = reserve(gpuMesh.vertexCount);
              w.subdivisionJobs.push_back({&gpuMesh, gpuMesh.vertexCount, skinBase, posedBase});
            }
            if (skinned) m = skinFrame;
            // Bounds: a morphed vertex is p₀ + Σ_t w_t·Δp_t, inside the bind box grown by each
            // w_t·[morphMin_t, morphMax_t]; every skinned vertex is a convex combination of J_i·v, so
            // the union of that box under every joint matrix contains it; a limit point is a convex
            // combination of posed cage vertices, so the cage's box serves a refined mesh too.
            glm::vec3 boxMin = skinCpu.bounds.min, boxMax = skinCpu.bounds.max;
            for (std::size_t t = 0; t < weights.size(); ++t) {
              const glm::vec3 a0 = weights[t] * skinMesh.morphMin[t], a1 = weights[t] * skinMesh.morphMax[t];
              boxMin += glm::min(a0, a1);
              boxMax += glm::max(a0, a1);
            }
            for (const glm::mat4& j : joints)
              for (int i = 0; i < 8; ++i) {
                glm::vec3 c{i & 1 ? boxMax.x : boxMin.x, i & 2 ? boxMax.y : boxMin.y, i & 4 ? boxMax.z : boxMin.z};
                glm::vec3 p = glm::vec3(m * (j * glm::vec4(c, 1.0f)));
                w.sceneMin = glm::min(w.sceneMin, p);
                w.sceneMax = glm::max(w.sceneMax, p);
                lo = glm::min(lo, p);
                hi = glm::max(hi, p);
              }
          } else if (pose && anim::isDeformed(a.cpu, n)) {
            posedBase = static_cast<std::uint32_t>(w.posedVertices.size() / 8);
            std::vector<glm::vec3> pos, nrm;
            for (std::size_t pi = 0; pi < meshCpu.primitives.size(); ++pi) {
              const asset::Primitive& prim = meshCpu.primitives[pi];
              if (anim::posePrimitive(a.cpu, n, pi, pose, pos, nrm)) m = skinFrame;
              for (std::size_t v = 0; v < pos.size(); ++v) {
                const glm::vec2 uv = v < prim.uv0.size() ? prim.uv0[v] : glm::vec2(0.0f);
                w.posedVertices.insert(w.posedVertices.end(), {pos[v].x, pos[v].y, pos[v].z, nrm[v].x, nrm[v].y, nrm[v].z, uv.x, uv.y});
                const glm::vec3 p = glm::vec3(m * glm::vec4(pos[v], 1.0f));
                w.sceneMin = glm::min(w.sceneMin, p);
                w.sceneMax = glm::max(w.sceneMax, p);
                lo = glm::min(lo, p);
                hi = glm::max(hi, p);
              }
            }
          } else {
            for (int i = 0; i < 8; ++i) {
              glm::vec3 c{i & 1 ? meshCpu.bounds.max.x : meshCpu.bounds.min.x,
                          i & 2 ? meshCpu.bounds.max.y : meshCpu.bounds.min.y,
                          i & 4 ? meshCpu.bounds.max.z : meshCpu.bounds.min.z};
              glm::vec3 p = glm::vec3(m * glm::vec4(c, 1.0f));
              w.sceneMin = glm::min(w.sceneMin, p);
              w.sceneMax = glm::max(w.sceneMax, p);
            }
          }
          for (std::uint32_t p = 0; p < gpuMesh.primitives.size(); ++p) {
            const auto& prim = gpuMesh.primitives[p];
            InstanceGpu inst{};
            inst.model = m;
            inst.normalMatrix = glm::mat4(glm::inverseTranspose(glm::mat3(m)));
            glm::vec3 albedo(1.0f), emissive(0.0f);
            bool baseTex = false, emissiveTex = false;
            if (prim.material < a.cpu.materials.size()) {
              const auto& mat = a.cpu.materials[prim.material];
              albedo = glm::vec3(mat.baseColorFactor);
              emissive = mat.emissiveFactor;
              baseTex = mat.baseColorTexture.texture >= 0;
              emissiveTex = mat.emissiveTexture.texture >= 0;
            }
            if (over && over->albedo) albedo = *over->albedo;
            if (over && over->emissive) emissive = *over->emissive;
            inst.albedo = glm::vec4(albedo, baseTex ? 1.0f : 0.0f);
            inst.emissive = glm::vec4(emissive, emissiveTex ? 1.0f : 0.0f);
            inst.ids = glm::uvec4(e.index(), 0, 0, 0);
            w.draws.push_back({&gpuMesh, p, static_cast<std::uint32_t>(w.instances.size()),
                               a.materialSets[prim.material], e.index(), dynamic, posedBase});
            w.draws.back().slLocal = slLocal;
            if (posedBase != DrawItem::kNotPosed) posedBounds.emplace_back(w.draws.size() - 1, std::make_pair(lo, hi));
            w.instances.push_back(inst);
          }
        }, pose ? &pose->local : nullptr);
      });
  if (w.draws.empty()) w.sceneMin = w.sceneMax = glm::vec3(0.0f);

  registry.view<scene::Light, scene::WorldTransform>().each(
      [&](ecs::Entity, scene::Light& L, scene::WorldTransform& world) {
        LightType type = L.type == scene::LightType::Point  ? LightType::Point
                         : L.type == scene::LightType::Spot ? LightType::Spot
                                                            : LightType::Directional;
        w.lights.push_back(makeLight(type, L.color, L.intensity, L.range.value_or(0.0f), L.innerConeRad,
                                     L.outerConeRad, L.shadows, world.matrix, L.radius));
      });
  if (!w.has("shadows"))
    for (auto& l : w.lights) l.shadow.x = -1.0f;
  buildShadowLayers(w, options.shadowResolution);

  // Camera: the active camera's world transform (scale removed), glTF-style perspective.
  const float aspect = float(options.extent.width) / float(options.extent.height);
  glm::mat4 camWorld(1.0f);
  scene::Camera cam;
  if (ecs::Entity c = scene::activeCamera(registry); !c.isNull()) {
    camWorld = registry.get<scene::WorldTransform>(c).matrix;
    cam = registry.get<scene::Camera>(c);
  }
  for (int i = 0; i < 3; ++i) camWorld[i] = glm::vec4(glm::normalize(glm::vec3(camWorld[i])), 0.0f);
  w.camera.view = glm::inverse(camWorld);
  w.camera.proj = perspectiveVk(cam.yfovRad, aspect, cam.near, cam.far);
  w.camera.viewProj = w.camera.proj * w.camera.view;
  w.camera.invViewProj = glm::inverse(w.camera.viewProj);
  w.camera.position = glm::vec4(glm::vec3(camWorld[3]), 1.0f);
  w.camera.resolution = glm::vec4(options.extent.width, options.extent.height, 1.0f / options.extent.width,
                                  1.0f / options.extent.height);
  w.cameraFar = cam.far;

  // Culling of posed draws against the camera and every shadow layer (DrawItem::inView/inShadow).
  // Shadow layers without their near plane: a caster between the light and the near plane still
  // shades what lies beyond it.
  for (const auto& [draw, box] : posedBounds) {
    DrawItem& d = w.draws[draw];
    d.inView = boxMeetsFrustum(w.camera.viewProj, box.first, box.second, true);
    d.inShadow = false;
    for (const ShadowLayer& layer : w.shadowLayers)
      d.inShadow = d.inShadow || boxMeetsFrustum(layer.viewProj, box.first, box.second, false);
  }
}

bool boxMeetsFrustum(const glm::mat4& viewProj, glm::vec3 lo, glm::vec3 hi, bool nearPlane) {
  glm::vec4 c[8];
  for (int i = 0; i < 8; ++i)
    c[i] = viewProj * glm::vec4(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z, 1.0f);
  // Vulkan clip space: −w ≤ x, y ≤ w and 0 ≤ z ≤ w. Outside when all 8 corners fail one plane
  // (each plane is a linear half-space of the homogeneous corner, so this holds behind the eye too).
  auto outside = [&](auto&& inside) {
    for (const glm::vec4& v : c)
      if (inside(v)) return false;
    return true;
  };
  if (outside([](const glm::vec4& v) { return v.x >= -v.w; }) || outside([](const glm::vec4& v) { return v.x <= v.w; }) ||
      outside([](const glm::vec4& v) { return v.y >= -v.w; }) || outside([](const glm::vec4& v) { return v.y <= v.w; }) ||
      outside([](const glm::vec4& v) { return v.z <= v.w; }))
    return false;
  return !(nearPlane && outside([](const glm::vec4& v) { return v.z >= 0.0f; }));
}

bool RenderWorld::posedInView() const {
  return std::any_of(draws.begin(), draws.end(), [](const DrawItem& d) { return d.posed() && d.inView; });
}

bool RenderWorld::posedInShadow() const {
  return std::any_of(draws.begin(), draws.end(), [](const DrawItem& d) { return d.posed() && d.inShadow; });
}

}  // namespace bounce::render
