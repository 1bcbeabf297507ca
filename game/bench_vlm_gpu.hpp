#pragma once
// `bounce bench vlm-lights` and `bounce bench vlm-k`: GPU milliseconds of the VLM passes on a level
// with a VLM (default content/levels/cornell-vlm.json), one line per setting.
//   vlm-lights (thesis Table 5.1 analogue): N = 20, 40, …, 240 virtual lights evaluated per pixel
//     with no grid to speak of — one cell whose list holds every light (K = N, range 100);
//   vlm-k (Table 5.3 analogue): cell lists of K = 10, 20, …, 120 slots in the level's grid, with
//     --lights lights (default 240) and range 100 so every list is full.
// The level's static VLM triangles are split (longest edge first) until the static and dynamic
// lights together number N: the same emitting surface, so the image stays the same while the cost
// grows. Each setting renders --warmup frames, then times --frames frames (medians).
#include "game/cli.hpp"

namespace bounce::game {

int runBenchVlmLights(const cli::Args& args);
int runBenchVlmK(const cli::Args& args);

}  // namespace bounce::game
