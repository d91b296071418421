#include "twisted_pair_state.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/prm_document.hpp"

namespace dtwire::fem {

using namespace dealii;

namespace {

// The file's columns (dtwire/core/csv.hpp: <quantity>_<unit>): quantity, dimension, unit written.
struct Column {
  const char* quantity;
  Dimension dimension;
  const char* unit;
};
const std::vector<Column>& columns() {
  static const std::vector<Column> list = [] {
    std::vector<Column> c{{"wire", Dimension::Dimensionless, "1"},     {"station_z_ref", Dimension::Length, "mm"},
                          {"axis_x", Dimension::Length, "mm"},         {"axis_y", Dimension::Length, "mm"},
                          {"axis_z", Dimension::Length, "mm"},         {"x", Dimension::Length, "mm"},
                          {"y", Dimension::Length, "mm"},              {"z", Dimension::Length, "mm"}};
    for (const char* k : {"b_e_xx", "b_e_yy", "b_e_zz", "b_e_xy", "b_e_xz", "b_e_yz"}) c.push_back({k, Dimension::Dimensionless, "1"});
    c.push_back({"equivalent_plastic_strain", Dimension::Dimensionless, "1"});
    c.push_back({"plastic_dissipation_density", Dimension::Stress, "MPa"});  // J/m3 = Pa
    c.push_back({"damage", Dimension::Dimensionless, "1"});
    for (const char* k : {"backstress_xx", "backstress_yy", "backstress_zz", "backstress_xy", "backstress_xz", "backstress_yz"})
      c.push_back({k, Dimension::Stress, "MPa"});
    c.push_back({"softening", Dimension::Dimensionless, "1"});
    return c;
  }();
  return list;
}
constexpr const char* kBottomKey = "twisted_from_z_ref_mm";
constexpr const char* kTopKey = "twisted_to_z_ref_mm";
// Symmetric tensor entries in the file's order: xx, yy, zz, xy, xz, yz.
constexpr unsigned kRow[6] = {0, 1, 2, 0, 0, 1}, kCol[6] = {0, 1, 2, 1, 2, 2};

double wrapped(double angle) { return std::remainder(angle, 2.0 * M_PI); }

// R^T T R with R the rotation by `angle` about z.
SymTensor2 rotated_back(const SymTensor2& t, double angle) {
  Tensor2 r;
  r[0][0] = r[1][1] = std::cos(angle);
  r[1][0] = std::sin(angle);
  r[0][1] = -r[1][0];
  r[2][2] = 1.0;
  return symmetrize(Tensor2(transpose(r) * Tensor2(t) * r));
}

}  // namespace

void write_twisted_pair_csv(const std::filesystem::path& file, double z0, double z1,
                            const std::vector<TwistedPairPoint>& points) {
  std::vector<std::vector<double>> si(columns().size());  // per column, SI
  for (const auto& p : points) {
    std::vector<double> row{double(p.wire), p.station_z_ref, p.axis[0], p.axis[1], p.axis[2],
                            p.position[0], p.position[1], p.position[2]};
    for (unsigned k = 0; k < 6; ++k) row.push_back(p.state.plastic_metric_inverse[kRow[k]][kCol[k]]);
    row.insert(row.end(), {p.state.equivalent_plastic_strain, p.state.plastic_dissipation, p.state.damage});
    for (unsigned k = 0; k < 6; ++k) row.push_back(p.state.backstress[kRow[k]][kCol[k]]);
    row.push_back(p.state.softening);
    for (std::size_t c = 0; c < row.size(); ++c) si[c].push_back(row[c]);
  }
  Curve curve;
  curve.set_metadata("content", "dtwire twisted pair state (As made/Release after path), one row per steel "
                                "quadrature point after the release; read by As made/Twisted pair state");
  curve.set_metadata(kBottomKey, format_number(1e3 * z0));
  curve.set_metadata(kTopKey, format_number(1e3 * z1));
  for (std::size_t c = 0; c < columns().size(); ++c)
    curve.add_channel_si(columns()[c].quantity, columns()[c].dimension, si[c], *find_unit(columns()[c].unit));
  write_csv(curve, file);
}

TwistedPairState::TwistedPairState(const std::filesystem::path& file,
                                   const std::vector<std::vector<AxisStation>>& mesh_axes)
    : file_(file), points_(2), stations_(2), mesh_axes_(mesh_axes) {
  const std::string name = file.string();
  const Curve curve = read_csv(file);  // names file:line of a malformed row
  std::vector<std::vector<double>> si;
  for (const auto& column : columns()) {
    const Channel* channel = curve.find(column.quantity);
    if (!channel || channel->unit.dimension != column.dimension)
      throw InputError(name, std::string("not a twisted pair state: expected a column ") + column.quantity + "_" +
                                 column.unit + " (or another unit of its dimension)");
    si.push_back(channel->si());
  }
  const auto height = [&](const char* key) {
    const auto value = parse_number(curve.metadata(key));
    if (!value) throw InputError(name, std::string("expected a metadata line '# ") + key + ": <number>'");
    return 1e-3 * *value;
  };
  z0_ = height(kBottomKey);
  z1_ = height(kTopKey);
  if (!(z1_ > z0_)) throw InputError(name, std::string(kTopKey) + " must lie above " + kBottomKey);
  for (std::size_t i = 0; i < curve.size(); ++i) {
    const auto v = [&](std::size_t c) { return si[c][i]; };
    if (v(0) != 0.0 && v(0) != 1.0) throw InputError(name, "row " + std::to_string(i + 1) + ": wire must be 0 or 1");
    TwistedPairPoint p;
    p.wire = static_cast<unsigned>(v(0));
    p.station_z_ref = v(1);
    for (unsigned c = 0; c < 3; ++c) p.axis[c] = v(2 + c), p.position[c] = v(5 + c);
    for (unsigned k = 0; k < 6; ++k) p.state.plastic_metric_inverse[kRow[k]][kCol[k]] = v(8 + k);
    if (!(determinant(p.state.plastic_metric_inverse) > 0.0))
      throw InputError(name, "row " + std::to_string(i + 1) + ": b_e is not positive definite");
    p.state.equivalent_plastic_strain = v(14);
    p.state.plastic_dissipation = v(15);
    p.state.damage = v(16);
    for (unsigned k = 0; k < 6; ++k) p.state.backstress[kRow[k]][kCol[k]] = v(17 + k);
    p.state.softening = v(23);
    if (!(p.state.softening >= 0.0 && p.state.softening < 1.0))
      throw InputError(name, "row " + std::to_string(i + 1) + ": softening must lie in [0, 1)");
    points_[p.wire].push_back(p);
  }
  for (unsigned w = 0; w < 2; ++w) {
    auto& p = points_[w];
    if (p.empty()) throw InputError(name, "no points of wire " + std::to_string(w) + " (a pair has two wires)");
    std::stable_sort(p.begin(), p.end(), [](const auto& a, const auto& b) { return a.station_z_ref < b.station_z_ref; });
    for (const auto& q : p)
      if (stations_[w].empty() || q.station_z_ref != stations_[w].back().z_ref) stations_[w].push_back({q.station_z_ref, q.axis});
    if (stations_[w].size() < 2) throw InputError(name, "wire " + std::to_string(w) + " has fewer than two stations");
    for (std::size_t k = 1; k < stations_[w].size(); ++k)
      window_ = std::max(window_, stations_[w][k].z_ref - stations_[w][k - 1].z_ref);
  }

  // The mesh's twist: where the two axes lie at the helix's radius from their midpoint.
  const std::string axes_name = "As made/Axis file";
  if (mesh_axes_.size() != 2) throw InputError(axes_name, "a twisted pair state needs a double-twist mesh (two wires)");
  for (const auto& wire : mesh_axes_)
    for (std::size_t k = 1; k < wire.size(); ++k)
      if (!(wire[k].point[2] > wire[k - 1].point[2]))
        throw InputError(axes_name, "the wire axes do not rise along z, as a `dtwire mesh dt` double twist's do");
  const double bottom = std::max(mesh_axes_[0].front().point[2], mesh_axes_[1].front().point[2]);
  const double top = std::min(mesh_axes_[0].back().point[2], mesh_axes_[1].back().point[2]);
  std::vector<std::pair<double, double>> half_distance;  // (z, |a0 - a1| / 2)
  double radius = std::numeric_limits<double>::max();
  for (const auto& wire : mesh_axes_)
    for (const auto& st : wire)
      if (st.point[2] >= bottom && st.point[2] <= top) {
        const double h = (mesh_axis(0, st.point[2]) - mesh_axis(1, st.point[2])).norm() / 2;
        half_distance.emplace_back(st.point[2], h);
        radius = std::min(radius, h);
      }
  z_lo_ = std::numeric_limits<double>::max();
  z_hi_ = -z_lo_;
  for (const auto& [z, h] : half_distance)
    if (h <= radius * (1.0 + 1e-3)) z_lo_ = std::min(z_lo_, z), z_hi_ = std::max(z_hi_, z);
  if (!(z_hi_ - z_lo_ > 4.0 * radius))
    throw InputError(axes_name, "no twist found in the mesh's axes (the wires never wind about each other)");
  for (const double f : {0.1, 0.3, 0.5, 0.7, 0.9})
    for (unsigned w = 0; w < 2; ++w) {
      const double z = z_lo_ + f * (z_hi_ - z_lo_), angle = turn(w, z);
      if (std::abs(angle) > M_PI / 2)
        throw InputError(name, "at " + std::to_string(static_cast<int>(100 * f)) + " % of the twist's height the pair's wire " +
                                   std::to_string(w) + " lies " + std::to_string(angle * 180 / M_PI) +
                                   " deg away from the mesh's: another twist sense or wire order (twist a pair from "
                                   "`dtwire mesh dt --half-turns 0` with this mesh's d and gap, turned the way its "
                                   "twist winds)");
    }
}

Point<3> TwistedPairState::pair_axis(unsigned wire, double z_ref) const {
  const auto& s = stations_[wire];
  if (z_ref <= s.front().z_ref) return s.front().axis;
  if (z_ref >= s.back().z_ref) return s.back().axis;
  const auto next = std::upper_bound(s.begin(), s.end(), z_ref, [](double z, const Station& st) { return z < st.z_ref; });
  const auto& a = *(next - 1);
  const double f = (z_ref - a.z_ref) / (next->z_ref - a.z_ref);
  return a.axis + f * (next->axis - a.axis);
}

Point<3> TwistedPairState::mesh_axis(unsigned wire, double z) const {
  const auto& s = mesh_axes_[wire];
  const auto next = std::upper_bound(s.begin(), s.end(), z, [](double h, const AxisStation& st) { return h < st.point[2]; });
  const auto& a = next == s.begin() ? s.front() : *(next - 1);
  const auto& b = next == s.end() ? s.back() : *next;
  const double f = b.point[2] > a.point[2] ? std::clamp((z - a.point[2]) / (b.point[2] - a.point[2]), 0.0, 1.0) : 0.0;
  Point<3> p;
  for (unsigned c = 0; c < 3; ++c) p[c] = a.point[c] + f * (b.point[c] - a.point[c]);
  return p;
}

double TwistedPairState::turn(unsigned wire, double z) const {
  const double z_ref = to_pair_height(z);
  const Tensor<1, 3> pair = pair_axis(wire, z_ref) - 0.5 * (pair_axis(0, z_ref) + pair_axis(1, z_ref));
  const Tensor<1, 3> mesh = mesh_axis(wire, z) - 0.5 * (mesh_axis(0, z) + mesh_axis(1, z));
  return wrapped(std::atan2(pair[1], pair[0]) - std::atan2(mesh[1], mesh[0]));
}

TransferredState TwistedPairState::at(unsigned wire, const Point<3>& x, const Point<3>& foot) const {
  TransferredState result;
  const double z = foot[2], slack = 1e-9;
  if (wire > 1 || z < z_lo_ - slack || z > z_hi_ + slack) return result;
  const double z_ref = to_pair_height(z), angle = turn(wire, z);
  Tensor<1, 3> offset = x - foot;
  const double c = std::cos(angle), s = std::sin(angle);
  offset = Tensor<1, 3>({c * offset[0] - s * offset[1], s * offset[0] + c * offset[1], offset[2]});
  const Point<3> target = pair_axis(wire, z_ref) + offset;
  const auto& p = points_[wire];
  const auto by_height = [](const TwistedPairPoint& q, double h) { return q.station_z_ref < h; };
  auto first = std::lower_bound(p.begin(), p.end(), z_ref - window_, by_height);
  const auto last = std::lower_bound(p.begin(), p.end(), z_ref + window_ + 1e-12, by_height);
  const TwistedPairPoint* nearest = nullptr;
  double best = std::numeric_limits<double>::max();
  for (; first != last; ++first)
    if (const double d = (first->position - target).norm_square(); d < best) best = d, nearest = &*first;
  if (!nearest) return result;
  result.inside = true;
  result.distance = std::sqrt(best);
  result.state = nearest->state;
  result.state.plastic_metric_inverse = rotated_back(nearest->state.plastic_metric_inverse, angle);
  result.state.backstress = rotated_back(nearest->state.backstress, angle);
  return result;
}

}  // namespace dtwire::fem
