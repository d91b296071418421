#include "report_html.hpp"

#include <fstream>
#include <sstream>
#include <vector>

#include "report_summary.hpp"

namespace dtwire::app {
namespace {

std::string escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string base64(const std::string& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) | (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                       static_cast<unsigned char>(bytes[i + 2]);
    for (int s : {18, 12, 6, 0}) out += table[(v >> s) & 63];
  }
  if (i < bytes.size()) {
    unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) v |= static_cast<unsigned char>(bytes[i + 1]) << 8;
    out += table[(v >> 18) & 63];
    out += table[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? table[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

// A data: URI for an image file under `base`, or the path itself if it cannot be read.
std::string image_source(const std::string& path, const std::filesystem::path& base) {
  const std::filesystem::path file = std::filesystem::path(path).is_absolute() ? std::filesystem::path(path) : base / path;
  const std::string ext = file.extension().string();
  const std::string type = ext == ".svg" ? "image/svg+xml" : ext == ".jpg" || ext == ".jpeg" ? "image/jpeg" : "image/png";
  std::ifstream in(file, std::ios::binary);
  if (!in) return path;
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return "data:" + type + ";base64," + base64(bytes.str());
}

// Inline Markdown: `code`, ![alt](image), [text](link), **bold**.
std::string inline_html(const std::string& text, const std::filesystem::path& base) {
  std::string out;
  bool bold = false;
  for (std::size_t i = 0; i < text.size();) {
    if (text[i] == '`') {
      const auto end = text.find('`', i + 1);
      if (end != std::string::npos) {
        out += "<code>" + escape(text.substr(i + 1, end - i - 1)) + "</code>";
        i = end + 1;
        continue;
      }
    }
    const bool image = text.compare(i, 2, "![") == 0;
    if (image || text[i] == '[') {
      const std::size_t open = i + (image ? 2 : 1);
      const auto middle = text.find("](", open);
      const auto close = middle == std::string::npos ? middle : text.find(')', middle + 2);
      if (close != std::string::npos) {
        const std::string label = text.substr(open, middle - open);
        const std::string target = text.substr(middle + 2, close - middle - 2);
        if (image)
          out += "<img alt=\"" + escape(label) + "\" src=\"" + image_source(target, base) + "\">";
        else
          out += "<a href=\"" + escape(target) + "\">" + inline_html(label, base) + "</a>";
        i = close + 1;
        continue;
      }
    }
    if (text.compare(i, 2, "**") == 0) {
      out += bold ? "</strong>" : "<strong>";
      bold = !bold;
      i += 2;
      continue;
    }
    out += escape(std::string(1, text[i]));
    ++i;
  }
  if (bold) out += "</strong>";
  return out;
}

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return {};
  return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

std::vector<std::string> table_cells(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  bool code = false;
  const std::string row = trim(line);
  for (std::size_t i = 1; i < row.size(); ++i) {
    if (row[i] == '`') code = !code;
    if (row[i] == '|' && !code && row[i - 1] != '\\') {
      cells.push_back(trim(cell));
      cell.clear();
    } else {
      cell += row[i];
    }
  }
  if (!trim(cell).empty()) cells.push_back(trim(cell));
  return cells;
}

bool is_separator_row(const std::string& line) {
  return line.find("---") != std::string::npos && line.find_first_not_of("|-: \t") == std::string::npos;
}

bool is_list_item(const std::string& line) {
  return line.rfind("- ", 0) == 0 || line.rfind("* ", 0) == 0;
}

const char* kStyle = R"(body{font-family:system-ui,-apple-system,"Segoe UI",sans-serif;max-width:1150px;margin:1.5em auto;padding:0 1em;line-height:1.45;color:#1d2329}
h1{font-size:1.6em;border-bottom:2px solid #345}h2{border-bottom:1px solid #ccd;margin-top:1.8em}h3{margin-top:1.3em}
table{border-collapse:collapse;margin:.6em 0;font-size:.92em}th,td{border:1px solid #c8ced6;padding:.25em .6em;text-align:left;vertical-align:top}
th{background:#e9eef4;cursor:pointer}tr:nth-child(even) td{background:#f6f8fa}
img{max-width:100%;border:1px solid #dde;margin:.4em 0}img.broken{outline:3px solid red}
code{background:#f0f2f5;padding:0 .2em;border-radius:3px}pre{background:#f0f2f5;padding:.6em;overflow-x:auto}
#summary{background:#f4f8fc;border:1px solid #b8cde0;border-radius:6px;padding:0 1em 1em}
#summary img{max-width:49%;vertical-align:top}#summary h2{margin-top:.5em}
)";

// Sort a table by a click on a header; mark images that did not load; count both for checks.
const char* kScript = R"(<script>
document.querySelectorAll('th').forEach(function(th){th.addEventListener('click',function(){
var table=th.closest('table'),body=table.tBodies[0],i=Array.prototype.indexOf.call(th.parentNode.children,th);
var asc=th.dataset.asc!=='1';th.dataset.asc=asc?'1':'0';
var rows=Array.prototype.slice.call(body.rows);rows.sort(function(a,b){
var x=a.cells[i]?a.cells[i].textContent:'',y=b.cells[i]?b.cells[i].textContent:'';
var p=parseFloat(x),q=parseFloat(y);var c=(!isNaN(p)&&!isNaN(q))?p-q:x.localeCompare(y);return asc?c:-c;});
rows.forEach(function(r){body.appendChild(r);});});});
var errors=0;window.addEventListener('error',function(){errors++;document.body.dataset.errors=errors;},true);
window.addEventListener('load',function(){var images=document.images,loaded=0;
for(var k=0;k<images.length;k++){if(images[k].complete&&images[k].naturalWidth>0)loaded++;else images[k].className='broken';}
document.body.dataset.images=loaded+'/'+images.length;document.body.dataset.errors=errors;});
</script>
)";

}  // namespace

std::string markdown_to_html(const std::string& markdown, const std::string& title,
                             const std::filesystem::path& base) {
  std::vector<std::string> lines;
  std::istringstream in(markdown);
  for (std::string line; std::getline(in, line);) lines.push_back(line);

  std::ostringstream html;
  html << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
       << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>" << escape(title)
       << "</title>\n<style>" << kStyle << "</style></head>\n<body>\n";
  bool in_summary = false;
  std::string paragraph;
  const auto flush_paragraph = [&] {
    if (!trim(paragraph).empty()) html << "<p>" << inline_html(trim(paragraph), base) << "</p>\n";
    paragraph.clear();
  };
  for (std::size_t i = 0; i < lines.size();) {
    const std::string& line = lines[i];
    const std::string stripped = trim(line);
    if (stripped.rfind("```", 0) == 0) {
      flush_paragraph();
      html << "<pre><code>";
      for (++i; i < lines.size() && trim(lines[i]).rfind("```", 0) != 0; ++i) html << escape(lines[i]) << "\n";
      html << "</code></pre>\n";
      ++i;
      continue;
    }
    if (stripped.rfind('#', 0) == 0) {
      flush_paragraph();
      const auto level = std::min<std::size_t>(stripped.find_first_not_of('#'), 6);
      const std::string text = trim(stripped.substr(level));
      if (level <= 2 && in_summary) {
        html << "</section>\n";
        in_summary = false;
      }
      const bool summary = level == 2 && text == "Summary";
      if (summary) {
        html << "<section id=\"summary\">\n";  // carries the heading's anchor
        in_summary = true;
      }
      html << "<h" << level;
      if (!summary) html << " id=\"" << escape(heading_anchor(text)) << "\"";
      html << ">" << inline_html(text, base) << "</h" << level << ">\n";
      ++i;
      continue;
    }
    if (stripped.rfind('|', 0) == 0) {
      flush_paragraph();
      const bool header = i + 1 < lines.size() && is_separator_row(lines[i + 1]);
      html << "<table>\n";
      if (header) {
        html << "<thead><tr>";
        for (const auto& cell : table_cells(line)) html << "<th>" << inline_html(cell, base) << "</th>";
        html << "</tr></thead>\n";
        i += 2;
      }
      html << "<tbody>\n";
      for (; i < lines.size() && trim(lines[i]).rfind('|', 0) == 0; ++i) {
        html << "<tr>";
        for (const auto& cell : table_cells(lines[i])) html << "<td>" << inline_html(cell, base) << "</td>";
        html << "</tr>\n";
      }
      html << "</tbody></table>\n";
      continue;
    }
    if (is_list_item(stripped)) {
      flush_paragraph();
      html << "<ul>\n";
      while (i < lines.size() && is_list_item(trim(lines[i]))) {
        std::string item = trim(lines[i]).substr(2);
        for (++i; i < lines.size() && lines[i].rfind("  ", 0) == 0 && !is_list_item(trim(lines[i])) &&
                  !trim(lines[i]).empty();
             ++i)
          item += " " + trim(lines[i]);
        html << "<li>" << inline_html(item, base) << "</li>\n";
      }
      html << "</ul>\n";
      continue;
    }
    if (stripped.empty()) flush_paragraph();
    else paragraph += " " + stripped;
    ++i;
  }
  flush_paragraph();
  if (in_summary) html << "</section>\n";
  html << kScript << "</body></html>\n";
  return html.str();
}

}  // namespace dtwire::app
