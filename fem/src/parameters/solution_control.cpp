// The .prm reader of one concern (parameters_reading.hpp): Load stepping and Newton: how each step is solved.
#include <deal.II/base/parameter_handler.h>

#include <cmath>
#include <sstream>

#include "dtwire/core/error.hpp"
#include "parameters_reading.hpp"

namespace dtwire::fem::prm_reading {

using dealii::ParameterHandler;
namespace Patterns = dealii::Patterns;

void declare_load_stepping(ParameterHandler& prm) {
  prm.enter_subsection("Load stepping");
  prm.declare_entry("Initial step", "0.01", Patterns::Double(0.0), "pseudo-time");
  prm.declare_entry("Minimum step", "1e-6", Patterns::Double(0.0), "");
  prm.declare_entry("Maximum step", "0.05", Patterns::Double(0.0), "");
  prm.declare_entry("Growth factor", "1.5", Patterns::Double(1.0), "");
  prm.declare_entry("Cutback factor", "0.5", Patterns::Double(0.0, 1.0), "");
  prm.declare_entry("Easy iterations", "4", Patterns::Integer(1), "");
  prm.leave_subsection();
}

void read_load_stepping(const Source& source, Parameters& p) {
  ParameterHandler& prm = source.prm;
  const std::string& name = source.name;
  prm.enter_subsection("Load stepping");
  p.stepping.initial_step = prm.get_double("Initial step");
  p.stepping.minimum_step = prm.get_double("Minimum step");
  p.stepping.maximum_step = prm.get_double("Maximum step");
  p.stepping.growth_factor = prm.get_double("Growth factor");
  p.stepping.cutback_factor = prm.get_double("Cutback factor");
  p.stepping.easy_iterations = prm.get_integer("Easy iterations");
  source.require(p.stepping.minimum_step > 0.0, "Load stepping", "Minimum step", "a pseudo-time step > 0");
  source.require(p.stepping.cutback_factor > 0.0 && p.stepping.cutback_factor < 1.0, "Load stepping", "Cutback factor",
          "a factor in (0, 1) exclusive");
  if (!(p.stepping.minimum_step <= p.stepping.initial_step && p.stepping.initial_step <= p.stepping.maximum_step))
    throw InputError(name, "Load stepping: expected Minimum step <= Initial step <= Maximum step");
  prm.leave_subsection();
}

void declare_newton(ParameterHandler& prm) {
  prm.enter_subsection("Newton");
  prm.declare_entry("Maximum iterations", "15", Patterns::Integer(1), "");
  prm.declare_entry("Relative tolerance", "1e-10", Patterns::Double(0.0), "");
  prm.declare_entry("Line search", "true", Patterns::Bool(), "");
  prm.declare_entry("Maximum line search steps", "5", Patterns::Integer(0), "");
  prm.declare_entry("Linear solver", "direct", Patterns::Selection("direct|gmres-amg|lagged-lu"),
                    "direct: MUMPS; gmres-amg: GMRES with PETSc GAMG and the rigid-body modes (large problems); "
                    "lagged-lu: GMRES preconditioned by the MUMPS factors of an earlier tangent, factorised anew "
                    "when GMRES needs more than Lagged LU iterations");
  prm.declare_entry("Lagged LU iterations", "15", Patterns::Integer(1, 200),
                    "lagged-lu: GMRES iterations before the tangent is factorised anew");
  prm.declare_entry("Linear tolerance", "1e-12", Patterns::Double(0.0), "gmres-amg: relative residual");
  prm.declare_entry("Maximum linear iterations", "2000", Patterns::Integer(1), "gmres-amg");
  prm.declare_entry("Tangent reuse contraction", "0", Patterns::Double(0.0, 1.0),
                    "direct solver: keep the last factorisation (modified Newton) while each iteration "
                    "reduced the residual below this fraction of the previous one; 0: a fresh tangent "
                    "every iteration (full Newton)");
  prm.leave_subsection();
}

void read_newton(const Source& source, Parameters& p) {
  ParameterHandler& prm = source.prm;
  prm.enter_subsection("Newton");
  p.newton.maximum_iterations = prm.get_integer("Maximum iterations");
  p.newton.relative_tolerance = prm.get_double("Relative tolerance");
  p.newton.line_search = prm.get_bool("Line search");
  p.newton.maximum_line_search_steps = prm.get_integer("Maximum line search steps");
  p.newton.krylov = prm.get("Linear solver") == "gmres-amg";
  if (prm.get("Linear solver") == "lagged-lu") p.newton.lagged_lu_iterations = prm.get_integer("Lagged LU iterations");
  p.newton.linear_tolerance = prm.get_double("Linear tolerance");
  source.require(p.newton.relative_tolerance > 0.0, "Newton", "Relative tolerance", "a tolerance > 0");
  p.newton.maximum_linear_iterations = prm.get_integer("Maximum linear iterations");
  p.newton.tangent_reuse_contraction = prm.get_double("Tangent reuse contraction");
  prm.leave_subsection();
}

}  // namespace dtwire::fem::prm_reading
