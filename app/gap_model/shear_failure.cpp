#include "model_effect.hpp"

namespace dtwire::app {
namespace {

// The shear branch of the failure locus (docs/fem.md), lowered to p of the tensile ductility.
class ShearFailure : public ModelEffect {
 public:
  std::string name() const override { return "shear_failure"; }
  std::string unsupported(const ModelContext& context) const override {
    return context.number("Material/Failure d1") != 0.0 || context.number("Material/Failure d2") != 0.0
               ? ""
               : "the .prm has no failure locus (Failure d1, d2) whose shear branch to lower";
  }
  void apply(double p, const ModelContext&, PrmDocument& edited) const override {
    edited.set("Material/Failure shear ductility ratio", number_text(p));
  }
};

}  // namespace

std::unique_ptr<ModelEffect> make_shear_failure() { return std::make_unique<ShearFailure>(); }

}  // namespace dtwire::app
