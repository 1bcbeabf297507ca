#pragma once
// SSAO and HBAO as techniques of the table (engine/gi/technique.hpp): screen-space, so every drawn
// surface takes part and nothing is baked.
#include "engine/gi/ao/node.hpp"
#include "engine/gi/technique.hpp"

namespace bounce::gi::ao {

const Technique& technique(Kind kind);

}  // namespace bounce::gi::ao
