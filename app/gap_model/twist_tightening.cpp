#include "model_effect.hpp"

namespace dtwire::app {
namespace {

// Extra clearance of the interweavement (mm) that the twist closes before the wires bear.
class TwistTightening : public ModelEffect {
 public:
  std::string name() const override { return "twist_tightening"; }
  std::string unsupported(const ModelContext& context) const override {
    return wire_contact_missing(context);
  }
  void apply(double p, const ModelContext&, PrmDocument& edited) const override {
    edited.set("Wire contact/Gap offset (mm)", number_text(p));
  }
};

}  // namespace

std::unique_ptr<ModelEffect> make_twist_tightening() { return std::make_unique<TwistTightening>(); }

}  // namespace dtwire::app
