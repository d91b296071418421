#pragma once
// The memory and disk a command would take, checked before it allocates or writes: a typo in a
// size must be refused by name (exit 2), not allocate until the kernel kills the machine's jobs.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace dtwire {

// "4G", "512M", "1.5G", "800K" or a number of bytes; throws InputError naming `option`.
std::uint64_t parse_byte_size(const std::string& text, const std::string& option);
// MemAvailable of /proc/meminfo [bytes]; none where it cannot be read.
std::optional<std::uint64_t> available_memory();
std::string format_bytes(double bytes);  // "1.2 GB"

// Throws InputError(source, ...) when `estimate` [bytes] exceeds `max_memory` if given, else the
// `available` memory; `what` says what the estimate counts ("3268 nodes, 4784 links, ...").
// (An MPI run passes the figure its first rank read, so that every rank decides alike.)
void check_memory(double estimate, const std::optional<std::uint64_t>& max_memory, const std::string& source,
                  const std::string& what, const std::optional<std::uint64_t>& available = available_memory());
// The nearest existing folder of `folder` (itself or a parent) and the bytes free on its file
// system; none where it cannot be read.
std::filesystem::path nearest_existing_folder(const std::filesystem::path& folder);
std::optional<std::uint64_t> free_disk_space(const std::filesystem::path& folder);
// Throws InputError(source, ...) when `estimate` [bytes] exceeds the free space of the file system
// that holds `folder` (or its nearest existing parent; `free` as read there).
void check_disk(double estimate, const std::filesystem::path& folder, const std::string& source, const std::string& what,
                const std::optional<std::uint64_t>& free);
void check_disk(double estimate, const std::filesystem::path& folder, const std::string& source, const std::string& what);

// The 1-minute load average of /proc/loadavg; none where it cannot be read.
std::optional<double> load_average();
// A warning when `threads` (> 1) of a run whose threads meet at a barrier every step would share
// `cores` with a `load` of other work: a descheduled thread holds up every step, so the run can
// take many times longer than on one thread. "" when they fit (load + threads <= cores + 0.5).
std::string oversubscription_warning(int threads, double load, unsigned cores);

}  // namespace dtwire
