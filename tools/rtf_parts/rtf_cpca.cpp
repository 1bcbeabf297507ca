// rtf_cpca: the CPCA error–ratio curve of one prop's RTF with the bases and coefficients stored as
// fp16 (issue 14, README Results "RTF", "Fourth pass": CPCA). A measurement. Since session 9 the
// field files hold the fp16 rounding (cpca.hpp quantize with no 8-bit components; `bounce bench rtf`'s ratio= is the
// stored ratio below), so the fp32 column comes from a compression of its own here.
//
// Bakes the level's dynamic object OBJECT (0-based, cornell-5's props as `bounce bench rtf` takes
// them) at the given settings, keeps the uncompressed ITF X, and for each component count n_e
// compresses it (cpca.hpp) and prints, with X̂ the reconstruction:
//   norm   = ‖X − X̂‖_F / ‖X‖_F      (`frobenius=`: the paper's "Frobenius norm of the difference", relative)
//   energy = norm²                   (relative squared error, what SHHS03 plots)
//   ratio  = N·D floats / (basis + α + cluster id) floats — what the GPU holds (fp32)
// then the same after rounding every basis entry and α to fp16 (cpca.hpp quantize with no 8-bit components) — the error
// measured AFTER quantization — with stored_ratio = 4·N·D bytes / (2·(basis + α) + 4·N) bytes.
//
// Per-cluster component counts chosen by error (the LAST count in the list is the most any cluster
// keeps, n_max): per cluster the α covariance Σ_r α αᵀ (n_max × n_max, Jacobi) gives the energy
// λ each principal direction of its subspace carries (its basis spans the subspace; rotating it onto
// these directions changes nothing else). Components taken greedily by λ over all clusters to a
// budget B = Σ_h n_h: error energy = ‖X − X̂_nmax‖² + Σ dropped λ (orthogonal parts), ratio =
// N·D / (Σ_h (n_h + 1)·D + Σ_r n_h(r) + N) floats (fp16: bytes as above). Exact for the clustering
// found at n_max; re-clustering at the chosen counts is not done.
//
// With REF_RAYS (> 0; issue 14, session 11, README "CPCA: the hit's transfer interpolated …") the
// prop is baked a second time with 6·REF_RAYS² projection rays per sample, X_ref, and it prints the
// projection's own error  noise = ‖X − X_ref‖_F / ‖X_ref‖_F  (the floor no compression of X gets
// under, measured against the finer bake), then per count the CPCA of X measured against X_ref
// (vs_ref = ‖X̂ − X_ref‖/‖X_ref‖, fp16) and the CPCA of X_ref itself (ref_norm = ‖X̂_ref − X_ref‖/‖X_ref‖).
//
// usage: rtf_cpca LEVEL OBJECT PROXIES SPHERES FACE RAYS CLUSTERS COMPONENTS[,COMPONENTS…] [REF_RAYS]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "engine/core/paths.hpp"
#include "engine/gi/dnrt/object_scene.hpp"
#include "engine/gi/rtf/bake.hpp"
#include "engine/gi/rtf/cpca.hpp"
#include "engine/scene/components.hpp"
#include "engine/scene/level.hpp"
#include "tools/rtf_parts/tool_object.hpp"

using namespace bounce;

namespace {

// Eigenvalues of a symmetric n×n matrix (row-major), cyclic Jacobi in double.
std::vector<double> eigenvalues(std::vector<double> a, int n) {
  for (int sweep = 0; sweep < 60; ++sweep) {
    double off = 0.0;
    for (int p = 0; p < n; ++p)
      for (int q = p + 1; q < n; ++q) off += a[std::size_t(p * n + q)] * a[std::size_t(p * n + q)];
    if (off < 1e-30) break;
    for (int p = 0; p < n; ++p)
      for (int q = p + 1; q < n; ++q) {
        const double apq = a[std::size_t(p * n + q)];
        if (std::abs(apq) < 1e-300) continue;
        const double theta = (a[std::size_t(q * n + q)] - a[std::size_t(p * n + p)]) / (2.0 * apq);
        const double t = (theta >= 0.0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
        const double c = 1.0 / std::sqrt(t * t + 1.0), sn = t * c;
        for (int k = 0; k < n; ++k) {  // A ← Jᵀ A J
          const double akp = a[std::size_t(k * n + p)], akq = a[std::size_t(k * n + q)];
          a[std::size_t(k * n + p)] = c * akp - sn * akq, a[std::size_t(k * n + q)] = sn * akp + c * akq;
        }
        for (int k = 0; k < n; ++k) {
          const double apk = a[std::size_t(p * n + k)], aqk = a[std::size_t(q * n + k)];
          a[std::size_t(p * n + k)] = c * apk - sn * aqk, a[std::size_t(q * n + k)] = sn * apk + c * aqk;
        }
      }
  }
  std::vector<double> out(static_cast<std::size_t>(n), 0.0);
  for (int i = 0; i < n; ++i) out[std::size_t(i)] = std::max(0.0, a[std::size_t(i * n + i)]);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 9) {
    std::fprintf(stderr, "usage: rtf_cpca LEVEL OBJECT PROXIES SPHERES FACE RAYS CLUSTERS COMPONENTS[,COMPONENTS...]\n");
    return 2;
  }
  gi::dnrt::LevelObjects objects;
  std::size_t index = 0;
  gi::rtf::FieldSettings s;
  if (!tools::loadToolObject("rtf_cpca", argv + 1, objects, index, s)) return 2;
  s.clusters = std::atoi(argv[7]);
  std::vector<int> counts;
  std::stringstream list(argv[8]);
  for (std::string item; std::getline(list, item, ',');) counts.push_back(std::atoi(item.c_str()));
  s.components = counts.front();
  const ref::SceneDesc object = gi::dnrt::objectScene(objects.registry, objects.entities[index], objects.assets);
  const auto t0 = std::chrono::steady_clock::now();
  const gi::rtf::BakeResult baked = gi::rtf::bake(object, s);
  std::fprintf(stderr, "rtf_cpca: baked in %.1f s\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  const std::size_t N = gi::rtf::sampleCount(s), D = gi::rtf::itfDimension(s);
  const int refRays = argc > 9 ? std::atoi(argv[9]) : 0;
  std::vector<float> reference;  // X_ref, the same samples with 6·REF_RAYS² projection rays
  double refNorm2 = 0.0;
  // ‖Y − X_ref‖_F / ‖X_ref‖_F, Y given sample by sample.
  const auto againstReference = [&](auto&& sampleOf) {
    double diff = 0.0;
    std::vector<float> row(D);
    for (std::size_t r = 0; r < N; ++r) {
      sampleOf(r, std::span<float>(row));
      for (std::size_t d = 0; d < D; ++d) {
        const double e = double(row[d]) - double(reference[r * D + d]);
        diff += e * e;
      }
    }
    return std::sqrt(diff / refNorm2);
  };
  if (refRays > 0) {
    gi::rtf::FieldSettings sr = s;
    sr.raysPerAxis = refRays;
    const auto t1 = std::chrono::steady_clock::now();
    reference = gi::rtf::bake(object, sr).itf;
    std::fprintf(stderr, "rtf_cpca: reference (6*%d^2 rays) baked in %.1f s\n", refRays,
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count());
    for (float x : reference) refNorm2 += double(x) * double(x);
    const double noise = againstReference([&](std::size_t r, std::span<float> out) {
      std::copy_n(baked.itf.begin() + std::ptrdiff_t(r * D), D, out.begin());
    });
    std::printf("rays=%d ref_rays=%d noise=%.4f (||X - X_ref|| / ||X_ref||)\n", s.raysPerAxis, refRays, noise);
    std::fflush(stdout);
  }
  for (int ne : counts) {
    gi::rtf::CpcaSettings cs;
    cs.clusters = s.clusters, cs.components = ne;
    const gi::rtf::Cpca full = gi::rtf::compress(baked.itf, D, cs);  // fp32 (baked.field.itf is rounded)
    const gi::rtf::CpcaError e = gi::rtf::measure(full, baked.itf);
    gi::rtf::Cpca c = full;
    gi::rtf::quantize(c, 0);
    const gi::rtf::CpcaError h = gi::rtf::measure(c, baked.itf);
    const double stored = h.stored;
    std::printf("clusters=%d components=%d fp32: ratio=%.1f norm=%.4f energy=%.5f | fp16: stored_ratio=%.1f norm=%.4f "
                "energy=%.5f\n", c.clusters, ne, e.ratio, e.frobenius, e.frobenius * e.frobenius, stored, h.frobenius,
                h.frobenius * h.frobenius);
    std::fflush(stdout);
    if (refRays > 0) {
      const double vsRef = againstReference([&](std::size_t r, std::span<float> out) { c.reconstruct(r, out); });
      gi::rtf::Cpca cr = gi::rtf::compress(reference, D, cs);
      gi::rtf::quantize(cr, 0);
      const double refOwn = gi::rtf::measure(cr, reference).frobenius;
      std::printf("clusters=%d components=%d fp16: vs_ref=%.4f (CPCA of X against X_ref) ref_norm=%.4f (CPCA of X_ref)\n",
                  c.clusters, ne, vsRef, refOwn);
      std::fflush(stdout);
    }
    if (ne != counts.back() || ne < 1) continue;
    // Per-cluster counts by error (header comment), from this (fp32) compression.
    double total = 0.0;
    for (float x : baked.itf) total += double(x) * double(x);
    const double residual = gi::rtf::measure(full, baked.itf).frobenius;
    const double base = residual * residual * total;  // ‖X − X̂_nmax‖²
    std::vector<std::vector<double>> cov(std::size_t(full.clusters), std::vector<double>(std::size_t(ne * ne), 0.0));
    std::vector<std::size_t> members(std::size_t(full.clusters), 0);
    for (std::size_t r = 0; r < N; ++r) {
      const float* a = full.alpha.data() + r * std::size_t(ne);
      auto& m = cov[full.cluster[r]];
      ++members[full.cluster[r]];
      for (int i = 0; i < ne; ++i)
        for (int j = 0; j < ne; ++j) m[std::size_t(i * ne + j)] += double(a[i]) * double(a[j]);
    }
    struct Part { double lambda; int cluster; };
    std::vector<Part> parts;
    for (int h = 0; h < full.clusters; ++h)
      for (double l : eigenvalues(cov[std::size_t(h)], ne)) parts.push_back({l, h});
    std::sort(parts.begin(), parts.end(), [](const Part& a, const Part& b) { return a.lambda > b.lambda; });
    double dropped = 0.0;
    for (const Part& p : parts) dropped += p.lambda;
    std::vector<int> keep(std::size_t(full.clusters), 0);
    double bestNormAt50 = -1.0;
    int bestBudgetAt50 = 0;
    for (std::size_t b = 0; b <= parts.size(); ++b) {
      if (b > 0) dropped -= parts[b - 1].lambda, ++keep[std::size_t(parts[b - 1].cluster)];
      double basisFloats = 0.0, alphaFloats = 0.0;
      for (int h = 0; h < full.clusters; ++h)
        basisFloats += double(keep[std::size_t(h)] + 1) * double(D), alphaFloats += double(keep[std::size_t(h)]) * double(members[std::size_t(h)]);
      const double ratio = double(N) * double(D) / (basisFloats + alphaFloats + double(N));
      const double stored = 4.0 * double(N) * double(D) / (2.0 * (basisFloats + alphaFloats) + 4.0 * double(N));
      const double energy = (base + std::max(0.0, dropped)) / total;
      if (ratio >= 50.0 && (bestNormAt50 < 0.0 || std::sqrt(energy) < bestNormAt50)) bestNormAt50 = std::sqrt(energy), bestBudgetAt50 = int(b);
      if (b % std::size_t(full.clusters) == 0 || b + 1 == parts.size())
        std::printf("by error: budget=%zu (mean %.1f per cluster, max %d) fp32 ratio=%.1f norm=%.4f energy=%.5f | fp16 stored_ratio=%.1f\n",
                    b, double(b) / full.clusters, *std::max_element(keep.begin(), keep.end()), ratio, std::sqrt(energy), energy,
                    stored);
    }
    std::printf("by error: at fp32 ratio >= 50 the least error is norm=%.4f energy=%.5f (budget %d)\n", bestNormAt50,
                bestNormAt50 * bestNormAt50, bestBudgetAt50);
  }
  return 0;
}
