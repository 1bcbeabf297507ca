// rtf_cpca_time: the CPCA (cpca.hpp, Eq. 9) alone on a stored ITF, timed (issue 14, session 13,
// README "Bake speed and CPCA, session 13"). A measurement: the field bake (33–59 s at 6·64²) is
// done once by `dump`, then `run` compresses the same X at any settings and thread count.
//   rtf_cpca_time dump LEVEL OBJECT PROXIES SPHERES FACE RAYS OUT   X (N·D floats, raw) to OUT
//   rtf_cpca_time run FILE D CLUSTERS COMPONENTS THREADS [HASH [ITERATIONS [POWER]]]
// `run` prints wall and CPU seconds of compress(), the fp16 Frobenius error and stored ratio as
// `bounce bench rtf` does, and (with HASH = 1) an FNV-1a hash of the basis, α and cluster ids:
// the same bytes for any THREADS is the determinism the CPCA promises.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <vector>

#include <tbb/global_control.h>

#include "engine/core/paths.hpp"
#include "engine/gi/dnrt/object_scene.hpp"
#include "engine/gi/rtf/bake.hpp"
#include "engine/gi/rtf/cpca.hpp"
#include "engine/scene/components.hpp"
#include "engine/scene/level.hpp"
#include "tools/rtf_parts/tool_object.hpp"

using namespace bounce;

namespace {
double cpuSeconds() { return double(std::clock()) / CLOCKS_PER_SEC; }
std::uint64_t fnv(const void* p, std::size_t n, std::uint64_t h) {
  const auto* b = static_cast<const unsigned char*>(p);
  for (std::size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
  return h;
}
}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "dump" && argc == 9) {
    gi::dnrt::LevelObjects objects;
    std::size_t index = 0;
    gi::rtf::FieldSettings s;
    if (!tools::loadToolObject("rtf_cpca_time", argv + 2, objects, index, s)) return 2;
    s.clusters = 1, s.components = 1;  // the bake's own CPCA is not what is measured here
    const ref::SceneDesc object = gi::dnrt::objectScene(objects.registry, objects.entities[index], objects.assets);
    const gi::rtf::BakeResult baked = gi::rtf::bake(object, s);
    std::ofstream out(argv[8], std::ios::binary);
    out.write(reinterpret_cast<const char*>(baked.itf.data()), std::streamsize(baked.itf.size() * sizeof(float)));
    std::printf("N=%zu D=%zu\n", gi::rtf::sampleCount(s), gi::rtf::itfDimension(s));
    return out ? 0 : 2;
  }
  if (mode == "run" && argc >= 7) {
    std::ifstream in(argv[2], std::ios::binary | std::ios::ate);
    const std::size_t D = std::size_t(std::atoll(argv[3]));
    const std::size_t bytes = in ? std::size_t(in.tellg()) : 0;
    if (!in || D == 0 || bytes % (D * sizeof(float)) != 0) {
      std::fprintf(stderr, "%s: size: not N·%zu floats\n", argv[2], D);
      return 2;
    }
    std::vector<float> X(bytes / sizeof(float));
    in.seekg(0);
    in.read(reinterpret_cast<char*>(X.data()), std::streamsize(bytes));
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism, std::size_t(std::atoi(argv[6])));
    gi::rtf::CpcaSettings cs;
    cs.clusters = std::atoi(argv[4]), cs.components = std::atoi(argv[5]);
    if (argc > 8) cs.iterations = std::atoi(argv[8]);
    if (argc > 9) cs.powerIterations = std::atoi(argv[9]);
    const double c0 = cpuSeconds();
    const auto t0 = std::chrono::steady_clock::now();
    gi::rtf::Cpca c = gi::rtf::compress(X, D, cs);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double cpu = cpuSeconds() - c0;
    gi::rtf::roundToHalf(c);
    const gi::rtf::CpcaError e = gi::rtf::measure(c, X);
    std::printf("power=%d iterations=%d clusters=%d components=%d threads=%s cpca_s=%.1f cpca_cpu_s=%.1f ratio=%.1f frobenius=%.4f", cs.powerIterations, cs.iterations, c.clusters,
                c.components, argv[6], wall, cpu, e.stored, e.frobenius);
    if (argc > 7 && std::atoi(argv[7]) == 1) {
      std::uint64_t h = 1469598103934665603ull;
      h = fnv(c.basis.data(), c.basis.size() * sizeof(float), h);
      h = fnv(c.alpha.data(), c.alpha.size() * sizeof(float), h);
      h = fnv(c.cluster.data(), c.cluster.size() * sizeof(std::uint32_t), h);
      std::printf(" hash=%016llx", static_cast<unsigned long long>(h));
    }
    std::printf("\n");
    return 0;
  }
  std::fprintf(stderr, "usage: rtf_cpca_time dump LEVEL OBJECT PROXIES SPHERES FACE RAYS OUT | run FILE D CLUSTERS COMPONENTS THREADS [HASH]\n");
  return 2;
}
