#pragma once
// A macro-element set calibrated on a bond of reference length L_ref, carried over to a link of
// another length L at equal strain (dem run's `length = "link"`). The thesis macro-element is a
// force-displacement law: the PFC7 plugin (macroelement_v1.cpp, stressStateEvolution) updates the
// force with kEA times the gap increment whatever the link's length, so a set is used as
// calibrated ("set", the plugin's way). At equal strain and equal plastic work per unit length:
//   axial stiffness EA_N and bending stiffness (per rotation) scale as L_ref / L,
//   k_F (1/m: hardening per metre of plastic elongation) and k_M (per degree of plastic
//   rotation: a link's rotation at a given curvature grows with its length) as L_ref / L,
//   the damage works W1_J, W2_J as L / L_ref;
// forces (N0, Nult, Nc), m_f, beta_f and the shapes are kept (the calibrate module's
// dem_specimen scales a set the same way).
// Both the thesis names and macro3d's own names are rescaled. Standard library only.
//
// A link split at its midpoint into `parts` equal links in series (dem run's
// `[mesh] nodes_per_wire = 3`): under one force each part carries 1/parts of the elongation and
// of the rotation, so each part must give the whole link's force and moment at 1/parts of its
// displacements, F_part(u/n, w/n) = F_whole(u, w), along the whole elastic-plastic-damage path.
// For the thesis and macro3d laws (yield surface in (F, M), hardening on the accumulated plastic
// displacements, damage on the plastic work) that holds exactly when every stiffness and every
// hardening rate per displacement or per rotation is multiplied by n (EA, EI, shear, torsion,
// k_F, k_M), the damage works W1, W2 and the reference length (the plastic-strain break) are
// divided by n, and macro3d's bending_axial_coupling kappa is multiplied by n^2 (its
// c = kappa L_ref / 24 in s_e = u - u_p + c |w|^2 must grow n times while L_ref shrinks n
// times); forces, moment capacities, shapes and ratios are kept. A parallel
// bond's length_m is divided by n. WirePM links are refused: axial force only, so a middle node
// between two of them would be a hinge.
#include <string>

#include "dtwire/dem/contact_law.hpp"

namespace dtwire::dem {

// Throws std::invalid_argument if the set has no reference_length_m > 0 or `link_length` <= 0.
ParameterMap rescale_to_link_length(const ParameterMap& parameters, double link_length);

// The set of one of `parts` equal links in series that together reproduce `parameters`' link
// (contract above). Throws std::invalid_argument for parts < 1, a WirePM or unknown law, or a
// parallel bond without its length_m.
ParameterMap split_in_series(const std::string& law, const ParameterMap& parameters, int parts);

}  // namespace dtwire::dem
