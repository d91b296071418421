#include "dtwire/calibrate/parameter.hpp"

#include <cmath>
#include <set>
#include <stdexcept>

namespace dtwire::calibrate {

double ParameterDefinition::effective_scale() const {
  if (scale > 0) return scale;
  if (initial != 0.0) return std::abs(initial);
  if (upper > lower) return upper - lower;
  return 1.0;
}

double ParameterDefinition::to_coordinate(double value) const {
  return logarithmic ? std::log(value / effective_scale()) : value / effective_scale();
}

double ParameterDefinition::from_coordinate(double z) const {
  return logarithmic ? effective_scale() * std::exp(z) : z * effective_scale();
}

double ParameterDefinition::derivative(double z) const { return logarithmic ? from_coordinate(z) : effective_scale(); }

std::vector<int> offset_bases(const std::vector<ParameterDefinition>& parameters) {
  const int n = static_cast<int>(parameters.size());
  std::vector<int> base(parameters.size(), -1);
  for (int i = 0; i < n; ++i) {
    const ParameterDefinition& p = parameters[static_cast<std::size_t>(i)];
    if (p.offset_from.empty()) continue;
    for (int j = 0; j < n; ++j)
      if (parameters[static_cast<std::size_t>(j)].name == p.offset_from) base[static_cast<std::size_t>(i)] = j;
    const std::string where = "parameter '" + p.name + "': offset_from '" + p.offset_from + "' ";
    if (base[static_cast<std::size_t>(i)] < 0) throw std::invalid_argument(where + "is not a fitted parameter");
    if (base[static_cast<std::size_t>(i)] == i) throw std::invalid_argument(where + "is the parameter itself");
  }
  // A chain longer than n passes a parameter twice: a cycle.
  for (int i = 0; i < n; ++i) {
    std::string chain = parameters[static_cast<std::size_t>(i)].name;
    int steps = 0;
    for (int j = base[static_cast<std::size_t>(i)]; j >= 0; j = base[static_cast<std::size_t>(j)]) {
      chain += " -> " + parameters[static_cast<std::size_t>(j)].name;
      if (j == i || ++steps > n)
        throw std::invalid_argument("parameter '" + parameters[static_cast<std::size_t>(i)].name +
                                    "': offset_from closes a cycle (" + chain + ")");
    }
  }
  return base;
}

void validate(const std::vector<ParameterDefinition>& parameters) {
  if (parameters.empty()) throw std::invalid_argument("no parameters to fit");
  std::set<std::string> names;
  for (const auto& p : parameters) {
    const std::string where = "parameter '" + p.name + "': ";
    if (p.name.empty()) throw std::invalid_argument("a parameter has an empty name");
    if (!names.insert(p.name).second) throw std::invalid_argument(where + "defined twice");
    if (!std::isfinite(p.initial) || !std::isfinite(p.lower) || !std::isfinite(p.upper) ||
        !std::isfinite(p.scale))
      throw std::invalid_argument(where + "initial, lower, upper and scale must be finite");
    if (!(p.lower < p.upper))
      throw std::invalid_argument(where + "expected lower < upper");
    if (p.initial < p.lower || p.initial > p.upper)
      throw std::invalid_argument(where + "initial value outside [lower, upper]");
    if (p.scale < 0) throw std::invalid_argument(where + "scale must be > 0");
    if (p.logarithmic && !(p.lower > 0)) throw std::invalid_argument(where + "logarithmic needs lower > 0");
  }
  offset_bases(parameters);
}

namespace {

// Sums `value` along each parameter's chain of offsets: out_i = value(i) + value(base of i) + ...
template <class Value>
std::vector<double> along_chains(const std::vector<ParameterDefinition>& parameters, const Value& value) {
  const std::vector<int> base = offset_bases(parameters);
  std::vector<double> out(parameters.size());
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    out[i] = value(i);
    for (int j = base[i]; j >= 0; j = base[static_cast<std::size_t>(j)]) out[i] += value(static_cast<std::size_t>(j));
  }
  return out;
}

}  // namespace

std::vector<double> resolve_offsets(const std::vector<ParameterDefinition>& parameters,
                                    const std::vector<double>& values) {
  if (values.size() != parameters.size()) throw std::invalid_argument("resolve_offsets: wrong number of values");
  return along_chains(parameters, [&](std::size_t i) { return values[i]; });
}

std::vector<double> offsets_from_resolved(const std::vector<ParameterDefinition>& parameters,
                                          const std::vector<double>& resolved) {
  if (resolved.size() != parameters.size())
    throw std::invalid_argument("offsets_from_resolved: wrong number of values");
  const std::vector<int> base = offset_bases(parameters);
  std::vector<double> out(resolved);
  for (std::size_t i = 0; i < out.size(); ++i)
    if (base[i] >= 0) out[i] -= resolved[static_cast<std::size_t>(base[i])];
  return out;
}

Eigen::MatrixXd offset_map(const std::vector<ParameterDefinition>& parameters) {
  const std::vector<int> base = offset_bases(parameters);
  const auto n = static_cast<Eigen::Index>(parameters.size());
  Eigen::MatrixXd a = Eigen::MatrixXd::Identity(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (int j = base[static_cast<std::size_t>(i)]; j >= 0; j = base[static_cast<std::size_t>(j)]) a(i, j) = 1.0;
  return a;
}

Eigen::MatrixXd resolve_covariance(const std::vector<ParameterDefinition>& parameters,
                                   const Eigen::MatrixXd& covariance) {
  const auto n = static_cast<Eigen::Index>(parameters.size());
  if (covariance.rows() != n || covariance.cols() != n)
    throw std::invalid_argument("resolve_covariance: the covariance is not n x n");
  const Eigen::MatrixXd a = offset_map(parameters);
  Eigen::MatrixXd out = a * covariance * a.transpose();
  return 0.5 * (out + out.transpose());  // exactly symmetric
}

std::vector<double> resolved_lower(const std::vector<ParameterDefinition>& parameters) {
  return along_chains(parameters, [&](std::size_t i) { return parameters[i].lower; });
}

std::vector<double> resolved_upper(const std::vector<ParameterDefinition>& parameters) {
  return along_chains(parameters, [&](std::size_t i) { return parameters[i].upper; });
}

std::vector<std::optional<double>> resolved_references(const std::vector<ParameterDefinition>& parameters) {
  const std::vector<int> base = offset_bases(parameters);
  std::vector<std::optional<double>> out(parameters.size());
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    out[i] = parameters[i].reference;
    for (int j = base[i]; j >= 0 && out[i]; j = base[static_cast<std::size_t>(j)]) {
      const auto& r = parameters[static_cast<std::size_t>(j)].reference;
      out[i] = r ? std::optional<double>(*out[i] + *r) : std::nullopt;
    }
  }
  return out;
}

std::vector<double> reference_point(const std::vector<ParameterDefinition>& parameters) {
  std::vector<double> out;
  for (const auto& p : parameters) out.push_back(p.reference.value_or(p.initial));
  return out;
}

std::string coordinate_name(const ParameterDefinition& parameter) {
  return parameter.offset_from.empty() ? parameter.name : parameter.name + " - " + parameter.offset_from;
}

ParameterValues to_values(const std::vector<ParameterDefinition>& parameters,
                          const std::vector<double>& values) {
  if (values.size() != parameters.size())
    throw std::invalid_argument("to_values: wrong number of values");
  const std::vector<double> resolved = resolve_offsets(parameters, values);
  ParameterValues out;
  for (std::size_t i = 0; i < parameters.size(); ++i) out[parameters[i].name] = resolved[i];
  return out;
}

}  // namespace dtwire::calibrate
