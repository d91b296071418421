#include "model_effect.hpp"

namespace dtwire::app {
namespace {

// The DT model's Coulomb coefficient between the wires (not the rigid tools' friction).
class WireFriction : public ModelEffect {
 public:
  std::string name() const override { return "wire_friction"; }
  std::string unsupported(const ModelContext& context) const override {
    return wire_contact_missing(context);
  }
  void apply(double p, const ModelContext&, PrmDocument& edited) const override {
    edited.set("Wire contact/Friction coefficient", number_text(p));
  }
};

}  // namespace

std::unique_ptr<ModelEffect> make_wire_friction() { return std::make_unique<WireFriction>(); }

}  // namespace dtwire::app
