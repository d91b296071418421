#pragma once
// Integral-type non-local average of a quadrature-point field (Pijaudier-Cabot & Bazant 1987,
// J. Eng. Mech. 113(10); the survey of Bazant & Jirasek 2002, J. Eng. Mech. 128(11), eq. 1-3):
//
//   f_bar(x) = sum_y a(x, y) f(y),   a(x, y) = w(|X - Y|) V_y / sum_z w(|X - Z|) V_z,
//   w(r) = (1 - r^2 / R^2)^2 for r < R, 0 beyond (the bell-shaped weight, their eq. 5),
//
// over the points y of the same group (one wire: an average does not reach across a contact
// interface into the other wire), at reference positions X (Lagrangian: the weights do not change
// with the deformation), with the point's own volume V (J x W of its quadrature rule). The local
// renormalisation (the denominator) makes a uniform field its own average, also where the ball is
// cut by the wire's surface; a linear field is its own average where the ball lies inside the body.
//
// The weights depend on the geometry alone, so they are found once (a hash grid of cell size R
// finds the pairs) and each average is one sparse row times the field. No deal.II: the solver
// gathers the points of every rank and hands them over (fem/src/solver_nonlocal.cpp).
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace dtwire::fem {

class NonlocalAverage {
 public:
  // `positions`, `volumes` and `groups` describe every point that may enter an average (all
  // ranks'); `own` lists the points whose averages this instance computes. Throws
  // std::invalid_argument on a radius <= 0, mismatched sizes, a volume <= 0 or an index out of range.
  NonlocalAverage(const std::vector<std::array<double, 3>>& positions, const std::vector<double>& volumes,
                  const std::vector<int>& groups, double radius, std::vector<std::size_t> own);

  // How many (own point, neighbour) pairs the weights would hold: 8 bytes each, counted before
  // they are stored so that a radius too large for the memory can be refused by name.
  static std::size_t count_pairs(const std::vector<std::array<double, 3>>& positions, const std::vector<int>& groups,
                                 double radius, const std::vector<std::size_t>& own);

  // The averages of the `own` points (in their order) of `values`, given for every point.
  std::vector<double> apply(const std::vector<double>& values) const;

  std::size_t size() const { return own_.size(); }
  // Points entering the average of own point i (itself included): the resolution of R by the mesh.
  std::size_t neighbours(std::size_t i) const { return row_start_[i + 1] - row_start_[i]; }
  double radius() const { return radius_; }

 private:
  double radius_;
  std::vector<std::size_t> own_;
  // Compressed rows: the neighbours of own point i are column_[row_start_[i] .. row_start_[i + 1]).
  std::vector<std::size_t> row_start_;
  std::vector<std::uint32_t> column_;
  std::vector<float> weight_;  // a(x, y); single precision: the field it averages is an indicator
  std::size_t point_count_ = 0;
};

}  // namespace dtwire::fem
