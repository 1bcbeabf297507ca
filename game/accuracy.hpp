#pragma once
// `bounce accuracy LEVEL`: every available technique configuration (accuracy_rows.hpp) rendered
// by the rasteriser and compared with the path-traced reference (engine/ref) of the same frame.
//
// Per row (one line of accuracy.csv, header exactly `technique,setting,gpu_ms,rel_rmse,effect_rel_rmse`):
//   gpu_ms          the sum of the medians over `measuredFrames` frames (after kWarmupFrames) of
//                   the GPU time of the row's lighting passes (AccuracyRow::passes and the
//                   optionalPasses that ran), outermost scopes only (rowGpuMs), in milliseconds;
//   rel_rmse        ref::relativeRmse(technique, reference) over the whole image;
//   effect_rel_rmse ref::objectEffectError(techWith, techWithout, refWith, refWithout).relativeError,
//                   "without" = the level minus its dynamic entities (accuracy_level.hpp); "nan"
//                   when the reference effect is zero (no dynamic objects, or none visible).
// Rows whose settings differ only in "ref=…" share one render and one timing. The reference is the row's: bounces 0 ("ref=direct") or unlimited ("ref=all"). References are
// cached by renderReference; the bounces-0 one is traced with 1 spp, which is exact (camera rays
// go through pixel centres and next-event estimation to punctual lights draws no random numbers).
//
// Files in `out`: accuracy.csv, accuracy.png (tools/plot_accuracy.py, when /usr/bin/python3 has
// matplotlib), heatmap-<technique>-<setting>.png per row ("reference | technique | error",
// engine/ref/image_heatmap.hpp) with the technique's linear image image-<technique>-<setting>.pfm
// (with --effect-images also the images the object-effect errors compare: AccuracyOptions::effectImages),
// heatmaps.csv (which the chart script reads to title the heat maps). The level without dynamic
// entities, which the reference tracer reads, goes to <cache>/levels, not `out`.
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "engine/core/image.hpp"
#include "engine/gpu/image_io.hpp"
#include "engine/ref/metrics.hpp"
#include "engine/ref/reference.hpp"
#include "game/accuracy_rows.hpp"

namespace bounce::game {

// First frames of each measured session, not timed: they compile pipelines (DESIGN.md).
inline constexpr std::uint32_t kAccuracyWarmupFrames = 5;

struct AccuracyOptions {
  std::filesystem::path level;
  std::filesystem::path out;
  std::uint32_t spp = 64;  // reference samples per pixel (the full reference; bounces 0 uses 1)
  std::uint32_t width = 256, height = 256;
  std::uint32_t frame = 0;  // simulation time frame · ref::kLevelFrameDt
  std::string device;       // Vulkan device name substring (empty: default)
  std::uint32_t measuredFrames = 20;
  std::filesystem::path referenceCache;  // renderReference's cache folder
  std::filesystem::path cookCache;
  bool progress = true;  // progress bars (they are quiet in CI and off a terminal anyway)
  bool chart = true;     // run tools/plot_accuracy.py
  // --effect-images: also write what the object-effect errors compare, as linear PFMs in `out`:
  // per row "without-<row>.pfm" (the technique without the dynamic entities; "image-<row>.pfm" is
  // the one with them), per reference kind "reference-<kind>-with.pfm" / "-without.pfm", and
  // "mask-indirect-only.pfm" (1 on the pixels indirect_effect_rel_rmse counts, else 0), and per
// reference kind with a noise estimate "reference-<kind>-half-with.pfm" / "-half-without.pfm" (the
// first half of the same samples; tools/effect_noise.py reads the folder).
  bool effectImages = false;
  std::optional<std::vector<AccuracyRow>> rows;  // empty: accuracyRows()
};

struct AccuracyResult {
  AccuracyRow row;
  double gpuMs = 0.0;
  double relRmse = 0.0;
  double effectRelRmse = 0.0;       // NaN when referenceEffectIsZero
  bool referenceEffectIsZero = false;
  // effect_rel_rmse over the pixels where the dynamic objects' effect is indirect only: neither
  // seen nor shadowing anything (indirectOnlyMask). That is the part DNRT, VLM, SL and RTF
  // model; a technique that leaves it out scores 1 there. NaN when the reference effect there is
  // zero. CSV column indirect_effect_rel_rmse (empty when NaN).
  double indirectEffectRelRmse = 0.0;
  // The reference's own noise in the two effects above and the errors corrected for it
  // (engine/ref/effect_noise.hpp, which derives them): *NoiseFloor = what a technique equal to the
  // converged effect scores against this reference (its rms noise over its effect's rms; 0 against
  // the exact bounces-0 reference), *Corrected = sqrt(max(0, e² − f²)/(1 − f²)), the error against
  // the converged effect (1 = effect missing, as before the correction). NaN where the error is
  // NaN, the reference has one sample per pixel and bounces, or f ≥ 1. CSV columns
  // effect_noise_floor, effect_rel_rmse_corrected, indirect_noise_floor,
  // indirect_effect_rel_rmse_corrected (empty when NaN).
  double effectNoiseFloor = std::numeric_limits<double>::quiet_NaN();
  double effectRelRmseCorrected = std::numeric_limits<double>::quiet_NaN();
  double indirectNoiseFloor = std::numeric_limits<double>::quiet_NaN();
  double indirectEffectRelRmseCorrected = std::numeric_limits<double>::quiet_NaN();
  std::filesystem::path heatMap;
  double heatMapScale = 0.0;  // the error the heat map's top colour stands for
  // On the Pareto front of the rows scored against the same reference: no such row is both
  // cheaper (gpu_ms) and more accurate (rel_rmse) — markParetoFront().
  bool pareto = false;
};

struct AccuracyReport {
  std::vector<AccuracyResult> rows;  // in accuracyRows() order, skipped rows left out
  std::vector<std::string> notes;    // one line per skipped row or missing output
  // What makes the numbers less than they seem: timings over fewer than kMinTrustedFrames frames;
  // a reference whose own noise (estimated from its two half-sample halves) exceeds
  // kMaxReferenceNoiseShare of the best row's error against it.
  std::vector<std::string> warnings;
  // Per reference kind ("ref=all", …) traced with more than one sample: the full reference's
  // estimated relative RMSE, relRmse(A, B) / 2 with A the first and B the second half of its
  // samples (A − B has twice the full image's noise amplitude).
  std::vector<std::pair<std::string, double>> referenceNoise;
  // Per reference kind with a noise estimate: the noise floors of the object effect (whole image)
  // and of the indirect-only effect (AccuracyResult::effectNoiseFloor / indirectNoiseFloor).
  struct EffectFloor {
    std::string kind;
    std::uint32_t spp = 0;
    double effect = 0.0, indirect = 0.0;  // NaN where the reference shows no effect
  };
  std::vector<EffectFloor> effectFloors;
  std::filesystem::path csv;
  std::optional<std::filesystem::path> chart;  // empty when no chart was drawn (see notes)
};

inline constexpr std::uint32_t kMinTrustedFrames = 10;
inline constexpr double kMaxReferenceNoiseShare = 1.0 / 3.0;

// The level without its dynamic entities as a file the reference tracer reads (withoutDynamicEntitiesJson),
// written atomically under cacheDir("levels") (the same bytes whichever process writes it); its path.
std::filesystem::path staticLevelFile(const scene::Level& level);

// The reference request runAccuracy makes for `input` (the level, or its static file).
ref::ReferenceRequest referenceRequest(const AccuracyOptions& options, const std::filesystem::path& input,
                                       std::optional<std::uint32_t> bounces, std::uint32_t spp);

// One path-traced reference runAccuracy(options) compares with, named for `bounce bake --only
// reference:PART`: PART is the reference kind ("direct", "1bounce", "all"), "-static" for the level
// without its dynamic objects, "-half" / "-static-half" for the half-sample ones the noise
// estimates use (the first half of the same samples: effect_noise.hpp).
struct AccuracyReference {
  std::string part;
  ref::ReferenceRequest request;
};
// Every reference runAccuracy(options) traces, for the rows it scores (options.rows, else every
// technique's). Writes the static level file; traces nothing.
std::vector<AccuracyReference> accuracyReferences(const AccuracyOptions& options);

// Sets AccuracyResult::pareto: per reference kind (the setting's "ref=…"), rows sorted by gpu_ms
// (ties: lower error first) are on the front when their rel_rmse is below every cheaper row's.
void markParetoFront(std::vector<AccuracyResult>& results);
// The setting's "ref=…" value ("all" when it names none).
std::string referenceKind(const std::string& setting);

// Runs every row. Bad input (level, options) throws InputError before anything is rendered.
AccuracyReport runAccuracy(const AccuracyOptions& options);

// The CSV text: the exact header, then one line per result.
// indirect_effect_rel_rmse (issue 15): AccuracyResult::indirectEffectRelRmse, empty where a row has
// none (the reference's effect on the indirect-only pixels is zero, e.g. against the direct-only
// reference).
// The four noise columns after it (AccuracyResult::effectNoiseFloor …) come last so that readers
// of the first six keep working.
inline constexpr const char* kAccuracyCsvHeader =
    "technique,setting,gpu_ms,rel_rmse,effect_rel_rmse,indirect_effect_rel_rmse,"
    "effect_noise_floor,effect_rel_rmse_corrected,indirect_noise_floor,indirect_effect_rel_rmse_corrected";
std::string formatAccuracyCsv(const std::vector<AccuracyResult>& results);
// A fixed-width table of the same numbers for the terminal.
std::string formatAccuracyTable(const std::vector<AccuracyResult>& results);

// Pixels where two direct-only (bounces 0) references, with and without the dynamic objects,
// agree: the objects are not seen there and cast no shadow there. The excluded region grows by
// one pixel so that silhouettes the rasteriser draws a pixel off stay out as well.
ref::PixelMask indirectOnlyMask(const ImageRGB& directWith, const ImageRGB& directWithout);

// Linear float image conversions between the GPU readback / tracer format and the metrics one.
ImageRGB toImageRgb(const gpu::FloatImage& image);

// Draws the chart from a CSV with tools/plot_accuracy.py under /usr/bin/python3. Returns false
// and fills `why` when it cannot (no python3, no matplotlib, script failure).
// With `heatmaps` (file,technique,setting,scale per heat map) the script also titles the heat maps.
bool plotAccuracy(const std::filesystem::path& csv, const std::filesystem::path& png, std::string& why,
                  const std::filesystem::path& heatmaps = {});

}  // namespace bounce::game
