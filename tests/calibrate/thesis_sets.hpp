#pragma once
// The published thesis sets (experiments/data/macroelement_thesis_params.json), prefixed with
// sw. and dt. as the dem_specimen simulator names them: shared by the dem_specimen tests.
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

#include "dtwire/dem/contact_law.hpp"

namespace dtwire::calibrate::testing {

inline dem::ParameterMap thesis_sets() {
  std::ifstream in(std::filesystem::path(DTWIRE_SOURCE_DIR) / "experiments/data/macroelement_thesis_params.json");
  const nlohmann::json root = nlohmann::json::parse(in);
  dem::ParameterMap out;
  for (const auto& [section, prefix] : {std::pair<std::string, std::string>{"single_wire", "sw."}, {"double_twist", "dt."}})
    for (const auto& [name, value] : root.at(section).items())
      if (value.is_number()) out[prefix + name] = value.get<double>();
  return out;
}

}  // namespace dtwire::calibrate::testing
