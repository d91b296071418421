// Validators of numeric command-line options (option_checks.hpp).
#include "option_checks.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "dtwire/core/atomic_file.hpp"
#include "dtwire/core/error.hpp"

namespace dtwire::app {
namespace {

std::string bound(double value) {
  if (value == std::numeric_limits<double>::max()) return "inf";
  std::ostringstream s;
  s << value;
  return s.str();
}

}  // namespace

CLI::Validator finite_in(double lowest, double highest, bool open_below) {
  const std::string interval =
      (open_below ? "(" : "[") + bound(lowest) + ", " + bound(highest) + (highest == std::numeric_limits<double>::max() ? ")" : "]");
  return CLI::Validator(
      [=](const std::string& text) -> std::string {
        double value = 0.0;
        if (!CLI::detail::lexical_cast(text, value) || !std::isfinite(value))
          return "expected a finite number in " + interval + ", got '" + text + "'";
        if ((open_below ? !(value > lowest) : !(value >= lowest)) || !(value <= highest))
          return "expected a number in " + interval + ", got " + text;
        return {};
      },
      "NUMBER in " + interval);
}

CLI::Validator unsigned_whole() {
  return CLI::Validator(
      [](const std::string& text) -> std::string {
        if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos)
          return "expected a whole number >= 0 (digits only), got '" + text + "'";
        return {};
      },
      "UINT");
}

void check_output_files(std::initializer_list<OutputOption> files) {
  for (const auto& [option, file] : files)
    if (!file.empty()) check_output_file(file, option);
}

void check_output_folders(std::initializer_list<OutputOption> folders) {
  for (const auto& [option, folder] : folders)
    if (!folder.empty()) check_output_folder(folder, option);
}

void check_plot_file(const std::string& file, const std::string& option) {
  if (file.empty()) return;
  std::string extension = std::filesystem::path(file).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  static const char* const kFormats[] = {".png", ".pdf", ".svg", ".eps", ".ps", ".jpg", ".jpeg", ".tif", ".tiff", ".webp"};
  if (std::none_of(std::begin(kFormats), std::end(kFormats), [&](const char* f) { return extension == f; }))
    throw InputError(option, "'" + file + "': expected a figure file ending in .png, .pdf, .svg, .eps, .ps, .jpg, .tif "
                             "or .webp (the format follows the name)");
  check_output_file(file, option);
}

}  // namespace dtwire::app
