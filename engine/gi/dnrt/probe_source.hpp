#pragma once
// The light probes as DNRT's c_j source (paper §5.2.1: "sampling and interpolating the coefficients
// of the light probes closest to O"). The volume's radiance SH at the object's centre, looked up as
// a point in the air (no normal: every direction counts), padded with zeros when the volume is
// order 2 and truncated to 9 coefficients when it is order 4.
#include "engine/gi/dnrt/irradiance_source.hpp"
#include "engine/gi/probes/probe_volume.hpp"

namespace bounce::gi::dnrt {

class ProbeSource final : public IrradianceSource {
 public:
  explicit ProbeSource(const probes::ProbeVolume& volume) : volume_(volume) {}
  std::array<glm::vec3, 9> radianceSH(glm::vec3 p) const override {
    const std::vector<glm::vec3> sh = volume_.radianceSH(p);
    std::array<glm::vec3, 9> out{};
    for (std::size_t i = 0; i < out.size() && i < sh.size(); ++i) out[i] = sh[i];
    return out;
  }

 private:
  const probes::ProbeVolume& volume_;
};

}  // namespace bounce::gi::dnrt
