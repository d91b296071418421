#pragma once
// `dtwire export`: what a DEM user takes home (formats in docs/dem_driver_export.md).
//   <wire_type>_parameters.{h5,json,csv}  parameter tables, SI, names carry their unit
//   <wire_type>_wirepm_yade.py           a YADE script (yade -n -x) building the WirePM material
//                                        and running the two-node pull-unload-reload-break path
//   macroelement_pfc7.dat                the thesis sets as commands of the public PFC7 plugin
//   c_abi/                               the contact-law shared library, its C header, the example
//                                        program and a README
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "dtwire/core/provenance.hpp"
#include "dtwire/dem/export_params.hpp"
#include "dtwire/dem/paths.hpp"

namespace dtwire::dem {

// Writes the three tables of every set; returns the files written.
std::vector<std::filesystem::path> export_parameter_tables(const std::vector<ParameterSet>& sets,
                                                           const std::filesystem::path& out,
                                                           const Provenance& provenance);

// The path the YADE script runs: the "cycles" path (pull-unload-reload, then pull to break).
LoadPath yade_script_path(const PathOptions& options);
// Python source for `yade -n -x SCRIPT [OUT.csv]`; writes time_s, axial_displacement_mm,
// axial_force_N (default output: `default_csv` beside the working directory). Throws
// std::invalid_argument if the WirePM parameters are bad or have no YADE equivalent.
std::string yade_wirepm_script(const ParameterMap& wirepm_parameters, const PathOptions& options,
                               const std::string& default_csv);
void write_yade_script(const ParameterMap& wirepm_parameters, const PathOptions& options,
                       const std::filesystem::path& script);

// Thesis macro-element sets (single_wire -> contact group SW, double_twist -> DT) as the
// `contact cmat add ... model macroelement property me_ea ...` commands of the public PFC7 plugin
// (marcoprevitali/macroelement-doubletwist-PFC7, load_properties.dat). Sets of other laws or
// wire types are left out; throws std::invalid_argument if none is left or a value is bad.
bool is_pfc7_macroelement_set(const ParameterSet& set);
std::string pfc7_macroelement_commands(const std::vector<ParameterSet>& sets, const Provenance& provenance);
// Reads such commands back: cmat number -> property -> value (comments after ';' ignored).
std::map<int, std::map<std::string, double>> read_pfc7_macroelement_commands(const std::string& text);

// Copies the contact-law library this process has loaded, the header (found under `include_dir`)
// and the example programs (*.c in `example_dir`), if present, to `out` and writes README.md with
// compile and link instructions. Returns the files written.
std::vector<std::filesystem::path> export_c_abi(const std::filesystem::path& out,
                                                const std::filesystem::path& include_dir,
                                                const std::filesystem::path& example_dir);

}  // namespace dtwire::dem
