#include "engine/scene/effects.hpp"

#include <array>

#include <nlohmann/json.hpp>

#include "engine/core/error.hpp"
#include "engine/core/suggest.hpp"
#include "engine/scene/json_reader.hpp"

namespace bounce::scene {

namespace {
constexpr std::array<std::string_view, kEffectCount> kNames = {"direct", "shadows", "probes", "dnrt", "vlm",
                                                                "sl",     "rtf",     "ssao",   "hbao"};
}

std::string_view effectName(Effect e) { return kNames[std::size_t(e)]; }

std::optional<Effect> effectFromName(std::string_view name) {
  for (std::size_t i = 0; i < kNames.size(); ++i)
    if (kNames[i] == name) return Effect(i);
  return std::nullopt;
}

std::string knownEffectNames() {
  std::string s;
  for (auto n : kNames) s += (s.empty() ? "" : ", ") + std::string(n);
  return s;
}

std::vector<std::string> EffectSet::names() const {
  std::vector<std::string> out;
  for (int i = 0; i < kEffectCount; ++i)
    if (has(Effect(i))) out.emplace_back(kNames[std::size_t(i)]);
  return out;
}

EffectSet parseEffectList(std::string_view list, const std::string& file) {
  EffectSet set;
  auto trim = [](std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
    return s;
  };
  if (trim(list).empty()) return set;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = list.find(',', start);
    const std::string_view name = trim(list.substr(start, comma == std::string_view::npos ? list.npos : comma - start));
    const auto effect = effectFromName(name);
    if (!effect)
      throwInputError(file, "--effects", "unknown effect " + json::inQuotes(name) + didYouMean(name, std::vector<std::string>(kNames.begin(), kNames.end())),
                      "one of: " + knownEffectNames());
    if (set.has(*effect))
      throwInputError(file, "--effects", "duplicate effect " + json::inQuotes(name), "each effect at most once");
    set.add(*effect);
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return set;
}

EffectSet parseEffects(const json::Node& node) {
  EffectSet set;
  for (const auto& e : node.array(0, kEffectCount, "at most " + std::to_string(kEffectCount) + " effect names")) {
    const std::string name = e.string(64);
    const auto effect = effectFromName(name);
    if (!effect)
      e.fail("unknown effect " + json::inQuotes(name) + didYouMean(name, std::vector<std::string>(kNames.begin(), kNames.end())),
             "one of: " + knownEffectNames());
    if (set.has(*effect)) e.fail("duplicate effect " + json::inQuotes(name), "each effect at most once");
    set.add(*effect);
  }
  return set;
}

}  // namespace bounce::scene
