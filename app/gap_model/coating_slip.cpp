#include <sstream>

#include "dtwire/core/error.hpp"
#include "dtwire/core/region_ids.hpp"
#include "dtwire/gap/effects.hpp"
#include "dtwire/meshes/msh_reader.hpp"
#include "model_effect.hpp"

namespace dtwire::app {
namespace {

std::vector<int> id_list(const ModelContext& context, const std::string& entry) {
  std::vector<int> ids;
  std::stringstream s(context.value(entry));
  for (std::string item; std::getline(s, item, ',');) {
    if (item.find_first_not_of(" \t") == std::string::npos) continue;
    const auto id = parse_number(item);
    if (!id || *id < 0 || *id != static_cast<int>(*id)) {
      const auto* e = context.model.find(entry);
      throw InputError(context.model.source(), e ? e->line : 0, 0,
                       "'" + entry + "': expected boundary ids (whole numbers), found '" + item + "'");
    }
    ids.push_back(static_cast<int>(*id));
  }
  return ids;
}

// Slip of the wire's coating in the grips: the top grips' bond slides at a force of p x the
// clamped model's peak force. Needs grips held by the lateral grip surfaces of a mesh file
// (ids 10 w + 4 and 10 w + 5 of `dtwire mesh sw|dt`, docs/meshes.md) with clamped ends under
// displacement control.
class CoatingSlip : public ModelEffect {
 public:
  std::string name() const override { return "coating_slip"; }
  std::string unsupported(const ModelContext& context) const override {
    if (context.value("Geometry/Mesh file").empty())
      return "the .prm has no mesh file with grip surfaces (`dtwire mesh sw|dt --grip-length`)";
    if (context.value("Boundary conditions/Bottom end") != "clamped" ||
        context.value("Boundary conditions/Top end") != "clamped" ||
        context.value("Boundary conditions/Control") != "displacement")
      return "the bonded grip needs clamped ends under displacement control";
    for (const char* entry : {"Boundary conditions/Top boundary ids", "Boundary conditions/Bottom boundary ids"})
      for (int id : id_list(context, entry))
        if (!regions::is_grip_lateral_boundary(id))
          return "the grips are not held by their lateral surfaces (Bottom / Top boundary ids " +
                 std::to_string(regions::kWireAStartGrip) + ", " + std::to_string(regions::kWireAEndGrip) + ", " +
                 std::to_string(regions::kWireBStartGrip) + ", " + std::to_string(regions::kWireBEndGrip) + ")";
    if (!(top_grip_area(context) > 0.0)) return "no face of the mesh file carries the Top boundary ids";
    return "";
  }
  void apply(double p, const ModelContext& context, PrmDocument& edited) const override {
    // At the neutral value (1: the bond would carry the peak) the grips stay as the .prm has them.
    if (p >= gap::find_effect(name()).neutral) return;
    if (!(context.grip.top_area > 0.0 && context.grip.reference_force > 0.0))
      throw ComputationError("gap --model: coating_slip needs the grips' area and the model's peak force");
    // Penalty 10 E / h: below its strength the bond is the clamp within 0.5 % of the stiffness
    // (docs/fem.md) at the cost of factor 1; a .prm with bonded grips keeps its own.
    if (context.value("Boundary conditions/Grip interface") != "bonded") {
      edited.set("Boundary conditions/Grip interface", "bonded");
      edited.set("Boundary conditions/Grip bond stiffness factor", "10");
    }
    edited.set("Boundary conditions/Grip bond strength (MPa)",
               number_text(p * context.grip.reference_force / context.grip.top_area * 1e-6));
  }
};

}  // namespace

std::unique_ptr<ModelEffect> make_coating_slip() { return std::make_unique<CoatingSlip>(); }

double top_grip_area(const ModelContext& context) {
  std::filesystem::path mesh = context.value("Geometry/Mesh file");
  if (mesh.is_relative()) mesh = context.directory / mesh;
  return meshes::msh_surface_area(mesh, id_list(context, "Boundary conditions/Top boundary ids"));
}

}  // namespace dtwire::app
