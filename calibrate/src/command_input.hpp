#pragma once
// The input file of one `command` experiment of a fit file. Internal to calibrate/.
#include <filesystem>
#include <functional>
#include <vector>

#include "dtwire/calibrate/command_simulator.hpp"
#include "toml_table.hpp"

namespace dtwire::calibrate {

// From `input_template` (a text with {name} placeholders; {template_dir} is its folder), or from
// `input_prm` + `prm_set` (an experiment .prm read as a typed document with the entries of
// `prm_set`, "Section/Entry" = value or "{placeholder}", set; a relative `Geometry/Mesh file`
// made absolute; when the program lists its parameters, every key must be one of them). The
// file read is added to `inputs` (provenance).
CommandSpecification command_experiment(const Table& experiment, CommandSpecification base,
                                        const std::function<std::filesystem::path(const std::string&)>& resolve,
                                        std::vector<std::filesystem::path>& inputs);

}  // namespace dtwire::calibrate
