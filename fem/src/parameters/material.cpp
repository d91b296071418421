// The .prm reader of one concern (parameters_reading.hpp): Material: elasticity, hardening, failure locus; Formulation: the element.
#include <deal.II/base/parameter_handler.h>

#include <cmath>
#include <sstream>

#include "dtwire/core/error.hpp"
#include "parameters_reading.hpp"

namespace dtwire::fem::prm_reading {

using dealii::ParameterHandler;
namespace Patterns = dealii::Patterns;

void declare_material(ParameterHandler& prm) {
  prm.enter_subsection("Material");
  prm.declare_entry("Young modulus (MPa)", "200000", Patterns::Double(0.0), "");
  prm.declare_entry("Poisson ratio", "0.3", Patterns::Double(-1.0, 0.5), "");
  prm.declare_entry("Hardening law", "linear", Patterns::Selection("linear|voce|swift|table"), "");
  prm.declare_entry("Yield stress (MPa)", "250", Patterns::Double(0.0), "linear, voce");
  prm.declare_entry("Hardening modulus (MPa)", "0", Patterns::Double(), "linear, voce: linear term");
  prm.declare_entry("Saturation stress (MPa)", "0", Patterns::Double(0.0), "voce");
  prm.declare_entry("Saturation rate", "0", Patterns::Double(0.0), "voce");
  prm.declare_entry("Swift coefficient (MPa)", "0", Patterns::Double(0.0), "swift: K");
  prm.declare_entry("Swift offset", "0.002", Patterns::Double(0.0), "swift: eps0");
  prm.declare_entry("Swift exponent", "0.2", Patterns::Double(0.0), "swift: n");
  prm.declare_entry("Hardening table", "", Patterns::Anything(),
                    "table: comma-separated plastic_strain:true_stress_MPa pairs");
  prm.declare_entry("Failure d1", "0", Patterns::Double(), "Johnson-Cook eps_f = d1 + d2 exp(d3 eta); 0, 0: off");
  prm.declare_entry("Failure d2", "0", Patterns::Double(), "");
  prm.declare_entry("Failure d3", "0", Patterns::Double(), "");
  prm.declare_entry("Failure shear ductility ratio", "1", Patterns::Double(0.01, 1.0),
                    "s: strain to failure in shear (Lode angle parameter 0) over that in axisymmetric "
                    "tension at the same triaxiality, eps_f = JC(eta) (s + (1 - s) theta^2); 1: Johnson-Cook");
  prm.declare_entry("Failure locus", "johnson-cook", Patterns::Selection("johnson-cook|hosford-coulomb"),
                    "johnson-cook: Failure d1-d3 and the shear ductility ratio; hosford-coulomb: Mohr & "
                    "Marcadet (2015) with Hosford-Coulomb a, b, c, n");
  prm.declare_entry("Hosford-Coulomb a", "2", Patterns::Double(1.0), "Hosford exponent (2: von Mises, 1: Tresca)");
  prm.declare_entry("Hosford-Coulomb b", "0", Patterns::Double(0.0),
                    "strain to fracture in uniaxial and equibiaxial tension; 0: off");
  prm.declare_entry("Hosford-Coulomb c", "0", Patterns::Double(0.0), "friction coefficient (normal stress weight)");
  prm.declare_entry("Hosford-Coulomb n", "0.1", Patterns::Double(0.0),
                    "stress-to-strain transformation exponent (Mohr & Marcadet 2015: 0.1)");
  prm.declare_entry("Softening displacement (mm)", "0", Patterns::Double(0.0),
                    "u_f: after the indicator reaches 1 the stress falls to zero over a crack opening u_f "
                    "(crack band, w grows by d(alpha) h / u_f); 0: the indicator only, no softening");
  prm.declare_entry("Nonlocal radius (mm)", "0", Patterns::Double(0.0),
                    "R: the crack starts where the average of the indicator over a ball of radius R "
                    "(bell-shaped weight, one wire) reaches 1; 0: where the indicator itself does");
  prm.declare_entry("Largest softening", "0.99", Patterns::Double(0.0, 1.0),
                    "w_max: a cracked point keeps 1 - w_max of its stress (a solvable system)");
  prm.declare_entry("Stop at failure", "true", Patterns::Bool(),
                    "end the run when the indicator reaches 1 (with softening: when the force has "
                    "fallen to the Failure stop force fraction of its peak)");
  prm.declare_entry("Failure stop force fraction", "0.1", Patterns::Double(0.0, 1.0),
                    "with softening: the break detection of a tensile machine, a drop to this fraction "
                    "of the largest force");
  prm.declare_entry("Kinematic modulus (MPa)", "0", Patterns::Double(0.0),
                    "Armstrong-Frederick C (0: no kinematic hardening), combined with the isotropic law");
  prm.declare_entry("Kinematic saturation rate", "0", Patterns::Double(0.0),
                    "Armstrong-Frederick gamma: backstress saturates at C/gamma (0: linear Prager)");
  prm.leave_subsection();
}

void read_material(const Source& source, Parameters& p) {
  ParameterHandler& prm = source.prm;
  const std::string& name = source.name;
  prm.enter_subsection("Material");
  p.material.young = prm.get_double("Young modulus (MPa)") * 1e6;
  p.material.poisson = prm.get_double("Poisson ratio");
  source.require(p.material.young > 0.0, "Material", "Young modulus (MPa)", "a modulus > 0");
  source.require(p.material.poisson > -1.0 && p.material.poisson < 0.5, "Material", "Poisson ratio",
          "a ratio in (-1, 0.5) exclusive (0.5: incompressible, no bulk modulus)");
  auto& h = p.material.hardening;
  h.law = parse_hardening_law(prm.get("Hardening law"));
  p.material.failure.d1 = prm.get_double("Failure d1");
  p.material.failure.d2 = prm.get_double("Failure d2");
  p.material.failure.d3 = prm.get_double("Failure d3");
  p.material.failure.shear_ductility_ratio = prm.get_double("Failure shear ductility ratio");
  auto& f = p.material.failure;
  f.locus = prm.get("Failure locus") == "hosford-coulomb" ? FractureLocus::hosford_coulomb : FractureLocus::johnson_cook;
  f.hc_a = prm.get_double("Hosford-Coulomb a");
  f.hc_b = prm.get_double("Hosford-Coulomb b");
  f.hc_c = prm.get_double("Hosford-Coulomb c");
  f.hc_n = prm.get_double("Hosford-Coulomb n");
  source.require(f.hc_n > 0.0, "Material", "Hosford-Coulomb n", "an exponent > 0 (Mohr & Marcadet 2015: 0.1)");
  f.softening_displacement = prm.get_double("Softening displacement (mm)") * 1e-3;
  f.largest_softening = prm.get_double("Largest softening");
  f.nonlocal_radius = prm.get_double("Nonlocal radius (mm)") * 1e-3;
  source.require(f.nonlocal_radius == 0.0 || f.enabled(), "Material", "Nonlocal radius (mm)",
                 "0 unless a failure locus is on (Failure d1/d2 or Hosford-Coulomb b)");
  source.require(f.largest_softening > 0.0 && f.largest_softening < 1.0, "Material", "Largest softening",
                 "a fraction in (0, 1) exclusive (1 leaves a cracked cell without stiffness)");
  source.require(f.softening_displacement == 0.0 || f.enabled(), "Material", "Softening displacement (mm)",
                 "0 unless a failure locus is on (Failure d1/d2 or Hosford-Coulomb b)");
  p.material.stop_at_failure = prm.get_bool("Stop at failure");
  p.material.stop_force_fraction = prm.get_double("Failure stop force fraction");
  p.material.kinematic.modulus = prm.get_double("Kinematic modulus (MPa)") * 1e6;
  p.material.kinematic.saturation_rate = prm.get_double("Kinematic saturation rate");
  h.yield_stress = prm.get_double("Yield stress (MPa)") * 1e6;
  h.linear_modulus = prm.get_double("Hardening modulus (MPa)") * 1e6;
  h.saturation_stress = prm.get_double("Saturation stress (MPa)") * 1e6;
  h.saturation_rate = prm.get_double("Saturation rate");
  h.swift_coefficient = prm.get_double("Swift coefficient (MPa)") * 1e6;
  h.swift_offset = prm.get_double("Swift offset");
  h.swift_exponent = prm.get_double("Swift exponent");
  for (const auto& [strain, stress] : source.pairs("Material", "Hardening table")) {
    h.table_plastic_strain.push_back(strain);
    h.table_stress.push_back(stress * 1e6);
  }
  try {
    IsotropicHardening check(h);
  } catch (const std::invalid_argument& e) {
    throw InputError(name, std::string("subsection Material: ") + e.what());
  }
  prm.leave_subsection();
}

void declare_formulation(ParameterHandler& prm) {
  prm.enter_subsection("Formulation");
  prm.declare_entry("Element", "fbar", Patterns::Selection("fbar|displacement"),
                    "fbar: locking-free mean-dilatation F-bar; displacement: plain Q1");
  prm.declare_entry("Polynomial degree", "1", Patterns::Integer(1, 2), "");
  prm.leave_subsection();
}

void read_formulation(const Source& source, Parameters& p) {
  ParameterHandler& prm = source.prm;
  prm.enter_subsection("Formulation");
  p.formulation.fbar = prm.get("Element") == "fbar";
  p.formulation.degree = prm.get_integer("Polynomial degree");
  prm.leave_subsection();
}

}  // namespace dtwire::fem::prm_reading
