#pragma once
// The incident-light service (issue 15 part 1): the SH of the light ARRIVING at a point — the probes'
// indirect light plus the level's real lights (point, spot, directional) projected analytically into
// SH at that point, times their visibility. One service for every technique that needs "the light
// at o" (DESIGN.md: the light arriving at a point is ONE shared service): DNRT's c_j (§5.3: in the
// paper, Unity light probes, which carry baked lights' direct light too), SL's pass 1, RTF's proxies.
//
// Order-3 RADIANCE SH (9 RGB coefficients, W/(m²·sr) per channel, world axes), the convention of
// engine/math/sh_eval.hpp: L(ω) = Σ L_i Y_i(ω), ω pointing towards the source. Cosine-convolve
// (irradianceSH) for irradiance E(n) = Σ c_j Y_j(n).
//
// Two faces, one code: the light projection is shaders/common/incident.glsl (GPU face, one
// function per light kind taking a visibility factor), compiled into incident.cpp as C++ (CPU face,
// addLight below); tests/unit/incident checks the two against each other on a device.
//
//   incident::Service light;                     // per session
//   light.setIndirect(&probes);                  // optional: the probes (or ConstantEnvironment)
//   light.setVisibility(&sceneVisibility);       // optional: default every light unoccluded
//   RadianceSH L = light.radianceSH(o, R, world.lights);   // per frame, per receiver
#include <array>
#include <span>

#include <glm/glm.hpp>

#include "engine/math/oct_map.hpp"
#include "engine/ref/scene_bvh.hpp"
#include "engine/render/gpu_types.hpp"

namespace bounce::gi::incident {

// Order-3 radiance SH, RGB: coefficient i = l(l+1)+m (sh_eval.hpp).
using RadianceSH = std::array<glm::vec3, 9>;

// ---- CPU face of incident.glsl (the same code, compiled as C++) -----------------------------------

// Adds `light`'s radiance SH at the receiver — a sphere of `radius` metres around `p` (0: the point
// p) — times `visibility` ∈ [0, 1], to `sh`. Point/spot: a uniform spherical cap of the directions
// from which the sphere sees the light, carrying the flux the sphere intercepts (incident.glsl's
// header derives it; a delta when radius = 0). Directional: a delta. incidentAddLight in GLSL.
void addLight(const render::LightGpu& light, glm::vec3 p, float radius, float visibility, RadianceSH& sh);
// Irradiance at p from one level light on a surface facing it, before the cosine and visibility
// (W/m² per channel): lights.glsl's incidentIrradiance itself, compiled as C++ (incident.cpp; the
// path tracer compiles the same file). Writes the unit direction towards the light and the distance
// (1e30 for directional). The techniques' CPU face (VLM's phase-1 mirror uses it too).
glm::vec3 lightIrradiance(const render::LightGpu& light, glm::vec3 p, glm::vec3& toLight, float& dist);

// The path tracer's description of the same light (engine/ref): type, position, direction,
// radiance, range window and spot cone copied member by member.
ref::RefLight refLight(const render::LightGpu& light);
// A uniform cap of half-angle α (cosAlpha = cos α) about unit direction toLight carrying
// irradiance-weight e = ∫_cap L dω (W/m² per channel): s_l-scaled delta (incidentAddCap).
void addCap(glm::vec3 toLight, float cosAlpha, glm::vec3 e, RadianceSH& sh);
// cos α of the cap from which a sphere of `radius` sees a point at `dist` (incidentCapCosine).
float capCosine(float radius, float dist);

// ---- visibility -----------------------------------------------------------------------------------

// How much of a receiver sees a light: a fraction in [0, 1].
struct Visibility {
  virtual ~Visibility() = default;
  // The receiver is the sphere of `radius` around p (0: the point p).
  virtual float visible(const render::LightGpu& light, glm::vec3 p, float radius) const = 0;
};

// Every light fully visible (tests; levels without geometry).
struct Unoccluded final : Visibility {
  float visible(const render::LightGpu&, glm::vec3, float) const override { return 1.0f; }
};

// Ray tests against a scene (Embree, engine/ref): the fraction of kVisibilityRays shadow rays that
// reach the light from points of the receiver — p itself and, for radius > 0, points on a disc of
// 0.7·radius through p facing the light (the part of the receiver a lamp sees). A DEPARTURE from
// "shadow-map visibility": DNRT asks about its object's centre, which the object itself occludes in
// the light's shadow map, so the CPU face traces the level's geometry WITHOUT the object instead
// (DNRT passes the static scene: the dynamic objects — this one and the others — are left out).
// GPU users (SL pass 1's surface samples) pass their shadow-map visibility to incident.glsl.
inline constexpr int kVisibilityRays = 9;
class SceneVisibility final : public Visibility {
 public:
  explicit SceneVisibility(ref::SceneDesc scene);
  float visible(const render::LightGpu& light, glm::vec3 p, float radius) const override;
  const ref::SceneBvh& bvh() const { return bvh_; }

 private:
  ref::SceneBvh bvh_;
};

// ---- indirect light -------------------------------------------------------------------------------

// Radiance SH of the indirect (baked) light at a point: the probe volume (ProbeSource, session_light.hpp) or
// a constant environment. Was gi::dnrt::IrradianceSource (still an alias there).
// A math::kOctMapRes² octahedral map of radiance (math/oct_map.hpp texels, W/(m²·sr) per channel).
using DirectionMap = std::array<glm::vec3, math::kOctMapTexels>;

struct IndirectSource {
  virtual ~IndirectSource() = default;
  virtual RadianceSH radianceSH(glm::vec3 p) const = 0;
  // The radiance SH at p and, from the same lookup, a direction map of the radiance there (SL's
  // pass 1 with "blocked_read": "map", README "SL's blocked light read from the probes' direction
  // maps, session 19"). This default: the SH evaluated at each texel's centre direction (a source
  // without a directional store); ProbeSource blends the probes' baked maps.
  virtual RadianceSH radianceShAndMap(glm::vec3 p, DirectionMap& map) const;
};

// Uniform radiance L (W/(m²·sr) per channel) from every direction at every point: L_00 = 2√π L.
class ConstantEnvironment final : public IndirectSource {
 public:
  explicit ConstantEnvironment(glm::vec3 radiance) : radiance_(radiance) {}
  RadianceSH radianceSH(glm::vec3 p) const override;

 private:
  glm::vec3 radiance_;
};

// c_j = Â_l L_lm (sh_convolve.hpp): the irradiance SH E(n) = Σ c_j Y_j(n) of radiance SH L.
RadianceSH irradianceSH(const RadianceSH& radiance);

// ---- the service ----------------------------------------------------------------------------------

// Per-band factors (l = 0, 1, 2) applied to the lights' SH (not to the indirect light's) before the
// service hands them out. A lamp's lobe truncated at l = 2 rings (negative lobes opposite the lamp);
// App. B.2's improved anti-radiance divides band l by Â_l, ×4 on band 2, and amplifies that ringing
// (issue 15: its 9-SH indirect-only error 0.959 against Eq. 12's 0.938 on cornell-1). A Hanning
// window, h_l = (1 + cos(π l / 3)) / 2 (Sloan, "Stupid Spherical Harmonics Tricks", §windowing),
// trades the ringing for a wider lobe. Measured (`bounce accuracy content/levels/cornell-1.json
// --rows direct,probes,dnrt --frames 3`, 4 / 9 SH, 32³, indirect-only, paper / improved): none
// 0.942 / 0.942, 0.938 / 0.959; Lanczos σ (sinc(l/3): 1, 0.827, 0.413) 0.944 / 0.941,
// 0.940 / 0.940; Hanning 0.945 / 0.942, 0.942 / 0.938. The window helps the improved
// anti-radiance and costs Eq. 12 a little, so callers choose: DNRT windows with Hanning for
// improved fields only (update.cpp).
using BandWindow = std::array<float, 3>;
inline constexpr BandWindow kNoWindow = {1.0f, 1.0f, 1.0f};
inline constexpr BandWindow kHanningWindow = {1.0f, 0.75f, 0.25f};
void applyWindow(const BandWindow& window, RadianceSH& sh);

class Service {
 public:
  // Not owned; must outlive the service. Null: no indirect light / every light unoccluded.
  void setIndirect(const IndirectSource* indirect) { indirect_ = indirect; }
  void setVisibility(const Visibility* visibility) { visibility_ = visibility; }
  const IndirectSource* indirect() const { return indirect_; }

  // The level's lights alone at the receiver (sphere of `radius` around p), with visibility,
  // windowed per band by `window`.
  RadianceSH lightsSH(glm::vec3 p, float radius, std::span<const render::LightGpu> lights,
                      const BandWindow& window = kNoWindow) const;
  // Indirect + lights (the lights' part windowed): the light arriving at the receiver.
  // `lightsPart` (optional): receives the lights' part alone (lightsSH, same window), the same
  // numbers the sum was made of, without tracing the lights' visibility twice.
  RadianceSH radianceSH(glm::vec3 p, float radius, std::span<const render::LightGpu> lights,
                        const BandWindow& window = kNoWindow, RadianceSH* lightsPart = nullptr) const;

 private:
  const IndirectSource* indirect_ = nullptr;
  const Visibility* visibility_ = nullptr;
};

}  // namespace bounce::gi::incident
