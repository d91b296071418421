#pragma once
// Where a result came from: tool version and git hash, time, command, and the SHA-256 of every
// input file, stored next to the results.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace dtwire {

struct Provenance {
  std::string tool_version;
  std::string git_hash;
  std::string created_utc;  // ISO 8601
  std::string command;
  std::string run_id;  // unique per run: every file one run writes carries the same id
  std::vector<std::pair<std::string, std::string>> input_sha256;  // path -> hex digest

  void add_input(const std::filesystem::path& path);  // throws InputError if unreadable
};

// The tool's version and the git commit it was built from, read at build time ("-dirty" with
// uncommitted changes to tracked files, "unknown" outside a git checkout).
const char* tool_version();
const char* git_hash();

Provenance make_provenance(const std::string& command,
                           const std::vector<std::filesystem::path>& inputs = {});

// A new run id: UTC time, process id and random bits ("20261124T121500Z-4242-9f3a1c7e").
std::string new_run_id();

std::string sha256_file(const std::filesystem::path& path);
std::string sha256_text(const std::string& text);
std::string utc_now_iso8601();

}  // namespace dtwire
