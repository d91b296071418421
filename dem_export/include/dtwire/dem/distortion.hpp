#pragma once
// Initial distortion of the mesh (Thoeni et al. 2013, "Discrete modelling of hexagonal wire
// meshes with a stochastically distorted contact model", Computers and Geotechnics 49; YADE
// WireMat type = 2, lambdau, seed in pkg/dem/WirePM.cpp, Ip2_WireMat_WireMat_WirePhys::go).
// A wire segment of the net is wavy: it straightens over an initial slack dL before it carries
// load. dL = lambda_u l0 r with l0 the link's length and
//   constant mode: r = 1                                    (YADE seed = -1)
//   random mode:   r from a triangular distribution on [0, 1] with mode 0.5 (YADE seed > 0).
//
// The random stream is YADE's, reproduced bit for bit: one boost::minstd_rand (Park-Miller,
// a = 48271, m = 2^31 - 1) seeded with `seed`, each draw u = (x - 1) / (m - 1) as
// boost::uniform_01 computes it and r = boost::triangle_distribution(0, 0.5, 1) of u. YADE
// draws once per WireMat interaction in the order the interactions are created; link k of our
// net takes the k-th draw (jump-ahead x_k = seed a^(k+1) mod m), so a YADE script that creates
// the links in our order (createInteraction) gives every link the same dL.
//
// WirePM has the distortion built in as YADE has it (wirepm.hpp: lambda_u, lambda_F, the strains
// referred to l0 + dL, the soft initial branch up to lambda_F F_1). The other laws get it from
// DistortedLaw below, YADE's lambda_F = 0 form: a pure shift of the axial curve by dL.
#include <cstdint>
#include <memory>
#include <string>

#include "dtwire/dem/contact_law.hpp"

namespace dtwire::dem {

enum class DistortionMode { None, Constant, Random };

struct Distortion {
  DistortionMode mode = DistortionMode::None;
  double lambda_u = 0.0;     // in [0, 1)
  std::int64_t seed = 0;     // random mode: in [1, 2^31 - 2]
};

// "none", "constant", "random"; throws std::invalid_argument for anything else.
DistortionMode distortion_mode_from_name(const std::string& name);
std::string distortion_mode_name(DistortionMode mode);

constexpr std::int64_t kLargestDistortionSeed = 2147483646;  // m - 2: minstd_rand's states are 1 .. m - 1

// The k-th (k = 0, 1, ...) triangular variate of YADE's stream for `seed` (see above).
double yade_triangular_variate(std::int64_t seed, std::uint64_t k);

// r of link k: 1 (constant), YADE's k-th draw (random), 0 (none).
double distortion_variate(const Distortion& distortion, std::uint64_t link_index);

// Pure shift of the axial curve by `slack` [m] (>= 0). The wrapped law is fed the axial
// displacement u_w = max(u - slack, 0) (other components unchanged) and the axial force is
//   N = 0             while u < slack  (the wire is still straightening),
//   N = N_w(u_w)      once u >= slack,
// so a monotonic pull gives N(u) = N_w(u - slack) exactly. Over any increment the work
// N du equals the wrapped law's work N_w du_w (both are zero while u < slack), so the energy
// account is the wrapped law's and keeps its balance exactly.
class DistortedLaw final : public ContactLaw {
 public:
  DistortedLaw(std::unique_ptr<ContactLaw> wrapped, double slack);
  DistortedLaw(const DistortedLaw& other);

  void update(const Vector6& displacement_increment) override;
  Vector6 forces() const override;
  EnergyAccount energy() const override { return wrapped_->energy(); }
  bool broken() const override { return wrapped_->broken(); }
  FailureMode failure_mode() const override { return wrapped_->failure_mode(); }
  std::string_view name() const override { return wrapped_->name(); }
  std::unique_ptr<ContactLaw> clone() const override { return std::make_unique<DistortedLaw>(*this); }

  double slack() const { return slack_; }
  const ContactLaw& wrapped() const { return *wrapped_; }

 private:
  std::unique_ptr<ContactLaw> wrapped_;
  double slack_;
  double axial_ = 0.0;  // total axial displacement u [m]
};

}  // namespace dtwire::dem
