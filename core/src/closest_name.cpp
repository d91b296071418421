#include "dtwire/core/closest_name.hpp"

#include <algorithm>
#include <cctype>

namespace dtwire {

std::string closest_name(const std::string& word, const std::vector<std::string>& candidates) {
  // Levenshtein distance, case-insensitive; a name within a third of its length (at least 2
  // edits) is close.
  const auto lower = [](char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); };
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(2, word.size() / 3) + 1;
  for (const std::string& candidate : candidates) {
    std::vector<std::size_t> row(candidate.size() + 1);
    for (std::size_t j = 0; j < row.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= word.size(); ++i) {
      std::size_t diagonal = row[0];
      row[0] = i;
      for (std::size_t j = 1; j <= candidate.size(); ++j) {
        const std::size_t above = row[j];
        const bool same = lower(word[i - 1]) == lower(candidate[j - 1]);
        row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1)});
        diagonal = above;
      }
    }
    if (row.back() < best_distance) {
      best_distance = row.back();
      best = candidate;
    }
  }
  return best;
}

std::string did_you_mean(const std::string& word, const std::vector<std::string>& candidates) {
  const std::string close = closest_name(word, candidates);
  return close.empty() ? std::string() : " (did you mean '" + close + "'?)";
}

}  // namespace dtwire
