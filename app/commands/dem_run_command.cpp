#include "dem_run_command.hpp"

#include <CLI/CLI.hpp>

#include <iostream>
#include <optional>
#include <sstream>
#include <thread>

#include "../cli.hpp"
#include "../plotting.hpp"
#include "dtwire/core/atomic_file.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/resources.hpp"
#include "dtwire/dem/run.hpp"
#include "dtwire/dem/run_footprint.hpp"
#include "option_checks.hpp"

namespace dtwire::app {
namespace {

struct RunCommandOptions {
  std::string file;
  std::string out;
  std::string yade_script;
  std::string yade_platter = "auto";
  bool export_only = false;
  bool quiet = false;
  bool no_frames = false;
  int threads = 0;
  std::vector<std::string> set_params;
  std::vector<std::string> set_entries;
  std::string plot;
  std::vector<std::string> compare;
  std::string max_memory;
  std::string label;
};

// Refuses, before anything is built or written, a run the machine cannot hold (exit 2).
void check_resources(const RunCommandOptions& o, const dem::RunInput& input, const std::filesystem::path& out) {
  const dem::RunFootprint f = dem::run_footprint(input, !o.no_frames);
  std::ostringstream panel;
  panel << "a " << input.mesh.width << " x " << input.mesh.height << " m panel (mesh.width_m, mesh.height_m): " << f.describe();
  std::optional<std::uint64_t> max_memory;
  if (!o.max_memory.empty()) max_memory = parse_byte_size(o.max_memory, "--max-memory");
  check_memory(f.memory, max_memory, input.file.string(), panel.str());
  check_disk(f.disk, out, input.file.string(), panel.str() + " (--no-frames writes none)");
}

void print_strip_summary(const dem::RunInput& input, const dem::RunSummary& s, const std::filesystem::path& out) {
  const dem::StripFigures& f = s.strip;
  std::cout << input.title << ": " << s.nodes << " nodes, " << s.links << " links, " << s.steps << " steps of "
            << s.time_step << " s (critical " << s.critical_time_step << " s), " << s.wall_seconds << " s wall\n"
            << "strip " << f.width << " m wide, free length " << f.free_length << " m; strength " << f.strength_per_width / 1000.0
            << " kN/m (peak " << s.peak_force / 1000.0 << " kN at " << 1000.0 * s.displacement_at_peak << " mm, strain "
            << 100.0 * f.strain_at_peak << " %); secant EA (10-50 % of the peak) ";
  if (f.secant.defined) std::cout << f.secant.value / 1000.0 << " kN/m";
  else std::cout << "undefined";
  std::cout << "; broken links " << s.broken_links << (f.torn ? " (torn through)" : "") << "; largest energy balance error "
            << 100.0 * s.largest_balance_error << " % of the work on the mesh\n"
            << "-> " << (out / "curve.csv").string() << ", " << (out / "results.h5").string() << ", "
            << (out / "summary.json").string() << "\n";
}

int run_dem_run(const RunCommandOptions& o) {
  check_output_folders({{"-o", o.out}});
  check_plot_file(o.plot, "--plot");
  if (!o.plot.empty()) {
    require_plotting("plot_punch.py", "--plot");
    require_plotting("plot_curves.py", "--plot");
  }
  dem::RunInput input = dem::read_run_input(o.file, o.set_entries);
  for (const std::string& entry : o.set_params) {
    const auto equals = entry.find('=');
    if (equals == std::string::npos) throw InputError("--set-params", "expected TAG=FILE, found '" + entry + "'");
    dem::override_link_set(input, entry.substr(0, equals), entry.substr(equals + 1), "--set-params");
    // The title labels the curve in plots: say which sets were swapped in.
    input.title += " [" + entry.substr(0, equals) + ": " + std::filesystem::path(entry.substr(equals + 1)).filename().string() + "]";
  }
  const std::filesystem::path out = o.out.empty() ? std::filesystem::path("dem-out") / input.file.stem() : std::filesystem::path(o.out);
  check_resources(o, input, out);
  if (!o.yade_script.empty()) {
    dem::YadeScriptOptions yade;
    yade.platter = o.yade_platter == "sphere"   ? dem::YadePlatter::Sphere
                   : o.yade_platter == "facets" ? dem::YadePlatter::Facets
                                                : dem::YadePlatter::Automatic;
    const std::string script = dem::yade_run_script(input, yade);
    write_file_atomically(o.yade_script, [&](std::ostream& os) { os << script; });
    std::cout << "YADE script: " << o.yade_script << " (run: yade -n -x " << o.yade_script << " OUT.csv)\n";
    if (o.export_only) return 0;
  } else if (o.export_only) {
    throw InputError("--export-only", "needs --yade-script FILE");
  }
  dem::RunOptions options;
  options.out = out;
  options.command_line = "dtwire dem run " + o.file;
  for (const std::string& entry : o.set_entries) options.command_line += " --set '" + entry + "'";
  for (const std::string& entry : o.set_params) options.command_line += " --set-params " + entry;
  if (o.threads > 0) options.command_line += " --threads " + std::to_string(o.threads);
  if (!o.label.empty()) options.command_line += " --label '" + o.label + "'";
  options.label = o.label;
  options.threads = o.threads;
  options.quiet = o.quiet;
  options.write_frames = !o.no_frames;
  const int threads = o.threads > 0 ? o.threads : input.engine.threads;
  if (const auto load = load_average())
    if (const std::string warning = oversubscription_warning(threads, *load, std::thread::hardware_concurrency());
        !warning.empty())
      std::cerr << "dtwire: warning: dem run: " << warning << "\n";
  remove_stale_temporaries(out);  // of a run killed while it wrote (atomic_file.hpp)
  remove_stale_temporaries(out / "frames");
  dem::RunSummary s;
  try {
    s = dem::run_simulation(input, options);
  } catch (const InputError&) {
    throw;  // found before anything is written
  } catch (const std::exception& e) {
    // A write failed (no space, file-size limit, I/O error): the files that mark a finished run
    // go, so neither a campaign nor a reader takes what is left for a result.
    std::error_code ignored;
    for (const char* marker : {"summary.json", "results.h5", "curve.csv"}) std::filesystem::remove(out / marker, ignored);
    throw std::runtime_error(std::string(e.what()) + "; the run's curve.csv, results.h5 and summary.json in " +
                             out.string() + " are removed");
  }
  const bool strip = input.tool == "strip_tension";
  if (strip) print_strip_summary(input, s, out);
  else std::cout << input.title << ": " << s.nodes << " nodes, " << s.links << " links, " << s.steps << " steps of "
            << s.time_step << " s (critical " << s.critical_time_step << " s; settling "
            << s.settle_time_step << " s), " << s.wall_seconds << " s wall\n"
            << "sag after settling " << 1000.0 * s.sag << " mm; peak force " << s.peak_force / 1000.0 << " kN at "
            << 1000.0 * s.displacement_at_peak << " mm; broken links " << s.broken_links
            << (s.stopped_at_failure ? " (stopped at the net's failure)" : "") << "; largest energy balance error " << 100.0 * s.largest_balance_error << " % of the work on the mesh\n"
            << "-> " << (out / "curve.csv").string() << ", " << (out / "results.h5").string() << "\n";
  if (s.failed) {
    // The partial results stay, marked failed (summary.json "status", curve.csv, results.h5).
    std::cerr << "dtwire: failed: dem run: " << s.failed->message() << "; partial results in " << out.string()
              << " (status failed)\n";
    return kExitFailure;
  }
  if (!o.plot.empty()) {
    // Punches against the thesis figures (plot_punch.py); other tools as plain curves.
    const bool punch = input.tool == "platter" && input.force_levels.empty();
    std::vector<std::string> arguments{o.plot};
    if (!punch)
      arguments.insert(arguments.end(), {strip ? "strain" : "tool_displacement", strip ? "force_per_width" : "tool_force",
                                         strip ? "Strip force per width against strain" : "Tool force against displacement"});
    arguments.push_back((out / "curve.csv").string());
    arguments.insert(arguments.end(), o.compare.begin(), o.compare.end());
    run_plot_script(punch ? "plot_punch.py" : "plot_curves.py", arguments);
    std::cout << "plot: " << o.plot << "\n";
  }
  return 0;
}

}  // namespace

void add_dem_run_command(CLI::App& dem, CommandSet& commands) {
  auto o = std::make_shared<RunCommandOptions>();
  CLI::App* run = dem.add_subcommand("run", "Mesh-scale DEM run of a wire net (punch, cyclic punch, impact, strip tension) from a TOML input");
  run->add_option("file", o->file, "Run input (.toml, docs/dem_engine.md)")->required()->check(CLI::ExistingFile);
  run->add_option("-o,--out", o->out, "Output directory (default dem-out/<input name>)");
  run->add_option("--threads", o->threads, "Threads for the link and node updates (default: the input's)")
      ->check(CLI::Range(1, 256));
  run->add_option("--yade-script", o->yade_script, "Also write the run as a YADE script (WirePM punch only)");
  run->add_option("--yade-platter", o->yade_platter,
                  "The platter in the YADE script: sphere (exact, a hemisphere platter only), facets (64 x 16 inscribed "
                  "triangles, any height) or auto (sphere for a hemisphere; default)")
      ->check(CLI::IsMember({"auto", "sphere", "facets"}));
  run->add_flag("--export-only", o->export_only, "Write the YADE script and stop");
  run->add_flag("--no-frames", o->no_frames, "No VTU frames");
  run->add_option("--set", o->set_entries,
                  "Replace or add an input entry, TABLE.KEY=VALUE with a TOML value (boundary.support=\"slider\"); checked as the file's");
  run->add_option("--set-params", o->set_params,
                  "TAG=FILE: take the sw, dt or selvedge law set from FILE (e.g. sw={out}/export/single_wire_parameters.json)");
  run->add_option("--plot", o->plot, "Plot tool force against displacement (PNG)");
  run->add_option("--compare", o->compare, "Other curve CSVs on the same plot")->check(CLI::ExistingFile);
  run->add_option("--label", o->label, "Short name of the run in plots and the campaign's mesh-scale table (default: the input's title)");
  run->add_flag("-q,--quiet", o->quiet, "No progress line");
  run->add_option("--max-memory", o->max_memory,
                  "Refuse runs whose memory estimate exceeds SIZE (4G, 512M; default: the available memory)");
  commands.add(run, [o] { return run_dem_run(*o); });
}

}  // namespace dtwire::app
