// The per-type link records of `dtwire dem run` (link_type_histograms.csv, link_types_at_peak.csv,
// link_paths.csv) on a small thesis-law punch: every intact link counted once per type, the paths
// are the links most loaded at the peak, and the recorded strain is the law's own elongation
// (the thesis law's axial force is EA_N (u - u_p) before damage).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "dtwire/dem/run.hpp"

namespace dtwire::dem {
namespace {

const std::string kData = std::string(DTWIRE_SOURCE_DIR) + "/experiments/data/";

// Rows of a CSV with '#' metadata lines, as header -> text.
std::vector<std::map<std::string, std::string>> read_rows(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string line;
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> fields;
    std::stringstream ss(line);
    std::string field;
    while (std::getline(ss, field, ',')) fields.push_back(field);
    if (line.back() == ',') fields.emplace_back();
    if (header.empty()) {
      header = fields;
      continue;
    }
    std::map<std::string, std::string> row;
    for (std::size_t c = 0; c < header.size(); ++c) row[header[c]] = c < fields.size() ? fields[c] : "";
    rows.push_back(row);
  }
  return rows;
}

double value(const std::map<std::string, std::string>& row, const std::string& column) { return std::stod(row.at(column)); }

TEST(LinkRecords, PerTypeHistogramsPathsAndQuantilesOfASmallThesisPunch) {
  const std::string params = kData + "macroelement_thesis_params.json";
  const std::string text = "title = \"small thesis punch\"\n"
                           "[mesh]\npattern = \"8x10_2.7mm\"\nwidth_m = 0.6\nheight_m = 0.6\n"
                           "[links.sw]\nlaw = \"thesis\"\nparams = \"" + params + "\"\nwire_type = \"single_wire\"\n"
                           "[links.dt]\nlaw = \"thesis\"\nparams = \"" + params + "\"\nwire_type = \"double_twist\"\n"
                           "[boundary]\npinned = [\"left\", \"right\", \"bottom\", \"top\"]\n"
                           "[dynamics]\nlocal_damping = 0.5\nmass_scale = 100\nsettle_s = 0.05\n"
                           "[tool]\nkind = \"platter\"\nbase_radius_m = 0.12\nheight_m = 0.05\ngap_m = 0.002\n"
                           "speed_m_per_s = 0.5\ntravel_m = 0.15\n"
                           "[output]\ninterval_s = 0.01\nframes = 0\n";
  const auto dir = std::filesystem::temp_directory_path() / "dtwire_link_records_test";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "punch.toml") << text;
  RunOptions options;
  options.quiet = true;
  options.write_frames = false;
  options.threads = 1;
  options.out = dir / "out";
  const RunInput input = read_run_input(dir / "punch.toml");
  const RunSummary run = run_simulation(input, options);
  ASSERT_GT(run.peak_force, 1000.0);
  const BuiltNet net = build_net(input);
  std::map<std::string, std::size_t> links_of_type;
  for (const NetLink& link : net.mesh.net.links) ++links_of_type[link_tag_name(link.tag)];

  // Per type: the counts of every histogram add up to the intact links at the peak.
  const auto at_peak = read_rows(options.out / "link_types_at_peak.csv");
  ASSERT_EQ(at_peak.size(), links_of_type.size());
  std::map<std::string, std::map<std::string, std::string>> summary;
  for (const auto& row : at_peak) summary[row.at("link_type")] = row;
  std::map<std::string, double> force_count, strain_count, plastic_count;
  for (const auto& row : read_rows(options.out / "link_type_histograms.csv")) {
    const std::string type = row.at("link_type");
    if (!row.at("force_count_at_peak_1").empty()) force_count[type] += value(row, "force_count_at_peak_1");
    if (!row.at("strain_count_at_peak_1").empty()) strain_count[type] += value(row, "strain_count_at_peak_1");
    if (!row.at("plastic_strain_count_at_peak_1").empty()) plastic_count[type] += value(row, "plastic_strain_count_at_peak_1");
  }
  for (const auto& [type, links] : links_of_type) {
    const auto& row = summary.at(type);
    EXPECT_EQ(value(row, "links_1"), static_cast<double>(links)) << type;
    const double intact = value(row, "links_1") - value(row, "broken_1");
    EXPECT_EQ(force_count[type], intact) << type;
    EXPECT_EQ(strain_count[type], intact) << type;
    EXPECT_EQ(plastic_count[type], intact) << type;  // the thesis law exposes its plastic elongation
    EXPECT_LE(value(row, "force_p50_N"), value(row, "force_p90_N")) << type;
    EXPECT_LE(value(row, "force_p90_N"), value(row, "force_max_N")) << type;
  }

  // Paths: kPathsPerType links per type; at the peak row the first is the type's largest force.
  const auto paths = read_rows(options.out / "link_paths.csv");
  std::map<std::string, std::set<std::string>> path_links;
  std::map<std::string, double> largest_at_peak;
  const double peak_mm = 1000.0 * run.displacement_at_peak;
  for (const auto& row : paths) {
    path_links[row.at("link_type")].insert(row.at("link_id"));
    if (std::abs(value(row, "tool_displacement_mm") - peak_mm) < 1e-9)
      largest_at_peak[row.at("link_type")] = std::max(largest_at_peak[row.at("link_type")], value(row, "force_N"));
  }
  for (const auto& [type, links] : links_of_type) {
    EXPECT_EQ(path_links[type].size(), std::min<std::size_t>(10, links)) << type;
    EXPECT_DOUBLE_EQ(largest_at_peak[type], value(summary.at(type), "force_max_N")) << type;
  }

  // The strain is the law's: the thesis force is d EA_N (u - u_p), u the recorded elongation
  // (the law's axial displacement), d = 1 until the damage starts, then below 1 for good. So each
  // path follows EA_N (u - u_p) to 0.01 N, on elastic and plastic rows, up to its damage onset and
  // stays below it after.
  const std::map<std::string, double> stiffness = {{"sw", 1.6e7}, {"dt", 1.71e6}};
  std::size_t plastic_rows = 0;
  std::set<std::string> damaged;
  for (const auto& row : paths) {
    const double u = 1e-3 * value(row, "elongation_mm");
    const double strain = value(row, "strain_1"), plastic = value(row, "plastic_strain_1");
    if (std::abs(strain) < 1e-12) continue;
    const double up = plastic / strain * u;  // the same length divides both strains
    const double effective = stiffness.at(row.at("link_type")) * (u - up);
    const double force = value(row, "force_N");
    const std::string where = row.at("link_type") + " link " + row.at("link_id") + " at " + row.at("tool_displacement_mm") + " mm";
    if (std::abs(force - effective) > 0.01) damaged.insert(row.at("link_id"));
    if (damaged.count(row.at("link_id"))) {
      EXPECT_LT(std::abs(force), std::abs(effective)) << where;
    } else if (plastic > 1e-4) {
      ++plastic_rows;
    }
  }
  EXPECT_GT(plastic_rows, 0u);  // the equality held on yielded links too
  EXPECT_LT(damaged.size(), path_links["sw"].size() + path_links["dt"].size());  // not every path damaged
}

}  // namespace
}  // namespace dtwire::dem
