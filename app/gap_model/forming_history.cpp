#include <filesystem>

#include "model_effect.hpp"

namespace dtwire::app {
namespace {

// The double twist as made (fem/src/forming_history.hpp): each fibre bent from straight wire
// into the mesh's axis with p times its bending strain, then released; p = 0 is the tight,
// stress-free model.
class FormingHistory : public ModelEffect {
 public:
  std::string name() const override { return "forming_history"; }
  std::string unsupported(const ModelContext& context) const override {
    if (const std::string missing = wire_contact_missing(context); !missing.empty()) return missing;
    const std::string mesh = context.value("Geometry/Mesh file"), axis = context.value("As made/Axis file");
    const auto file = axis.empty() ? (context.directory / mesh).replace_extension(".axis.csv") : context.directory / axis;
    return std::filesystem::is_regular_file(file)
               ? ""
               : "no axis file " + file.string() + " beside the mesh (`dtwire mesh dt -o X.msh` writes X.axis.csv)";
  }
  void apply(double p, const ModelContext&, PrmDocument& edited) const override {
    edited.set("As made/Forming history", p > 0.0 ? "true" : "false");
    edited.set("As made/Forming scale", number_text(p));
    edited.set("As made/State file", "");  // formed anew at this scale, not read from a saved state
    edited.set("As made/Twisted pair state", "");  // the scale is the bending forming's, everywhere
  }
};

}  // namespace

std::unique_ptr<ModelEffect> make_forming_history() { return std::make_unique<FormingHistory>(); }

}  // namespace dtwire::app
