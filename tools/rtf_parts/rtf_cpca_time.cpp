// rtf_cpca_time: the CPCA (cpca.hpp, Eq. 9) alone on a stored ITF, timed (issue 14, session 13,
// README "Bake speed and CPCA, session 13"). A measurement: the field bake (33–59 s at 6·64²) is
// done once by `dump`, then `run` compresses the same X at any settings and thread count.
//   rtf_cpca_time dump LEVEL OBJECT PROXIES SPHERES FACE RAYS OUT [VERTEX_RAYS]   X (N·D floats, raw) to OUT
//     (VERTEX_RAYS: the vertex transfer's rays per axis, Eq. 8; default FieldSettings' 16)
//   rtf_cpca_time run FILE D CLUSTERS COMPONENTS THREADS [HASH [ITERATIONS [POWER]]]
// `run` prints wall and CPU seconds of compress(), the stored field's Frobenius error and stored ratio as
// `bounce bench rtf` does, and (with HASH = 1) an FNV-1a hash of the basis, α and cluster ids:
// the same bytes for any THREADS is the determinism the CPCA promises. With RTF_CPCA_GROUP=S set,
// also the error's share per group of S samples (README "CPCA on every prop, session 14").
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <string>
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
  if (mode == "dump" && (argc == 9 || argc == 10)) {
    gi::dnrt::LevelObjects objects;
    std::size_t index = 0;
    gi::rtf::FieldSettings s;
    if (!tools::loadToolObject("rtf_cpca_time", argv + 2, objects, index, s)) return 2;
    if (argc == 10) s.vertexRaysPerAxis = std::atoi(argv[9]);
    if (s.vertexRaysPerAxis < 1 || s.vertexRaysPerAxis > 256) {
      std::fprintf(stderr, "rtf_cpca_time: VERTEX_RAYS: %s out of range (expected 1..256)\n", argv[9]);
      return 2;
    }
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
    // RTF_CPCA_BYTE_COMPONENTS=n₈: the last n₈ components stored in 8 bits (cpca.hpp quantize), as
    // `bounce bench rtf --byte-components` (README "CPCA: the tail in 8 bits, session 15").
    // Checked here, not by quantize (an out-of-range n₈ is an InternalError there): one line, exit 2.
    const char* n8 = std::getenv("RTF_CPCA_BYTE_COMPONENTS");
    long byteComponents = 0;
    if (n8 && *n8) {
      char* end = nullptr;
      byteComponents = std::strtol(n8, &end, 10);
      if (*end != '\0' || byteComponents < 0 || byteComponents > c.components) {
        std::fprintf(stderr, "rtf_cpca_time: RTF_CPCA_BYTE_COMPONENTS: '%s' is not a component count (expected an integer 0..%d)\n",
                     n8, c.components);
        return 2;
      }
    }
    gi::rtf::quantize(c, int(byteComponents));
    const gi::rtf::CpcaError e = gi::rtf::measure(c, X);
    std::printf("power=%d iterations=%d clusters=%d components=%d threads=%s cpca_s=%.1f cpca_cpu_s=%.1f ratio=%.1f frobenius=%.4f", cs.powerIterations, cs.iterations, c.clusters,
                c.components, argv[6], wall, cpu, e.stored, e.frobenius);
    // RTF_CPCA_SAVE=PREFIX: the (stored: quantize) α and cluster ids to PREFIX.alpha (N·ne floats) and
    // PREFIX.cluster (N uint32), the basis to PREFIX.basis (n_c·(n_e+1)·D floats): to study α's quantisation offline (README "CPCA: the tail in 8 bits, session 15").
    if (const char* save = std::getenv("RTF_CPCA_SAVE"); save && *save) {
      std::ofstream a(std::string(save) + ".alpha", std::ios::binary), k(std::string(save) + ".cluster", std::ios::binary);
      a.write(reinterpret_cast<const char*>(c.alpha.data()), std::streamsize(c.alpha.size() * sizeof(float)));
      k.write(reinterpret_cast<const char*>(c.cluster.data()), std::streamsize(c.cluster.size() * sizeof(std::uint32_t)));
      std::ofstream b(std::string(save) + ".basis", std::ios::binary);
      b.write(reinterpret_cast<const char*>(c.basis.data()), std::streamsize(c.basis.size() * sizeof(float)));
    }
    if (argc > 7 && std::atoi(argv[7]) == 1) {
      std::uint64_t h = 1469598103934665603ull;
      h = fnv(c.basis.data(), c.basis.size() * sizeof(float), h);
      h = fnv(c.alpha.data(), c.alpha.size() * sizeof(float), h);
      h = fnv(c.cluster.data(), c.cluster.size() * sizeof(std::uint32_t), h);
      std::printf(" hash=%016llx", static_cast<unsigned long long>(h));
    }
    std::printf("\n");
    // RTF_CPCA_GROUP=S: the share of ‖X − X̂‖² and of ‖X‖² per group of S consecutive samples (S =
    // 6·FACE², one sphere): where the error sits.
    if (const char* g = std::getenv("RTF_CPCA_GROUP"); g && std::atoll(g) > 0) {
      const std::size_t S = std::size_t(std::atoll(g)), N = c.samples();
      std::vector<double> err((N + S - 1) / S, 0.0), norm(err.size(), 0.0);
      std::vector<float> xr(D);
      double errSum = 0.0, normSum = 0.0;
      for (std::size_t r = 0; r < N; ++r) {
        c.reconstruct(r, xr);
        for (std::size_t d = 0; d < D; ++d) {
          const double t = X[r * D + d];
          err[r / S] += (t - xr[d]) * (t - xr[d]), norm[r / S] += t * t;
        }
      }
      for (std::size_t k = 0; k < err.size(); ++k) errSum += err[k], normSum += norm[k];
      for (std::size_t k = 0; k < err.size(); ++k)
        std::printf("group=%zu err_share=%.4f norm_share=%.4f relative=%.4f\n", k, err[k] / errSum, norm[k] / normSum,
                    norm[k] > 0.0 ? std::sqrt(err[k] / norm[k]) : 0.0);
    }
    return 0;
  }
  std::fprintf(stderr, "usage: rtf_cpca_time dump LEVEL OBJECT PROXIES SPHERES FACE RAYS OUT [VERTEX_RAYS] | run FILE D CLUSTERS COMPONENTS THREADS [HASH]\n");
  return 2;
}
