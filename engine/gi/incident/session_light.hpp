#pragma once
// The incident-light service's per-session inputs, one set shared by every technique that asks for
// the light arriving at a point (issue 15: "put it where all techniques find it"): DNRT's c_j, RTF's
// proxies, SL's pass 1 (through its SH at the SLs' centres).
//   indirect():        the probes' baked volume when the probes run, else the level's background;
//   lightVisibility(): rays to each light through the level's STATIC geometry (SceneVisibility:
//                      the dynamic objects are left out, so an object never shadows its own
//                      centre), one Embree BVH per session, built the first time a technique asks;
//   surfaces():        the same static scene with its textures, for the light a static surface
//                      reflects (ref::surfaceAlbedo at a hit: RTF's room shadows); its own BVH, built
//                      only when asked, so the shadow rays' scene holds no decoded textures.
// A technique reaches it through sessionLight(sc), which creates Services::light on first use, so
// a level whose techniques never ask builds nothing.
#include <filesystem>
#include <memory>

#include "engine/gi/incident/incident.hpp"
#include "engine/gi/probes/probe_volume.hpp"
#include "engine/gi/technique.hpp"

namespace bounce::gi::incident {

// The probe volume as an IndirectSource (DNRT paper §5.2.1: "sampling and interpolating the
// coefficients of the light probes closest to O"): its radiance SH at p looked up as a point in the
// air (no normal: every direction counts), padded with zeros when the volume is order 2 and
// truncated to 9 coefficients when it is order 4.
class ProbeSource final : public IndirectSource {
 public:
  explicit ProbeSource(const probes::ProbeVolume& volume) : volume_(volume) {}
  RadianceSH radianceSH(glm::vec3 p) const override;
  // The probes' SH and direction maps blended with one set of lookup weights (ProbeVolume::radianceAt).
  RadianceSH radianceShAndMap(glm::vec3 p, DirectionMap& map) const override;

 private:
  const probes::ProbeVolume& volume_;
};

class SessionLight {
 public:
  // `probes` (not owned, may be null) must outlive this; `level` too.
  SessionLight(const scene::Level& level, std::filesystem::path cookCache, const probes::ProbeVolume* probes);
  const IndirectSource& indirect() const { return *indirect_; }
  const SceneVisibility& lightVisibility();
  const ref::SceneBvh& surfaces();

 private:
  const scene::Level& level_;
  std::filesystem::path cookCache_;
  std::unique_ptr<IndirectSource> indirect_;
  std::unique_ptr<SceneVisibility> visibility_;
  std::unique_ptr<ref::SceneBvh> surfaces_;
};

// The session's SessionLight (sc.services.light), created on first use from the probe volume the
// probes technique left in sc.services (it comes first in the table).
SessionLight& sessionLight(SessionContext& sc);

}  // namespace bounce::gi::incident
