#include <sstream>

#include "model_effect.hpp"

namespace dtwire::app {

const std::vector<std::unique_ptr<ModelEffect>>& model_effects() {
  static const std::vector<std::unique_ptr<ModelEffect>> all = [] {
    std::vector<std::unique_ptr<ModelEffect>> list;
    list.push_back(make_geometry_imperfection());
    list.push_back(make_residual_stress());
    list.push_back(make_wire_friction());
    list.push_back(make_twist_tightening());
    list.push_back(make_shear_failure());
    list.push_back(make_coating_slip());
    list.push_back(make_forming_history());
    list.push_back(make_junction_fracture());
    return list;
  }();
  return all;
}

const ModelEffect* find_model_effect(const std::string& name) {
  for (const auto& effect : model_effects())
    if (effect->name() == name) return effect.get();
  return nullptr;
}

std::string wire_contact_missing(const ModelContext& context) {
  return context.value("Wire contact/Enabled") == "true"
             ? ""
             : "the .prm has no enabled `subsection Wire contact` (a DT model, docs/fem_dt.md)";
}

std::string number_text(double value) {
  std::ostringstream s;
  s.precision(10);
  s << value;
  return s.str();
}

}  // namespace dtwire::app
