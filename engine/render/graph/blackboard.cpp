#include "engine/render/graph/blackboard.hpp"

#include "engine/core/error.hpp"

namespace bounce::rg {

namespace {
const char* kindName(ResourceKind k) { return k == ResourceKind::Texture ? "texture" : "buffer"; }
}  // namespace

void Blackboard::remove(std::string_view key) {
  auto it = entries_.find(key);
  if (it != entries_.end()) entries_.erase(it);
}

std::vector<std::string> Blackboard::keys() const {
  std::vector<std::string> out;
  for (auto& [k, e] : entries_) out.push_back(k);
  return out;
}

const Blackboard::Entry& Blackboard::lookup(std::string_view key, ResourceKind kind) const {
  auto it = entries_.find(key);
  if (it == entries_.end()) {
    std::string known;
    for (auto& [k, e] : entries_) known += (known.empty() ? "" : ", ") + k;
    throw InternalError("render graph blackboard: no entry '" + std::string(key) + "' (entries: " +
                        (known.empty() ? "none" : known) + ")");
  }
  if (it->second.kind != kind)
    throw InternalError("render graph blackboard: entry '" + std::string(key) + "' is a " +
                        kindName(it->second.kind) + ", asked for a " + kindName(kind));
  return it->second;
}

}  // namespace bounce::rg
