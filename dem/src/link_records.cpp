// Per-type link records of a punch (see link_records.hpp).
#include "link_records.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>

#include "dtwire/core/atomic_file.hpp"
#include "dtwire/core/csv.hpp"
#include "dtwire/dem/distortion.hpp"
#include "dtwire/dem/thesis_macroelement.hpp"
#include "dtwire/dem/wirepm.hpp"

namespace dtwire::dem {
namespace {

constexpr double kForceBin = 250.0;   // [N], as link_force_histogram.csv
constexpr double kStrainBin = 0.0025;  // [1]
constexpr double kYielded = 1e-3;      // plastic strain above which a link counts as yielded [1]
constexpr double kNone = std::numeric_limits<double>::quiet_NaN();

// The law's plastic elongation [m]; NaN for laws that do not expose one.
double plastic_elongation(const ContactLaw& law) {
  if (const auto* distorted = dynamic_cast<const DistortedLaw*>(&law)) return plastic_elongation(distorted->wrapped());
  if (const auto* thesis = dynamic_cast<const ThesisMacroElement*>(&law)) return thesis->plastic_elongation();
  if (const auto* wirepm = dynamic_cast<const WirePmLaw*>(&law)) return wirepm->plastic_elongation();
  return std::numeric_limits<double>::quiet_NaN();
}

// Nearest-rank quantile of sorted values; NaN for none.
double quantile(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(sorted.size())));
  return sorted[std::clamp<std::size_t>(rank, 1, sorted.size()) - 1];
}

std::string number(double value) { return std::isnan(value) ? std::string() : format_number(value); }

long bin_of(double value, double width) { return static_cast<long>(std::floor(value / width)); }

}  // namespace

const std::vector<std::string>& LinkRecorder::file_names() {
  static const std::vector<std::string> names = {"link_type_histograms.csv", "link_types_at_peak.csv", "link_paths.csv"};
  return names;
}

LinkRecorder::LinkRecorder(const HexMesh& mesh) {
  for (const NetLink& link : mesh.net.links) {
    length_.push_back((mesh.net.nodes[link.b].position - mesh.net.nodes[link.a].position).norm());
    tag_.push_back(link.tag);
  }
}

void LinkRecorder::sample(const Engine& engine, double tool_displacement_mm) {
  Sample s{tool_displacement_mm, {}, {}, {}};
  const std::size_t n = engine.link_count();
  s.force.resize(n, kNone);
  s.elongation.resize(n, kNone);
  s.plastic.resize(n, kNone);
  for (std::size_t l = 0; l < n; ++l) {
    const ContactLaw& law = *engine.link(l).law;
    if (law.broken()) continue;
    s.force[l] = law.forces()[0];
    s.elongation[l] = engine.link_law_length(l) - length_[l];
    s.plastic[l] = plastic_elongation(law);
  }
  samples_.push_back(std::move(s));
}

void LinkRecorder::write(const std::filesystem::path& out, const std::string& run_id) const {
  if (samples_.empty()) return;
  const Sample& peak = samples_[peak_];
  std::vector<LinkTag> types;
  for (LinkTag tag : tag_)
    if (std::find(types.begin(), types.end(), tag) == types.end()) types.push_back(tag);

  // Values at the peak per type (intact links only; NaN plastic strains left out).
  struct AtPeak {
    std::vector<double> force, strain, plastic;
    std::size_t links = 0, broken = 0;
    double tension = 0.0;
  };
  std::vector<AtPeak> at(types.size());
  long force_top = 0, strain_low = 0, strain_high = 0;
  for (std::size_t l = 0; l < tag_.size(); ++l) {
    AtPeak& a = at[std::find(types.begin(), types.end(), tag_[l]) - types.begin()];
    ++a.links;
    if (std::isnan(peak.force[l])) {
      ++a.broken;
      continue;
    }
    a.force.push_back(peak.force[l]);
    a.tension += std::max(0.0, peak.force[l]);
    a.strain.push_back(peak.elongation[l] / length_[l]);
    if (!std::isnan(peak.plastic[l])) a.plastic.push_back(peak.plastic[l] / length_[l]);
  }
  for (AtPeak& a : at) {
    for (double f : a.force) force_top = std::max(force_top, bin_of(std::abs(f), kForceBin));
    for (const auto* values : {&a.strain, &a.plastic})
      for (double e : *values) {
        strain_low = std::min(strain_low, bin_of(e, kStrainBin));
        strain_high = std::max(strain_high, bin_of(e, kStrainBin));
      }
  }

  write_file_atomically(out / "link_type_histograms.csv", [&](std::ostream& os) {
    os << "# run_id: " << run_id << "\n# counts of intact links at the peak force; tool_displacement_mm: "
       << format_number(peak.tool_displacement_mm) << "\n"
       << "link_type,link_force_low_N,link_force_high_N,force_count_at_peak_1,strain_low_1,strain_high_1,"
          "strain_count_at_peak_1,plastic_strain_count_at_peak_1\n";
    const long rows = std::max(force_top + 1, strain_high - strain_low + 1);
    for (std::size_t t = 0; t < types.size(); ++t) {
      const AtPeak& a = at[t];
      for (long r = 0; r < rows; ++r) {
        os << link_tag_name(types[t]) << ',';
        if (r <= force_top) {
          const auto count = std::count_if(a.force.begin(), a.force.end(), [&](double f) { return bin_of(std::abs(f), kForceBin) == r; });
          os << format_number(r * kForceBin) << ',' << format_number((r + 1) * kForceBin) << ',' << count << ',';
        } else {
          os << ",,,";
        }
        const long b = strain_low + r;
        if (b <= strain_high) {
          auto in_bin = [&](double e) { return bin_of(e, kStrainBin) == b; };
          os << format_number(b * kStrainBin) << ',' << format_number((b + 1) * kStrainBin) << ','
             << std::count_if(a.strain.begin(), a.strain.end(), in_bin) << ',';
          if (!a.plastic.empty()) os << std::count_if(a.plastic.begin(), a.plastic.end(), in_bin);
        } else {
          os << ",,,";
        }
        os << '\n';
      }
    }
  });

  write_file_atomically(out / "link_types_at_peak.csv", [&](std::ostream& os) {
    os << "# run_id: " << run_id << "\n# intact links at the peak force; quantiles nearest-rank; yielded: plastic strain above "
       << format_number(kYielded) << "\n"
       << "link_type,links_1,broken_1,tension_sum_N,force_p50_N,force_p90_N,force_max_N,strain_p50_1,strain_p90_1,"
          "strain_max_1,plastic_strain_p50_1,plastic_strain_p90_1,plastic_strain_max_1,yielded_1\n";
    for (std::size_t t = 0; t < types.size(); ++t) {
      AtPeak a = at[t];
      for (auto* values : {&a.force, &a.strain, &a.plastic}) std::sort(values->begin(), values->end());
      const auto yielded = std::count_if(a.plastic.begin(), a.plastic.end(), [](double e) { return e > kYielded; });
      os << link_tag_name(types[t]) << ',' << a.links << ',' << a.broken << ',' << format_number(a.tension);
      for (const auto* values : {&a.force, &a.strain, &a.plastic})
        os << ',' << number(quantile(*values, 0.5)) << ',' << number(quantile(*values, 0.9)) << ','
           << number(values->empty() ? std::nan("") : values->back());
      os << ',' << (a.plastic.empty() ? std::string() : std::to_string(yielded)) << '\n';
    }
  });

  // The kPathsPerType links of each type with the largest axial force at the peak, each followed
  // from the first output row until the peak and on while it holds.
  std::vector<std::size_t> chosen;
  for (LinkTag type : types) {
    std::vector<std::size_t> of_type;
    for (std::size_t l = 0; l < tag_.size(); ++l)
      if (tag_[l] == type && !std::isnan(peak.force[l])) of_type.push_back(l);
    const std::size_t keep = std::min(kPathsPerType, of_type.size());
    std::partial_sort(of_type.begin(), of_type.begin() + keep, of_type.end(),
                      [&](std::size_t x, std::size_t y) { return peak.force[x] > peak.force[y]; });
    chosen.insert(chosen.end(), of_type.begin(), of_type.begin() + keep);
  }
  write_file_atomically(out / "link_paths.csv", [&](std::ostream& os) {
    os << "# run_id: " << run_id << "\n# the " << kPathsPerType
       << " links of each type with the largest axial force at the peak; rows while the link is intact\n"
       << "link_id,link_type,tool_displacement_mm,elongation_mm,strain_1,plastic_strain_1,force_N\n";
    for (std::size_t l : chosen)
      for (const Sample& s : samples_) {
        if (std::isnan(s.force[l])) continue;
        os << l << ',' << link_tag_name(tag_[l]) << ',' << format_number(s.tool_displacement_mm) << ','
           << format_number(1000.0 * s.elongation[l]) << ',' << format_number(s.elongation[l] / length_[l]) << ','
           << number(s.plastic[l] / length_[l]) << ',' << format_number(s.force[l]) << '\n';
      }
  });
}

}  // namespace dtwire::dem
