// relight_full: why pass `probes.relight` relights a DELTA on the baked SH and not the whole light
// (README "Probes relit each frame"). For a level's static scene it projects, per probe, the surfels'
// full one-step light — ρ/π·(direct light with static visibility + the baked probes' irradiance at
// the surfel) — through the relight bake's rays (the pass's own gather, relight.cpp) and compares
// the probes' irradiance E(n) at the 6 axis normals with the baked, path-traced probes'. A
// diagnostic run by hand, not installed:  build/release/relight_full content/levels/cornell-1.json
#include <cmath>
#include <cstdio>

#include "engine/core/paths.hpp"
#include "engine/gi/probes/bake.hpp"
#include "engine/gi/probes/relight.hpp"
#include "engine/math/sh.hpp"
#include "game/session.hpp"

using namespace bounce;
using namespace bounce::gi::probes;

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: relight_full LEVEL\n");
    return 2;
  }
  const scene::Level level = scene::loadLevel(argv[1]);
  const ProbeSettings settings = settingsFrom(level);
  const BakeInput input = prepare(level, game::cookCacheDir(), settings);
  const LoadResult baked = loadOrBake(level, game::cookCacheDir(), cacheDir("probes"), settings);
  const ProbeVolume& v = baked.volume;
  const RelightData data = loadOrBakeRelight(input, v.grid, cacheDir("probes"));
  std::vector<render::LightGpu> lights;
  for (const ref::RefLight& l : input.scene.lights) {
    render::LightGpu g{};
    const float type = l.type == ref::RefLightType::Directional ? 0.0f : l.type == ref::RefLightType::Point ? 1.0f : 2.0f;
    g.positionType = glm::vec4(l.position, type);
    g.directionRange = glm::vec4(l.direction, l.range);
    g.radiance = glm::vec4(l.radiance, l.radius);
    g.cone = glm::vec4(l.cosOuter, l.cosInner, 0.0f, 0.0f);
    lights.push_back(g);
  }
  const ref::SceneBvh bvh{ref::SceneDesc(input.scene)};
  const std::vector<float> vStatic = staticVisibility(bvh, data.surfels, lights);
  const std::vector<float> dark(vStatic.size(), 0.0f);
  std::vector<glm::vec3> radiance(data.surfels.size());
  for (std::size_t s = 0; s < data.surfels.size(); ++s) {
    const Surfel& sf = data.surfels[s];
    // −(the loss when V_now = 0) = the surfel's direct irradiance with static visibility.
    const glm::vec3 direct = -surfelDirectLoss(sf, s, lights, dark, vStatic);
    radiance[s] = sf.albedo / float(math::kPi) * (direct + v.irradiance(sf.position, sf.normal));
  }
  const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  double num = 0.0, den = 0.0, worst = 0.0;
  std::size_t n = 0;
  for (std::size_t p = 0; p < v.grid.probeCount(); ++p) {
    if (!v.valid[p]) continue;
    glm::vec3 full[9];
    gatherProbe(data, p, radiance, full);
    std::vector<glm::vec3> a(v.sh.begin() + std::ptrdiff_t(p * v.coeffs()), v.sh.begin() + std::ptrdiff_t((p + 1) * v.coeffs()));
    std::vector<glm::vec3> b(full, full + v.coeffs());
    for (const glm::vec3& ax : axes) {
      const glm::vec3 ea = sh::evalIrradiance<glm::vec3, float>(a, ax), eb = sh::evalIrradiance<glm::vec3, float>(b, ax);
      const glm::vec3 d = eb - ea;
      num += double(glm::dot(d, d));
      den += double(glm::dot(ea, ea));
      worst = std::max(worst, double(glm::length(d) / std::max(glm::length(ea), 1e-9f)));
      ++n;
    }
  }
  std::printf("%s: %zu surfels, %zu probe-normals: full one-step relight vs baked E: rel. RMS %.4f, worst %.3f\n", argv[1],
              data.surfels.size(), n, std::sqrt(num / den), worst);
  return 0;
}
