#pragma once
// Report and JSON files of the gap commands.
#include <string>

namespace dtwire::app {

// `text` to `path`, written under a temporary name and renamed, parent folders made; nothing
// when `path` is empty.
void write_text(const std::string& path, const std::string& text);

}  // namespace dtwire::app
