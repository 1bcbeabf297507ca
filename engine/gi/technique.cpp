#include "engine/gi/technique.hpp"

#include <cstdio>
#include <mutex>
#include <set>

namespace bounce::gi {

std::optional<std::string> effectNote(const Technique& technique, const LevelContext& lc) {
  const std::string name(technique.name());
  std::string why;
  if (technique.takesPart(lc, &why)) return std::nullopt;
  return "note: effect " + name + " is named but no entity takes part (" + why + "): no pass";
}

void printNoteOnce(const std::string& note) {
  static std::mutex mutex;
  static std::set<std::string> printed;
  std::lock_guard lock(mutex);
  if (!printed.insert(note).second) return;
  std::fprintf(stderr, "%s\n", note.c_str());
}

}  // namespace bounce::gi
