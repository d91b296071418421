#pragma once
// The FE runner of `dtwire gap --model M.prm`: re-runs the experiment through `dtwire run` as a
// subprocess (calibrate's CommandSimulator) on a copy of the .prm with the model-only effects
// switched on through its parameters. gap does not depend on fem; this lives in app/.
#include <filesystem>
#include <map>
#include <string>

#include "dtwire/gap/effects.hpp"

namespace dtwire::app {

// Plastic pre-strain of the `residual_stress` effect at twist_plasticity_1 = 1: the mean
// bending strain of a 2.7 mm wire wound on its partner in the double twist (helix radius
// 1.35 mm, 3 half turns over 40 mm: curvature 0.068 /mm, surface strain 0.092, section mean
// of |y| 4R/(3 pi) -> 0.04).
inline constexpr double kTwistingPlasticStrain = 0.04;

struct FeModel {
  gap::ModelRunner run;  // cached by the edited .prm text; each new run prints one line
  std::map<std::string, std::string> unsupported;  // model-only effect -> reason
  int* runs = nullptr;                              // FE runs done so far
  std::filesystem::path work;                       // run directories (removed after success)
};

// Reads the .prm (InputError naming it when missing). Runs go to `work` (a fresh temp
// directory when empty); each run's directory is removed after success.
FeModel make_fe_model(const std::filesystem::path& prm, std::filesystem::path work = {});

// What `coating_slip` needs to turn its bond capacity (a fraction of the clamped model's peak
// force) into the bond strength of the .prm: the bonded area of the top grips (m^2, from the mesh
// file) and the clamped model's largest force magnitude (N).
struct GripBond {
  double top_area = 0.0;
  double reference_force = 0.0;
};

// The .prm text with the effects switched on (exposed for tests). Throws ComputationError for
// an effect the .prm cannot express.
std::string edit_prm(const std::string& text, const std::vector<gap::AppliedEffect>& effects,
                     const std::filesystem::path& prm_directory, const GripBond& grip = {});

}  // namespace dtwire::app
