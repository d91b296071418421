#include "dtwire/gap/force_curve.hpp"

#include <algorithm>
#include <cmath>
#include <exception>

#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"

namespace dtwire::gap {
namespace {

const Channel* find_any(const Curve& curve, std::initializer_list<const char*> names) {
  for (const char* name : names)
    if (const Channel* c = curve.find(name)) return c;
  return nullptr;
}

std::string columns_of(const Curve& curve) {
  std::string out;
  for (const Channel& c : curve.channels()) out += (out.empty() ? "" : ", ") + c.column_name();
  return out;
}

std::vector<double> checked_si(const Channel& channel, Dimension expected, const std::string& file,
                               const std::string& what) {
  if (channel.unit.dimension != expected)
    throw InputError(file, "column '" + channel.column_name() + "': expected " + what + " in a " +
                               std::string(dimension_name(expected)) + " unit, found '" +
                               channel.unit.symbol + "' (" +
                               std::string(dimension_name(channel.unit.dimension)) + ")");
  return channel.si();
}

}  // namespace

void validate_force_curve(const ForceCurve& curve) {
  if (curve.u.size() != curve.f.size())
    throw InputError(curve.source, "displacement and force differ in length");
  if (curve.u.size() < kMinimumCurvePoints)
    throw InputError(curve.source, "a curve needs at least " + std::to_string(kMinimumCurvePoints) +
                                       " points, found " + std::to_string(curve.u.size()));
  for (std::size_t i = 0; i < curve.u.size(); ++i)
    if (!std::isfinite(curve.u[i]) || !std::isfinite(curve.f[i]))
      throw InputError(curve.source, "point " + std::to_string(i + 1) + " is not a finite number");
}

std::string row_order_warning(const ForceCurve& curve) {
  if (curve.u.size() < 3) return "";
  const auto [lowest, highest] = std::minmax_element(curve.u.begin(), curve.u.end());
  const double large_step = 0.05 * (*highest - *lowest);
  if (!(large_step > 0.0)) return "";
  int previous_direction = 0;
  std::size_t large_steps = 0, reversals = 0;
  for (std::size_t i = 1; i < curve.u.size(); ++i) {
    const double step = curve.u[i] - curve.u[i - 1];
    if (std::abs(step) <= large_step) continue;
    const int direction = step > 0.0 ? 1 : -1;
    if (previous_direction != 0 && direction != previous_direction) ++reversals;
    previous_direction = direction;
    ++large_steps;
  }
  if (reversals < 5 || static_cast<double>(reversals) <= 0.4 * static_cast<double>(large_steps - 1)) return "";
  return curve.source + ": the displacement reverses at " + std::to_string(reversals) + " of " +
         std::to_string(large_steps) + " large steps: are the rows in the order of the test? (rows that are " +
         "shuffled or sorted by force read as dozens of load cycles)";
}

void read_strip_geometry(const Curve& curve, ForceCurve& out) {
  const auto metre = [&](const std::string& key) {
    const std::string text = curve.metadata(key);
    if (text.empty()) return 0.0;
    try {
      const double v = std::stod(text);
      return std::isfinite(v) && v > 0 ? v : 0.0;
    } catch (const std::exception&) {
      return 0.0;
    }
  };
  out.strip_width_m = metre("strip_width_m");
  out.free_length_m = metre("free_length_m");
}

ForceCurve load_force_curve(const std::filesystem::path& path, const CurveConversion& conversion) {
  const std::string file = path.string();
  const Curve curve = read_csv(path);
  ForceCurve out;
  out.source = file;
  read_strip_geometry(curve, out);
  if (!conversion.displacement_channel.empty()) {
    const Channel* displacement = curve.find(conversion.displacement_channel);
    const Channel* force = curve.find(conversion.force_channel);
    if (!displacement || !force)
      throw InputError(file, "expected the channels " + conversion.displacement_channel + " and " +
                                 conversion.force_channel + " (--columns), found: " + columns_of(curve));
    out.u = checked_si(*displacement, Dimension::Length, file, "a displacement");
    out.f = checked_si(*force, Dimension::Force, file, "a force");
    validate_force_curve(out);
    return out;
  }
  const Channel* displacement = find_any(curve, {"displacement", "elongation", "extension"});
  const Channel* force = curve.find("force");
  if (displacement && force) {
    out.u = checked_si(*displacement, Dimension::Length, file, "a displacement");
    out.f = checked_si(*force, Dimension::Force, file, "a force");
  } else if (const Channel* strain = curve.find("strain"); strain && curve.find("stress")) {
    const Channel& stress = curve.channel("stress");
    if (!conversion.gauge_length_m || !conversion.area_m2)
      throw InputError(file, "strain/stress curve: give --gauge-mm and --area-mm2 to turn it into "
                             "displacement and force");
    const auto e = checked_si(*strain, Dimension::Dimensionless, file, "a strain");
    const auto s = checked_si(stress, Dimension::Stress, file, "a stress");
    for (std::size_t i = 0; i < e.size(); ++i) {
      out.u.push_back(e[i] * *conversion.gauge_length_m);
      out.f.push_back(s[i] * *conversion.area_m2);
    }
  } else {
    throw InputError(file, "expected columns displacement_<length unit> and force_<force unit> "
                           "(or strain_1 and stress_<unit>), found: " + columns_of(curve) +
                               "; name other channels with --columns DISPLACEMENT,FORCE (a DEM punch's: "
                               "--columns tool_displacement,tool_force)");
  }
  validate_force_curve(out);
  return out;
}

}  // namespace dtwire::gap
