#pragma once
// "Did you mean …" for a misspelt name (a level key, an effect, a command, an option): the known
// name nearest by edit distance, when it is near enough to be a typo rather than another word.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace bounce {

// Optimal-string-alignment distance (insertions, deletions, substitutions and swaps of two
// neighbouring characters each cost 1), case-insensitive.
std::size_t editDistance(std::string_view a, std::string_view b);

// The candidate nearest to `given` when its distance is at most max(1, |given| / 3) — one slip in a
// short word, two in a long one — and it is not `given` itself; ties go to the earlier candidate.
std::optional<std::string> nearestName(std::string_view given, const std::vector<std::string>& candidates);

// ", did you mean "NAME"?" for nearestName(), else "" — appended to an error's "what".
std::string didYouMean(std::string_view given, const std::vector<std::string>& candidates);

}  // namespace bounce
