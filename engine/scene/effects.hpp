#pragma once
// Effects a level calls for. A pass or bake exists only for effects named in the level's list
// (or in the --effects override).
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace bounce::scene {

namespace json {
class Node;
}

enum class Effect : std::uint8_t { Direct, Shadows, Probes, Dnrt, Vlm, Sl, Rtf, Ssao, Hbao };
inline constexpr int kEffectCount = 9;

std::string_view effectName(Effect e);
std::optional<Effect> effectFromName(std::string_view name);
// "direct, shadows, probes, ..." — for "(expected one of: …)" messages.
std::string knownEffectNames();

class EffectSet {
 public:
  bool has(Effect e) const { return bits_ & bit(e); }
  void add(Effect e) { bits_ |= bit(e); }
  bool empty() const { return bits_ == 0; }
  // Names in the canonical order of the Effect enum.
  std::vector<std::string> names() const;
  friend bool operator==(EffectSet, EffectSet) = default;

 private:
  static std::uint32_t bit(Effect e) { return 1u << unsigned(e); }
  std::uint32_t bits_ = 0;
};

// Parses a comma-separated list ("direct,shadows"; spaces around names ignored; "" is the
// empty set). Errors are InputError "file: --effects: unknown effect "x" (expected one of: …)"
// or "... duplicate effect".
EffectSet parseEffectList(std::string_view list, const std::string& file);

// Parses a JSON array of effect names (a level's "effects", a capture script's "effects"):
// errors point at the offending element, e.g. "/effects/1: unknown effect "x" (expected …)".
EffectSet parseEffects(const json::Node& node);

}  // namespace bounce::scene
