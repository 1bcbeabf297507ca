#include "engine/gi/sl/sphere_fit.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace bounce::gi::sl::fit {
namespace {

double eq2(const glm::dvec3& p, const Sphere& s) {  // Eq. 2
  return s.radius > 0.0 ? glm::length(p - s.centre) / s.radius : std::numeric_limits<double>::infinity();
}

bool holds(const Sphere& s, const glm::dvec3& p) { return glm::length(p - s.centre) <= s.radius; }

// Ritter's growth step: the smallest sphere holding `s` and `p` (centre moves towards p).
void grow(Sphere& s, const glm::dvec3& p) {
  if (const double d = glm::length(p - s.centre); d > s.radius) {
    const double nr = 0.5 * (s.radius + d);
    s.centre += (d - nr) / d * (p - s.centre);
    s.radius = nr * (1.0 + 1e-7);
  }
}

}  // namespace

std::size_t nearestSphere(const glm::dvec3& p, const std::vector<Sphere>& spheres) {
  std::size_t best = 0;
  double bd = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < spheres.size(); ++i)
    if (const double d = eq2(p, spheres[i]); d < bd) bd = d, best = i;
  return best;
}

Sphere enclosing(const std::vector<glm::dvec3>& pts) {
  if (pts.empty()) return {};
  glm::dvec3 x = pts[0];
  auto farthest = [&](const glm::dvec3& from) {
    std::size_t best = 0;
    double bd = -1.0;
    for (std::size_t i = 0; i < pts.size(); ++i)
      if (const double d = glm::length(pts[i] - from); d > bd) bd = d, best = i;
    return pts[best];
  };
  const glm::dvec3 y = farthest(x), z = farthest(y);
  glm::dvec3 c = 0.5 * (y + z);
  double r = 0.5 * glm::length(z - y);
  for (const auto& p : pts)
    if (const double d = glm::length(p - c); d > r) {
      const double nr = 0.5 * (r + d);
      c += (d - nr) / d * (p - c);
      r = nr;
    }
  // Bădoiu–Clarkson refinement: step the centre towards the farthest point with a shrinking step,
  // keep the best enclosing radius.
  glm::dvec3 cc = c;
  for (int it = 1; it <= 200; ++it) {
    const glm::dvec3 f = farthest(cc);
    cc += (f - cc) / double(it + 1);
    double rr = 0.0;
    for (const auto& p : pts) rr = std::max(rr, glm::length(p - cc));
    if (rr < r) r = rr, c = cc;
  }
  return {c, r * (1.0 + 1e-6) + 1e-12};
}

std::vector<Sphere> cluster(const std::vector<glm::dvec3>& pts, int k, int iterations) {
  // Farthest-point seeds from the first point: deterministic and spread over the surface.
  std::vector<glm::dvec3> seeds = {pts[0]};
  std::vector<double> dist(pts.size(), std::numeric_limits<double>::infinity());
  while (int(seeds.size()) < k) {
    std::size_t best = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      dist[i] = std::min(dist[i], glm::length(pts[i] - seeds.back()));
      if (dist[i] > dist[best]) best = i;
    }
    seeds.push_back(pts[best]);
  }
  std::vector<Sphere> spheres(seeds.size());
  for (std::size_t i = 0; i < seeds.size(); ++i) spheres[i] = {seeds[i], 1.0};  // equal radii: Euclidean first pass
  std::vector<Sphere> best;
  double bestVolume = std::numeric_limits<double>::infinity();
  for (int it = 0; it <= iterations; ++it) {
    std::vector<std::vector<glm::dvec3>> clusters(spheres.size());
    for (const auto& p : pts) clusters[nearestSphere(p, spheres)].push_back(p);
    // An empty cluster takes the point worst served by its sphere (largest Eq. 2 distance).
    for (auto& cl : clusters)
      if (cl.empty()) {
        std::size_t worst = 0;
        double wd = -1.0;
        for (std::size_t i = 0; i < pts.size(); ++i)
          if (const double d = eq2(pts[i], spheres[nearestSphere(pts[i], spheres)]); d > wd) wd = d, worst = i;
        cl.push_back(pts[worst]);
      }
    double volume = 0.0;
    for (std::size_t i = 0; i < spheres.size(); ++i) {
      spheres[i] = enclosing(clusters[i]);
      volume += spheres[i].radius * spheres[i].radius * spheres[i].radius;
    }
    // Every point lies in its cluster's sphere, so every iterate bounds all `pts`.
    if (volume < bestVolume) bestVolume = volume, best = spheres;
  }
  return best;
}

void coverTriangles(std::vector<Sphere>& spheres, const std::vector<glm::dvec3>& a, const std::vector<glm::dvec3>& b,
                    const std::vector<glm::dvec3>& c, double minEdge) {
  std::vector<std::array<glm::dvec3, 3>> stack;
  for (std::size_t t = 0; t < a.size(); ++t) {
    stack.push_back({a[t], b[t], c[t]});
    while (!stack.empty()) {
      const auto tri = stack.back();
      stack.pop_back();
      bool inside = false;
      for (const Sphere& s : spheres)
        if (holds(s, tri[0]) && holds(s, tri[1]) && holds(s, tri[2])) {
          inside = true;
          break;
        }
      if (inside) continue;
      const double edge = std::max({glm::length(tri[1] - tri[0]), glm::length(tri[2] - tri[1]), glm::length(tri[0] - tri[2])});
      if (edge > minEdge) {
        const glm::dvec3 ab = 0.5 * (tri[0] + tri[1]), bc = 0.5 * (tri[1] + tri[2]), ca = 0.5 * (tri[2] + tri[0]);
        stack.push_back({tri[0], ab, ca});
        stack.push_back({ab, tri[1], bc});
        stack.push_back({ca, bc, tri[2]});
        stack.push_back({ab, bc, ca});
        continue;
      }
      // A small piece no sphere holds whole: grow its nearest sphere (Eq. 2) over its corners;
      // Ritter's grown sphere contains the old one, so what was covered stays covered.
      Sphere& s = spheres[nearestSphere((tri[0] + tri[1] + tri[2]) / 3.0, spheres)];
      for (const glm::dvec3& p : tri) grow(s, p);
    }
  }
}

}  // namespace bounce::gi::sl::fit
