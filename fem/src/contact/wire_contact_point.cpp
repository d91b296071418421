#include "wire_contact_point.hpp"

#include <Sacado.hpp>

#include <algorithm>
#include <cmath>
#include <type_traits>

namespace dtwire::fem::contact {
namespace {

constexpr int kDofs = 24;
using Ad = Sacado::Fad::SFad<double, kDofs>;

template <typename T>
using Vec = std::array<T, 3>;

double value_of(double x) { return x; }
double value_of(const Ad& x) { return x.val(); }

template <typename T>
Vec<T> operator-(const Vec<T>& a, const Vec<T>& b) { return {{a[0] - b[0], a[1] - b[1], a[2] - b[2]}}; }
template <typename T>
Vec<T> operator+(const Vec<T>& a, const Vec<T>& b) { return {{a[0] + b[0], a[1] + b[1], a[2] + b[2]}}; }
template <typename T, typename S>
Vec<T> scaled(const S& s, const Vec<T>& a) { return {{s * a[0], s * a[1], s * a[2]}}; }
template <typename T>
T dot(const Vec<T>& a, const Vec<T>& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
template <typename T>
Vec<T> cross(const Vec<T>& a, const Vec<T>& b) {
  return {{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}};
}
template <typename T>
T norm(const Vec<T>& a) {
  using std::sqrt;
  return sqrt(dot(a, a));
}
template <typename T>
Vec<T> from(const Vector3& x) { return {{T(x[0]), T(x[1]), T(x[2])}}; }
template <typename T>
Vector3 values(const Vec<T>& a) {
  Vector3 out;
  for (unsigned c = 0; c < 3; ++c) out[c] = value_of(a[c]);
  return out;
}

template <typename T>
std::array<T, 4> bilinear_shape(const T& xi, const T& eta) {
  return {{(1.0 - xi) * (1.0 - eta), xi * (1.0 - eta), (1.0 - xi) * eta, xi * eta}};
}
template <typename T, typename S>
Vec<T> interpolate(const std::array<S, 4>& N, const std::array<Vec<T>, 4>& vertex) {
  Vec<T> out{{T(0.0), T(0.0), T(0.0)}};
  for (unsigned v = 0; v < 4; ++v) out = out + scaled(N[v], vertex[v]);
  return out;
}

// The contact point evaluated in arithmetic T: double, or Ad seeded with the 24 dofs.
template <typename T>
struct PointResult {
  ContactResponse response;
  std::array<T, kDofs> force;
};

template <typename T>
PointResult<T> evaluate(const WireContactPointInput& in, const ContactLaw& law) {
  PointResult<T> out;
  const auto dof = [](double value, int index) {
    if constexpr (std::is_same_v<T, Ad>) return Ad(kDofs, index, value);
    else return value;
  };
  std::array<Vec<T>, 4> slave, master;
  for (unsigned v = 0; v < 4; ++v)
    for (unsigned c = 0; c < 3; ++c) {
      slave[v][c] = in.slave_reference[v][c] + dof(in.slave_displacement[3 * v + c], 3 * v + c);
      master[v][c] = in.master_reference[v][c] + dof(in.master_displacement[3 * v + c], 12 + 3 * v + c);
    }
  const Vec<T> x = interpolate(bilinear_shape(in.slave_xi, in.slave_eta), slave);

  // Closest point: one Newton correction of the converged (xi0, eta0) in arithmetic T. Its value
  // is the converged one; its derivative is -J^-1 dF/du (implicit function theorem), F = (r.x_xi,
  // r.x_eta), r = x - y, J with the twist term r.y_xieta of the bilinear face. A parameter
  // clamped to an edge of the face stays there (zero derivative).
  const double xi0 = in.master_xi, eta0 = in.master_eta;
  const auto tangents = [&](const T& xi, const T& eta) {
    const Vec<T> a = scaled(1.0 - eta, master[1] - master[0]) + scaled(eta, master[3] - master[2]);
    const Vec<T> b = scaled(1.0 - xi, master[2] - master[0]) + scaled(xi, master[3] - master[1]);
    return std::pair<Vec<T>, Vec<T>>(a, b);
  };
  T xi(xi0), eta(eta0);
  {
    const Vec<T> r = x - interpolate(bilinear_shape(T(xi0), T(eta0)), master);
    const auto [a, b] = tangents(T(xi0), T(eta0));
    const Vec<T> twist = master[0] - master[1] - master[2] + master[3];
    const T F1 = dot(r, a), F2 = dot(r, b);
    const double J11 = -value_of(dot(a, a)), J22 = -value_of(dot(b, b));
    const double J12 = -value_of(dot(a, b)) + value_of(dot(r, twist));
    const bool xi_free = xi0 > 0.0 && xi0 < 1.0, eta_free = eta0 > 0.0 && eta0 < 1.0;
    const double det = J11 * J22 - J12 * J12;
    if (xi_free && eta_free && std::abs(det) > 1e-14 * std::abs(J11 * J22)) {
      xi = xi0 - (J22 * F1 - J12 * F2) / det;
      eta = eta0 - (J11 * F2 - J12 * F1) / det;
    } else if (xi_free && J11 != 0.0) {
      xi = xi0 - F1 / J11;
    } else if (eta_free && J22 != 0.0) {
      eta = eta0 - F2 / J22;
    }
  }
  const auto N = bilinear_shape(xi, eta);
  const Vec<T> y = interpolate(N, master);
  const auto [a, b] = tangents(xi, eta);
  const Vec<T> normal_raw = cross(a, b);
  const Vec<T> n = scaled(in.master_sign / norm(normal_raw), normal_raw);

  ContactResponse& r = out.response;
  for (auto& f : out.force) f = T(0.0);
  const T gap = dot(x - y, n) + in.gap_offset;
  const T pressure = in.history.multiplier - law.normal_penalty * gap;
  r.gap = value_of(gap);
  if (!(value_of(pressure) > 0.0)) return out;  // open
  r.active = true;
  r.pressure = value_of(pressure);
  Vec<T> traction = scaled(pressure, n);

  if (law.friction > 0.0) {
    // Elastic predictor on the motion of x relative to the master material point it faces
    // (Wriggers 2006, eq. 10.47): anchor = x_n + (y(xi) - y_n(xi)).
    std::array<Vec<T>, 4> master_committed;
    for (unsigned v = 0; v < 4; ++v)
      for (unsigned c = 0; c < 3; ++c)
        master_committed[v][c] = T(in.master_reference[v][c] + in.master_committed_displacement[3 * v + c]);
    const Vec<T> y_committed = interpolate(N, master_committed);
    const Vec<T> motion = x - from<T>(in.committed_slave_position) - (y - y_committed);
    const Vec<T> slip_trial = motion - scaled(dot(motion, n), n);
    const Vec<T> t_old = from<T>(in.history.tangential_traction);
    const Vec<T> trial = t_old - scaled(dot(t_old, n), n) - scaled(law.tangential_penalty, slip_trial);
    const T trial_norm = norm(trial);
    const T limit = law.friction * pressure;
    const bool stick = in.forced == FrictionStatus::free ? value_of(trial_norm) <= value_of(limit)
                                                         : in.forced == FrictionStatus::stick;
    Vec<T> tangential = trial;
    if (!stick && value_of(trial_norm) > 0.0) {  // radial return (Wriggers 2006, eq. 10.51)
      tangential = scaled(limit / trial_norm, trial);
      r.slipping = true;
      r.slip_increment = std::max(0.0, value_of(trial_norm) - value_of(limit)) / law.tangential_penalty;
      r.dissipation = value_of(limit) * r.slip_increment;
    }
    r.tangential_traction = values(tangential);
    traction = traction + tangential;
  }
  r.traction = values(traction);

  const auto Ns = bilinear_shape(in.slave_xi, in.slave_eta);
  for (unsigned v = 0; v < 4; ++v)
    for (unsigned c = 0; c < 3; ++c) {
      out.force[3 * v + c] = -Ns[v] * traction[c] * in.weight;
      out.force[12 + 3 * v + c] = N[v] * traction[c] * in.weight;
    }
  return out;
}

}  // namespace

WireContactPointOutput evaluate_wire_contact_point(const WireContactPointInput& input, const ContactLaw& law,
                                                   bool with_tangent) {
  WireContactPointOutput out;
  if (!with_tangent) {
    const auto result = evaluate<double>(input, law);
    out.response = result.response;
    out.force = result.force;
    return out;
  }
  const auto result = evaluate<Ad>(input, law);
  out.response = result.response;
  for (int i = 0; i < kDofs; ++i) {
    out.force[i] = result.force[i].val();
    for (int j = 0; j < kDofs; ++j) out.stiffness[i][j] = result.force[i].dx(j);
  }
  return out;
}

}  // namespace dtwire::fem::contact
