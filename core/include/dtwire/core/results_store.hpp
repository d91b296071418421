#pragma once
// HDF5 results store. Layout (all names are HDF5 paths):
//   /provenance            attrs tool_version, git_hash, created_utc, command
//   /provenance/inputs     one string attr per input file: path -> sha256
//   /curves/<name>         attr channel_order (comma list); one dataset per channel named
//                          <quantity>_<unit> with attrs quantity, unit; metadata as attrs
//                          "meta:<key>"
//   /parameters/<name>     scalar dataset (value) with attrs unit and, if known, sigma
//   /fields                string attrs describing field outputs (e.g. VTU file names)
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "dtwire/core/curve.hpp"
#include "dtwire/core/provenance.hpp"

namespace dtwire {

struct Parameter {
  std::string name;
  double value = 0.0;
  std::string unit;  // SI symbol, "1" if dimensionless
  std::optional<double> sigma;
};

struct Results {
  std::vector<std::pair<std::string, Curve>> curves;
  std::vector<Parameter> parameters;
  std::vector<std::pair<std::string, std::string>> fields;
  Provenance provenance;
};

// Atomic: built in memory, written to a temporary file and renamed (write_bytes_atomically).
// Throws std::runtime_error naming the file and the reason (HDF5's error stack, or the system's
// for the write) on failure, and std::invalid_argument on non-finite values (never written).
void write_results(const Results& results, const std::filesystem::path& path);
// Throws InputError if the file is missing or not a dtwire results file.
Results read_results(const std::filesystem::path& path);

}  // namespace dtwire
