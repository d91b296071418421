#pragma once
// Suggestions for misspelled names (unknown .prm entries, JSON keys, campaign fields).
#include <string>
#include <vector>

namespace dtwire {

// The closest of `candidates` to `word` (edit distance), or "" if none is close.
std::string closest_name(const std::string& word, const std::vector<std::string>& candidates);

// " (did you mean 'x'?)" for the closest candidate, or "" if none is close.
std::string did_you_mean(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace dtwire
