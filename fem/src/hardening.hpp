#pragma once
// Isotropic hardening laws: flow stress sigma_y(alpha) and its slope, alpha the equivalent
// (logarithmic) plastic strain. Stresses in Pa. Plain C++, no deal.II.
#include <string>
#include <vector>

namespace dtwire::fem {

enum class HardeningLaw { linear, voce, swift, table };

struct HardeningParameters {
  HardeningLaw law = HardeningLaw::linear;
  double yield_stress = 0.0;       // linear, voce: sigma_0
  double linear_modulus = 0.0;     // linear, voce: H (the linear term)
  double saturation_stress = 0.0;  // voce: sigma_inf
  double saturation_rate = 0.0;    // voce: delta
  double swift_coefficient = 0.0;  // swift: K in K (eps0 + alpha)^n
  double swift_offset = 0.0;       // swift: eps0 > 0
  double swift_exponent = 0.0;     // swift: n
  std::vector<double> table_plastic_strain;  // table: strictly increasing, first 0
  std::vector<double> table_stress;          // table: true stress at those strains
};

HardeningLaw parse_hardening_law(const std::string& name);  // throws std::invalid_argument

class IsotropicHardening {
 public:
  // Throws std::invalid_argument naming the bad parameter.
  explicit IsotropicHardening(HardeningParameters parameters);

  double flow_stress(double alpha) const;
  double slope(double alpha) const;  // d sigma_y / d alpha (right derivative at table knots)
  const HardeningParameters& parameters() const { return p_; }

 private:
  std::size_t table_segment(double alpha) const;
  HardeningParameters p_;
};

}  // namespace dtwire::fem
