#pragma once
// Output of a diagnosis: the JSON contract (docs/gap.md), a Markdown summary, and the data the
// plotting script (scripts/plot_gap.py) draws.
#include <string>

#include <nlohmann/json.hpp>

#include "dtwire/gap/diagnosis.hpp"

namespace dtwire::gap {

// Throws ComputationError if any number is not finite (nothing non-finite is ever written).
nlohmann::json diagnosis_json(const Diagnosis& diagnosis);
std::string diagnosis_markdown(const Diagnosis& diagnosis);
// Curves (mm, N), gap regions and the best augmented model.
nlohmann::json plot_data_json(const Diagnosis& diagnosis);

// Magnitudes beyond their plausible range: [{effect, parameter, value, plausible: [lo, hi]}].
nlohmann::json beyond_range_json(const std::vector<BeyondRange>& beyond);

// Throws ComputationError naming the first non-finite number's path.
void require_finite(const nlohmann::json& value, const std::string& path = "");

}  // namespace dtwire::gap
