#include <sstream>
#include <utility>
#include <vector>

#include "dtwire/core/error.hpp"
#include "model_effect.hpp"

namespace dtwire::app {
namespace {

// Plastic pre-strain at twist_plasticity_1 = 1: the mean bending strain of a 2.7 mm wire wound
// on its partner in the double twist (helix radius 1.35 mm, 3 half turns over 40 mm: curvature
// 0.068 /mm, surface strain 0.092, section mean of |y| 4R/(3 pi) -> 0.04).
constexpr double kTwistingPlasticStrain = 0.04;

// Hardening table "e:s, ..." of `entry` read as numbers (errors name the file and line).
std::vector<std::pair<double, double>> table_points(const ModelContext& context, const std::string& entry) {
  const std::string table = context.value(entry);
  std::vector<std::pair<double, double>> points;
  std::stringstream s(table);
  for (std::string item; std::getline(s, item, ',');) {
    const auto colon = item.find(':');
    const auto strain = parse_number(item.substr(0, colon)), stress = colon == std::string::npos
                                                                          ? std::nullopt
                                                                          : parse_number(item.substr(colon + 1));
    if (!strain || !stress) {
      const auto* e = context.model.find(entry);
      throw InputError(context.model.source(), e ? e->line : 0, 0,
                       "'" + entry + "': expected 'strain:stress' pairs, found '" + item + "'");
    }
    points.emplace_back(*strain, *stress);
  }
  if (points.size() < 2) throw ComputationError("residual_stress: the hardening table needs two points");
  return points;
}

// The table shifted by a plastic pre-strain a0: sigma'(e) = sigma(e + a0).
std::string shifted_table(const std::vector<std::pair<double, double>>& points, double a0) {
  const auto stress_at = [&](double e) {  // piecewise linear, last slope continued
    std::size_t k = 1;
    while (k + 1 < points.size() && points[k].first < e) ++k;
    const auto& [e0, s0] = points[k - 1];
    const auto& [e1, s1] = points[k];
    return s0 + (s1 - s0) * (e - e0) / (e1 - e0);
  };
  std::string out = "0:" + number_text(stress_at(a0));
  int kept = 0;
  for (const auto& [e, sigma] : points)
    if (e > a0) {
      out += ", " + number_text(e - a0) + ":" + number_text(sigma);
      ++kept;
    }
  if (kept == 0) out += ", 1:" + number_text(stress_at(a0 + 1.0));
  return out;
}

// Residual stresses of the twisting, as the plastic pre-strain p x 0.04 they leave: the
// hardening curve starts that far along.
class ResidualStress : public ModelEffect {
 public:
  std::string name() const override { return "residual_stress"; }
  std::string unsupported(const ModelContext& context) const override {
    const std::string law = context.value("Material/Hardening law");
    return law == "table" || law == "linear" ? "" : "plastic pre-strain only for table and linear hardening";
  }
  void apply(double p, const ModelContext& context, PrmDocument& edited) const override {
    const double a0 = p * kTwistingPlasticStrain;
    if (context.value("Material/Hardening law") == "table") {
      edited.set("Material/Hardening table", shifted_table(table_points(context, "Material/Hardening table"), a0));
    } else {
      const double yield = context.number("Material/Yield stress (MPa)");
      edited.set("Material/Yield stress (MPa)",
                 number_text(yield + context.number("Material/Hardening modulus (MPa)") * a0));
    }
  }
};

}  // namespace

std::unique_ptr<ModelEffect> make_residual_stress() { return std::make_unique<ResidualStress>(); }

}  // namespace dtwire::app
