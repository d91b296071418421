#pragma once
// A simulator turns parameter values into a curve: an FE virtual experiment, a DEM contact law
// replaying a load path, or an analytic model. No deal.II types here, so every module can
// implement it.
#include <string>
#include <utility>
#include <vector>

#include "dtwire/calibrate/parameter.hpp"
#include "dtwire/core/curve.hpp"

namespace dtwire::calibrate {

class Simulator {
 public:
  virtual ~Simulator() = default;

  // The curve for these parameter values (SI, by name; the fit passes every fitted parameter).
  // Throws ComputationError when the simulation fails (non-convergence, invalid state): the
  // fit then rejects the step instead of stopping.
  virtual Curve simulate(const ParameterValues& parameters) const = 0;

  // Everything besides the parameters that determines the result (model, load path,
  // settings), as text; its SHA-256 keys the results cache.
  virtual std::string identity() const = 0;

  // True if simulate() may run concurrently on one object. Perturbed runs of a simulator
  // that is not thread safe run one after another.
  virtual bool thread_safe() const { return true; }

  // The channels simulate() returns, with their dimensions, when known before a run (empty:
  // unknown, e.g. an external program), so that a fit definition is checked when it is read.
  virtual std::vector<std::pair<std::string, Dimension>> channels() const { return {}; }

  // The parameter names simulate() reads, when known before a run (empty: unknown), so that a
  // fitted parameter no simulator reads (a misspelling) is refused when the fit is read.
  virtual std::vector<std::string> parameter_names() const { return {}; }
};

}  // namespace dtwire::calibrate
