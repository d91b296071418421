#pragma once
// `dtwire dem run FILE`: a validation run of the wire net (punch, cyclic punch, impact, strip
// tension: strip_tension.hpp) from a TOML input (format in docs/dem_engine.md), its outputs, and
// the same run as a YADE script.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "dtwire/core/curve.hpp"
#include "dtwire/dem/distortion.hpp"
#include "dtwire/dem/engine.hpp"
#include "dtwire/dem/hex_mesh.hpp"
#include "dtwire/dem/run_checks.hpp"
#include "dtwire/dem/strip_tension.hpp"

namespace dtwire::dem {

struct LinkSetInput {
  std::string law;
  ParameterMap parameters;  // from the parameter file (+ backbone), with the overrides applied
  ParameterMap overrides;   // the input's `parameters` table (kept when --set-params swaps the file)
  ParameterMap scales;      // the input's `scale` table: factors on the set's values, after the overrides
  // "set": used as calibrated (the PFC7 plugin); "link": rescaled to each link's length at equal
  // strain (dtwire/dem/length_rescaling.hpp).
  std::string length = "set";
  std::vector<std::filesystem::path> files;
  Distortion distortion;  // Thoeni et al. 2013 initial slack of every link of this type
};

// How the supported edges hold their nodes (docs/dem_engine.md, "Supports and initial state").
enum class EdgeSupport { Pinned, Hinged, Slider };
EdgeSupport parse_edge_support(const std::string& name);  // throws std::invalid_argument
std::string edge_support_name(EdgeSupport support);

struct RunInput {
  std::filesystem::path file;
  std::string title;
  std::string pattern = "8x10_2.7mm";
  HexMeshSpec mesh;
  std::map<LinkTag, LinkSetInput> link_sets;
  unsigned pinned_sides = kLeft | kRight | kBottom | kTop;
  EdgeSupport support = EdgeSupport::Pinned;
  double pretension_strain = 0.0;  // in-plane stretch of the whole net, imposed at t = 0
  // Thesis pre-load: the pre-tension stretch is searched so that the settled net sags this much
  // (0: the given pretension_strain) [m].
  double presag = 0.0;
  // Slack state of the thesis's cyclic tests: a horizontal wall this far below the net's base,
  // on which the net settles with its supported edges free in the plane (0: none) [m].
  double wall_below = 0.0;
  EngineOptions engine;
  double settle_time = 0.0;  // [s] gravity only, before the tool moves (the longest, with a rest ratio)
  // > 0: the settle ends at rest, YADE's unbalanced-force ratio below this, with kinetic damping
  // (settle.hpp); 0: it lasts settle_time.
  double settle_rest_ratio = 0.0;
  // Tool: "platter", "boulder", "none" or "strip_tension" (strip_tension.hpp).
  std::string tool = "platter";
  StripTensionInput strip;
  ToolContactLaw contact;
  double platter_base_radius = 0.5, platter_height = 0.181;  // Pol et al. 2017 (STL of the PFC7 example)
  double start_gap = 0.005;  // tool surface below the lowest node surface at the start [m]
  double speed = 0.01;       // [m/s]
  double travel = 0.7;       // platter travel [m]
  std::vector<double> force_levels;  // cyclic punch: reverse at each force [N]
  double unload_force = 100.0;       // cyclic punch: reload below this force [N]
  // Monotonic punch: the push ends once the net has failed, i.e. a link has broken and the
  // recorded force has fallen below this fraction of its peak (0: the whole travel).
  double stop_below_peak_fraction = 0.0;
  double boulder_side = 0.30, boulder_corner_plane = 0.1875, boulder_mass = 44.5;
  double duration = 0.0;  // [s] after settling (impact); 0: until the platter travel is done
  double output_interval = 0.05;  // [s]
  int frames = 20;
  RunChecks checks;
};

// Throws InputError naming file:line and the field for anything malformed or missing.
// `overrides`: TABLE.KEY=VALUE entries (VALUE in TOML) applied to the file before it is read
// (`dem run --set`); an entry that is not TOML or not a key of the format is an error.
RunInput read_run_input(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});

// Replaces the parameter set of one link type ("sw", "dt", "selvedge") by the only set (or the
// set `wire_type`) of `params`; the law is the file's, else the input's. Throws InputError
// naming `option`.
void override_link_set(RunInput& input, const std::string& tag, const std::filesystem::path& params,
                       const std::string& option);

// The mesh, node fixities and one law per link (reference length of WirePM links set to the
// link's own length, as YADE does). With a distortion, link k gets the slack
// lambda_u l0 r_k (distortion.hpp): WirePM through its own lambda_u (YADE's type 2), every other
// law wrapped in DistortedLaw. Throws InputError naming the field.
struct BuiltNet {
  HexMesh mesh;
  std::vector<EngineLink> links;
};
BuiltNet build_net(const RunInput& input);
// The initial imposed positions (pre-tension stretch about the panel centre).
std::vector<Vector3> pretensioned_positions(const RunInput& input, const HexMesh& mesh);

struct RunOptions {
  std::filesystem::path out;
  std::string command_line;
  // The curve's short name in plots and in the campaign's mesh-scale table (e.g. "thesis
  // published"); empty: the input's title.
  std::string label;
  int threads = 0;  // 0: the input's
  long parallel_threshold = -1;  // -1: the engine's default (EngineOptions)
  bool quiet = false;
  bool write_frames = true;
};

struct RunSummary {
  Curve history;
  double peak_force = 0.0, displacement_at_peak = 0.0;  // [N], [m]
  double onset = -1.0, force_at_420mm = -1.0;  // punch_figures.hpp: [m] (-1: no onset), [N] (-1: not reached)
  double largest_balance_error = 0.0;  // |error| / work on the mesh, largest over the run
  double sag = 0.0;  // largest downward displacement after settling [m]
  double pretension_strain = 0.0;  // the stretch used (searched for a pre-load's sag)
  double kinetic_after_settling = 0.0;  // [J], the quasi-static check of the settled state
  double time_step = 0.0, critical_time_step = 0.0;  // of the tool phase
  double settle_time_step = 0.0;  // the settling's (the tool parked: a longer step)
  double settle_seconds = 0.0;    // how long it settled [s] (settle_time unless it came to rest)
  bool settled_at_rest = false;   // the rest ratio was reached (settle_rest_ratio > 0)
  double settle_unbalanced_ratio = 0.0;  // at the settle's end (Engine::unbalanced_force_ratio)
  long settle_arrests = 0;        // kinetic-damping arrests while settling
  double settle_local_damping_from = -1.0;  // when the local damping joined the settle [s]; < 0: never
  double wall_entered_at = -1.0;  // the slack state's wall entered the run at this time [s] (-1: never)
  std::size_t nodes = 0, links = 0, broken_links = 0;
  long steps = 0;
  bool stopped_at_failure = false;  // the push ended by tool.stop_below_peak_fraction
  double wall_seconds = 0.0;
  StripFigures strip;  // kind = "strip_tension" only
  std::optional<FailedCheck> failed;  // the check that stopped the run (its results are partial)
};

// Runs and writes <out>/curve.csv, results.h5, histograms, frames; throws InputError for input
// errors found while setting up (e.g. a tool inside the mesh), ComputationError otherwise. A run
// stopped by a check (run_checks.hpp) writes its partial results marked failed and returns with
// `failed` set.
RunSummary run_simulation(const RunInput& input, const RunOptions& options);

// How the platter goes to YADE. Sphere: one sphere body, the exact surface (the platter must be
// a hemisphere, tool.height_m = tool.base_radius_m), the force averaged over every step as ours.
// Facets: the semi-spheroid inscribed as segments x rings triangles, the force averaged over 25
// samples per output interval; its reaction departs from the exact platter's by several percent
// near the peak while the net agrees link by link (docs/dem_engine.md, "The YADE export").
// Automatic: sphere for a hemisphere, facets otherwise.
enum class YadePlatter { Automatic, Sphere, Facets };

struct YadeScriptOptions {
  YadePlatter platter = YadePlatter::Automatic;
  int facet_segments = 64, facet_rings = 16;
};

// Python source for `yade -n -x SCRIPT OUT.csv`: the same mesh, WirePM links, boundary,
// pre-tension, gravity, damping, mass scale, time step and platter as the run.
// Throws InputError if the run cannot be expressed in YADE (non-WirePM laws, selvedge, a
// sphere platter that is not a hemisphere, ...).
std::string yade_run_script(const RunInput& input, const YadeScriptOptions& options = {});

}  // namespace dtwire::dem
