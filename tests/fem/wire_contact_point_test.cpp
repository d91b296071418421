// The consistent tangent of one wire-wire contact point (issue 5), label verification:
// - on a flat master face the traction is the penalty law's closed form (p = eps_N * penetration,
//   Coulomb t_T = mu p when slipping);
// - on a warped, tilted master face the AD tangent equals central finite differences of the
//   nodal forces, where every perturbed state re-projects the point (so the projection, normal
//   and anchor variations are all checked), for frictionless, sticking and slipping points and a
//   point whose projection is clamped to an edge of the face.
#include <gtest/gtest.h>

#include <cmath>

#include "contact/bilinear_face.hpp"
#include "contact/wire_contact_point.hpp"

namespace dtwire::fem::contact {
namespace {

Vector3 vec(double x, double y, double z) {
  Vector3 v;
  v[0] = x;
  v[1] = y;
  v[2] = z;
  return v;
}

// Slave face above a master face; displacements chosen so that the point at (0.3, 0.6) of the
// slave face penetrates the master face by about `penetration`.
struct Case {
  WireContactPointInput input;
  ContactLaw law;
};

Case make_case(double mu, bool warped, double penetration, const Vector3& drag, double master_motion = 1e-6) {
  Case c;
  auto& in = c.input;
  const double h = 1e-3;  // 1 mm faces
  if (warped)
    in.master_reference = {{vec(0, 0, 0), vec(h, 0, 0.08 * h), vec(0, h, -0.05 * h), vec(h, h, 0.2 * h)}};
  else
    in.master_reference = {{vec(0, 0, 0), vec(h, 0, 0), vec(0, h, 0), vec(h, h, 0)}};
  in.master_sign = 1.0;  // outward normal +z
  in.slave_reference = {{vec(0.1 * h, 0.05 * h, 0.3 * h), vec(1.0 * h, 0.1 * h, 0.32 * h),
                         vec(0.05 * h, 0.9 * h, 0.31 * h), vec(0.95 * h, 1.05 * h, 0.36 * h)}};
  in.slave_xi = 0.3;
  in.slave_eta = 0.6;
  in.weight = 0.25 * h * h;
  // The master face moved a little since the last converged step (about 1 nm).
  for (unsigned i = 0; i < 12; ++i) {
    in.master_committed_displacement[i] = 0.0;
    in.master_displacement[i] = master_motion * h * std::sin(1.0 + i);
  }
  BilinearFace slave, master;
  slave.vertex = in.slave_reference;
  const Vector3 x = slave.position(in.slave_xi, in.slave_eta);
  // Drag the slave face, then move it down so that the point sits `penetration` below the
  // master surface.
  for (unsigned v = 0; v < 4; ++v) {
    slave.vertex[v] += drag;
    for (unsigned k = 0; k < 3; ++k) {
      in.slave_displacement[3 * v + k] = drag[k];
      master.vertex[v][k] = in.master_reference[v][k] + in.master_displacement[3 * v + k];
    }
  }
  const Vector3 dragged = slave.position(in.slave_xi, in.slave_eta);
  const auto proj = project_onto_face(master, dragged);
  const Vector3 n = master.outward_normal(proj.xi, proj.eta);
  const double height = (dragged - master.position(proj.xi, proj.eta)) * n;
  for (unsigned v = 0; v < 4; ++v)
    for (unsigned k = 0; k < 3; ++k) in.slave_displacement[3 * v + k] -= (height + penetration) * n[k];
  in.committed_slave_position = x;
  c.law.normal_penalty = 2e14;
  c.law.tangential_penalty = 2e14;
  c.law.friction = mu;
  return c;
}

// Re-project and evaluate (the solver's sequence: search in doubles, then the point).
WireContactPointOutput evaluate_at(WireContactPointInput in, const ContactLaw& law, bool tangent) {
  BilinearFace slave, master;
  for (unsigned v = 0; v < 4; ++v)
    for (unsigned k = 0; k < 3; ++k) {
      slave.vertex[v][k] = in.slave_reference[v][k] + in.slave_displacement[3 * v + k];
      master.vertex[v][k] = in.master_reference[v][k] + in.master_displacement[3 * v + k];
    }
  const auto proj = project_onto_face(master, slave.position(in.slave_xi, in.slave_eta));
  in.master_xi = proj.xi;
  in.master_eta = proj.eta;
  return evaluate_wire_contact_point(in, law, tangent);
}

// Largest |K_ad - K_fd| relative to the largest |K_ad| entry.
double tangent_error(const Case& c) {
  const auto exact = evaluate_at(c.input, c.law, true);
  double largest = 0.0, error = 0.0;
  for (const auto& row : exact.stiffness)
    for (const double k : row) largest = std::max(largest, std::abs(k));
  const double step = 1e-10;  // m: well inside one stick/slip status at these penalties
  for (unsigned j = 0; j < 24; ++j) {
    WireContactPointInput plus = c.input, minus = c.input;
    auto& up = j < 12 ? plus.slave_displacement[j] : plus.master_displacement[j - 12];
    auto& down = j < 12 ? minus.slave_displacement[j] : minus.master_displacement[j - 12];
    up += step;
    down -= step;
    const auto fp = evaluate_at(plus, c.law, false), fm = evaluate_at(minus, c.law, false);
    for (unsigned i = 0; i < 24; ++i)
      error = std::max(error, std::abs((fp.force[i] - fm.force[i]) / (2 * step) - exact.stiffness[i][j]));
  }
  return error / largest;
}

TEST(WireContactPoint, FlatFaceGivesThePenaltyLawInClosedForm) {
  const double penetration = 2e-8;
  const auto c = make_case(0.0, false, penetration, vec(0, 0, 0), 0.0);
  const auto out = evaluate_at(c.input, c.law, true);
  ASSERT_TRUE(out.response.active);
  EXPECT_NEAR(out.response.pressure / (c.law.normal_penalty * penetration), 1.0, 1e-9);
  // Nodal forces: the slave face is pushed up (+z) with p w in total, the master down.
  double slave_z = 0.0, master_z = 0.0;
  for (unsigned v = 0; v < 4; ++v) {
    slave_z += out.force[3 * v + 2];
    master_z += out.force[12 + 3 * v + 2];
  }
  const double total = out.response.pressure * c.input.weight;
  EXPECT_NEAR(-slave_z / total, 1.0, 1e-9);  // internal force = -(traction on the body)
  EXPECT_NEAR(master_z / total, 1.0, 1e-9);

  // Dragged far along x: slipping, tangential traction mu p against the motion.
  const auto slip = make_case(0.3, false, penetration, vec(5e-7, 0, 0), 0.0);
  const auto s = evaluate_at(slip.input, slip.law, false);
  ASSERT_TRUE(s.response.slipping);
  EXPECT_NEAR(s.response.tangential_traction.norm() / (0.3 * s.response.pressure), 1.0, 1e-9);
  EXPECT_LT(s.response.tangential_traction[0], 0.0);
}

TEST(WireContactPoint, FrictionlessTangentMatchesFiniteDifferences) {
  const auto c = make_case(0.0, true, 3e-8, vec(1e-5, -2e-5, 0));
  ASSERT_TRUE(evaluate_at(c.input, c.law, false).response.active);
  EXPECT_LT(tangent_error(c), 1e-6);  // measured 3e-10 (FD truncation and round-off)
}

TEST(WireContactPoint, StickingTangentMatchesFiniteDifferences) {
  const auto c = make_case(0.5, true, 3e-8, vec(1e-9, 0, 0));
  const auto out = evaluate_at(c.input, c.law, false);
  ASSERT_TRUE(out.response.active);
  ASSERT_FALSE(out.response.slipping);
  EXPECT_LT(tangent_error(c), 1e-6);  // measured 3e-10 to 2e-9
}

TEST(WireContactPoint, SlippingTangentMatchesFiniteDifferences) {
  const auto c = make_case(0.3, true, 3e-8, vec(2e-6, 1e-6, 0));
  const auto out = evaluate_at(c.input, c.law, false);
  ASSERT_TRUE(out.response.slipping);
  EXPECT_LT(tangent_error(c), 1e-6);  // measured 3e-10 to 2e-9
}

TEST(WireContactPoint, EdgeClampedProjectionTangentMatchesFiniteDifferences) {
  // Dragged beyond the master face's edge x = h: xi is clamped to 1, eta stays free.
  const auto c = make_case(0.3, true, 3e-8, vec(0.9e-3, 0, 0));
  const auto out = evaluate_at(c.input, c.law, false);
  ASSERT_TRUE(out.response.active);
  WireContactPointInput in = c.input;
  BilinearFace slave, master;
  for (unsigned v = 0; v < 4; ++v)
    for (unsigned k = 0; k < 3; ++k) {
      slave.vertex[v][k] = in.slave_reference[v][k] + in.slave_displacement[3 * v + k];
      master.vertex[v][k] = in.master_reference[v][k] + in.master_displacement[3 * v + k];
    }
  const auto proj = project_onto_face(master, slave.position(in.slave_xi, in.slave_eta));
  ASSERT_EQ(proj.xi, 1.0);
  ASSERT_GT(proj.eta, 0.0);
  ASSERT_LT(proj.eta, 1.0);
  EXPECT_LT(tangent_error(c), 1e-6);  // measured 3e-10 to 2e-9
}

}  // namespace
}  // namespace dtwire::fem::contact
