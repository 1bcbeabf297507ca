#pragma once
// Light probes as a technique of the table (engine/gi/technique.hpp): every static surface takes
// part, one bake job (the level's irradiance volume), the node of node.hpp, and the volume offered
// to later techniques as Services::probeVolume (DNRT's c_j).
#include "engine/gi/technique.hpp"

namespace bounce::gi::probes {

const Technique& technique();

}  // namespace bounce::gi::probes
