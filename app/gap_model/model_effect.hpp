#pragma once
// The model-only effects of `dtwire gap --model M.prm`: each switches an effect on in the FE
// experiment through the .prm entries that express it (one effect per file). They read the
// user's .prm as a typed document with the solver's declared defaults behind it, so an entry
// the file leaves out has fem's default, and a value that is not a number is an error naming
// file:line.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "dtwire/core/prm_document.hpp"

namespace dtwire::app {

// What `coating_slip` needs to turn its bond capacity (a fraction of the clamped model's peak
// force) into the bond strength of the .prm: the bonded area of the top grips (m^2, from the mesh
// file) and the clamped model's largest force magnitude (N).
struct GripBond {
  double top_area = 0.0;
  double reference_force = 0.0;
};

struct ModelContext {
  const PrmDocument& model;     // the .prm as the user wrote it
  const PrmDocument& declared;  // the solver's entries with their defaults (`dtwire parameters`)
  std::filesystem::path directory;  // of the .prm: relative mesh files are found from here
  GripBond grip;

  std::string value(const std::string& path) const { return model.value(path, &declared); }
  double number(const std::string& path) const { return model.number(path, &declared); }
};

class ModelEffect {
 public:
  virtual ~ModelEffect() = default;
  virtual std::string name() const = 0;
  // Why this .prm cannot show the effect, or "" when it can.
  virtual std::string unsupported(const ModelContext& context) const = 0;
  // Switches the effect on at strength p (the gap effect's parameter) in `edited`.
  virtual void apply(double p, const ModelContext& context, PrmDocument& edited) const = 0;
};

// Every model-only effect; nullptr for a name that has none.
const ModelEffect* find_model_effect(const std::string& name);
const std::vector<std::unique_ptr<ModelEffect>>& model_effects();

std::unique_ptr<ModelEffect> make_geometry_imperfection();
std::unique_ptr<ModelEffect> make_residual_stress();
std::unique_ptr<ModelEffect> make_wire_friction();
std::unique_ptr<ModelEffect> make_twist_tightening();
std::unique_ptr<ModelEffect> make_shear_failure();
std::unique_ptr<ModelEffect> make_coating_slip();
std::unique_ptr<ModelEffect> make_forming_history();
std::unique_ptr<ModelEffect> make_junction_fracture();

// coating_slip: the bonded area of the top grips (m^2), from the faces of the .prm's mesh file
// that carry its Top boundary ids.
double top_grip_area(const ModelContext& context);

// Why a DT effect cannot be shown: "" when the .prm enables the contact between the wires.
std::string wire_contact_missing(const ModelContext& context);

// Shortest text that reads back as the same number to 10 digits.
std::string number_text(double value);

}  // namespace dtwire::app
