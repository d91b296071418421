// Parameter tables per wire type: HDF5 (core results store), JSON (the calibrate format, so it
// reads back) and CSV (name,value,unit,sigma).
#include <nlohmann/json.hpp>

#include <ostream>
#include <stdexcept>

#include "dtwire/core/atomic_file.hpp"
#include "dtwire/core/csv.hpp"
#include "dtwire/core/results_store.hpp"
#include "dtwire/dem/export.hpp"

namespace dtwire::dem {
namespace {

void check_name(const std::string& text, const std::string& what) {
  if (text.find_first_of(",\"\n\r") != std::string::npos)
    throw std::invalid_argument(what + " '" + text + "' contains a comma, quote or newline");
}

}  // namespace

std::vector<std::filesystem::path> export_parameter_tables(const std::vector<ParameterSet>& sets,
                                                           const std::filesystem::path& out,
                                                           const Provenance& provenance) {
  std::filesystem::create_directories(out);
  std::vector<std::filesystem::path> written;
  for (const ParameterSet& set : sets) {
    check_name(set.wire_type, "wire type");
    const std::filesystem::path stem = out / (set.wire_type + "_parameters");

    Results results;
    results.provenance = provenance;
    for (const ParameterEntry& e : set.entries) results.parameters.push_back({e.name, e.value, e.unit, e.sigma});
    results.fields.emplace_back("wire_type", set.wire_type);
    if (!set.law.empty()) results.fields.emplace_back("law", set.law);
    write_results(results, stem.string() + ".h5");
    written.emplace_back(stem.string() + ".h5");

    nlohmann::json document = {{"wire_type", set.wire_type}, {"units", "SI"}, {"parameters", nlohmann::json::array()}};
    if (!set.law.empty()) document["law"] = set.law;
    document["provenance"] = {{"tool_version", provenance.tool_version},
                              {"git_hash", provenance.git_hash},
                              {"created_utc", provenance.created_utc},
                              {"run_id", provenance.run_id}};
    for (const ParameterEntry& e : set.entries) {
      nlohmann::json item = {{"name", e.name}, {"value", e.value}, {"unit", e.unit}};
      if (e.sigma) item["sigma"] = *e.sigma;
      document["parameters"].push_back(item);
    }
    write_file_atomically(stem.string() + ".json", [&](std::ostream& os) { os << document.dump(2) << "\n"; });
    written.emplace_back(stem.string() + ".json");

    write_file_atomically(stem.string() + ".csv", [&](std::ostream& os) {
      os << "# wire_type: " << set.wire_type << "\n";
      if (!set.law.empty()) os << "# law: " << set.law << "\n";
      os << "# run_id: " << provenance.run_id << "\n";
      os << "# units: SI (unit column; 1 = dimensionless)\nname,value,unit,sigma\n";
      for (const ParameterEntry& e : set.entries) {
        check_name(e.name, "parameter name");
        check_name(e.unit, "unit");
        os << e.name << ',' << format_number(e.value) << ',' << e.unit << ','
           << (e.sigma ? format_number(*e.sigma) : "") << "\n";
      }
    });
    written.emplace_back(stem.string() + ".csv");
  }
  return written;
}

}  // namespace dtwire::dem
