// Memory and disk checks before a command allocates or writes (resources.hpp).
#include "dtwire/core/resources.hpp"

#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>

#include "dtwire/core/error.hpp"

namespace dtwire {

std::uint64_t parse_byte_size(const std::string& text, const std::string& option) {
  std::istringstream is(text);
  double value = 0.0;
  std::string unit;
  is >> value;
  if (is.fail() || !std::isfinite(value) || !(value > 0.0))
    throw InputError(option, "expected a positive size such as 4G, 512M or 800K, found '" + text + "'");
  is >> unit;
  const std::string rest = is.eof() ? "" : "x";
  for (char& c : unit) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));  // 4g as 4G
  double factor = 0.0;
  if (unit.empty() || unit == "B") factor = 1.0;
  else if (unit == "K" || unit == "KB") factor = 1024.0;
  else if (unit == "M" || unit == "MB") factor = 1024.0 * 1024.0;
  else if (unit == "G" || unit == "GB") factor = 1024.0 * 1024.0 * 1024.0;
  else if (unit == "T" || unit == "TB") factor = 1024.0 * 1024.0 * 1024.0 * 1024.0;
  if (factor == 0.0 || !rest.empty() || value * factor > 1e18)
    throw InputError(option, "expected a positive size such as 4G, 512M or 800K, found '" + text + "'");
  return static_cast<std::uint64_t>(value * factor);
}

std::optional<std::uint64_t> available_memory() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  std::uint64_t kilobytes = 0;
  std::string unit;
  while (meminfo >> key >> kilobytes >> unit)
    if (key == "MemAvailable:") return kilobytes * 1024;
  return std::nullopt;
}

std::optional<double> load_average() {
  std::ifstream loadavg("/proc/loadavg");
  double one_minute = 0.0;
  if (loadavg >> one_minute && one_minute >= 0.0) return one_minute;
  return std::nullopt;
}

std::string oversubscription_warning(int threads, double load, unsigned cores) {
  if (threads <= 1 || cores == 0 || load + threads <= cores + 0.5) return {};
  std::ostringstream text;
  text.precision(2);
  text << threads << " threads on " << cores << " cores that already carry a load of " << load
       << ": the threads meet every step, so a descheduled one holds up all (a punch took over 5 x its one-thread "
          "time so); --threads 1 beside other work";
  return text.str();
}

std::string format_bytes(double bytes) {
  const char* units[] = {"B", "KB", "MB", "GB", "TB", "PB", "EB"};
  int u = 0;
  while (bytes >= 1024.0 && u < 6) {
    bytes /= 1024.0;
    ++u;
  }
  std::ostringstream os;
  os.precision(bytes < 10.0 ? 2 : 3);
  os << bytes << " " << units[u];
  return os.str();
}

void check_memory(double estimate, const std::optional<std::uint64_t>& max_memory, const std::string& source,
                  const std::string& what, const std::optional<std::uint64_t>& available) {
  const std::optional<std::uint64_t> limit = max_memory ? max_memory : available;
  if (!limit || estimate <= static_cast<double>(*limit)) return;
  throw InputError(source, "needs about " + format_bytes(estimate) + " of memory (" + what + "), above " +
                               (max_memory ? "--max-memory " + format_bytes(static_cast<double>(*limit))
                                           : "the " + format_bytes(static_cast<double>(*limit)) +
                                                 " available (MemAvailable, /proc/meminfo)") +
                               "; nothing was run (a larger limit: --max-memory SIZE)");
}

std::filesystem::path nearest_existing_folder(const std::filesystem::path& folder) {
  std::filesystem::path existing = std::filesystem::absolute(folder);
  while (!std::filesystem::exists(existing) && existing.has_parent_path() && existing != existing.parent_path())
    existing = existing.parent_path();
  return existing;
}

std::optional<std::uint64_t> free_disk_space(const std::filesystem::path& folder) {
  std::error_code error;
  const std::filesystem::space_info space = std::filesystem::space(nearest_existing_folder(folder), error);
  if (error) return std::nullopt;
  return space.available;
}

void check_disk(double estimate, const std::filesystem::path& folder, const std::string& source, const std::string& what,
                const std::optional<std::uint64_t>& free) {
  if (!free || estimate <= static_cast<double>(*free)) return;
  throw InputError(source, "would write about " + format_bytes(estimate) + " (" + what + "), above the " +
                               format_bytes(static_cast<double>(*free)) + " free on the file system of " +
                               nearest_existing_folder(folder).string() + "; nothing was written");
}

void check_disk(double estimate, const std::filesystem::path& folder, const std::string& source, const std::string& what) {
  check_disk(estimate, folder, source, what, free_disk_space(folder));
}

}  // namespace dtwire
