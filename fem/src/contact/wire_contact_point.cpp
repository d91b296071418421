#include "wire_contact_point.hpp"

#include <Sacado.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <type_traits>

namespace dtwire::fem::contact {
namespace {

constexpr int kFaceDofs = 24;  // slave face and master face
constexpr int kMaxDofs = kFaceDofs + 3 * static_cast<int>(kMaxNeighbourVertices);
using FaceAd = Sacado::Fad::SFad<double, kFaceDofs>;     // faceted normal: fixed size, fastest
using PatchAd = Sacado::Fad::SLFad<double, kMaxDofs>;    // smoothed normal: runtime size

template <typename T>
constexpr bool is_ad = !std::is_same_v<T, double>;

template <typename T>
using Vec = std::array<T, 3>;

double value_of(double x) { return x; }
template <typename T, std::enable_if_t<is_ad<T>, int> = 0>
double value_of(const T& x) { return x.val(); }

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

// Corner normal x_xi x x_eta of a bilinear face at one of its vertices (unnormalised: the
// sum over the faces around a vertex is weighted by their corner areas).
template <typename T>
Vec<T> corner_normal(const std::array<const Vec<T>*, 4>& x, unsigned corner) {
  const Vec<T> a = corner < 2 ? *x[1] - *x[0] : *x[3] - *x[2];
  const Vec<T> b = corner % 2 == 0 ? *x[2] - *x[0] : *x[3] - *x[1];
  return cross(a, b);
}

// The contact point evaluated in arithmetic T: double, or an AD type seeded with the dofs.
template <typename T>
struct PointResult {
  ContactResponse response;
  std::vector<T> force;
};

template <typename T>
PointResult<T> evaluate(const WireContactPointInput& in, const ContactLaw& law, int n_dofs) {
  PointResult<T> out;
  const auto dof = [n_dofs](double value, int index) {
    if constexpr (is_ad<T>) return T(n_dofs, index, value);
    else return value;
  };
  std::array<Vec<T>, 4> slave, master;
  for (unsigned v = 0; v < 4; ++v)
    for (unsigned c = 0; c < 3; ++c) {
      slave[v][c] = in.slave_reference[v][c] + dof(in.slave_displacement[3 * v + c], 3 * v + c);
      master[v][c] = in.master_reference[v][c] + dof(in.master_displacement[3 * v + c], 12 + 3 * v + c);
    }
  const bool smoothed = !in.vertex_corners[0].empty();  // every vertex has corners (checked)
  std::vector<Vec<T>> neighbour(in.neighbour_reference.size());
  for (unsigned k = 0; k < neighbour.size(); ++k)
    for (unsigned c = 0; c < 3; ++c)
      neighbour[k][c] = in.neighbour_reference[k][c] + dof(in.neighbour_displacement[3 * k + c], kFaceDofs + 3 * k + c);
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
  Vec<T> normal_raw = scaled(in.master_sign, cross(a, b));
  if (smoothed) {
    const auto vertex = [&](unsigned i) -> const Vec<T>* { return i < 4 ? &master[i] : &neighbour[i - 4]; };
    normal_raw = Vec<T>{{T(0.0), T(0.0), T(0.0)}};
    for (unsigned v = 0; v < 4; ++v) {
      Vec<T> sum{{T(0.0), T(0.0), T(0.0)}};
      for (const NormalCorner& corner : in.vertex_corners[v]) {
        const std::array<const Vec<T>*, 4> corner_vertices{
            {vertex(corner.face[0]), vertex(corner.face[1]), vertex(corner.face[2]), vertex(corner.face[3])}};
        sum = sum + scaled(corner.sign, corner_normal(corner_vertices, corner.corner));
      }
      normal_raw = normal_raw + scaled(N[v] / norm(sum), sum);
    }
  }
  const Vec<T> n = scaled(1.0 / norm(normal_raw), normal_raw);

  ContactResponse& r = out.response;
  out.force.assign(static_cast<std::size_t>(n_dofs), T(0.0));
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

template <typename T>
WireContactPointOutput with_tangent_in(const WireContactPointInput& input, const ContactLaw& law, int n_dofs) {
  WireContactPointOutput out;
  const auto result = evaluate<T>(input, law, n_dofs);
  out.response = result.response;
  out.force.resize(static_cast<std::size_t>(n_dofs));
  out.stiffness.assign(static_cast<std::size_t>(n_dofs * n_dofs), 0.0);
  for (int i = 0; i < n_dofs; ++i) {
    out.force[i] = result.force[i].val();
    if (result.force[i].size() == 0) continue;  // a force that stayed constant (open point)
    for (int j = 0; j < n_dofs; ++j) out.stiffness[i * n_dofs + j] = result.force[i].dx(j);
  }
  return out;
}

}  // namespace

WireContactPointOutput evaluate_wire_contact_point(const WireContactPointInput& input, const ContactLaw& law,
                                                   bool with_tangent) {
  const unsigned neighbours = input.neighbour_reference.size();
  if (neighbours > kMaxNeighbourVertices || input.neighbour_displacement.size() != 3 * neighbours)
    throw std::invalid_argument("wire contact point: " + std::to_string(neighbours) +
                                " neighbour vertices (at most " + std::to_string(kMaxNeighbourVertices) +
                                ", 3 displacements each)");
  for (const auto& corners : input.vertex_corners)
    for (const NormalCorner& corner : corners)
      if (corner.corner > 3 || *std::max_element(corner.face.begin(), corner.face.end()) >= 4 + neighbours)
        throw std::invalid_argument("wire contact point: a normal corner names a vertex outside the patch");
  const bool smoothed = !input.vertex_corners[0].empty();
  for (const auto& corners : input.vertex_corners)
    if (corners.empty() == smoothed)
      throw std::invalid_argument("wire contact point: a smoothed normal needs corners at all four vertices");
  const int n_dofs = kFaceDofs + 3 * static_cast<int>(neighbours);
  if (!with_tangent) {
    auto result = evaluate<double>(input, law, n_dofs);
    WireContactPointOutput out;
    out.response = result.response;
    out.force = std::move(result.force);
    return out;
  }
  if (neighbours == 0 && !smoothed) return with_tangent_in<FaceAd>(input, law, n_dofs);
  return with_tangent_in<PatchAd>(input, law, n_dofs);
}

}  // namespace dtwire::fem::contact
