#pragma once
// VLM as a technique of the table (engine/gi/technique.hpp): entities carrying virtual lights (a
// `vlm` component, or a mesh whose glTF nodes say extras.bounce_vlm) take part; nothing is baked
// (the static grid is built once per session, §4.3); the runtime and node of node.hpp.
#include "engine/gi/technique.hpp"

namespace bounce::gi::vlm {

const Technique& technique();

}  // namespace bounce::gi::vlm
