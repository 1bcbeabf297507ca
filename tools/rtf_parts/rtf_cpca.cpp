// rtf_cpca: the CPCA error–ratio curve of one prop's RTF with the bases and coefficients stored as
// fp16 (issue 14, README Results "RTF", "Fourth pass": CPCA). A measurement, not the shipped format:
// the field files and the ξ pass hold fp32 (`bounce bench rtf`'s ratio= counts floats).
//
// Bakes the level's dynamic object OBJECT (0-based, cornell-5's props as `bounce bench rtf` takes
// them) at the given settings, keeps the uncompressed ITF X, and for each component count n_e
// compresses it (cpca.hpp) and prints, with X̂ the reconstruction:
//   norm   = ‖X − X̂‖_F / ‖X‖_F      (`frobenius=`: the paper's "Frobenius norm of the difference", relative)
//   energy = norm²                   (relative squared error, what SHHS03 plots)
//   ratio  = N·D floats / (basis + α + cluster id) floats — what the GPU holds (fp32)
// then the same after rounding every basis entry and α to fp16 (glm::packHalf1x16) — the error
// measured AFTER quantization — with stored_ratio = 4·N·D bytes / (2·(basis + α) + 4·N) bytes.
//
// usage: rtf_cpca LEVEL OBJECT PROXIES SPHERES FACE RAYS CLUSTERS COMPONENTS[,COMPONENTS…]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include <glm/gtc/packing.hpp>

#include "engine/core/paths.hpp"
#include "engine/gi/dnrt/object_scene.hpp"
#include "engine/gi/rtf/bake.hpp"
#include "engine/gi/rtf/cpca.hpp"
#include "engine/scene/components.hpp"
#include "engine/scene/level.hpp"

using namespace bounce;

int main(int argc, char** argv) {
  if (argc < 9) {
    std::fprintf(stderr, "usage: rtf_cpca LEVEL OBJECT PROXIES SPHERES FACE RAYS CLUSTERS COMPONENTS[,COMPONENTS...]\n");
    return 2;
  }
  const scene::Level level = scene::loadLevel(argv[1]);
  const std::size_t index = std::size_t(std::atoi(argv[2]));
  gi::dnrt::LevelObjects objects;
  gi::dnrt::loadLevelObjects(level, cacheDir("cooked"), objects);
  if (index >= objects.entities.size()) {
    std::fprintf(stderr, "rtf_cpca: object %zu of %zu\n", index, objects.entities.size());
    return 2;
  }
  gi::rtf::FieldSettings s;
  s.proxies = std::atoi(argv[3]), s.spheres = std::atoi(argv[4]), s.faceSize = std::atoi(argv[5]);
  s.raysPerAxis = std::atoi(argv[6]), s.clusters = std::atoi(argv[7]);
  std::vector<int> counts;
  std::stringstream list(argv[8]);
  for (std::string item; std::getline(list, item, ',');) counts.push_back(std::atoi(item.c_str()));
  s.components = counts.front();
  const ref::SceneDesc object = gi::dnrt::objectScene(objects.registry, objects.entities[index], objects.assets);
  const auto t0 = std::chrono::steady_clock::now();
  const gi::rtf::BakeResult baked = gi::rtf::bake(object, s);
  std::fprintf(stderr, "rtf_cpca: baked in %.1f s\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  const std::size_t N = gi::rtf::sampleCount(s), D = gi::rtf::itfDimension(s);
  for (int ne : counts) {
    gi::rtf::CpcaSettings cs;
    cs.clusters = s.clusters, cs.components = ne;
    gi::rtf::Cpca c = ne == s.components ? baked.field.itf : gi::rtf::compress(baked.itf, D, cs);
    const gi::rtf::CpcaError e = gi::rtf::measure(c, baked.itf);
    for (float& x : c.basis) x = glm::unpackHalf1x16(glm::packHalf1x16(x));
    for (float& x : c.alpha) x = glm::unpackHalf1x16(glm::packHalf1x16(x));
    const gi::rtf::CpcaError h = gi::rtf::measure(c, baked.itf);
    const double stored = 4.0 * double(N) * double(D) / (2.0 * double(c.basis.size() + c.alpha.size()) + 4.0 * double(N));
    std::printf("clusters=%d components=%d fp32: ratio=%.1f norm=%.4f energy=%.5f | fp16: stored_ratio=%.1f norm=%.4f "
                "energy=%.5f\n", c.clusters, ne, e.ratio, e.frobenius, e.frobenius * e.frobenius, stored, h.frobenius,
                h.frobenius * h.frobenius);
    std::fflush(stdout);
  }
  return 0;
}
