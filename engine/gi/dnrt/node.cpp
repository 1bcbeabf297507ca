#include "engine/gi/dnrt/node.hpp"

#include <algorithm>
#include <atomic>
#include <cstring>
#include <functional>
#include <iterator>
#include <optional>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/core/error.hpp"
#include "engine/gi/resolution.hpp"  // header only: the resolution steps and the reduced size
#include "engine/gpu/commands.hpp"
#include "engine/render/mesh_gpu.hpp"
#include "engine/render/passes/rendering.hpp"
#include "engine/render/passes/skinning_pass.hpp"
#include "engine/render/passes/gbuffer_pass.hpp"
#include "engine/render/hdr_format.hpp"

namespace bounce::gi::dnrt {

namespace {
constexpr VkDescriptorType kSampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
constexpr VkDescriptorType kStorage = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
constexpr VkDescriptorType kUniform = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
constexpr VkDescriptorType kStorageImage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;        // "gbuffer.depth" (gbuffer_pass.cpp)
// The depth's layout in the dnrt pass: a read-only depth attachment (the box draws' test) that the
// shaders also sample (rg::Usage::DepthRead beside SampledFragment).
constexpr VkImageLayout kDepthReadOnly = VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL;

struct Push {
  std::uint32_t object = 0;
};

struct CombinePush {  // combine.comp's Push
  std::int32_t srcZ = 0, dstZ = 0, size = 0;
  std::int32_t occlusionZ = 0;  // kOcclusion: the occlusion term's first z layer
};

// combine.comp's uniform block Record (std140): one object's k and a (DnrtShaderObject's) and its
// occlusion term's, read at constant offsets (combine.comp says why not from the records' storage buffer).
struct CombineRecord {
  glm::vec4 k[7]{};
  glm::vec4 a{0.0f};
  glm::vec4 occlusionK[7]{};
  glm::vec4 occlusionA{0.0f};
};
// Each CombineRecord at a multiple of 256 bytes, the largest minUniformBufferOffsetAlignment Vulkan allows.
constexpr VkDeviceSize kCombineRecordStride = 256;
static_assert(sizeof(CombineRecord) == kCombineRecordStride, "combine.comp's Record");
// objectBuffer's layout: 2·count DnrtShaderObjects (the objects', then their occlusion terms'), then from
// this offset the objects' CombineRecords.
VkDeviceSize combineRecordsOffset(std::size_t count) {
  const VkDeviceSize records = 2 * count * sizeof(DnrtShaderObject);
  return (records + kCombineRecordStride - 1) / kCombineRecordStride * kCombineRecordStride;
}

// combine.comp's local size (why 8 wide in x: there).
constexpr glm::uvec3 kCombineLocal(8, 4, 4);

struct ClusterPush {  // clustered.frag's Push
  glm::vec4 invAtlasSize;
  std::uint32_t tileBase = 0, tilesX = 0, pad[2] = {0, 0};
};
constexpr VkDeviceSize kClusterBatchBytes = kClusterBatch * sizeof(DnrtClusterObject);  // 7680: 256-aligned

struct CullPush {  // tile_cull.comp's Push
  glm::mat4 invViewProj;
  glm::vec2 invSize;
  std::uint32_t tileBase = 0, tilesX = 0, tilesY = 0, pad = 0;
};

struct FusedReducedPush {  // fused_reduced.comp's Push
  glm::mat4 invViewProj;
  glm::vec4 worldToQ[3];
  glm::vec4 extents;  // x inner, y outer (units of R), z entity id + 1 (0 = none), w grid N
};
static_assert(sizeof(FusedReducedPush) == 128, "fused_reduced.comp's push block");
// fused_reduced.comp's local size (why 32×8: there).
constexpr glm::uvec2 kFusedReducedLocal(32, 8);

struct CubePush {
  glm::mat4 viewProj;
  glm::vec4 origin;
  std::uint32_t instance = 0, pad[3] = {0, 0, 0};
};

// Face frames as intrusion.glsl: forward and up hint.
constexpr float kFaces[6][6] = {{1, 0, 0, 0, -1, 0}, {-1, 0, 0, 0, -1, 0}, {0, 1, 0, 0, 0, 1},
                                {0, -1, 0, 0, 0, -1}, {0, 0, 1, 0, -1, 0},  {0, 0, -1, 0, -1, 0}};
}  // namespace

glm::mat4 cubeFaceViewProj(int face, glm::vec3 origin, float nearM, float farM) {
  const glm::vec3 f(kFaces[face][0], kFaces[face][1], kFaces[face][2]);
  const glm::vec3 up(kFaces[face][3], kFaces[face][4], kFaces[face][5]);
  return glm::perspectiveRH_ZO(glm::half_pi<float>(), 1.0f, nearM, farM) * glm::lookAt(origin, origin + f, up);
}

FieldTextures::FieldTextures(gpu::Context& ctx, const Field& field, const std::string& name)
    : field_(std::make_shared<const Field>(field)) {
  static std::atomic<std::uint64_t> next{1};
  id_ = next++;
  for (std::size_t t = 0; t < field.textures.size(); ++t) {
    gpu::ImageDesc d;
    d.type = gpu::ImageType::Tex3D;
    d.format = VK_FORMAT_R8G8B8A8_UNORM;
    d.width = d.height = d.depth = std::uint32_t(field.n());
    d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    d.name = "dnrt." + name + "." + std::to_string(t);
    images_.push_back(std::make_unique<gpu::Image>(ctx, d));
    gpu::upload(ctx, *images_.back(), field.textures[t]);
  }
  if (images_.empty()) throw InternalError("dnrt: a field without textures");
}

VkImageView FieldTextures::view(int slot) const {
  const std::size_t i = std::size_t(slot);
  return (i < images_.size() ? images_[i] : images_[0])->view();
}

Node::Node(gpu::Context& ctx, const render::Pipelines& shared, std::uint32_t framesInFlight)
    : ctx_(ctx),
      inputLayout_(ctx, {{0, kSampled}, {1, kSampled}, {2, kSampled}, {3, kStorage}, {4, kSampled}}, "dnrt.inputs"),
      fieldLayout_(ctx, {{0, kSampled}, {1, kSampled}}, "dnrt.field"),  // combined volume, intrusion map
      layout_(ctx, {shared.frameLayout, inputLayout_, fieldLayout_},
              {VkPushConstantRange{VK_SHADER_STAGE_ALL, 0, sizeof(Push)}}, "dnrt"),
      cubeLayout_(ctx, {shared.frameLayout}, {VkPushConstantRange{VK_SHADER_STAGE_ALL, 0, sizeof(CubePush)}},
                  "dnrt.cube"),
      objectBuffers_(framesInFlight),
      fusedBuffers_(framesInFlight),
      fusedTileBuffers_(framesInFlight),
      fusedClusterBuffers_(framesInFlight),
      clusterLayout_(ctx, {{0, kUniform}, {1, kSampled}}, "dnrt.cluster"),  // records, combined atlas
      clusterPipelineLayout_(ctx, {shared.frameLayout, inputLayout_, clusterLayout_},
                             {VkPushConstantRange{VK_SHADER_STAGE_ALL, 0, sizeof(ClusterPush)}}, "dnrt.clustered"),
      tileBuffers_(framesInFlight),
      clusterObjectBuffers_(framesInFlight),
      combineLayout_(ctx, {{0, kUniform}, {1, kSampled}, {2, kSampled}, {3, kSampled}, {4, kSampled}, {5, kSampled},
                           {6, kSampled}, {7, kSampled}, {8, kStorageImage}, {9, kSampled}, {10, kSampled},
                           {11, kSampled}, {12, kSampled}, {13, kSampled}, {14, kSampled}, {15, kSampled}},
                     "dnrt.combine"),
      combinePipelineLayout_(ctx, {combineLayout_},
                             {VkPushConstantRange{VK_SHADER_STAGE_ALL, 0, sizeof(CombinePush)}},
                             "dnrt.combine"),
      cullLayout_(ctx, {{0, kSampled}, {1, kStorage}, {2, kUniform}}, "dnrt.cull"),  // depth, masks, records
      cullPipelineLayout_(ctx, {cullLayout_}, {VkPushConstantRange{VK_SHADER_STAGE_ALL, 0, sizeof(CullPush)}},
                          "dnrt.cull"),
      upsample_(ctx, shared, "dnrt.upsample"),
      fusedReducedInputs_(ctx, {{0, kSampled}, {1, kSampled}, {2, kSampled}, {3, kStorageImage}},
                          "dnrt.fused.reduced"),  // depth, normal, combined volume, target
      fusedReducedLayout_(ctx, {fusedReducedInputs_},
                          {VkPushConstantRange{VK_SHADER_STAGE_ALL, 0, sizeof(FusedReducedPush)}},
                          "dnrt.fused.reduced") {
  {
    gpu::ShaderModule cull(ctx, "dnrt/tile_cull.comp.spv");
    cull_ = gpu::createComputePipeline(ctx, cullPipelineLayout_, cull, "dnrt.tile-cull");
  }
  {
    gpu::ShaderModule combine(ctx, "dnrt/combine.comp.spv");
    for (std::uint32_t v = 0; v < 4; ++v) {  // v: sh9 | occlusion << 1 (combine.comp's constants 0, 1)
      const std::uint32_t sh9 = v & 1u, occlusion = v >> 1;
      combine_[v] = gpu::createComputePipeline(
          ctx, combinePipelineLayout_, combine,
          std::string(sh9 ? "dnrt.combine.sh9" : "dnrt.combine.sh4") + (occlusion ? ".occlusion" : ""), nullptr,
          {sh9, occlusion});
    }
  }
  fullscreenVert_ = gpu::ShaderModule(ctx, "passes/fullscreen.vert.spv");
  clusterFrag_ = gpu::ShaderModule(ctx, "dnrt/clustered.frag.spv");
  vert_ = gpu::ShaderModule(ctx, "dnrt/dnrt.vert.spv");
  frag_ = gpu::ShaderModule(ctx, "dnrt/dnrt.frag.spv");

  gpu::ShaderModule cubeVert(ctx, "dnrt/cube_depth.vert.spv"), cubeFrag(ctx, "dnrt/cube_depth.frag.spv");
  gpu::GraphicsPipelineDesc c;
  c.vertex = &cubeVert;
  c.fragment = &cubeFrag;
  c.bindings = {{0, 32, false}};  // render::MeshGpu vertices: position, normal, uv0 (32 bytes)
  c.attributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0}};
  c.colorFormats = {VK_FORMAT_R32_SFLOAT};
  c.depthFormat = VK_FORMAT_D32_SFLOAT;
  c.depthTest = c.depthWrite = true;
  c.depthCompare = VK_COMPARE_OP_LESS;
  c.name = "dnrt.cube";
  cube_ = gpu::createGraphicsPipeline(ctx, cubeLayout_, c);

  gpu::ImageDesc none;
  none.format = VK_FORMAT_R32_SFLOAT;
  none.layers = 6;
  none.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  none.name = "dnrt.no-intrusion";
  noIntrusion_ = std::make_unique<gpu::Image>(ctx, none);
  const float far[6] = {1e30f, 1e30f, 1e30f, 1e30f, 1e30f, 1e30f};
  gpu::upload(ctx, *noIntrusion_, {reinterpret_cast<const std::uint8_t*>(far), sizeof far});
}

const gpu::Pipeline& Node::pipeline(const Variant& v) {
  const std::size_t key = (v.intrusion ? 1u : 0u) | (v.fullScreen ? 2u : 0u) | (v.selfInNormal ? 4u : 0u) |
                          stepIndex(v.step) << 3;
  gpu::Pipeline& p = variants_[key];
  if (p.handle()) return p;
  gpu::GraphicsPipelineDesc d;
  d.vertex = &vert_;
  d.fragment = &frag_;
  d.colorFormats = {render::kLightingHdrFormat};  // "lighting.hdr", or "dnrt.half" / "dnrt.quarter" (the same format)
  d.blend = gpu::Blend::Additive;
  // Box: back faces of the cube, each covered pixel once, inside or out. Full screen: one triangle.
  d.cull = v.fullScreen ? VK_CULL_MODE_NONE : VK_CULL_MODE_FRONT_BIT;
  // The box's back face against the scene's depth (the G-buffer's, read-only): a pixel whose surface
  // lies behind where its view ray leaves the cube is outside the cube (s = 0), so it fails the test
  // before the fragment shader runs; a surface inside the cube, or in front of it, passes.
  // Below full resolution the reduced target has no depth of its size: no test (s(r) in the shader
  // keeps the same receivers; the box still bounds the shaded samples).
  const bool reduced = v.step > 1u;
  d.depthFormat = reduced ? VK_FORMAT_UNDEFINED : kDepthFormat;
  d.depthTest = !v.fullScreen && !reduced;
  d.depthWrite = false;
  d.depthCompare = VK_COMPARE_OP_GREATER_OR_EQUAL;
  // dnrt.frag id 0, 2 and 3, dnrt.vert id 1
  d.specialization = {v.intrusion ? 1u : 0u, v.fullScreen ? 1u : 0u, v.selfInNormal ? 1u : 0u, v.step};
  d.name = std::string("dnrt.") + (v.fullScreen ? "fullscreen" : "box") + (v.intrusion ? ".intrusion" : "") +
           (v.selfInNormal ? "" : ".entity") + (reduced ? ".step" + std::to_string(v.step) : "");
  p = gpu::createGraphicsPipeline(ctx_, layout_, d);
  return p;
}

const gpu::Pipeline& Node::clusteredPipeline(bool single, bool selfInNormal, std::uint32_t step) {
  gpu::Pipeline& p = clustered_[(single ? 1u : 0u) | (selfInNormal ? 2u : 0u) | stepIndex(step) << 2];
  if (p.handle()) return p;
  gpu::GraphicsPipelineDesc d;
  d.vertex = &fullscreenVert_;
  d.fragment = &clusterFrag_;
  d.colorFormats = {render::kLightingHdrFormat};
  d.blend = gpu::Blend::Additive;
  // The dnrt pass's read-only depth attachment (not tested here); none on a reduced target.
  d.depthFormat = step > 1u ? VK_FORMAT_UNDEFINED : kDepthFormat;
  // clustered.frag kSingle, kSelfInNormal, kStep
  d.specialization = {single ? 1u : 0u, selfInNormal ? 1u : 0u, step};
  d.name = std::string("dnrt.clustered") + (single ? ".single" : "") + (selfInNormal ? "" : ".entity") +
           (step > 1u ? ".step" + std::to_string(step) : "");
  p = gpu::createGraphicsPipeline(ctx_, clusterPipelineLayout_, d);
  return p;
}

gpu::Buffer& Node::objectBuffer(std::uint32_t slot, const std::vector<NodeObject>& objects) {
  return objectBuffer(objectBuffers_, slot, objects);
}

gpu::Buffer& Node::objectBuffer(std::vector<gpu::Buffer>& ring, std::uint32_t slot,
                                const std::vector<NodeObject>& objects) {
  // This slot's object records (the ring waited for the slot's fence before the frame began). The
  // combine pass and the draw pass both call this in one frame; the second writes the same bytes.
  // Record i: object i; record objects.size() + i: its occlusion term (NodeObject::occlusion), if any;
  // from combineRecordsOffset on, object i's CombineRecord (both terms' k and a, for combine.comp).
  gpu::Buffer& buffer = ring[slot % ring.size()];
  const VkDeviceSize bytes = combineRecordsOffset(objects.size()) + objects.size() * kCombineRecordStride;
  if (!buffer || buffer.size() < bytes)
    buffer = gpu::Buffer(ctx_, {bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                gpu::MemoryUsage::Upload, "dnrt.objects"});
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const DnrtShaderObject folded = fold(objects[i].data);
    std::memcpy(buffer.mapped() + i * sizeof(DnrtShaderObject), &folded, sizeof(DnrtShaderObject));
    const DnrtShaderObject occlusion = objects[i].occlusion ? fold(objects[i].occlusionData) : DnrtShaderObject{};
    std::memcpy(buffer.mapped() + (objects.size() + i) * sizeof(DnrtShaderObject), &occlusion,
                sizeof(DnrtShaderObject));
    CombineRecord combine;
    std::copy(std::begin(folded.k), std::end(folded.k), combine.k);
    combine.a = folded.a;
    std::copy(std::begin(occlusion.k), std::end(occlusion.k), combine.occlusionK);
    combine.occlusionA = occlusion.a;
    std::memcpy(buffer.mapped() + combineRecordsOffset(objects.size()) + i * kCombineRecordStride, &combine,
                sizeof combine);
  }
  return buffer;
}

void Node::recordCombine(VkCommandBuffer cmd, const render::PassContext& pc, gpu::Buffer& records, std::size_t count,
                         const NodeObject& object, std::size_t i, const Slots& slot, const Slots* occlusionSlot,
                         VkImageView target, std::int32_t srcZ, std::int32_t occlusionZ, std::int32_t dstZ,
                         std::int32_t size) {
  VkSampler point = pc.samplers->get({VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST});
  const gpu::Pipeline& p = combine_[(object.data.extents.z > 4.5f ? 1 : 0) | (occlusionSlot ? 2 : 0)];
  p.bind(cmd);
  VkDescriptorSet set = pc.frame().descriptors->allocate(combineLayout_);
  gpu::DescriptorWriter w;
  w.buffer(0, records, kUniform, combineRecordsOffset(count) + i * kCombineRecordStride, kCombineRecordStride);
  for (int s = 0; s < 7; ++s) {
    w.sampledImage(std::uint32_t(s + 1), slot(s), point);
    w.sampledImage(std::uint32_t(s + 9), occlusionSlot ? (*occlusionSlot)(s) : slot(s), point);
  }
  w.storageImage(8, target);
  w.update(ctx_, set);
  p.bindSet(cmd, 0, set);
  p.push(cmd, CombinePush{srcZ, dstZ, size, occlusionZ});
  const auto groups = [size](std::uint32_t local) { return (std::uint32_t(size) + local - 1) / local; };
  vkCmdDispatch(cmd, groups(kCombineLocal.x), groups(kCombineLocal.y), groups(kCombineLocal.z));
}

std::vector<Node::ClusterItem> Node::placeInAtlas(const std::vector<NodeObject>& objects,
                                                  const std::vector<std::size_t>& asked, glm::uvec3& combinedSize) {
  if (asked.empty()) return {};
  std::vector<const FieldTextures*> textures;  // per asked object: its field, then its occlusion field if any
  for (std::size_t i : asked) {
    textures.push_back(objects[i].textures);
    if (objects[i].occlusion) textures.push_back(objects[i].occlusion);
  }
  const std::vector<int> bricks = atlasFor(textures);
  std::vector<ClusterItem> items;
  std::size_t t = 0;
  for (std::size_t i : asked) {
    const int brick = bricks[t++];
    const int occlusionBrick = objects[i].occlusion ? bricks[t++] : -1;
    const auto side = std::uint32_t(objects[i].data.extents.w) + 2u;  // a padded brick (cluster.hpp)
    if (brick < 0 || (objects[i].occlusion && occlusionBrick < 0) ||
        combinedSize.z + side > ctx_.limits().maxImageDimension3D)
      continue;  // no room: the caller draws it alone
    items.push_back({i, brick, occlusionBrick, combinedSize.z});
    combinedSize = glm::uvec3(std::max(combinedSize.x, side), std::max(combinedSize.y, side), combinedSize.z + side);
  }
  return items;
}

void Node::recordAtlasCombine(VkCommandBuffer cmd, const render::PassContext& pc, gpu::Buffer& records,
                              const std::vector<NodeObject>& objects, const std::vector<ClusterItem>& items,
                              VkImageView target) {
  const Slots atlasSlot = [this](int s) {
    return atlas_.slots[std::size_t(s) < atlas_.slots.size() ? std::size_t(s) : 0]->view();
  };
  for (const ClusterItem& item : items) {
    const bool occlusion = item.occlusionBrick >= 0;  // both bricks in the one atlas
    recordCombine(cmd, pc, records, objects.size(), objects[item.object], item.object, atlasSlot,
                  occlusion ? &atlasSlot : nullptr, target, std::int32_t(atlas_.layout.z0[std::size_t(item.brick)]),
                  occlusion ? std::int32_t(atlas_.layout.z0[std::size_t(item.occlusionBrick)]) : 0,
                  std::int32_t(item.z), std::int32_t(objects[item.object].data.extents.w) + 2);
  }
}

std::size_t Node::writeClusterBuffers(const render::PassContext& pc, const std::vector<NodeObject>& objects,
                                      const std::vector<ClusterItem>& items, glm::uvec2 resolution, gpu::Buffer& tiles,
                                      gpu::Buffer& records, const std::string& prefix) {
  const std::size_t batches = (items.size() + kClusterBatch - 1) / kClusterBatch;
  const VkDeviceSize recordBytes = batches * kClusterBatchBytes;
  if (!records || records.size() < recordBytes)
    records = gpu::Buffer(ctx_, {recordBytes, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::MemoryUsage::Upload,
                                 prefix + "cluster-objects"});
  std::memset(records.mapped(), 0, recordBytes);
  std::vector<glm::mat4> boxes;
  for (std::size_t k = 0; k < items.size(); ++k) {
    const NodeObject& o = objects[items[k].object];
    const DnrtClusterObject rec = clusterObject(fold(o.data), items[k].z);
    std::memcpy(records.mapped() + k * sizeof(DnrtClusterObject), &rec, sizeof rec);
    boxes.push_back(o.data.boxToWorld);
  }
  const std::vector<std::uint32_t> masks = binObjects(pc.world->camera.viewProj, resolution, boxes);
  const VkDeviceSize tileBytes = masks.size() * sizeof(std::uint32_t);
  if (!tiles || tiles.size() < tileBytes)
    tiles = gpu::Buffer(ctx_, {tileBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::Upload, prefix + "tiles"});
  std::memcpy(tiles.mapped(), masks.data(), tileBytes);
  return masks.size();
}

void Node::recordTileCull(VkCommandBuffer cmd, const render::PassContext& pc, VkImageView depth,
                          VkImageLayout depthLayout, gpu::Buffer& tiles, gpu::Buffer& records, std::size_t batches,
                          glm::uvec2 resolution) {
  const TileGrid grid = tileGrid(resolution);
  const VkSampler point = pc.samplers->get({VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST});
  cull_.bind(cmd);
  for (std::size_t b = 0; b < batches; ++b) {
    VkDescriptorSet set = pc.frame().descriptors->allocate(cullLayout_);
    gpu::DescriptorWriter w;
    w.sampledImage(0, depth, point, depthLayout);
    w.buffer(1, tiles);
    w.buffer(2, records, kUniform, b * kClusterBatchBytes, kClusterBatchBytes);
    w.update(ctx_, set);
    cull_.bindSet(cmd, 0, set);
    cull_.push(cmd, CullPush{pc.world->camera.invViewProj, 1.0f / glm::vec2(resolution),
                             std::uint32_t(b * grid.count()), grid.tilesX, grid.tilesY});
    vkCmdDispatch(cmd, (grid.tilesX + 7) / 8, (grid.tilesY + 7) / 8, 1);  // local size 8×8, a tile each
  }
  VkMemoryBarrier written{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT};
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, 0, 1, &written,
                       0, nullptr, 0, nullptr);
}

probes::FusedDnrt Node::addFused(rg::RenderGraph& graph, const render::PassContext& pcIn, const NodeObject& object,
                                 std::uint32_t step, bool split) {
  if (!object.textures) throw InternalError("dnrt: object '" + object.name + "' has no field textures");
  step = gi::checkedStep(step);
  const render::PassContext* pc = &pcIn;
  struct CombineData {
    rg::Handle<rg::Texture> volume;
  };
  const auto n = std::uint32_t(object.data.extents.w);
  // Its own pass name: addTo's "dnrt.combine" may run in the same frame for the other objects (the graph
  // takes each name once). `profile` shows both; `bench dnrt` counts DNRT as dnrt.combine +
  // dnrt.combine.fused + dnrt (+ the fused term's share of probes).
  const auto& combine = graph.addPass<CombineData>(
      "dnrt.combine.fused",
      [&](rg::Builder& b, CombineData& d) {
        d.volume = b.write(b.create<rg::Texture>("dnrt.combined." + object.name,
                                                 rg::TextureDesc{n, n, n, 1, 1, rg::Format::RGBA16F, false}),
                           rg::Usage::StorageWrite);
      },
      [this, pc, objects = std::vector<NodeObject>{object}](const CombineData& d, const rg::PassResources& res,
                                                            rg::CommandContext& c) {
        VkCommandBuffer cmd = pc->cmd(c);
        gpu::Buffer& buffer = objectBuffer(fusedBuffers_, pc->frame().slot, objects);
        const FieldTextures* field = objects[0].textures;
        const FieldTextures* occlusion = objects[0].occlusion;
        const Slots fieldSlot = [field](int s) { return field->view(s); };
        const Slots occlusionSlot = [occlusion](int s) { return occlusion->view(s); };
        recordCombine(cmd, *pc, buffer, 1, objects[0], 0, fieldSlot, occlusion ? &occlusionSlot : nullptr,
                      pc->backend->image(res.texture(d.volume)).view(), 0, 0, 0, std::int32_t(objects[0].data.extents.w));
      });
  const DnrtShaderObject folded = fold(object.data);
  probes::FusedDnrt out;
  out.volume = combine.volume;
  for (int r = 0; r < 3; ++r) out.push.worldToQ[r] = folded.worldToQ[r];
  out.push.centreWorld = folded.centreWorld;
  out.push.extents = glm::vec4(folded.extents.x, folded.extents.y, float(folded.ids.x), folded.extents.w);
  out.step = step;
  // The split pays at full resolution, where the term per pixel is a trilinear tap; below it the term is one
  // texelFetch and a division a pixel, and the second early-depth-tested raster of the screen cost more than
  // the ≈ 30 % of pixels it skips (README "DNRT's fused term only inside its outer cube, session 19").
  out.split = split && step == 1u &&
              eyeInsideOuterCube(object.data.boxToWorld, pc->world->camera.view, pc->world->camera.proj);
  if (step == 1u) return out;
  // Below full resolution: f = s Σ_j c_j M_j at G-buffer pixel step·j (fused_reduced.comp), premultiplied
  // by the sample's validity, for the probes pass's bilinear blend of it (probes.frag dnrtReducedQuadTap).
  struct ReducedData {
    rg::Handle<rg::Texture> depth, normal, volume, target;
  };
  const glm::uvec2 fullSize(std::uint32_t(pc->world->camera.resolution.x), std::uint32_t(pc->world->camera.resolution.y));
  const glm::uvec2 size = gi::reducedSize(fullSize, step);
  auto& bb = graph.blackboard();
  const auto& reduced = graph.addPass<ReducedData>(
      "dnrt.fused.reduced",
      [&](rg::Builder& b, ReducedData& d) {
        d.depth = b.read(bb.get<rg::Texture>("gbuffer.depth"), rg::Usage::SampledCompute);
        d.normal = b.read(bb.get<rg::Texture>("gbuffer.normal"), rg::Usage::SampledCompute);
        d.volume = b.read(combine.volume, rg::Usage::SampledCompute);
        d.target = b.write(b.create<rg::Texture>(std::string("dnrt.fused.") + gi::resolutionName(step),
                                                 rg::TextureDesc{size.x, size.y, 1, 1, 1, rg::Format::RGBA16F, false}),
                           rg::Usage::StorageWrite);
      },
      [this, pc, step, size, push = FusedReducedPush{pc->world->camera.invViewProj, {out.push.worldToQ[0],
                                                     out.push.worldToQ[1], out.push.worldToQ[2]}, out.push.extents}](
          const ReducedData& d, const rg::PassResources& res, rg::CommandContext& c) {
        VkCommandBuffer cmd = pc->cmd(c);
        gpu::Pipeline& p = fusedReduced_[step == 2u ? 0u : 1u];
        if (p.handle() == VK_NULL_HANDLE) {
          gpu::ShaderModule comp(ctx_, "dnrt/fused_reduced.comp.spv");
          p = gpu::createComputePipeline(ctx_, fusedReducedLayout_, comp, "dnrt.fused.reduced.step" + std::to_string(step),
                                         nullptr, {step});  // kStep
        }
        auto view = [&](rg::Handle<rg::Texture> h) { return pc->backend->image(res.texture(h)).view(); };
        VkDescriptorSet set = pc->frame().descriptors->allocate(fusedReducedInputs_);
        const VkSampler point = pc->samplers->get({VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST});
        gpu::DescriptorWriter w;
        w.sampledImage(0, view(d.depth), point)
            .sampledImage(1, view(d.normal), point)
            // trilinear, as the full-resolution term reads the same volume
            .sampledImage(2, view(d.volume), pc->samplers->get({VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_NEAREST}))
            .storageImage(3, view(d.target))
            .update(ctx_, set);
        p.bind(cmd);
        p.bindSet(cmd, 0, set);
        p.push(cmd, push);
        vkCmdDispatch(cmd, (size.x + kFusedReducedLocal.x - 1u) / kFusedReducedLocal.x,
                      (size.y + kFusedReducedLocal.y - 1u) / kFusedReducedLocal.y, 1);  // a sample an invocation
      });
  out.reduced = reduced.target;
  return out;
}

std::optional<probes::FusedDnrt> Node::addFusedCluster(rg::RenderGraph& graph, const render::PassContext& pcIn,
                                                       const std::vector<NodeObject>& objectsIn, bool tileCull,
                                                       std::vector<bool>& taken) {
  taken.assign(objectsIn.size(), false);
  if (objectsIn.empty()) return std::nullopt;
  if (objectsIn.size() > kClusterBatch) throw InternalError("dnrt: more fused objects than one batch");
  for (const NodeObject& o : objectsIn)
    if (!o.textures || o.intrusion || o.data.ids.x > render::kEntityInNormalMax)
      throw InternalError("dnrt: object '" + o.name + "' cannot be fused");
  const render::PassContext* pc = &pcIn;
  // The atlas bricks and combined-atlas bricks, as addTo's clustered objects; `objects` are the ones
  // with room, in order, and items[k] is objects[k]'s (its record k in the pass's buffers).
  std::vector<std::size_t> asked(objectsIn.size());
  for (std::size_t i = 0; i < asked.size(); ++i) asked[i] = i;
  glm::uvec3 size(0u);
  std::vector<ClusterItem> items = placeInAtlas(objectsIn, asked, size);
  if (items.empty()) return std::nullopt;
  std::vector<NodeObject> objects;
  for (ClusterItem& item : items) {
    taken[item.object] = true;
    objects.push_back(objectsIn[item.object]);
    item.object = objects.size() - 1;
  }
  const glm::uvec2 resolution(std::uint32_t(pc->world->camera.resolution.x), std::uint32_t(pc->world->camera.resolution.y));
  const TileGrid grid = tileGrid(resolution);

  struct CombineData {
    rg::Handle<rg::Texture> atlas, depth;
  };
  auto& bb = graph.blackboard();
  // addFused's pass name: one fused combine a frame, whichever form (`bench dnrt` counts it as DNRT).
  const auto& combine = graph.addPass<CombineData>(
      "dnrt.combine.fused",
      [&](rg::Builder& b, CombineData& d) {
        d.atlas = b.write(b.create<rg::Texture>("dnrt.combined.fused-atlas",
                                                rg::TextureDesc{size.x, size.y, size.z, 1, 1, rg::Format::RGBA16F, false}),
                          rg::Usage::StorageWrite);
        if (tileCull) d.depth = b.read(bb.get<rg::Texture>("gbuffer.depth"), rg::Usage::SampledCompute);
      },
      [this, pc, objects, items, resolution, tileCull](const CombineData& d, const rg::PassResources& res,
                                                       rg::CommandContext& c) {
        VkCommandBuffer cmd = pc->cmd(c);
        const std::size_t slot = pc->frame().slot % fusedTileBuffers_.size();
        // 1. Σ_j c_j M_j per grid vertex into each object's brick (combine.comp), as addTo's clustered objects.
        gpu::Buffer& buffer = objectBuffer(fusedBuffers_, pc->frame().slot, objects);
        recordAtlasCombine(cmd, *pc, buffer, objects, items, pc->backend->image(res.texture(d.atlas)).view());
        // 2. The records (clustered.frag's, std140) and the tile masks (the screen hulls, one batch).
        gpu::Buffer& tiles = fusedTileBuffers_[slot];
        gpu::Buffer& records = fusedClusterBuffers_[slot];
        writeClusterBuffers(*pc, objects, items, resolution, tiles, records, "dnrt.fused-");
        // 3. The masks cut by each tile's depth range (tile_cull.comp), then visible to the probes pass
        // (which reads them outside the graph: a buffer of this node's).
        if (tileCull)
          recordTileCull(cmd, *pc, pc->backend->image(res.texture(d.depth)).view(),
                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, tiles, records, 1, resolution);
      });
  probes::FusedDnrt out;
  out.volume = combine.atlas;
  out.push.centreWorld = glm::vec4(1.0f / glm::vec3(size), float(grid.tilesX));
  out.bindCluster = [this](gpu::DescriptorWriter& w, const render::PassContext& p) {
    const std::size_t slot = p.frame().slot % fusedTileBuffers_.size();
    w.buffer(10, fusedTileBuffers_[slot]);
    w.buffer(11, fusedClusterBuffers_[slot], kUniform, 0, kClusterBatchBytes);
  };
  return out;
}

std::vector<int> Node::atlasFor(const std::vector<const FieldTextures*>& textures) {
  const auto brickOf = [&](std::uint64_t id) {
    const auto it = std::find(atlas_.ids.begin(), atlas_.ids.end(), id);
    const int b = it == atlas_.ids.end() ? -1 : int(it - atlas_.ids.begin());
    return b < int(atlas_.layout.z0.size()) ? b : -1;  // left out of the layout: no room
  };
  bool grow = false;
  for (const FieldTextures* t : textures)
    if (std::find(atlas_.ids.begin(), atlas_.ids.end(), t->id()) == atlas_.ids.end()) {
      atlas_.ids.push_back(t->id());
      atlas_.fields.push_back(t->sharedField());
      grow = true;
    }
  if (grow) {
    std::vector<const Field*> fields;
    for (const auto& f : atlas_.fields) fields.push_back(f.get());
    const AtlasLayout layout = atlasLayout(fields, ctx_.limits().maxImageDimension3D);
    std::vector<std::unique_ptr<gpu::Image>> slots;
    for (int slot = 0; slot < layout.slots; ++slot) {
      gpu::ImageDesc d;
      d.type = gpu::ImageType::Tex3D;
      d.format = VK_FORMAT_R8G8B8A8_UNORM;
      d.width = layout.size.x, d.height = layout.size.y, d.depth = layout.size.z;
      d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
      d.name = "dnrt.atlas." + std::to_string(slot);
      slots.push_back(std::make_unique<gpu::Image>(ctx_, d));
      gpu::upload(ctx_, *slots.back(), atlasTexels(layout, fields, slot));
    }
    ctx_.waitIdle();  // frames in flight may still sample the old atlas
    atlas_.layout = layout;
    atlas_.slots = std::move(slots);
  }
  std::vector<int> bricks;
  for (const FieldTextures* t : textures) bricks.push_back(brickOf(t->id()));
  return bricks;
}

void Node::addTo(rg::RenderGraph& graph, const render::PassContext& pcIn, std::vector<NodeObject> objects,
                 NodeSettings settings) {
  if (objects.empty()) return;
  for (const NodeObject& o : objects)
    if (!o.textures) throw InternalError("dnrt: object '" + o.name + "' has no field textures");
  auto& bb = graph.blackboard();
  const render::PassContext* pc = &pcIn;
  const auto modeOf = [&](const NodeObject& o) { return settings.mode.value_or(o.mode); };
  // The clustered draw's objects (placeInAtlas); intrusion and no room: drawn alone.
  glm::uvec3 combinedSize(0u);
  std::vector<std::size_t> asked;
  for (std::size_t i = 0; i < objects.size(); ++i)
    if (modeOf(objects[i]) == Mode::Clustered && !objects[i].intrusion) asked.push_back(i);
  const std::vector<ClusterItem> cluster = placeInAtlas(objects, asked, combinedSize);
  std::vector<bool> clustered(objects.size(), false);
  for (const ClusterItem& item : cluster) clustered[item.object] = true;
  // Intrusion maps first, one pass per object that asks (timed as "dnrt.cube/<name>").
  std::vector<std::optional<rg::Handle<rg::Texture>>> maps(objects.size());
  const std::uint32_t res = settings.intrusionResolution;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    NodeObject& o = objects[i];
    o.data.ids.y = o.intrusion ? 1u : 0u;
    if (!o.intrusion) continue;
    struct CubeData {
      rg::Handle<rg::Texture> map, depth;
    };
    const glm::vec3 origin(o.data.centreWorld);
    const float radius = o.data.centreWorld.w, reach = o.data.extents.y * radius * 1.75f;  // > √3·outer
    const std::uint32_t self = o.data.ids.x;  // entity + 1 of the object, whose own mesh is skipped
    const auto& cube = graph.addPass<CubeData>(
        "dnrt.cube/" + o.name,
        [&](rg::Builder& b, CubeData& d) {
          d.map = b.write(b.create<rg::Texture>("dnrt.intrusion." + o.name,
                                                rg::TextureDesc{res, res, 1, 6, 1, rg::Format::R32F, false}),
                          rg::Usage::ColorAttachment);
          d.depth = b.write(b.create<rg::Texture>("dnrt.intrusion-depth." + o.name,
                                                  rg::TextureDesc{res, res, 1, 1, 1, rg::Format::D32F, false}),
                            rg::Usage::DepthAttachment);
          render::readSkinnedVertices(graph, b);  // posed neighbours intrude with their pose
        },
        [this, pc, origin, radius, reach, self, res](const CubeData& d, const rg::PassResources& r,
                                                     rg::CommandContext& c) {
          VkCommandBuffer cmd = pc->cmd(c);
          gpu::Image& map = pc->backend->image(r.texture(d.map));
          gpu::Image& depth = pc->backend->image(r.texture(d.depth));
          for (int face = 0; face < 6; ++face) {
            render::Attachment color{pc->frameView(map, VK_IMAGE_VIEW_TYPE_2D, std::uint32_t(face), 1)};
            color.clear.color = {{1e30f, 0.0f, 0.0f, 0.0f}};
            render::Attachment z{depth.view()};
            z.clear.depthStencil = {1.0f, 0};
            render::beginRendering(ctx_, cmd, {res, res}, {&color, 1}, &z);
            cube_.bind(cmd);
            cube_.bindSet(cmd, 0, pc->frameSet);
            CubePush push{cubeFaceViewProj(face, origin, 0.05f * radius, reach), glm::vec4(origin, 0.0f)};
            for (const render::DrawItem& draw : pc->world->draws) {
              if (draw.entity + 1u == self) continue;
              const auto& prim = draw.mesh->primitives[draw.primitive];
              pc->bindGeometry(cmd, draw);  // a skinned neighbour as posed this frame
              push.instance = draw.instance;
              cube_.push(cmd, push);
              vkCmdDrawIndexed(cmd, prim.indexCount, 1, prim.firstIndex, prim.vertexOffset, 0);
            }
            ctx_.cmdEndRendering(cmd);
          }
        });
    maps[i] = cube.map;
  }

  // This frame's Σ_j c_j M_j per grid vertex (combine.comp), RGBA16F: a volume per drawn object,
  // and one atlas with a brick per clustered object. The draws then take one trilinear tap instead
  // of 3 (4 SH) or 7 (9 SH).
  struct CombineData {
    std::vector<std::optional<rg::Handle<rg::Texture>>> volumes;
    std::optional<rg::Handle<rg::Texture>> atlas;
  };
  std::vector<std::optional<rg::Handle<rg::Texture>>> volumes(objects.size());
  std::optional<rg::Handle<rg::Texture>> combinedAtlas;
  {
    const auto& combine = graph.addPass<CombineData>(
        "dnrt.combine",
        [&](rg::Builder& b, CombineData& d) {
          if (!cluster.empty())
            d.atlas = b.write(b.create<rg::Texture>("dnrt.combined.atlas",
                                                    rg::TextureDesc{combinedSize.x, combinedSize.y, combinedSize.z, 1,
                                                                    1, rg::Format::RGBA16F, false}),
                              rg::Usage::StorageWrite);
          d.volumes.resize(objects.size());
          for (std::size_t i = 0; i < objects.size(); ++i) {
            if (clustered[i]) continue;
            const auto n = std::uint32_t(objects[i].data.extents.w);
            d.volumes[i] = b.write(b.create<rg::Texture>("dnrt.combined." + objects[i].name,
                                                         rg::TextureDesc{n, n, n, 1, 1, rg::Format::RGBA16F, false}),
                                   rg::Usage::StorageWrite);
          }
        },
        [this, pc, objects, cluster](const CombineData& d, const rg::PassResources& res, rg::CommandContext& c) {
          VkCommandBuffer cmd = pc->cmd(c);
          gpu::Buffer& buffer = objectBuffer(pc->frame().slot, objects);
          for (std::size_t i = 0; i < objects.size(); ++i) {
            if (!d.volumes[i]) continue;
            const FieldTextures* field = objects[i].textures;
            const FieldTextures* occlusion = objects[i].occlusion;
            const Slots fieldSlot = [field](int s) { return field->view(s); };
            const Slots occlusionSlot = [occlusion](int s) { return occlusion->view(s); };
            recordCombine(cmd, *pc, buffer, objects.size(), objects[i], i, fieldSlot,
                          occlusion ? &occlusionSlot : nullptr, pc->backend->image(res.texture(*d.volumes[i])).view(),
                          0, 0, 0, std::int32_t(objects[i].data.extents.w));
          }
          if (d.atlas) recordAtlasCombine(cmd, *pc, buffer, objects, cluster, pc->backend->image(res.texture(*d.atlas)).view());
        });
    volumes = combine.volumes;
    combinedAtlas = combine.atlas;
  }

  struct Data {
    render::DeferredInputs g;  // with entity
    rg::Handle<rg::Texture> hdr;
    std::vector<std::optional<rg::Handle<rg::Texture>>> maps, volumes;
    std::optional<rg::Handle<rg::Texture>> atlas;
  };
  const bool cullsTiles = !cluster.empty() && settings.tileCull;
  // Full resolution: the draws add to "lighting.hdr". Half, quarter: they add into the transient
  // "dnrt.half" / "dnrt.quarter" (⌈size/step⌉, cleared) and "dnrt.upsample" below adds it to "lighting.hdr".
  const std::uint32_t step = gi::checkedStep(settings.step);
  const bool reduced = step > 1u;
  const glm::uvec2 fullSize(std::uint32_t(pc->world->camera.resolution.x), std::uint32_t(pc->world->camera.resolution.y));
  const glm::uvec2 reducedExtent = gi::reducedSize(fullSize, step);
  // The depth's layout in the pass: read-only attachment and sampled at full resolution; sampled only below.
  const VkImageLayout depthLayout = reduced ? VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL : kDepthReadOnly;
  const auto& data = graph.addPass<Data>(
      "dnrt",
      [&](rg::Builder& b, Data& d) {
        d.g = render::readDeferredInputs(b, bb, /*withEntity=*/true);
        d.hdr = reduced ? b.write(b.create<rg::Texture>(std::string("dnrt.") + gi::resolutionName(step),
                                                        rg::TextureDesc{reducedExtent.x, reducedExtent.y, 1, 1, 1,
                                                                        rg::Format::RGBA16F, false}),
                                  rg::Usage::ColorAttachment)
                        : b.write(bb.get<rg::Texture>("lighting.hdr"), rg::Usage::ColorAttachment);
        for (const auto& m : maps) d.maps.push_back(m ? std::optional(b.read(*m, rg::Usage::SampledFragment)) : std::nullopt);
        for (const auto& v : volumes)
          d.volumes.push_back(v ? std::optional(b.read(*v, rg::Usage::SampledFragment)) : std::nullopt);
        if (combinedAtlas) d.atlas = b.read(*combinedAtlas, rg::Usage::SampledFragment);
        if (cullsTiles) b.read(d.g.depth, rg::Usage::SampledCompute);  // tile_cull.comp
        if (!reduced) b.read(d.g.depth, rg::Usage::DepthRead);  // the box draws' depth test, read-only (pipeline())
      },
      [this, pc, objects = std::move(objects), cluster = std::move(cluster), clustered = std::move(clustered),
       tileCull = settings.tileCull, selfInNormalAllowed = settings.selfInNormal, step, reduced, fullSize, depthLayout,
       modeOf = [mode = settings.mode](const NodeObject& o) { return mode.value_or(o.mode); }](
          const Data& d, const rg::PassResources& res, rg::CommandContext& c) {
        VkCommandBuffer cmd = pc->cmd(c);
        gpu::Buffer& buffer = objectBuffer(pc->frame().slot, objects);

        VkSampler point = pc->samplers->get({VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST});
        VkSampler linear = pc->samplers->get({VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_NEAREST});
        auto view = [&](rg::Handle<rg::Texture> h) { return pc->backend->image(res.texture(h)).view(); };
        VkDescriptorSet inputs = pc->frame().descriptors->allocate(inputLayout_);
        gpu::DescriptorWriter writer;
        render::writeDeferredInputs(writer, d.g, *pc, res, point, depthLayout)
            .buffer(3, buffer)
            .sampledImage(4, view(d.g.entity), point)
            .update(ctx_, inputs);

        gpu::Image& target = pc->backend->image(res.texture(d.hdr));
        // "dnrt.half" / "dnrt.quarter" starts at zero (samples no object reaches stay 0); "lighting.hdr"
        // keeps its light.
        render::Attachment color{target.view(), !reduced && res.keepsContents(d.hdr)};
        const VkExtent2D extent{target.desc().width, target.desc().height};
        // Clustered draws (cluster.hpp): this frame's tile masks and records, one draw per 32 objects
        // below, the masks first cut by each tile's depth range (tile_cull.comp, one dispatch a batch;
        // before the rendering begins, as a dispatch must be).
        std::optional<TileGrid> clusterGrid;
        std::size_t batches = 0;
        gpu::Buffer* records = nullptr;
        VkDescriptorSet clusterInputs = VK_NULL_HANDLE;
        if (!cluster.empty()) {
          const glm::uvec2 resolution = fullSize;  // tiles of G-buffer pixels, at any step
          clusterGrid = tileGrid(resolution);
          batches = (cluster.size() + kClusterBatch - 1) / kClusterBatch;
          const std::size_t slot = pc->frame().slot % tileBuffers_.size();
          gpu::Buffer& tiles = tileBuffers_[slot];
          records = &clusterObjectBuffers_[slot];
          lastTileCount_ = writeClusterBuffers(*pc, objects, cluster, resolution, tiles, *records, "dnrt.");
          lastTileSlot_ = slot;
          clusterInputs = pc->frame().descriptors->allocate(inputLayout_);
          gpu::DescriptorWriter writer;
          render::writeDeferredInputs(writer, d.g, *pc, res, point, depthLayout)
              .buffer(3, tiles)
              .sampledImage(4, view(d.g.entity), point)
              .update(ctx_, clusterInputs);
          // The masks cut here are read by clustered.frag below.
          if (tileCull) recordTileCull(cmd, *pc, view(d.g.depth), depthLayout, tiles, *records, batches, resolution);
        }

        render::Attachment depth{view(d.g.depth)};
        depth.readOnly = true;
        render::beginRendering(ctx_, cmd, extent, {&color, 1}, reduced ? nullptr : &depth);
        gpu::TimestampPool* ts = pc->frame().timestamps.get();
        const gpu::Pipeline* bound = nullptr;
        for (std::size_t i = 0; i < objects.size(); ++i) {
          if (clustered[i]) continue;
          const bool full = modeOf(objects[i]) == Mode::FullScreen;
          // The self test from the normal's w where the object's id fits it exactly (dnrt.frag).
          const bool selfInNormal = selfInNormalAllowed && objects[i].data.ids.x <= render::kEntityInNormalMax;
          const gpu::Pipeline& p = pipeline({objects[i].intrusion, full, selfInNormal, step});
          if (bound != &p) {  // bind on a change of variant (per object: intrusion, "mode", id size)
            p.bind(cmd);
            p.bindSet(cmd, 0, pc->frameSet);
            p.bindSet(cmd, 1, inputs);
            bound = &p;
          }
          VkDescriptorSet fieldSet = pc->frame().descriptors->allocate(fieldLayout_);
          gpu::DescriptorWriter w;
          w.sampledImage(0, view(*d.volumes[i]), linear);
          gpu::Image& map = d.maps[i] ? pc->backend->image(res.texture(*d.maps[i])) : *noIntrusion_;
          w.sampledImage(1, pc->frameView(map, VK_IMAGE_VIEW_TYPE_2D_ARRAY, 0, 6), point);
          w.update(ctx_, fieldSet);
          p.bindSet(cmd, 2, fieldSet);
          p.push(cmd, Push{std::uint32_t(i)});
          if (ts) ts->begin(cmd, "dnrt/" + objects[i].name);
          vkCmdDraw(cmd, full ? 3 : 36, 1, 0, 0);
          if (ts) ts->end(cmd);
        }
        if (!cluster.empty()) {
          const glm::vec4 invAtlas(1.0f / glm::vec3(pc->backend->image(res.texture(*d.atlas)).desc().width,
                                                    pc->backend->image(res.texture(*d.atlas)).desc().height,
                                                    pc->backend->image(res.texture(*d.atlas)).desc().depth),
                                   0.0f);
          for (std::size_t b = 0; b < batches; ++b) {
            const std::size_t end = std::min(cluster.size(), (b + 1) * kClusterBatch);
            // One object in the batch: record 0 as uniforms, no loops (clustered.frag kSingle). The self
            // test from the normal's w where every object's id fits it (dnrt.frag's kSelfInNormal).
            bool selfInNormal = selfInNormalAllowed;
            for (std::size_t k = b * kClusterBatch; k < end; ++k)
              selfInNormal = selfInNormal && objects[cluster[k].object].data.ids.x <= render::kEntityInNormalMax;
            const gpu::Pipeline& p = clusteredPipeline(end - b * kClusterBatch == 1, selfInNormal, step);
            p.bind(cmd);
            p.bindSet(cmd, 0, pc->frameSet);
            p.bindSet(cmd, 1, clusterInputs);
            VkDescriptorSet set = pc->frame().descriptors->allocate(clusterLayout_);
            gpu::DescriptorWriter w;
            w.buffer(0, *records, kUniform, b * kClusterBatchBytes, kClusterBatchBytes);
            w.sampledImage(1, view(*d.atlas), linear);
            w.update(ctx_, set);
            p.bindSet(cmd, 2, set);
            p.push(cmd, ClusterPush{invAtlas, std::uint32_t(b * clusterGrid->count()), clusterGrid->tilesX});
            vkCmdDraw(cmd, 3, 1, 0, 0);
          }
        }
        ctx_.cmdEndRendering(cmd);
      });
  if (!reduced) {
    bb.put("lighting.hdr", data.hdr);
    return;
  }

  // The reduced target's upsample over every pixel: ρ_r times the depth- and normal-aware blend of the
  // 4 nearest samples, added to "lighting.hdr" (gi/upsample_pass.hpp).
  upsample_.addTo(graph, *pc, data.hdr, step);
}

std::vector<std::uint32_t> Node::lastTileMasks() const {
  if (lastTileCount_ == 0) return {};
  const auto* m = reinterpret_cast<const std::uint32_t*>(tileBuffers_[lastTileSlot_].mapped());
  return std::vector<std::uint32_t>(m, m + lastTileCount_);
}

}  // namespace bounce::gi::dnrt
