#include "model_effect.hpp"

namespace dtwire::app {
namespace {

// The junction's fracture of issue 50 (docs/fem_dt.md, "The junction's fracture"): the formed bend
// where the single wire leaves the twist runs out of ductility first. Switched on as the
// Hosford-Coulomb locus with a = 2, c = 0 (Mohr & Marcadet 2015: the strain to fracture is b in
// every stress state, so the indicator is the accumulated plastic strain over b) and a crack band
// of 0.03 mm (the wire snaps within about half a millimetre, as a breaking wire does), replacing
// the model's own failure model; the run goes on through the crack. p = 1 / b (0: the model's own).
constexpr double kCrackOpeningMm = 0.03;

class JunctionFracture : public ModelEffect {
 public:
  std::string name() const override { return "junction_fracture"; }
  std::string unsupported(const ModelContext& context) const override {
    if (const std::string missing = wire_contact_missing(context); !missing.empty()) return missing;
    if (context.value("Material/Failure locus") == "hosford-coulomb" && context.number("Material/Hosford-Coulomb b") > 0.0)
      return "the .prm already carries a Hosford-Coulomb locus (Hosford-Coulomb b = " +
             context.value("Material/Hosford-Coulomb b") +
             "): give the model without it (e.g. --model-set 'Material/Failure locus=johnson-cook')";
    return "";
  }
  void apply(double p, const ModelContext&, PrmDocument& edited) const override {
    if (p <= 0.0) return;
    edited.set("Material/Failure locus", "hosford-coulomb");
    edited.set("Material/Hosford-Coulomb a", "2");
    edited.set("Material/Hosford-Coulomb b", number_text(1.0 / p));
    edited.set("Material/Hosford-Coulomb c", "0");
    edited.set("Material/Softening displacement (mm)", number_text(kCrackOpeningMm));
    edited.set("Material/Stop at failure", "false");
  }
};

}  // namespace

std::unique_ptr<ModelEffect> make_junction_fracture() { return std::make_unique<JunctionFracture>(); }

}  // namespace dtwire::app
