#pragma once
// A pose of one cooked asset and the jobs that make it, in ozz-animation's order:
//   ClipJob          sample every channel of one clip at one time → node-local matrices + morph weights
//   LocalToModelJob  chain the local matrices from each root → model matrices (asset space)
//   JointMatricesJob per skin, model[joint] · inverseBind[joint] (glTF 2.0 §3.7.3.3)
// Each is a struct of inputs and outputs with validate() and run(); evaluatePose() runs all three.
//
// Nodes a clip does not animate keep their file transform, computed exactly as the static path
// computes it (scene::nodeLocal: T·R·S, or the node's matrix), so an unanimated node renders
// bit-identically with or without a pose. The skinned mesh node's own transform is ignored, as the
// spec requires: joint matrices take vertices from the bind pose to asset space directly.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "engine/asset/cooked_asset.hpp"

namespace bounce::anim {

struct Pose {
  std::vector<glm::mat4> local;              // per node
  std::vector<glm::mat4> model;              // per node: local chained from its root (asset space)
  std::vector<std::vector<float>> weights;   // per node: morph weights; empty = the mesh's defaults
  std::vector<std::vector<glm::mat4>> joints;  // per skin: joint matrices, one per joint
};

// Samples clip `clip` of `asset` at `time` seconds (clip time, already looped/clamped by the
// caller) into pose->local and pose->weights. clip = -1: the rest pose (no channel applied).
struct ClipJob {
  const asset::CookedAsset* asset = nullptr;
  int clip = -1;
  float time = 0.0f;
  Pose* pose = nullptr;
  bool validate() const;
  bool run() const;
};

// pose->model from pose->local: parents before children, every parentless node a root (identity).
struct LocalToModelJob {
  const asset::CookedAsset* asset = nullptr;
  Pose* pose = nullptr;
  bool validate() const;
  bool run() const;
};

// pose->joints from pose->model and each skin's inverse bind matrices.
struct JointMatricesJob {
  const asset::CookedAsset* asset = nullptr;
  Pose* pose = nullptr;
  bool validate() const;
  bool run() const;
};

// The three jobs in order. Throws InternalError if one fails (a validated CookedAsset never does).
void evaluatePose(const asset::CookedAsset& asset, int clip, float time, Pose& pose);

// The default morph weights of a mesh node's pose (the pose's when animated, else the mesh's).
const std::vector<float>& morphWeights(const asset::CookedAsset& asset, const Pose* pose, int node);

}  // namespace bounce::anim
