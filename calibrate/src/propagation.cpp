#include "dtwire/calibrate/propagation.hpp"

#include <Eigen/Eigenvalues>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <map>
#include <stdexcept>

#include "dtwire/core/error.hpp"

namespace dtwire::calibrate {
namespace {

using nlohmann::json;

double number_field(const json& object, const std::string& key, const std::string& field,
                    const std::filesystem::path& file) {
  const auto found = object.find(key);
  if (found == object.end() || !found->is_number())
    throw InputError(file.string(), "field '" + field + "." + key + "': expected a number");
  return found->get<double>();
}

}  // namespace

FitUncertainty read_fit_uncertainty(const std::filesystem::path& file, const std::string& prefix) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string(), "cannot open the fit's parameters.json");
  json root;
  try {
    root = json::parse(in);
  } catch (const json::parse_error& e) {
    throw InputError(file.string(), std::string("not JSON: ") + e.what());
  }
  if (!root.is_object() || !root.contains("parameters") || !root["parameters"].is_array())
    throw InputError(file.string(), "field 'parameters': expected the list a `dtwire fit` writes");
  const json& names = root.value("covariance_parameters", json::array());
  if (!names.is_array()) throw InputError(file.string(), "field 'covariance_parameters': expected a list of names");

  FitUncertainty fit;
  fit.file = file;
  std::map<std::string, std::size_t> index_in_file;  // covariance row of each fitted parameter
  std::vector<std::size_t> rows;
  for (std::size_t k = 0; k < root["parameters"].size(); ++k) {
    const json& p = root["parameters"][k];
    const std::string field = "parameters[" + std::to_string(k) + "]";
    if (!p.is_object() || !p.contains("name") || !p["name"].is_string())
      throw InputError(file.string(), "field '" + field + ".name': expected a string");
    if (!p.value("fitted", false)) continue;
    const std::string name = p["name"];
    if (name.rfind(prefix, 0) != 0) continue;
    UncertainParameter u;
    u.name = name;
    u.unit = p.value("unit", "1");
    u.value = number_field(p, "value", field, file);
    u.lower = number_field(p, "lower", field, file);
    u.upper = number_field(p, "upper", field, file);
    if (!(u.lower <= u.value && u.value <= u.upper))
      throw InputError(file.string(), "field '" + field + ".value': " + name + " lies outside its [lower, upper]");
    u.identified = p.value("identified", false);
    if (p.contains("coordinate")) {
      const json& c = p["coordinate"];
      if (!c.is_string() || (c != "log" && c != "linear"))
        throw InputError(file.string(), "field '" + field + ".coordinate': expected \"linear\" or \"log\"");
      u.logarithmic = c == "log";
    } else {
      fit.coordinates_recorded = false;
    }
    if (p.contains("offset_from")) {
      if (!p["offset_from"].is_string() || !p.contains("offset") || !p["offset"].is_object())
        throw InputError(file.string(), "field '" + field + ".offset': expected the offset's numbers with offset_from");
      u.offset_from = p["offset_from"];
      u.offset_lower = number_field(p["offset"], "lower", field + ".offset", file);
      u.offset_upper = number_field(p["offset"], "upper", field + ".offset", file);
    }
    std::size_t row = names.size();
    for (std::size_t j = 0; j < names.size(); ++j)
      if (names[j] == name) row = j;
    rows.push_back(row);
    fit.parameters.push_back(u);
  }
  if (fit.parameters.empty())
    throw InputError(file.string(), "field 'parameters': no fitted parameter" +
                                        (prefix.empty() ? std::string() : " named " + prefix + "*"));
  for (const UncertainParameter& p : fit.parameters)
    if (!p.offset_from.empty()) {
      bool found = false;
      for (const UncertainParameter& q : fit.parameters) found = found || q.name == p.offset_from;
      if (!found)
        throw InputError(file.string(), "field 'parameters': " + p.name + " is an offset from " + p.offset_from +
                                            ", which is not among the fitted parameters read");
    }

  const json& covariance = root.value("covariance", json());
  if (covariance.is_array()) {
    const std::size_t n = names.size();
    if (covariance.size() != n) throw InputError(file.string(), "field 'covariance': expected " + std::to_string(n) + " rows (covariance_parameters)");
    for (std::size_t r : rows)
      if (r >= n) throw InputError(file.string(), "field 'covariance_parameters': a fitted parameter is missing from it");
    fit.covariance.assign(rows.size(), std::vector<double>(rows.size(), 0.0));
    for (std::size_t a = 0; a < rows.size(); ++a) {
      const json& row = covariance[rows[a]];
      if (!row.is_array() || row.size() != n)
        throw InputError(file.string(), "field 'covariance[" + std::to_string(rows[a]) + "]': expected " + std::to_string(n) + " numbers");
      for (std::size_t b = 0; b < rows.size(); ++b) {
        if (!row[rows[b]].is_number())
          throw InputError(file.string(), "field 'covariance[" + std::to_string(rows[a]) + "][" + std::to_string(rows[b]) +
                                              "]': expected a number (the fit's covariance has a null entry)");
        fit.covariance[a][b] = row[rows[b]].get<double>();
      }
    }
  } else if (!covariance.is_null()) {
    throw InputError(file.string(), "field 'covariance': expected a matrix or null");
  }
  return fit;
}

ParameterSampler::ParameterSampler(const FitUncertainty& fit, std::uint64_t seed) : fit_(fit), generator_(seed) {
  const std::size_t n = fit_.parameters.size();
  const bool have_covariance = !fit_.covariance.empty();
  if (have_covariance && fit_.covariance.size() != n) throw std::invalid_argument("covariance: wrong size");
  for (std::size_t i = 0; i < n; ++i) {
    const UncertainParameter& p = fit_.parameters[i];
    if (p.logarithmic && !(p.lower > 0.0 && p.value > 0.0))
      throw std::invalid_argument(p.name + ": a log coordinate needs a value and bounds > 0");
    if (!(p.lower <= p.value && p.value <= p.upper)) throw std::invalid_argument(p.name + ": value outside its bounds");
    normal_.push_back(have_covariance && p.identified);
    if (normal_.back()) normal_index_.push_back(i);
  }
  // Cov(y) on the identified block: dv/dy = v for a log coordinate, 1 otherwise.
  const std::size_t m = normal_index_.size();
  Eigen::MatrixXd c(m, m);
  for (std::size_t a = 0; a < m; ++a)
    for (std::size_t b = 0; b < m; ++b) {
      const std::size_t i = normal_index_[a], j = normal_index_[b];
      // JSON round trips keep about 15 digits: a relative 1e-9 of the entries' scale is not symmetry lost.
      if (std::abs(fit_.covariance[i][j] - fit_.covariance[j][i]) >
          1e-9 * std::sqrt(std::abs(fit_.covariance[i][i] * fit_.covariance[j][j])))
        throw std::invalid_argument("covariance: not symmetric at " + fit_.parameters[i].name + ", " + fit_.parameters[j].name);
      const double di = fit_.parameters[i].logarithmic ? fit_.parameters[i].value : 1.0;
      const double dj = fit_.parameters[j].logarithmic ? fit_.parameters[j].value : 1.0;
      c(a, b) = fit_.covariance[i][j] / (di * dj);
    }
  factor_.assign(m, std::vector<double>(m, 0.0));
  if (m > 0) {
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(0.5 * (c + c.transpose()));
    for (std::size_t a = 0; a < m; ++a)
      for (std::size_t k = 0; k < m; ++k)
        factor_[a][k] = eigen.eigenvectors()(a, k) * std::sqrt(std::max(eigen.eigenvalues()(k), 0.0));
  }
  coordinate_covariance_.assign(n, std::vector<double>(n, 0.0));
  for (std::size_t a = 0; a < m; ++a)
    for (std::size_t b = 0; b < m; ++b) coordinate_covariance_[normal_index_[a]][normal_index_[b]] = c(a, b);
  for (std::size_t i = 0; i < n; ++i)
    if (!normal_[i]) {
      const double width = to_coordinate(i, fit_.parameters[i].upper) - to_coordinate(i, fit_.parameters[i].lower);
      coordinate_covariance_[i][i] = width * width / 12.0;
    }
}

double ParameterSampler::to_coordinate(std::size_t i, double value) const {
  return fit_.parameters[i].logarithmic ? std::log(value) : value;
}

double ParameterSampler::from_coordinate(std::size_t i, double y) const {
  return fit_.parameters[i].logarithmic ? std::exp(y) : y;
}

double ParameterSampler::coordinate_sd(std::size_t i) const { return std::sqrt(coordinate_covariance_[i][i]); }

bool ParameterSampler::within_constraints(const std::vector<double>& v, std::string* why) const {
  for (std::size_t i = 0; i < v.size(); ++i) {
    const UncertainParameter& p = fit_.parameters[i];
    if (!(v[i] >= p.lower && v[i] <= p.upper)) {
      if (why) *why = p.name + " outside [lower, upper]";
      return false;
    }
    if (p.offset_from.empty()) continue;
    for (std::size_t j = 0; j < v.size(); ++j)
      if (fit_.parameters[j].name == p.offset_from) {
        const double d = v[i] - v[j];
        if (!(d >= p.offset_lower && d <= p.offset_upper)) {
          if (why) *why = p.name + " - " + p.offset_from + " outside the offset's [lower, upper]";
          return false;
        }
      }
  }
  return true;
}

double ParameterSampler::uniform01() { return static_cast<double>(generator_() >> 11) * 0x1.0p-53; }

double ParameterSampler::standard_normal() {
  // Box-Muller (1958): two independent normals from two uniforms; the second is kept.
  if (spare_normal_) {
    const double z = *spare_normal_;
    spare_normal_.reset();
    return z;
  }
  const double u1 = 1.0 - uniform01();  // in (0, 1]: the logarithm stays finite
  const double u2 = uniform01();
  const double r = std::sqrt(-2.0 * std::log(u1));
  constexpr double two_pi = 6.283185307179586;
  spare_normal_ = r * std::sin(two_pi * u2);
  return r * std::cos(two_pi * u2);
}

std::vector<double> ParameterSampler::draw(const std::function<bool(const std::vector<double>&)>& admissible,
                                           int max_tries) {
  const std::size_t n = fit_.parameters.size(), m = normal_index_.size();
  std::map<std::string, int> refusals;
  for (int attempt = 0; attempt < max_tries; ++attempt) {
    std::vector<double> v(n);
    std::vector<double> z(m);
    for (double& x : z) x = standard_normal();
    for (std::size_t a = 0; a < m; ++a) {
      const std::size_t i = normal_index_[a];
      double dy = 0.0;
      for (std::size_t k = 0; k < m; ++k) dy += factor_[a][k] * z[k];
      // As a step from the value (v e^dy on a log coordinate): a zero spread gives the value itself.
      const double value = fit_.parameters[i].value;
      v[i] = fit_.parameters[i].logarithmic ? value * std::exp(dy) : value + dy;
    }
    for (std::size_t i = 0; i < n; ++i)
      if (!normal_[i]) {
        const double lo = to_coordinate(i, fit_.parameters[i].lower), hi = to_coordinate(i, fit_.parameters[i].upper);
        v[i] = from_coordinate(i, lo + uniform01() * (hi - lo));
      }
    std::string why;
    if (!within_constraints(v, &why)) {
      ++refused_, ++refusals[why];
      continue;
    }
    if (admissible && !admissible(v)) {
      ++refused_, ++refusals["the caller's check (e.g. the contact law)"];
      continue;
    }
    ++accepted_;
    return v;
  }
  std::string most;
  int count = 0;
  for (const auto& [why, k] : refusals)
    if (k > count) most = why, count = k;
  throw std::runtime_error("no admissible parameter set in " + std::to_string(max_tries) + " draws from " +
                           fit_.file.string() + "; most often refused: " + most);
}

}  // namespace dtwire::calibrate
