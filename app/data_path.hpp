#pragma once
// dtwire finds its data (experiments/, scripts/) relative to its own binary, so an installed
// copy works without the source tree: the nearest share/dtwire folder above the binary
// (<prefix>/bin/dtwire -> <prefix>/share/dtwire; in the build tree build/share/dtwire links to
// the sources), or $DTWIRE_DATA_DIR if set.
#include <filesystem>
#include <string>

namespace dtwire::app {

// The running binary (/proc/self/exe).
std::filesystem::path executable_path();

// The data folder (if there is none: <binary folder>/../share/dtwire, so a missing file is named
// where an installed copy would have it).
std::filesystem::path data_dir();

// data_dir() / relative, e.g. data_path("experiments/default/campaign.toml").
std::filesystem::path data_path(const std::string& relative);

}  // namespace dtwire::app
