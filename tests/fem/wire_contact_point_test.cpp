// The consistent tangent of one wire-wire contact point (issue 5), label verification:
// - on a flat master face the traction is the penalty law's closed form (p = eps_N * penetration,
//   Coulomb t_T = mu p when slipping);
// - on a warped, tilted master face the AD tangent equals central finite differences of the
//   nodal forces, where every perturbed state re-projects the point (so the projection, normal
//   and anchor variations are all checked), for frictionless, sticking and slipping points and a
//   point whose projection is clamped to an edge of the face;
// - smoothed normals: on a faceted cylinder the interpolated normal equals the exact radial
//   direction at the vertices and is continuous across a facet edge (where the faceted normal
//   jumps by the facet angle); their tangent, over the neighbour vertices' dofs too, equals
//   finite differences.
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
  for (const double k : exact.stiffness) largest = std::max(largest, std::abs(k));
  const double step = 1e-10;  // m: well inside one stick/slip status at these penalties
  for (unsigned j = 0; j < 24; ++j) {
    WireContactPointInput plus = c.input, minus = c.input;
    auto& up = j < 12 ? plus.slave_displacement[j] : plus.master_displacement[j - 12];
    auto& down = j < 12 ? minus.slave_displacement[j] : minus.master_displacement[j - 12];
    up += step;
    down -= step;
    const auto fp = evaluate_at(plus, c.law, false), fm = evaluate_at(minus, c.law, false);
    for (unsigned i = 0; i < 24; ++i)
      error = std::max(error, std::abs((fp.force[i] - fm.force[i]) / (2 * step) - exact.tangent(i, j)));
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

// A faceted cylinder (radius R, `facets` around, axis z) as a grid of bilinear faces, outward
// normals; master face (i, j) spans angles i, i + 1 and heights j, j + 1. The smoothed-normal
// input of face (i0, j0): its patch (its own vertices first) and corners, as the solver builds them.
struct FacetedCylinder {
  double radius = 1e-3, height = 0.5e-3;
  unsigned facets = 8, rows = 3;
  Vector3 vertex(unsigned i, unsigned j) const {
    const double angle = 2 * M_PI * (i % facets) / facets;
    return vec(radius * std::cos(angle), radius * std::sin(angle), height * j);
  }
  // Face vertex order (0,0), (1,0), (0,1), (1,1): xi around, eta along z (outward normal +).
  std::array<std::pair<unsigned, unsigned>, 4> face(unsigned i, unsigned j) const {
    return {{{i % facets, j}, {(i + 1) % facets, j}, {i % facets, j + 1}, {(i + 1) % facets, j + 1}}};
  }
  void fill(WireContactPointInput& in, unsigned i0, unsigned j0) const {
    std::vector<std::pair<unsigned, unsigned>> patch;
    const auto local = [&](std::pair<unsigned, unsigned> v) {
      for (unsigned k = 0; k < patch.size(); ++k)
        if (patch[k] == v) return k;
      patch.push_back(v);
      return static_cast<unsigned>(patch.size() - 1);
    };
    const auto own = face(i0, j0);
    for (unsigned v = 0; v < 4; ++v) {
      local(own[v]);
      in.master_reference[v] = vertex(own[v].first, own[v].second);
    }
    for (unsigned v = 0; v < 4; ++v)
      for (unsigned i = 0; i < facets; ++i)
        for (unsigned j = 0; j + 1 <= rows; ++j) {
          const auto f = face(i, j);
          for (unsigned corner = 0; corner < 4; ++corner)
            if (f[corner] == own[v]) {
              NormalCorner c;
              for (unsigned k = 0; k < 4; ++k) c.face[k] = local(f[k]);
              c.corner = corner;
              in.vertex_corners[v].push_back(c);
            }
        }
    for (unsigned k = 4; k < patch.size(); ++k) {
      in.neighbour_reference.push_back(vertex(patch[k].first, patch[k].second));
      for (unsigned c = 0; c < 3; ++c) in.neighbour_displacement.push_back(0.0);
    }
    in.master_sign = 1.0;
  }
};

// Slave point held at polar angle `angle` and height z, `penetration` inside the faceted
// surface's smoothed normal direction; returns the traction direction.
WireContactPointOutput cylinder_point(const FacetedCylinder& cyl, unsigned face_i, double angle, double z,
                                      bool smoothed, double mu = 0.0) {
  WireContactPointInput in;
  cyl.fill(in, face_i, 1);
  if (!smoothed) {
    for (auto& corners : in.vertex_corners) corners.clear();
    in.neighbour_reference.clear();
    in.neighbour_displacement.clear();
  }
  // Place the slave face's point on the facet plane at this angle, slightly inside it.
  BilinearFace master;
  master.vertex = in.master_reference;
  const Vector3 dir = vec(std::cos(angle), std::sin(angle), 0.0);
  const Vector3 n_facet = master.outward_normal(0.5, 0.5);
  const double facet_distance = master.position(0.5, 0.5) * n_facet;  // the plane's distance from the axis
  const Vector3 on_plane = dir * (facet_distance / (dir * n_facet)) + vec(0, 0, z);
  const Vector3 x = on_plane - 2e-8 * n_facet;
  const double h = 0.2e-3;
  in.slave_reference = {{x + vec(-h, 0, -h), x + vec(h, 0, -h), x + vec(-h, 0, h), x + vec(h, 0, h)}};
  in.slave_xi = 0.5;
  in.slave_eta = 0.5;
  in.weight = 1e-8;
  in.committed_slave_position = x;
  ContactLaw law;
  law.normal_penalty = law.tangential_penalty = 2e14;
  law.friction = mu;
  return evaluate_at(in, law, true);
}

TEST(WireContactPoint, SmoothedNormalIsRadialAtVerticesAndContinuousOverFacetEdges) {
  const FacetedCylinder cyl;
  const double edge = 2 * M_PI / cyl.facets;  // face 0 spans [0, edge] in angle
  const double z = 1.5 * cyl.height;
  const auto direction = [](const WireContactPointOutput& out) {
    return out.response.traction / out.response.traction.norm();
  };
  // Just before and after the edge at angle `edge` (faces 0 and 1): faceted normals differ by
  // the facet angle (45 deg), smoothed ones by the angle the point moved.
  const double d = 1e-6;
  const auto faceted_before = cylinder_point(cyl, 0, edge - d, z, false);
  const auto faceted_after = cylinder_point(cyl, 1, edge + d, z, false);
  ASSERT_TRUE(faceted_before.response.active && faceted_after.response.active);
  EXPECT_NEAR(std::acos(direction(faceted_before) * direction(faceted_after)), edge, 1e-6);
  const auto smooth_before = cylinder_point(cyl, 0, edge - d, z, true);
  const auto smooth_after = cylinder_point(cyl, 1, edge + d, z, true);
  ASSERT_TRUE(smooth_before.response.active && smooth_after.response.active);
  EXPECT_LT(std::acos(std::min(1.0, direction(smooth_before) * direction(smooth_after))), 1e-5);
  // At the edge the averaged vertex normal is the exact radial direction of the cylinder.
  const Vector3 radial = vec(std::cos(edge), std::sin(edge), 0.0);
  EXPECT_NEAR(direction(smooth_before) * radial, 1.0, 1e-9);
  // At the facet's middle, by symmetry, the facet normal again.
  const auto smooth_middle = cylinder_point(cyl, 0, 0.5 * edge, z, true);
  EXPECT_NEAR(direction(smooth_middle) * vec(std::cos(0.5 * edge), std::sin(0.5 * edge), 0.0), 1.0, 1e-9);
}

TEST(WireContactPoint, SmoothedNormalTangentMatchesFiniteDifferencesOverTheNeighbours) {
  FacetedCylinder cyl;
  for (const double mu : {0.0, 0.3}) {
    const auto base = cylinder_point(cyl, 0, 0.3, 1.3 * cyl.height, true, mu);
    ASSERT_TRUE(base.response.active);
    // Rebuild the input that cylinder_point used, then disturb every dof a little so that the
    // patch is not symmetric, and compare the AD tangent with central differences.
    WireContactPointInput c;
    cyl.fill(c, 0, 1);
    ASSERT_GT(c.neighbour_reference.size(), 4u);
    const unsigned n = 24 + 3 * c.neighbour_reference.size();
    EXPECT_EQ(base.force.size(), n);
    for (unsigned k = 0; k < c.neighbour_displacement.size(); ++k) c.neighbour_displacement[k] = 2e-6 * std::sin(3.0 + k);
    for (unsigned k = 0; k < 12; ++k) c.master_displacement[k] = 2e-6 * std::cos(1.0 + k);
    BilinearFace master;
    for (unsigned v = 0; v < 4; ++v)
      for (unsigned k = 0; k < 3; ++k) master.vertex[v][k] = c.master_reference[v][k] + c.master_displacement[3 * v + k];
    const Vector3 target = master.position(0.4, 0.6);
    const Vector3 inward = -master.outward_normal(0.4, 0.6);
    const double h = 0.2e-3;
    const Vector3 x = target + 3e-8 * inward;
    c.slave_reference = {{x + vec(-h, 0, -h), x + vec(h, 0, -h), x + vec(-h, 0, h), x + vec(h, 0, h)}};
    c.slave_xi = c.slave_eta = 0.5;
    c.weight = 1e-8;
    c.committed_slave_position = x - vec(0, 0, mu > 0 ? 1e-6 : 0.0);  // slipping when mu > 0
    ContactLaw law;
    law.normal_penalty = law.tangential_penalty = 2e14;
    law.friction = mu;
    const auto exact = evaluate_at(c, law, true);
    ASSERT_TRUE(exact.response.active);
    // Errors relative to the largest entry of the face columns (penalty scale) and of the
    // neighbour columns (pressure x area / facet size: the normal's variation), separately.
    double largest_face = 0.0, largest_neighbour = 0.0, error_face = 0.0, error_neighbour = 0.0;
    for (unsigned i = 0; i < n; ++i)
      for (unsigned j = 0; j < n; ++j)
        (j < 24 ? largest_face : largest_neighbour) =
            std::max(j < 24 ? largest_face : largest_neighbour, std::abs(exact.tangent(i, j)));
    const double step = 1e-10;
    for (unsigned j = 0; j < n; ++j) {
      WireContactPointInput plus = c, minus = c;
      auto& up = j < 12 ? plus.slave_displacement[j] : j < 24 ? plus.master_displacement[j - 12] : plus.neighbour_displacement[j - 24];
      auto& down = j < 12 ? minus.slave_displacement[j] : j < 24 ? minus.master_displacement[j - 12] : minus.neighbour_displacement[j - 24];
      up += step;
      down -= step;
      const auto fp = evaluate_at(plus, law, false), fm = evaluate_at(minus, law, false);
      for (unsigned i = 0; i < n; ++i) {
        const double e = std::abs((fp.force[i] - fm.force[i]) / (2 * step) - exact.tangent(i, j));
        (j < 24 ? error_face : error_neighbour) = std::max(j < 24 ? error_face : error_neighbour, e);
      }
    }
    EXPECT_LT(error_face / largest_face, 1e-6) << "mu " << mu;
    EXPECT_LT(error_neighbour / largest_neighbour, 1e-4) << "mu " << mu;
    // The neighbour columns are of the size the normal's variation predicts: p w / facet size.
    const double facet = 2 * M_PI * cyl.radius / cyl.facets;
    const double expected = exact.response.pressure * c.weight / facet;
    EXPECT_GT(largest_neighbour / expected, 0.1) << "mu " << mu;
    EXPECT_LT(largest_neighbour / expected, 10.0) << "mu " << mu;
  }
}

TEST(WireContactPoint, SmoothedNormalRejectsAnIncompletePatch) {
  FacetedCylinder cyl;
  WireContactPointInput in;
  cyl.fill(in, 0, 1);
  in.vertex_corners[2].clear();
  ContactLaw law;
  law.normal_penalty = 1.0;
  EXPECT_THROW(evaluate_wire_contact_point(in, law, false), std::invalid_argument);
  cyl.fill(in, 0, 1);
  in.neighbour_displacement.pop_back();
  EXPECT_THROW(evaluate_wire_contact_point(in, law, false), std::invalid_argument);
}

}  // namespace
}  // namespace dtwire::fem::contact
