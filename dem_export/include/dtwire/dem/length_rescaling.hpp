#pragma once
// A macro-element set calibrated on a bond of reference length L_ref, carried over to a link of
// another length L at equal strain (dem run's `length = "link"`). The thesis macro-element is a
// force-displacement law: the PFC7 plugin (macroelement_v1.cpp, stressStateEvolution) updates the
// force with kEA times the gap increment whatever the link's length, so a set is used as
// calibrated ("set", the plugin's way). At equal strain and equal plastic work per unit length:
//   axial stiffness EA_N and bending stiffness (per rotation) scale as L_ref / L,
//   k_F (1/m: hardening per metre of plastic elongation) as L_ref / L,
//   the damage works W1_J, W2_J as L / L_ref;
// forces (N0, Nult, Nc), m_f, beta_f, k_M (per degree of rotation) and the shapes are kept.
// Both the thesis names and macro3d's own names are rescaled. Standard library only.
#include "dtwire/dem/contact_law.hpp"

namespace dtwire::dem {

// Throws std::invalid_argument if the set has no reference_length_m > 0 or `link_length` <= 0.
ParameterMap rescale_to_link_length(const ParameterMap& parameters, double link_length);

}  // namespace dtwire::dem
