#pragma once
// Named handles shared between the code that adds passes: the G-buffer publishes
// "gbuffer.normal", a GI node later reads it by that name instead of receiving it through layers
// of arguments. A handle on the blackboard is an ordinary handle: after a pass writes the
// resource again, whoever wrote it must put() the new version, or readers get a stale-handle
// error from the graph.
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/render/graph/resource.hpp"

namespace bounce::rg {

class Blackboard {
 public:
  // Publish (or replace) the handle stored under `key`.
  template <typename T>
  void put(std::string key, Handle<T> handle) {
    entries_[std::move(key)] = Entry{T::kind, handle.index, handle.version};
  }

  // The handle stored under `key`; throws InternalError naming the key (and the keys there are)
  // when it is absent or holds the other kind of resource.
  template <typename T>
  Handle<T> get(std::string_view key) const {
    const Entry& e = lookup(key, T::kind);
    return Handle<T>{e.index, e.version};
  }

  // The handle under `key`, or nothing when absent (for optional inputs, e.g. "ao.term").
  template <typename T>
  std::optional<Handle<T>> find(std::string_view key) const {
    if (!contains(key)) return std::nullopt;
    return get<T>(key);
  }

  bool contains(std::string_view key) const { return entries_.find(key) != entries_.end(); }
  void remove(std::string_view key);
  std::vector<std::string> keys() const;  // sorted
  void clear() { entries_.clear(); }

 private:
  struct Entry {
    ResourceKind kind;
    std::uint32_t index;
    std::uint32_t version;
  };
  const Entry& lookup(std::string_view key, ResourceKind kind) const;

  std::map<std::string, Entry, std::less<>> entries_;
};

}  // namespace bounce::rg
