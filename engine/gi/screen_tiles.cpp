#include "engine/gi/screen_tiles.hpp"

#include <algorithm>
#include <cmath>

namespace bounce::gi {

TileGrid tileGrid(glm::uvec2 resolution) {
  return {(resolution.x + kScreenTile - 1) / kScreenTile, (resolution.y + kScreenTile - 1) / kScreenTile};
}

PixelRect screenRect(const glm::mat4& viewProj, const glm::mat4& boxToWorld, glm::uvec2 resolution) {
  const PixelRect full{0, 0, resolution.x, resolution.y};
  glm::vec2 lo(1e30f), hi(-1e30f);
  bool beyondFar = true;
  for (int c = 0; c < 8; ++c) {
    const glm::vec4 corner(float(c & 1) * 2.0f - 1.0f, float((c >> 1) & 1) * 2.0f - 1.0f,
                           float((c >> 2) & 1) * 2.0f - 1.0f, 1.0f);
    const glm::vec4 clip = viewProj * (boxToWorld * corner);
    // At or behind the eye plane the projection wraps: keep every tile (the per-pixel test decides).
    if (!(clip.w > 1e-6f)) return full;
    const glm::vec3 ndc = glm::vec3(clip) / clip.w;
    beyondFar = beyondFar && ndc.z > 1.0f;
    lo = glm::min(lo, glm::vec2(ndc));
    hi = glm::max(hi, glm::vec2(ndc));
  }
  if (beyondFar) return {};
  // NDC −1..1 → pixels 0..W (a pixel's centre is at x + 0.5); widened to whole pixels.
  const glm::vec2 res(resolution);
  const glm::vec2 a = glm::clamp(glm::floor((lo * 0.5f + 0.5f) * res), glm::vec2(0.0f), res);
  const glm::vec2 b = glm::clamp(glm::ceil((hi * 0.5f + 0.5f) * res), glm::vec2(0.0f), res);
  PixelRect r{std::uint32_t(a.x), std::uint32_t(a.y), std::uint32_t(b.x), std::uint32_t(b.y)};
  return r.empty() ? PixelRect{} : r;
}

ScreenHull screenHull(const glm::mat4& viewProj, const glm::mat4& boxToWorld, glm::uvec2 resolution) {
  ScreenHull h;
  if (screenRect(viewProj, boxToWorld, resolution).empty()) return h;
  std::vector<glm::vec2> p;
  for (int c = 0; c < 8; ++c) {
    const glm::vec4 corner(float(c & 1) * 2.0f - 1.0f, float((c >> 1) & 1) * 2.0f - 1.0f,
                           float((c >> 2) & 1) * 2.0f - 1.0f, 1.0f);
    const glm::vec4 clip = viewProj * (boxToWorld * corner);
    if (!(clip.w > 1e-6f)) {
      h.all = true;
      return h;
    }
    p.push_back((glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(resolution));
  }
  // Andrew's monotone chain.
  std::sort(p.begin(), p.end(), [](glm::vec2 a, glm::vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  const auto cross = [](glm::vec2 o, glm::vec2 a, glm::vec2 b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
  };
  std::vector<glm::vec2> hull(16);
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p[i]) <= 0.0f) --k;
    hull[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(hull[k - 2], hull[k - 1], p[i]) <= 0.0f) --k;
    hull[k++] = p[i];
  }
  hull.resize(k > 1 ? k - 1 : k);
  h.points = std::move(hull);
  return h;
}

bool hullMeetsSquare(const ScreenHull& h, glm::vec2 lo, glm::vec2 hi) {
  if (h.all) return true;
  if (h.points.empty()) return false;
  glm::vec2 hmin(1e30f), hmax(-1e30f);
  for (const glm::vec2 q : h.points) hmin = glm::min(hmin, q), hmax = glm::max(hmax, q);
  if (hmax.x < lo.x || hmin.x > hi.x || hmax.y < lo.y || hmin.y > hi.y) return false;
  // Each hull edge's outward side: the square is separated when all its corners lie beyond it.
  const glm::vec2 corners[4] = {lo, {hi.x, lo.y}, hi, {lo.x, hi.y}};
  for (std::size_t i = 0; i < h.points.size(); ++i) {
    const glm::vec2 a = h.points[i], b = h.points[(i + 1) % h.points.size()];
    const glm::vec2 outward(b.y - a.y, a.x - b.x);  // counter-clockwise hull: right of a→b is out
    bool separated = true;
    for (const glm::vec2 c : corners) separated = separated && glm::dot(c - a, outward) > 0.0f;
    if (separated) return false;
  }
  return true;
}

std::vector<std::uint32_t> binObjects(const glm::mat4& viewProj, glm::uvec2 resolution,
                                      std::span<const glm::mat4> boxes) {
  const TileGrid grid = tileGrid(resolution);
  const std::size_t batches = (boxes.size() + kTileMaskBits - 1) / kTileMaskBits;
  std::vector<std::uint32_t> masks(batches * grid.count(), 0u);
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const PixelRect r = screenRect(viewProj, boxes[i], resolution);
    if (r.empty()) continue;
    const ScreenHull hull = screenHull(viewProj, boxes[i], resolution);
    std::uint32_t* batch = masks.data() + (i / kTileMaskBits) * grid.count();
    const std::uint32_t bit = 1u << (i % kTileMaskBits);
    for (std::uint32_t ty = r.y0 / kScreenTile; ty < (r.y1 + kScreenTile - 1) / kScreenTile; ++ty)
      for (std::uint32_t tx = r.x0 / kScreenTile; tx < (r.x1 + kScreenTile - 1) / kScreenTile; ++tx) {
        // The tile's pixels' centres span [16 tx + 0.5, 16 tx + 15.5]; widened by half a pixel
        // each way so a pixel the cube's raster would cover is never left out.
        const glm::vec2 lo(float(tx * kScreenTile), float(ty * kScreenTile));
        if (hullMeetsSquare(hull, lo, lo + float(kScreenTile))) batch[std::size_t(ty) * grid.tilesX + tx] |= bit;
      }
  }
  return masks;
}

}  // namespace bounce::gi
