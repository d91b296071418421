#include <algorithm>
#include <cmath>

#include "model_effect.hpp"

namespace dtwire::app {
namespace {

// Hosford-Coulomb (Mohr & Marcadet 2015, eq. 20; fem/src/j2_log_plasticity.hpp) in pure shear
// (triaxiality 0, Lode angle parameter 0: principal stresses 1/sqrt3, 0, -1/sqrt3 at unit von
// Mises stress): the Coulomb term vanishes and eps_f / b = ((1 + c) / g_a)^(1/n) with the
// Hosford term g_a = ((2 (1/sqrt3)^a + (2/sqrt3)^a) / 2)^(1/a), 2/sqrt3 at a = 1, 1 at a = 2.
double shear_over_uniaxial(double a, double c, double n) {
  const double hosford = std::pow(0.5 * (2.0 * std::pow(1.0 / std::sqrt(3.0), a) + std::pow(2.0 / std::sqrt(3.0), a)),
                                  1.0 / a);
  return std::pow((1.0 + c) / hosford, 1.0 / n);
}

// The Hosford exponent in [1, 2] whose shear ductility is `ratio` times the uniaxial one (the
// ratio falls monotonically as a falls); the range's end where the ratio lies beyond it.
double hosford_exponent_for(double ratio, double c, double n) {
  double low = 1.0, high = 2.0;
  if (ratio <= shear_over_uniaxial(low, c, n)) return low;
  if (ratio >= shear_over_uniaxial(high, c, n)) return high;
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (low + high);
    (shear_over_uniaxial(mid, c, n) < ratio ? low : high) = mid;
  }
  return 0.5 * (low + high);
}

// The shear branch of the failure locus (docs/fem.md), lowered to p of the tensile ductility:
// the Johnson-Cook locus's `Failure shear ductility ratio`, or the Hosford-Coulomb exponent a
// that gives that ratio at the model's c and n (the junction fracture of issue 50).
class ShearFailure : public ModelEffect {
 public:
  std::string name() const override { return "shear_failure"; }
  std::string unsupported(const ModelContext& context) const override {
    if (hosford_coulomb(context))
      return context.number("Material/Hosford-Coulomb b") > 0.0
                 ? ""
                 : "the .prm's Hosford-Coulomb locus is off (Hosford-Coulomb b = 0): no shear branch to lower";
    return context.number("Material/Failure d1") != 0.0 || context.number("Material/Failure d2") != 0.0
               ? ""
               : "the .prm has no failure locus (Failure d1, d2 or Hosford-Coulomb b) whose shear branch to lower";
  }
  void apply(double p, const ModelContext& context, PrmDocument& edited) const override {
    if (!hosford_coulomb(context)) {
      edited.set("Material/Failure shear ductility ratio", number_text(p));
      return;
    }
    const double a = hosford_exponent_for(p, context.number("Material/Hosford-Coulomb c"),
                                          context.number("Material/Hosford-Coulomb n"));
    edited.set("Material/Hosford-Coulomb a", number_text(a));
  }

 private:
  static bool hosford_coulomb(const ModelContext& context) {
    return context.value("Material/Failure locus") == "hosford-coulomb";
  }
};

}  // namespace

std::unique_ptr<ModelEffect> make_shear_failure() { return std::make_unique<ShearFailure>(); }

}  // namespace dtwire::app
