#include "game/accuracy.hpp"

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <set>

#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "engine/core/hash.hpp"
#include "engine/core/paths.hpp"
#include "engine/core/progress.hpp"
#include "engine/gpu/presenter_offscreen.hpp"
#include "engine/ref/effect_noise.hpp"
#include "engine/ref/image_heatmap.hpp"
#include "engine/ref/metrics.hpp"
#include "engine/ref/reference.hpp"
#include "game/accuracy_level.hpp"
#include "game/session.hpp"
#include "game/timing_stats.hpp"
#include "game/render_limits.hpp"

namespace bounce::game {
namespace {

// Heat-map panels are exposed so that the reference's mean lands on middle grey (0.18,
// Reinhard et al. 2002, "Photographic tone reproduction"): the Cornell levels' radiances are
// ~0.05, which plain exposure 1 draws nearly black.
constexpr double kPanelMiddleGrey = 0.18;

std::string joinList(const std::vector<std::string>& items) {
  std::string s;
  for (const auto& e : items) s += (s.empty() ? "" : ",") + e;
  return s;
}

// "spacing=0.25m;ref=all" → "spacing-0.25m-ref-all": a file-name-safe form of a setting.
std::string slug(const std::string& s) {
  std::string out;
  for (char c : s) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '_';
    out += keep ? c : '-';
  }
  return out;
}

// A path quoted for /bin/sh: inside single quotes only the quote itself needs escaping.
std::string shellQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// A CSV field: quoted (RFC 4180) only when it holds a comma, quote or line break.
std::string csvField(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

// Rows with the same technique, effects and setting apart from "ref=…" render the same image.
std::string renderKey(const AccuracyRow& row) {
  std::string setting;
  std::size_t start = 0;
  while (start <= row.setting.size()) {
    std::size_t end = row.setting.find(';', start);
    if (end == std::string::npos) end = row.setting.size();
    const std::string item = row.setting.substr(start, end - start);
    if (item.rfind("ref=", 0) != 0) setting += item + ";";
    start = end + 1;
  }
  return row.technique + "|" + joinList(row.effects) + "|" + setting;
}

// The rasteriser's image of one configuration. With `timings` it also times the row's passes,
// and returns no image when the renderer lacks one of them (rowAvailable).
struct TechniqueRender {
  ImageRGB image;
  std::vector<std::string> executedPasses;
};

TechniqueRender renderTechnique(gpu::Context& ctx, gpu::OffscreenPresenter& presenter, scene::Level level,
                                double time, const AccuracyRow& row, std::uint32_t measuredFrames,
                                TimingCollector* timings) {
  Session session(ctx, std::move(level));
  session.update(time);
  render::FrameSettings settings;
  settings.keepHdr = true;
  session.render(presenter, settings);
  TechniqueRender out;
  out.executedPasses = session.renderer().executedPasses();
  if (timings && !rowAvailable(row, out.executedPasses)) {
    // Session does not wait for its frames when destroyed, and its GPU scene goes first.
    session.renderer().frames().waitIdle();
    return out;  // the caller skips the row
  }
  if (timings) {
    // The pose is fixed at `time`: every measured frame renders the same image.
    for (std::uint32_t f = 1; f < kAccuracyWarmupFrames + measuredFrames; ++f) {
      session.render(presenter, settings);
      timings->collect(session.renderer().frames(), kAccuracyWarmupFrames);
    }
  }
  const VkExtent2D extent = presenter.extent();
  gpu::FloatImage hdr{extent.width, extent.height, session.renderer().readHdr()};
  if (timings) timings->collect(session.renderer().frames(), kAccuracyWarmupFrames);
  out.image = toImageRgb(hdr);
  return out;
}

// The noise floors of one reference kind (engine/ref/effect_noise.hpp) from its full and
// first-half references, with and without the dynamic objects, onto every row of that kind.
void setEffectNoise(AccuracyReport& report, const std::string& kind, std::uint32_t spp, const ImageRGB& fullWith,
                    const ImageRGB& fullWithout, const ImageRGB& halfWith, const ImageRGB& halfWithout,
                    const ref::PixelMask* indirectMask) {
  const ref::EffectNoise whole = ref::effectNoise(fullWith, fullWithout, halfWith, halfWithout);
  const ref::EffectNoise indirect = ref::effectNoise(fullWith, fullWithout, halfWith, halfWithout, indirectMask);
  report.effectFloors.push_back({kind, spp, whole.floor, indirect.floor});
  for (auto& r : report.rows) {
    if (referenceKind(r.row.setting) != kind) continue;
    r.effectNoiseFloor = whole.floor;
    r.effectRelRmseCorrected = ref::noiseCorrectedError(r.effectRelRmse, whole.floor);
    r.indirectNoiseFloor = indirect.floor;
    r.indirectEffectRelRmseCorrected = ref::noiseCorrectedError(r.indirectEffectRelRmse, indirect.floor);
  }
}

}  // namespace

ref::PixelMask indirectOnlyMask(const ImageRGB& with, const ImageRGB& without) {
  if (with.width != without.width || with.height != without.height)
    throw InternalError("accuracy: direct-only references of different sizes");
  // The two traces differ only by the extra geometry; elsewhere they agree up to float rounding
  // of the hit points in a different BVH (1e-4 relative is far above that, far below a shadow).
  constexpr float kSame = 1e-4f;
  ref::PixelMask differs(with.width, with.height);
  for (int y = 0; y < with.height; ++y)
    for (int x = 0; x < with.width; ++x) {
      const glm::vec3 a = with.pixels[std::size_t(y) * with.width + x], b = without.pixels[std::size_t(y) * with.width + x];
      const glm::vec3 d = glm::abs(a - b);
      if (std::max({d.x, d.y, d.z}) > kSame * (1.0f + std::max({a.x, a.y, a.z, b.x, b.y, b.z}))) differs.set(x, y);
    }
  ref::PixelMask out(with.width, with.height, true);
  for (int y = 0; y < with.height; ++y)
    for (int x = 0; x < with.width; ++x)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx >= 0 && yy >= 0 && xx < with.width && yy < with.height && differs.test(xx, yy)) out.set(x, y, false);
        }
  return out;
}

ImageRGB toImageRgb(const gpu::FloatImage& image) {
  if (image.rgb.size() != std::size_t(image.width) * image.height * 3)
    throw InternalError("accuracy: float image of " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                        " holds " + std::to_string(image.rgb.size()) + " values");
  ImageRGB out(int(image.width), int(image.height));
  for (std::size_t i = 0; i < out.pixels.size(); ++i)
    out.pixels[i] = glm::vec3(image.rgb[3 * i], image.rgb[3 * i + 1], image.rgb[3 * i + 2]);
  return out;
}

std::string formatAccuracyCsv(const std::vector<AccuracyResult>& results) {
  std::string out = std::string(kAccuracyCsvHeader) + "\n";
  char numbers[128];
  for (const auto& r : results) {
    // %.6g keeps small errors readable; NaN prints as "nan", which the plot script skips.
    std::snprintf(numbers, sizeof numbers, "%.6g,%.6g,%.6g,", r.gpuMs, r.relRmse, r.effectRelRmse);
    // The optional columns: empty where NaN.
    auto field = [](double v) {
      if (!std::isfinite(v)) return std::string();
      char text[32];
      std::snprintf(text, sizeof text, "%.6g", v);
      return std::string(text);
    };
    out += csvField(r.row.technique) + "," + csvField(r.row.setting) + "," + numbers + field(r.indirectEffectRelRmse) +
           "," + field(r.effectNoiseFloor) + "," + field(r.effectRelRmseCorrected) + "," + field(r.indirectNoiseFloor) +
           "," + field(r.indirectEffectRelRmseCorrected) + "\n";
  }
  return out;
}

std::string formatAccuracyTable(const std::vector<AccuracyResult>& results) {
  std::string out;
  char line[256];
  // "corrected": the indirect-only error against the converged effect (the reference's noise
  // taken out, AccuracyResult::indirectEffectRelRmseCorrected).
  std::snprintf(line, sizeof line, "%-10s %-56s %9s %9s %16s %14s %10s %6s\n", "technique", "setting", "gpu ms", "rel rmse",
                "effect rel rmse", "indirect-only", "corrected", "pareto");
  out += line;
  for (const auto& r : results) {
    std::snprintf(line, sizeof line, "%-10s %-56s %9.4f %9.4f %16.4f %14.4f %10.4f %6s\n", r.row.technique.c_str(),
                  r.row.setting.c_str(), r.gpuMs, r.relRmse, r.effectRelRmse, r.indirectEffectRelRmse,
                  r.indirectEffectRelRmseCorrected, r.pareto ? "*" : "");
    out += line;
  }
  // The front per reference, cheapest first: the rows worth their cost.
  std::map<std::string, std::vector<const AccuracyResult*>> fronts;
  for (const auto& r : results)
    if (r.pareto) fronts[referenceKind(r.row.setting)].push_back(&r);
  for (auto& [kind, rows] : fronts) {
    std::stable_sort(rows.begin(), rows.end(), [](auto* a, auto* b) { return a->gpuMs < b->gpuMs; });
    out += "Pareto front vs ref=" + kind + " (cheapest first):";
    for (const auto* r : rows) {
      std::snprintf(line, sizeof line, " %s %s (%.2f ms, %.4f);", r->row.technique.c_str(), r->row.setting.c_str(), r->gpuMs,
                    r->relRmse);
      out += line;
    }
    out.back() = '\n';
  }
  return out;
}

std::string referenceKind(const std::string& setting) {
  std::size_t start = 0;
  while (start <= setting.size()) {
    std::size_t end = setting.find(';', start);
    if (end == std::string::npos) end = setting.size();
    if (setting.compare(start, 4, "ref=") == 0) return setting.substr(start + 4, end - start - 4);
    start = end + 1;
  }
  return "all";
}

void markParetoFront(std::vector<AccuracyResult>& results) {
  std::map<std::string, std::vector<AccuracyResult*>> byKind;
  for (auto& r : results) {
    r.pareto = false;
    if (std::isfinite(r.gpuMs) && std::isfinite(r.relRmse)) byKind[referenceKind(r.row.setting)].push_back(&r);
  }
  for (auto& [kind, rows] : byKind) {
    std::stable_sort(rows.begin(), rows.end(), [](const AccuracyResult* a, const AccuracyResult* b) {
      return a->gpuMs != b->gpuMs ? a->gpuMs < b->gpuMs : a->relRmse < b->relRmse;
    });
    double best = std::numeric_limits<double>::infinity();
    for (AccuracyResult* r : rows)
      if (r->relRmse < best) r->pareto = true, best = r->relRmse;
  }
}

bool plotAccuracy(const std::filesystem::path& csv, const std::filesystem::path& png, std::string& why,
                  const std::filesystem::path& heatmaps) {
  const std::filesystem::path script = toolsDir() / "plot_accuracy.py";
  std::string cmd =
      "/usr/bin/python3 " + shellQuote(script.string()) + " " + shellQuote(csv.string()) + " " + shellQuote(png.string());
  if (!heatmaps.empty()) cmd += " " + shellQuote(heatmaps.string());
  const int status = std::system(cmd.c_str());
  if (status == -1 || !WIFEXITED(status)) {
    why = "could not run /usr/bin/python3";
    return false;
  }
  // The script's exit codes: 0 drawn, 3 matplotlib missing; /bin/sh gives 127 for no python3.
  switch (WEXITSTATUS(status)) {
    case 0: return true;
    case 3: why = "/usr/bin/python3 has no matplotlib (Debian: python3-matplotlib)"; return false;
    case 127: why = "/usr/bin/python3 not found"; return false;
    default: why = script.string() + " failed with exit code " + std::to_string(WEXITSTATUS(status)); return false;
  }
}

std::filesystem::path staticLevelFile(const scene::Level& level) {
  // The static level is the tracer's input, not a result: it lives in the cache, not in `out`.
  const std::filesystem::path path =
      cacheDir("levels") / (level.source.stem().string() + "-" + Hasher().str(level.source.string()).hex().substr(0, 8) +
                            "-static.json");
  std::filesystem::create_directories(path.parent_path());
  writeFileAtomic(path, withoutDynamicEntitiesJson(level));  // the same bytes whoever writes it
  return path;
}

ref::ReferenceRequest referenceRequest(const AccuracyOptions& options, const std::filesystem::path& input,
                                       std::optional<std::uint32_t> bounces, std::uint32_t spp) {
  ref::ReferenceRequest r;
  r.input = input;
  r.frame = options.frame;
  r.spp = spp;
  r.bounces = bounces;
  r.resolution = std::pair{options.width, options.height};
  r.cacheDir = options.referenceCache;
  r.cookCache = options.cookCache;
  r.progress = options.progress;
  return r;
}

std::vector<AccuracyReference> accuracyReferences(const AccuracyOptions& options) {
  const scene::Level level = scene::loadLevel(options.level);
  const std::vector<AccuracyRow> rows = options.rows ? *options.rows : accuracyRows();
  const std::filesystem::path staticPath = staticLevelFile(level);
  std::set<std::uint32_t> kinds;  // bounces, in the order of the set (0, 1, ..., unlimited)
  for (const auto& row : rows) kinds.insert(row.referenceBounces.value_or(ref::kUnlimitedBounces));
  std::vector<AccuracyReference> out;
  for (const std::uint32_t b : kinds) {
    const std::optional<std::uint32_t> bounces = b == ref::kUnlimitedBounces ? std::nullopt : std::optional(b);
    const std::string kind = b == 0 ? "direct" : b == ref::kUnlimitedBounces ? "all" : std::to_string(b) + "bounce";
    const std::uint32_t spp = b == 0 ? 1u : options.spp;  // bounces 0 is exact with one sample (header comment)
    out.push_back({kind, referenceRequest(options, options.level, bounces, spp)});
    out.push_back({kind + "-static", referenceRequest(options, staticPath, bounces, spp)});
    if (b != 0 && options.spp >= 2) {  // the noise estimates' half-sample references (step 4)
      out.push_back({kind + "-half", referenceRequest(options, options.level, bounces, options.spp / 2)});
      out.push_back({kind + "-static-half", referenceRequest(options, staticPath, bounces, options.spp / 2)});
    }
  }
  return out;
}

AccuracyReport runAccuracy(const AccuracyOptions& options) {
  // 1. Inputs, validated before any work: the level, its rows, the level without dynamic objects.
  const scene::Level level = scene::loadLevel(options.level);
  const std::vector<AccuracyRow> rows = options.rows ? *options.rows : accuracyRows();
  for (const auto& row : rows) {
    scene::Level check = level;
    scene::overrideEffects(check, joinList(row.effects));  // unknown effect names are InputError
  }
  const scene::Level staticLevel = withoutDynamicEntities(level);
  std::filesystem::create_directories(options.out);
  const std::filesystem::path staticPath = staticLevelFile(level);
  const double time = double(options.frame) * ref::kLevelFrameDt;

  // 2. References, with and without the dynamic objects, for every reference kind a row uses.
  std::map<std::pair<bool, std::uint32_t>, ImageRGB> references;
  auto reference = [&](bool withDynamic, std::optional<std::uint32_t> bounces) -> const ImageRGB& {
    const std::uint32_t b = bounces.value_or(ref::kUnlimitedBounces);
    auto& slot = references[{withDynamic, b}];
    if (slot.empty())
      slot = toImageRgb(ref::renderReference(referenceRequest(options, withDynamic ? options.level : staticPath, bounces,
                                                              b == 0 ? 1u : options.spp))
                            .image);
    return slot;
  };

  // 3. Each row: render with and without, time, compare, draw its heat map.
  AccuracyReport report;
  gpu::Context ctx({options.device});
  checkRenderSize(ctx, {std::uint32_t(options.width), std::uint32_t(options.height)}, "bounce accuracy", "--resolution");
  gpu::OffscreenPresenter presenter(ctx, {options.width, options.height});
  Progress progress("accuracy " + options.level.filename().string(), rows.size());
  // Rows that differ only in the reference they are compared with share one render and one
  // timing (the same configuration timed twice would show two numbers for one cost).
  struct Rendered {
    ImageRGB with, without;
    double gpuMs = 0.0;
    std::vector<std::string> executedPasses;
    bool available = false;
    std::string badInput;  // the row's configuration is bad input (one line): skipped, the run goes on
  };
  std::map<std::string, Rendered> rendered;
  std::optional<ref::PixelMask> indirectMask;  // from the direct-only references, on first use
  std::set<std::string> effectImagesDone;      // --effect-images: reference kinds and the mask written
  for (const auto& row : rows) {
    const std::string key = renderKey(row);
    if (!rendered.count(key)) {
      scene::Level with = level, without = staticLevel;
      for (scene::Level* l : {&with, &without}) {
        scene::overrideEffects(*l, joinList(row.effects));
        if (row.configure) row.configure(*l);
      }
      TimingCollector timings;
      Rendered& r = rendered[key];
      TechniqueRender techWith;
      // A row's settings can make a level that its technique refuses (e.g. SL's spheres + parents
      // beyond pass 2's blocks): the session throws before any frame, so the row is skipped with the
      // line, not the whole run stopped.
      try {
        techWith = renderTechnique(ctx, presenter, with, time, row, options.measuredFrames, &timings);
      } catch (const InputError& err) {
        r.badInput = err.what();
      }
      if (r.badInput.empty()) {
        r.executedPasses = techWith.executedPasses;
        r.available = rowAvailable(row, techWith.executedPasses);
      }
      if (r.available) {
        r.with = std::move(techWith.image);
        r.without = renderTechnique(ctx, presenter, without, time, row, options.measuredFrames, nullptr).image;
        r.gpuMs = rowGpuMs(row, timings.stats());
      }
    }
    const Rendered& tech = rendered.at(key);
    if (!tech.badInput.empty()) {
      report.notes.push_back("skipped " + row.technique + " " + row.setting + ": bad input: " + tech.badInput);
      progress.advance();
      continue;
    }
    if (!tech.available) {
      report.notes.push_back("skipped " + row.technique + " " + row.setting + ": the renderer ran " +
                             joinList(tech.executedPasses) + " but the row needs " + joinList(row.passes));
      progress.advance();
      continue;
    }
    const ImageRGB& techWith = tech.with;
    const ImageRGB& techWithout = tech.without;

    AccuracyResult result;
    result.row = row;
    result.gpuMs = tech.gpuMs;
    const ImageRGB& refWith = reference(true, row.referenceBounces);
    const ImageRGB& refWithout = reference(false, row.referenceBounces);
    result.relRmse = ref::relativeRmse(techWith, refWith);
    const ref::ObjectEffectError effect = ref::objectEffectError(techWith, techWithout, refWith, refWithout);
    result.referenceEffectIsZero = effect.referenceEffectIsZero;
    result.effectRelRmse = effect.referenceEffectIsZero ? std::numeric_limits<double>::quiet_NaN() : effect.relativeError;
    if (effect.referenceEffectIsZero)
      report.notes.push_back(row.technique + " " + row.setting +
                             ": the reference shows no effect of dynamic objects; effect_rel_rmse is nan");

    if (!indirectMask) indirectMask = indirectOnlyMask(reference(true, 0), reference(false, 0));
    const ref::ObjectEffectError indirect =
        ref::objectEffectError(techWith, techWithout, refWith, refWithout, &*indirectMask);
    result.indirectEffectRelRmse =
        indirect.referenceEffectIsZero ? std::numeric_limits<double>::quiet_NaN() : indirect.relativeError;

    ref::ComparisonOptions panel;
    const double mean = meanValue(refWith);
    if (mean > 0.0) panel.exposure = float(kPanelMiddleGrey / mean);
    const std::string name = slug(row.technique) + "-" + slug(row.setting);
    result.heatMap = options.out / ("heatmap-" + name + ".png");
    writePfm(options.out / ("image-" + name + ".pfm"), techWith);
    if (options.effectImages) {
      writePfm(options.out / ("without-" + name + ".pfm"), techWithout);
      const std::string kind = referenceKind(row.setting);
      if (effectImagesDone.insert(kind).second) {
        writePfm(options.out / ("reference-" + kind + "-with.pfm"), refWith);
        writePfm(options.out / ("reference-" + kind + "-without.pfm"), refWithout);
      }
      if (effectImagesDone.insert("mask").second) {
        ImageRGB mask(techWith.width, techWith.height);
        for (std::size_t i = 0; i < mask.pixels.size(); ++i) mask.pixels[i] = glm::vec3(indirectMask->testIndex(i) ? 1.0f : 0.0f);
        writePfm(options.out / "mask-indirect-only.pfm", mask);
      }
    }
    const ref::Comparison comparison = ref::comparisonImage(refWith, techWith, panel);
    result.heatMapScale = comparison.scale;
    writePng(result.heatMap, comparison.image);
    report.rows.push_back(std::move(result));
    progress.advance();
  }
  progress.finish();

  markParetoFront(report.rows);

  // 4. What limits the numbers: too few timed frames, a noisy reference.
  if (options.measuredFrames < kMinTrustedFrames)
    report.warnings.push_back("--frames " + std::to_string(options.measuredFrames) + ": GPU ms are medians of fewer than " +
                              std::to_string(kMinTrustedFrames) + " frames and vary by up to 2x between runs; use --frames " +
                              std::to_string(kMinTrustedFrames) + " or more");
  std::set<std::uint32_t> noiseDone;
  for (const auto& r : report.rows) {
    const std::uint32_t b = r.row.referenceBounces.value_or(ref::kUnlimitedBounces);
    if (b == 0 || options.spp < 2 || !noiseDone.insert(b).second) continue;  // bounces 0 is exact with 1 spp
    // The first half of the samples is the spp/2 reference (sample s is drawn from index s, so it
    // is a prefix); the second half is 2·full − first.
    const ref::ReferenceRequest half = referenceRequest(options, options.level, r.row.referenceBounces, options.spp / 2);
    const ImageRGB first = toImageRgb(ref::renderReference(half).image);
    const ImageRGB& full = reference(true, r.row.referenceBounces);
    const ImageRGB firstWithout =
        toImageRgb(ref::renderReference(referenceRequest(options, staticPath, r.row.referenceBounces, options.spp / 2)).image);
    const std::string kind = referenceKind(r.row.setting);
    setEffectNoise(report, kind, options.spp, full, reference(false, r.row.referenceBounces), first, firstWithout,
                   &*indirectMask);
    if (options.effectImages) {
      writePfm(options.out / ("reference-" + kind + "-half-with.pfm"), first);
      writePfm(options.out / ("reference-" + kind + "-half-without.pfm"), firstWithout);
    }
    ImageRGB second = full;
    for (std::size_t i = 0; i < second.pixels.size(); ++i) second.pixels[i] = 2.0f * full.pixels[i] - first.pixels[i];
    const double noise = ref::relativeRmse(first, second) / 2.0;
    report.referenceNoise.emplace_back(kind, noise);
    double best = std::numeric_limits<double>::infinity();
    for (const auto& o : report.rows)
      if (referenceKind(o.row.setting) == kind) best = std::min(best, o.relRmse);
    if (noise > kMaxReferenceNoiseShare * best) {
      char text[320];
      std::snprintf(text, sizeof text,
                    "reference ref=%s: its own noise (rel. RMSE ~%.4f, from two half-sample references) is more than a "
                    "third of the best row's error (%.4f): differences between rows below ~%.4f are noise; raise --spp "
                    "(noise falls as 1/sqrt(spp))",
                    kind.c_str(), noise, best, noise);
      report.warnings.push_back(text);
    }
  }

  // The exact bounces-0 reference has no noise: floor 0, the errors are their own corrected form.
  for (auto& r : report.rows)
    if (r.row.referenceBounces == 0u) {
      r.effectNoiseFloor = r.indirectNoiseFloor = 0.0;
      r.effectRelRmseCorrected = ref::noiseCorrectedError(r.effectRelRmse, 0.0);
      r.indirectEffectRelRmseCorrected = ref::noiseCorrectedError(r.indirectEffectRelRmse, 0.0);
    }

  // 5. The CSV and the chart.
  report.csv = options.out / "accuracy.csv";
  writeFileAtomic(report.csv, formatAccuracyCsv(report.rows));
  std::string heatmaps = "file,technique,setting,scale\n";
  for (const auto& r : report.rows) {
    char scale[32];
    std::snprintf(scale, sizeof scale, "%.6g", r.heatMapScale);
    heatmaps += csvField(r.heatMap.string()) + "," + csvField(r.row.technique) + "," + csvField(r.row.setting) + "," + scale + "\n";
  }
  const std::filesystem::path heatmapsCsv = options.out / "heatmaps.csv";
  writeFileAtomic(heatmapsCsv, heatmaps);
  if (options.chart) {
    std::string why;
    const std::filesystem::path png = options.out / "accuracy.png";
    if (plotAccuracy(report.csv, png, why, heatmapsCsv))
      report.chart = png;
    else
      report.notes.push_back("no chart: " + why);
  }
  return report;
}

}  // namespace bounce::game
