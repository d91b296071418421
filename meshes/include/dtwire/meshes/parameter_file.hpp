#pragma once
// .prm files for `dtwire mesh sw|dt --prm FILE`, in deal.II ParameterHandler syntax:
//   # comment
//   set twist-length = 40     # mm
// One `set` per line, names as the command-line options without "--" (spaces and underscores
// are read as dashes, case ignored), values in the same units (mm, deg, counts).
#include <filesystem>
#include <string>

#include "dtwire/meshes/parameters.hpp"

namespace dtwire::meshes {

// Applies every `set` in the file to `parameters` and records each value's file:line:column
// in `locations`. Throws InputError (file:line:column) for syntax errors, unknown names,
// parameters the kind does not use, repeated names and values that are not numbers.
void read_parameter_file(const std::filesystem::path& path, MeshParameters& parameters,
                         FieldLocations& locations);
void parse_parameter_text(const std::string& text, const std::string& source,
                          MeshParameters& parameters, FieldLocations& locations);

}  // namespace dtwire::meshes
