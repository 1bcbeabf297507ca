#include "engine/gi/incident/session_light.hpp"

#include <algorithm>

#include "engine/gi/probes/bake.hpp"

namespace bounce::gi::incident {

RadianceSH ProbeSource::radianceSH(glm::vec3 p) const {
  const std::vector<glm::vec3> sh = volume_.radianceSH(p);
  RadianceSH out{};
  for (std::size_t i = 0; i < out.size() && i < sh.size(); ++i) out[i] = sh[i];
  return out;
}

RadianceSH ProbeSource::radianceShAndMap(glm::vec3 p, DirectionMap& map) const {
  std::vector<glm::vec3> sh, texels;
  volume_.radianceAt(p, glm::vec3(0.0f), sh, &texels);
  RadianceSH out{};
  for (std::size_t i = 0; i < out.size() && i < sh.size(); ++i) out[i] = sh[i];
  std::copy(texels.begin(), texels.end(), map.begin());
  return out;
}

SessionLight::SessionLight(const scene::Level& level, std::filesystem::path cookCache, const probes::ProbeVolume* probes)
    : level_(level), cookCache_(std::move(cookCache)) {
  if (probes)
    indirect_ = std::make_unique<ProbeSource>(*probes);
  else
    indirect_ = std::make_unique<ConstantEnvironment>(level.background);
}

const SceneVisibility& SessionLight::lightVisibility() {
  if (!visibility_) {
    ref::SceneDesc occluders = probes::staticScene(level_, cookCache_, nullptr, /*withTextures=*/false);
    for (ref::RefMaterial& m : occluders.materials) m.albedoTexture = m.emissiveTexture = -1;  // shadow rays only
    visibility_ = std::make_unique<SceneVisibility>(std::move(occluders));
  }
  return *visibility_;
}

const ref::SceneBvh& SessionLight::surfaces() {
  if (!surfaces_) surfaces_ = std::make_unique<ref::SceneBvh>(probes::staticScene(level_, cookCache_, nullptr, /*withTextures=*/true));
  return *surfaces_;
}

SessionLight& sessionLight(SessionContext& sc) {
  if (!sc.services.light)
    sc.services.light = std::make_shared<SessionLight>(sc.level, sc.cookCache, sc.services.probeVolume);
  return *sc.services.light;
}

}  // namespace bounce::gi::incident
