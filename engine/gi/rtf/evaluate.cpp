#include "engine/gi/rtf/evaluate.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "engine/core/error.hpp"
#include "engine/core/parallel.hpp"
#include "engine/math/sh.hpp"

namespace bounce::gi::rtf {

namespace {

ShScalar unitVisibility() {
  ShScalar v{};
  v[0] = kUnitVisibility;
  return v;
}

// Cube-map face and continuous texel coordinates of a direction: the inverse of
// sh::cubeTexelDirection (its comment has the Vulkan face table).
void faceCoordinates(glm::vec3 d, int size, int& face, float& fx, float& fy) {
  const glm::vec3 a = glm::abs(d);
  float u = 0.0f, v = 0.0f;
  if (!(a.x > 0.0f || a.y > 0.0f || a.z > 0.0f)) d = glm::vec3(1.0f, 0.0f, 0.0f);  // q = o: any face
  if (a.x >= a.y && a.x >= a.z && a.x > 0.0f) {
    face = d.x > 0.0f ? 0 : 1;
    u = d.x > 0.0f ? -d.z / a.x : d.z / a.x;
    v = -d.y / a.x;
  } else if (a.y >= a.z) {
    face = d.y > 0.0f ? 2 : 3;
    u = d.x / a.y;
    v = d.y > 0.0f ? d.z / a.y : -d.z / a.y;
  } else {
    face = d.z > 0.0f ? 4 : 5;
    u = d.z > 0.0f ? d.x / a.z : -d.x / a.z;
    v = -d.y / a.z;
  }
  if (!(a.x > 0.0f || a.y > 0.0f || a.z > 0.0f)) face = 0, u = 0.0f, v = 0.0f;
  fx = glm::clamp((u + 1.0f) * 0.5f * float(size) - 0.5f, 0.0f, float(size - 1));
  fy = glm::clamp((v + 1.0f) * 0.5f * float(size) - 0.5f, 0.0f, float(size - 1));
}

}  // namespace

ShRgb toWorld(const ShRgb& c, const Placement& p) {
  ShRgb out{};
  gi::shToWorld<glm::vec3>(p, std::span<const glm::vec3>(c), std::span<glm::vec3>(out));
  return out;
}

ShScalar toWorld(const ShScalar& c, const Placement& p) {
  ShScalar out{};
  gi::shToWorld<float>(p, std::span<const float>(c), std::span<float>(out));
  return out;
}

ShRgb toLocal(const ShRgb& c, const Placement& p) {
  ShRgb out{};
  gi::shToLocal<glm::vec3>(p, std::span<const glm::vec3>(c), std::span<glm::vec3>(out));
  return out;
}

float radialWeight(float ra, float rb, float r) {
  const float r2 = std::max(r * r, ra * ra), a2 = ra * ra, b2 = rb * rb;
  return glm::clamp((r2 - a2) * b2 / (r2 * (b2 - a2)), 0.0f, 1.0f);
}

float tailFade(const FieldSettings& s, float r, float reach) {
  const float rN = sphereRadius(s, s.spheres - 1), dr = (s.outerRadius - s.innerRadius) / float(s.spheres - 1);
  if (r <= rN) return 1.0f;
  const float end = reach > rN + dr ? reach : rN + dr;
  return (rN / r) * (rN / r) * glm::clamp((end - r) / (kFadeRamp * dr), 0.0f, 1.0f);
}

float tailReach(const Field& f, float tail) {
  const FieldSettings& s = f.settings;
  if (!(tail > 0.0f)) return 0.0f;
  const int per = samplesPerSphere(s);
  const std::size_t first = std::size_t(s.spheres - 1) * std::size_t(per);
  double omega = 0.0;
  for (int i = 0; i < per; ++i) omega += 4.0 * math::kPi - double(f.oof[(first + std::size_t(i)) * kShCount]) / sh::constants::kY00;
  omega = std::max(0.0, omega / double(per));
  const float rN = sphereRadius(s, s.spheres - 1), dr = (s.outerRadius - s.innerRadius) / float(s.spheres - 1);
  const float reach = rN * float(std::sqrt(omega / (double(tail) * math::kPi)));
  return reach > rN + dr ? reach : 0.0f;
}

Lookup lookup(const FieldSettings& s, glm::vec3 q, float reach) {
  Lookup l;
  const float r = glm::length(q);
  const float r0 = sphereRadius(s, 0), rN = sphereRadius(s, s.spheres - 1);
  const float dr = (s.outerRadius - s.innerRadius) / float(s.spheres - 1);
  int s0 = 0, s1 = 0;
  float w1 = 0.0f, fade = 1.0f;  // w1: weight of sphere s1 (s0 gets 1 − w1); fade: × both
  if (r <= r0) {
    s0 = s1 = 0;
  } else if (r >= rN) {
    s0 = s1 = s.spheres - 1;
    fade = tailFade(s, r, reach);
  } else {
    const float t = (r - s.innerRadius) / dr;
    s0 = std::min(int(std::floor(t)), s.spheres - 2);
    s1 = s0 + 1;
    w1 = radialWeight(sphereRadius(s, s0), sphereRadius(s, s1), r);
  }
  int face = 0;
  float fx = 0.0f, fy = 0.0f;
  faceCoordinates(r > 0.0f ? q / r : glm::vec3(0.0f), s.faceSize, face, fx, fy);
  const int x0 = std::min(int(fx), s.faceSize - 1), y0 = std::min(int(fy), s.faceSize - 1);
  const int x1 = std::min(x0 + 1, s.faceSize - 1), y1 = std::min(y0 + 1, s.faceSize - 1);
  const float ax = fx - float(x0), ay = fy - float(y0);
  const int n2 = s.faceSize * s.faceSize, per = samplesPerSphere(s);
  const int xs[2] = {x0, x1}, ys[2] = {y0, y1};
  const float wx[2] = {1.0f - ax, ax}, wy[2] = {1.0f - ay, ay};
  const int ss[2] = {s0, s1};
  const float ws[2] = {(1.0f - w1) * fade, w1 * fade};
  int c = 0;
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      for (int e = 0; e < 2; ++e, ++c) {
        l.sample[std::size_t(c)] = std::uint32_t(ss[a] * per + face * n2 + ys[b] * s.faceSize + xs[e]);
        l.weight[std::size_t(c)] = ws[a] * wy[b] * wx[e];
      }
  return l;
}

std::vector<glm::vec3> eigenCache(const Field& f, std::span<const glm::vec3> L) {
  const int m = f.settings.proxies, ne = f.itf.components, nc = f.itf.clusters;
  if (L.size() != std::size_t(m) * kShCount) throw InternalError("rtf::eigenCache: proxy light is not m·16 coefficients");
  const std::size_t D = itfDimension(f.settings);
  std::vector<glm::vec3> u(std::size_t(nc) * std::size_t(ne + 1) * kShCount, glm::vec3(0.0f));
  for (std::size_t he = 0; he < std::size_t(nc) * std::size_t(ne + 1); ++he) {
    const float* E = f.itf.basis.data() + he * D;
    for (int k = 0; k < m; ++k)
      for (int i = 0; i < kShCount; ++i) {
        glm::vec3 sum(0.0f);
        for (int j = 0; j < kShCount; ++j) {
          const float* e = E + itfIndex(k, i, j, 0);
          const glm::vec3& l = L[std::size_t(k) * kShCount + std::size_t(j)];
          sum += glm::vec3(e[0], e[1], e[2]) * l;
        }
        u[he * kShCount + std::size_t(i)] += sum;
      }
  }
  return u;
}

std::vector<glm::vec3> xiCache(const Field& f, std::span<const glm::vec3> L) {
  const std::vector<glm::vec3> u = eigenCache(f, L);
  const std::size_t N = sampleCount(f.settings);
  const int ne = f.itf.components;
  std::vector<glm::vec3> xi(N * kShCount, glm::vec3(0.0f));
  for (std::size_t r = 0; r < N; ++r) {
    const glm::vec3* uh = u.data() + std::size_t(f.itf.cluster[r]) * std::size_t(ne + 1) * kShCount;
    for (int i = 0; i < kShCount; ++i) {
      glm::vec3 x = uh[i];
      for (int e = 1; e <= ne; ++e) x += f.itf.alpha[r * std::size_t(ne) + std::size_t(e - 1)] * uh[std::size_t(e) * kShCount + std::size_t(i)];
      xi[r * kShCount + std::size_t(i)] = x;
    }
  }
  return xi;
}

ShRgb interreflection(const Field& f, std::span<const glm::vec3> xi, glm::vec3 q, float reach) {
  const Lookup l = lookup(f.settings, q, reach);
  ShRgb out{};
  for (int c = 0; c < 8; ++c) {
    if (l.weight[std::size_t(c)] == 0.0f) continue;
    const glm::vec3* x = xi.data() + std::size_t(l.sample[std::size_t(c)]) * kShCount;
    for (int i = 0; i < kShCount; ++i) out[std::size_t(i)] += l.weight[std::size_t(c)] * x[i];
  }
  return out;
}

ShScalar occlusion(const Field& f, glm::vec3 q, float reach) {
  const Lookup l = lookup(f.settings, q, reach);
  ShScalar out{};
  float total = 0.0f;
  for (int c = 0; c < 8; ++c) {
    const float w = l.weight[std::size_t(c)];
    total += w;
    for (int i = 0; i < kShCount; ++i) out[std::size_t(i)] += w * f.oof[std::size_t(l.sample[std::size_t(c)]) * kShCount + std::size_t(i)];
  }
  out[0] += (1.0f - total) * kUnitVisibility;  // beyond the field: fade to unoccluded
  return out;
}

ShRgb sourceRadiance(const dnrt::IrradianceSource& source, glm::vec3 p) {
  const auto nine = source.radianceSH(p);
  ShRgb out{};
  std::copy(nine.begin(), nine.end(), out.begin());
  return out;
}

Incident incidentRadiance(std::span<const Object> objects, std::span<const std::vector<glm::vec3>* const> xi,
                          const dnrt::IrradianceSource* source, glm::vec3 q, int skip) {
  std::vector<Placement> placed;
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    placed.push_back(place(*objects[i].field, objects[i].world));
    if (int(i) != skip) order.push_back(i);
  }
  // Algorithm 1: near to far, so each object's light is occluded by the objects nearer to q.
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return glm::length(q - placed[a].centreWorld) < glm::length(q - placed[b].centreWorld);
  });
  Incident in;
  ShScalar V = unitVisibility();
  std::vector<float> Vv(V.begin(), V.end());
  for (std::size_t i : order) {
    const Field& f = *objects[i].field;
    const Placement& p = placed[i];
    const glm::vec3 qLocal = (glm::vec3(p.worldToLocal * glm::vec4(q, 1.0f)) - f.centre) / f.radius;
    if (i < xi.size() && xi[i] != nullptr) {
      const ShRgb I = toWorld(interreflection(f, *xi[i], qLocal, objects[i].reach), p);
      std::vector<glm::vec3> Vrgb(Vv.begin(), Vv.end());
      const auto lit = sh::product<glm::vec3>(std::span<const glm::vec3>(Vrgb), std::span<const glm::vec3>(I), kShOrder);
      for (int k = 0; k < kShCount; ++k) in.radiance[std::size_t(k)] += lit[std::size_t(k)];
    }
    const ShScalar O = toWorld(occlusion(f, qLocal, objects[i].reach), p);
    Vv = sh::product<float>(std::span<const float>(Vv), std::span<const float>(O), kShOrder);
  }
  if (source != nullptr) {
    const ShRgb L = sourceRadiance(*source, q);
    std::vector<glm::vec3> Vrgb(Vv.begin(), Vv.end());
    const auto lit = sh::product<glm::vec3>(std::span<const glm::vec3>(Vrgb), std::span<const glm::vec3>(L), kShOrder);
    for (int k = 0; k < kShCount; ++k) in.radiance[std::size_t(k)] += lit[std::size_t(k)];
  }
  std::copy(Vv.begin(), Vv.end(), in.visibility.begin());
  return in;
}

BounceResult bounce(std::span<const Object> objects, const dnrt::IrradianceSource& source, int bounces) {
  const std::vector<const dnrt::IrradianceSource*> sources(objects.size(), &source);
  return bounce(objects, sources, bounces);
}

BounceResult bounce(std::span<const Object> objects, std::span<const dnrt::IrradianceSource* const> sources, int bounces) {
  if (bounces < 1 || bounces > 4) throw InternalError("rtf::bounce: bounces must be in 1..4");
  const std::size_t n = objects.size();
  if (sources.size() != n || std::count(sources.begin(), sources.end(), nullptr) > 0)
    throw InternalError("rtf::bounce: one source per object");
  std::vector<Placement> placed;
  for (const Object& o : objects) placed.push_back(place(*o.field, o.world));
  BounceResult result;
  result.proxyLight.resize(n);
  std::vector<std::vector<glm::vec3>> current(n), xi(n);
  for (int b = 0; b < bounces; ++b) {
    std::vector<const std::vector<glm::vec3>*> xiPtr(n, nullptr);
    if (b > 0)
      for (std::size_t i = 0; i < n; ++i) xi[i] = xiCache(*objects[i].field, current[i]), xiPtr[i] = &xi[i];
    std::vector<std::vector<glm::vec3>> next(n);
    std::vector<std::pair<std::size_t, std::size_t>> proxies;  // (J, k): every object's proxies
    for (std::size_t J = 0; J < n; ++J) {
      next[J].assign(objects[J].field->proxies.size() * kShCount, glm::vec3(0.0f));
      for (std::size_t k = 0; k < objects[J].field->proxies.size(); ++k) proxies.emplace_back(J, k);
    }
    // Each proxy on its own over TBB's pool (cornell-5's step is ≈ 16 ms of one thread's CPU a frame, the
    // room shadows ≈ 3 of it; README "RTF's textured albedo and the bouncing step's cost, session 19"):
    // every proxy writes only its own slots and the energy is summed in proxy order afterwards, so the
    // result is the serial loop's bit for bit on any thread count.
    std::vector<double> proxyEnergy(proxies.size(), 0.0);
    parallelFor(0, proxies.size(), [&](std::size_t i) {
      const auto [J, k] = proxies[i];
      const glm::vec3 chi = glm::vec3(objects[J].world * glm::vec4(objects[J].field->proxies[k], 1.0f));
      const Incident in = incidentRadiance(objects, xiPtr, b == 0 ? sources[J] : nullptr, chi, int(J));
      const ShRgb local = toLocal(in.radiance, placed[J]);
      std::copy(local.begin(), local.end(), next[J].begin() + std::ptrdiff_t(k * kShCount));
      proxyEnergy[i] = double(local[0].r + local[0].g + local[0].b) / 3.0;
    });
    double energy = 0.0;
    for (const double e : proxyEnergy) energy += e;
    result.bounceEnergy.push_back(energy);
    for (std::size_t J = 0; J < n; ++J) {
      if (result.proxyLight[J].empty()) result.proxyLight[J].assign(next[J].size(), glm::vec3(0.0f));
      for (std::size_t e = 0; e < next[J].size(); ++e) result.proxyLight[J][e] += next[J][e];
    }
    current = std::move(next);
  }
  for (std::size_t i = 0; i < n; ++i) result.xi.push_back(xiCache(*objects[i].field, result.proxyLight[i]));
  return result;
}

Shading shade(std::span<const Object> objects, const BounceResult& bounced, const dnrt::IrradianceSource& source,
              glm::vec3 r, glm::vec3 n, glm::vec3 rho, int skip, int shCount) {
  std::vector<const std::vector<glm::vec3>*> xiPtr;
  for (const auto& x : bounced.xi) xiPtr.push_back(&x);
  const Incident in = incidentRadiance(objects, xiPtr, nullptr, r, skip);
  const ShRgb L = sourceRadiance(source, r);
  ShRgb blocked{};
  {
    std::vector<glm::vec3> notV(kShCount);
    for (int k = 0; k < kShCount; ++k) notV[std::size_t(k)] = glm::vec3((k == 0 ? kUnitVisibility : 0.0f) - in.visibility[std::size_t(k)]);
    const auto b = sh::product<glm::vec3>(std::span<const glm::vec3>(notV), std::span<const glm::vec3>(L), kShOrder);
    std::copy(b.begin(), b.end(), blocked.begin());
  }
  const auto irradiance = [&](const ShRgb& radiance) {
    const auto e = sh::convolveCosine<glm::vec3>(std::span<const glm::vec3>(radiance));
    return sh::evalSum<glm::vec3, float>(std::span<const glm::vec3>(e).first(std::size_t(shCount == 4 ? 4 : kShCount)),
                                         glm::normalize(n));
  };
  Shading s;
  const glm::vec3 k = rho / float(math::kPi);
  s.interreflected = k * irradiance(in.radiance);
  s.blocked = k * irradiance(blocked);
  return s;
}

}  // namespace bounce::gi::rtf
