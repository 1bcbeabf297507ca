#include "engine/gi/dnrt/gpu_object.hpp"

#include "engine/gi/dnrt/irradiance_source.hpp"

namespace bounce::gi::dnrt {

DnrtObjectGpu packObject(const Field& field, const glm::mat4& world, const std::array<glm::vec3, 9>& radiance,
                         std::int64_t entityIndex) {
  const Placement pl = place(field, world);
  const auto c = toLocal(irradianceSH(radiance), pl);
  DnrtObjectGpu g;
  g.worldToLocal = pl.worldToLocal;
  // Unit cube → local outer cube about o → world.
  const float half = field.settings.outerExtent * field.radius;
  glm::mat4 box(half);
  box[3] = glm::vec4(field.centre, 1.0f);
  // A mirroring world matrix (det < 0) flips the cube's winding: the node's CULL_FRONT would keep the
  // faces nearest the camera, and GREATER_OR_EQUAL against the scene's depth would reject every
  // receiver. Mirroring the unit cube back (it is symmetric, so it covers the same points) keeps
  // boxToWorld's determinant positive and its back faces back faces.
  // The placement's flag, not a float determinant of `world`: that is s³, 0 or denormal for the tiny
  // scales place() accepts.
  if (pl.mirrored) box[0] = -box[0];
  g.boxToWorld = world * box;
  g.centreWorld = glm::vec4(pl.centreWorld, pl.radiusWorld);
  g.centreLocal = glm::vec4(field.centre, field.radius);
  g.extents = glm::vec4(field.settings.innerExtent, field.settings.outerExtent, float(field.settings.shCount),
                        float(field.settings.grid));
  for (int j = 0; j < 9; ++j) g.c[j] = glm::vec4(j < field.settings.shCount ? c[std::size_t(j)] : glm::vec3(0.0f), 0.0f);
  for (std::size_t t = 0; t < field.textures.size() && t < 7; ++t)
    for (int k = 0; k < 4; ++k) {
      g.lo[t][k] = field.ranges[t * 4 + std::size_t(k)].lo;
      g.hi[t][k] = field.ranges[t * 4 + std::size_t(k)].hi;
    }
  g.ids.x = entityIndex >= 0 ? std::uint32_t(entityIndex) + 1u : 0u;
  return g;
}

DnrtShaderObject fold(const DnrtObjectGpu& g) {
  DnrtShaderObject f;
  f.boxToWorld = g.boxToWorld;
  // q = (worldToLocal·r − o_local) / R_local as one affine map; its rows are what the shader dots.
  glm::mat4 toQ = g.worldToLocal;
  toQ[3] -= glm::vec4(glm::vec3(g.centreLocal), 0.0f);
  toQ = glm::mat4(1.0f / g.centreLocal.w) * toQ;
  toQ[3][3] = 1.0f;  // the scale above applies to xyz rows only
  for (int row = 0; row < 3; ++row) f.worldToQ[row] = glm::vec4(toQ[0][row], toQ[1][row], toQ[2][row], toQ[3][row]);
  f.centreWorld = g.centreWorld;
  f.extents = g.extents;
  f.ids = g.ids;
  // Slot t, component i holds SH j of channel ch (Table 2).
  for (int t = 0; t < 7; ++t)
    for (int i = 0; i < 4; ++i) {
      int j = 0, ch = 0;
      if (t < 6) {
        j = (t < 3 ? 0 : 4) + i, ch = t % 3;
      } else {
        if (i == 3) continue;  // slot 6's alpha is unused
        j = 8, ch = i;
      }
      const float c = g.c[j][ch];
      f.k[t][i] = (g.hi[t][i] - g.lo[t][i]) * c;
      f.a[ch] += g.lo[t][i] * c;
    }
  return f;
}

DnrtClusterObject clusterObject(const DnrtShaderObject& f, std::uint32_t z0) {
  DnrtClusterObject c;
  for (int row = 0; row < 3; ++row) c.worldToQ[row] = f.worldToQ[row];
  c.centreWorld = f.centreWorld;
  c.extents = f.extents;
  for (int t = 0; t < 7; ++t) c.k[t] = f.k[t];
  c.a = f.a;
  c.atlas = glm::vec4(1.5f, 1.5f, float(z0) + 1.5f, 0.0f);  // one padding texel, then texel centres
  c.ids = f.ids;
  return c;
}

}  // namespace bounce::gi::dnrt
