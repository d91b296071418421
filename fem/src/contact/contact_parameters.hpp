#pragma once
// The `subsection Contact` of a .prm file: rigid analytic tools in contact with one boundary of
// the wire, their prescribed displacement paths, penalty, friction and augmentation settings.
// Values in SI here; the file uses mm and MPa.
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "contact_kernel.hpp"
#include "dtwire/core/region_ids.hpp"

namespace dealii {
class ParameterHandler;
}

namespace dtwire::fem::contact {

constexpr unsigned kMaximumTools = 4;

struct ToolParameters {
  ToolShape shape = ToolShape::plane;
  std::array<double, 3> point{};      // m, at pseudo-time 0
  std::array<double, 3> direction{};  // unit: plane outward normal, cylinder axis
  double radius = 0.0;                // m, cylinder or groove
  std::array<double, 3> groove_axis{};  // unit, grooved plate (perpendicular to direction)
  // (pseudo-time, tool displacement in m), piecewise linear; constant after the last knot.
  std::vector<std::pair<double, std::array<double, 3>>> path;
};

struct ContactParameters {
  std::vector<unsigned> boundary_ids{0};  // wire boundaries that touch the tools (0: SW lateral surface)
  double friction = 0.0;                // Coulomb mu
  double normal_penalty_factor = 10.0;  // epsilon_N = factor E / h, h the smallest contact face size
  double tangential_penalty_factor = 10.0;
  unsigned maximum_augmentations = 0;   // Uzawa updates per step (0: pure penalty)
  double gap_tolerance = 1e-6;          // m, largest penetration accepted without augmenting
  std::vector<ToolParameters> tools;    // empty: no contact
  bool keep_samples = false;            // not in the .prm: per-point samples in the step records

  bool enabled() const { return !tools.empty(); }
};

// `subsection Wire contact`: frictional contact between two deformable wires (the double twist),
// Gauss points of the slave surface against the bilinear faces of the master surface.
struct WireContactParameters {
  bool enabled = false;
  std::vector<unsigned> slave_ids{regions::kWireALateral}, master_ids{regions::kWireBLateral};  // DT mesh
  double friction = 0.2;                // Coulomb mu between the wires
  double normal_penalty_factor = 10.0;  // epsilon_N = factor E / h
  double tangential_penalty_factor = 10.0;
  unsigned maximum_augmentations = 0;
  double gap_tolerance = 1e-6;          // m
  double search_distance = 0.0;         // m; 0: a quarter of the wire diameter
  // m, added to every wire-wire gap: the initial clearance (> 0) or interference (< 0) of the
  // interweavement beyond the meshed one; the twist-tightening unknown of calibration fit (2).
  double gap_offset = 0.0;
  unsigned points_per_direction = 2;    // Gauss points per direction on each slave face
  unsigned flip_limit = 4;              // status changes within a step before the status is frozen
  bool smoothed_normals = false;        // master normal from averaged vertex normals (wire_contact_point.hpp)
  bool keep_samples = false;            // not in the .prm: per-point samples in the step records
};

void declare_contact_parameters(dealii::ParameterHandler& prm);
// Reads the subsection; throws InputError naming `file` and the entry on bad values. Every
// tool-path knot inside the load path must also be a knot of the load path (`knot_times`), so
// that load steps land on it.
ContactParameters parse_contact_parameters(dealii::ParameterHandler& prm, const std::string& file,
                                           const std::vector<double>& knot_times);

WireContactParameters parse_wire_contact_parameters(dealii::ParameterHandler& prm, const std::string& file);

// Comma-separated boundary ids ("3, 13"); throws InputError naming file and entry.
std::vector<unsigned> parse_id_list(const std::string& text, const std::string& file, const std::string& entry);

// Tool displacement (m) at pseudo-time t.
std::array<double, 3> tool_displacement(const ToolParameters& tool, double t);

}  // namespace dtwire::fem::contact
