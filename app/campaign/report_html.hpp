#pragma once
// report.html: the campaign report as one self-contained page (images embedded as data: URIs,
// no network), converted from the Markdown the report writes: headings with anchors, tables
// (sortable by a click on a column header), lists, code, links, emphasis and images.
#include <filesystem>
#include <string>

namespace dtwire::app {

// `base` is the folder the Markdown's relative image paths start from.
std::string markdown_to_html(const std::string& markdown, const std::string& title,
                             const std::filesystem::path& base);

}  // namespace dtwire::app
