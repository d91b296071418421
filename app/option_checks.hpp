#pragma once
// Validators of numeric command-line options. CLI11's Range, PositiveNumber and NonNegativeNumber
// compare, and every comparison with NaN is false, so NaN passes them; their messages print an
// open bound as DBL_MAX's 309 digits. These refuse NaN and infinity and print bounds as written.
#include <initializer_list>
#include <limits>
#include <string>
#include <utility>

#include <CLI/CLI.hpp>

namespace dtwire::app {

// A finite number in [lowest, highest] (lowest excluded when `open_below`).
CLI::Validator finite_in(double lowest, double highest = std::numeric_limits<double>::max(), bool open_below = false);

// A finite number > 0.
inline CLI::Validator finite_positive() { return finite_in(0.0, std::numeric_limits<double>::max(), true); }

// A whole number >= 0 written without a sign (a seed): "-1" would wrap to 2^64 - 1 in an unsigned.
CLI::Validator unsigned_whole();

// Output paths checked before any work (core's check_output_file / check_output_folder): each pair
// is (option, path); empty paths (options not given) are skipped.
using OutputOption = std::pair<const char*, std::string>;
void check_output_files(std::initializer_list<OutputOption> files);
void check_output_folders(std::initializer_list<OutputOption> folders);

// A figure file: a format matplotlib writes (png, pdf, svg, eps, ps, jpg, tif, webp), in a
// folder that can be written. Throws InputError naming `option`.
void check_plot_file(const std::string& file, const std::string& option);

}  // namespace dtwire::app
