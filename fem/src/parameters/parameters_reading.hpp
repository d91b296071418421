#pragma once
// The .prm reader split by concern (fem/src/parameters/*.cpp, one file per subsection or pair of
// subsections): each declares its entries and reads them into Parameters, converting to SI.
// parameters.cpp strings them together (declare, parse, --set, read each concern).
#include <array>
#include <filesystem>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "../parameters.hpp"
#include "../prm_check.hpp"

namespace dealii {
class ParameterHandler;
}

namespace dtwire::fem::prm_reading {

// The parsed file and where each entry came from, so that a bad value is reported where it was
// given: --set, the file's line, or the file (a default).
struct Source {
  dealii::ParameterHandler& prm;
  const std::filesystem::path& file;
  const std::string& name;
  const EntryLines& lines;
  const std::set<std::string>& set_on_command_line;

  // Called inside `section`.
  // Called inside `section`: an InputError naming --set, file:line or the file when !ok.
  void require(bool ok, const std::string& section, const std::string& entry, const std::string& expected) const;
  // An InputError about `entry` of `section`: at --set when the entry was given there, else at
  // the file's line of the entry.
  [[noreturn]] void fail(const std::string& section, const std::string& entry, const std::string& message) const;
  // `time:value` pairs separated by commas (finite numbers); a bad item fails at the entry.
  std::vector<std::pair<double, double>> pairs(const std::string& section, const std::string& entry) const;
  std::array<double, 3> vector3(const std::string& entry) const;  // three finite numbers
  std::array<double, 3> unit(const std::string& entry) const;     // a non-zero direction, normalised
};

// Whether the file starts like a gmsh mesh ($MeshFormat, or $NOD in format 1).
bool looks_like_gmsh(const std::filesystem::path& mesh);
EndCondition end_condition(const std::string& s);

void declare_geometry(dealii::ParameterHandler& prm);
void read_geometry(const Source& source, Parameters& p);
void declare_material(dealii::ParameterHandler& prm);
void read_material(const Source& source, Parameters& p);
void declare_formulation(dealii::ParameterHandler& prm);
void read_formulation(const Source& source, Parameters& p);
void declare_forming(dealii::ParameterHandler& prm);
void read_forming(const Source& source, Parameters& p);
void declare_boundary_conditions(dealii::ParameterHandler& prm);
void read_boundary_conditions(const Source& source, Parameters& p);
void declare_load_stepping(dealii::ParameterHandler& prm);
void read_load_stepping(const Source& source, Parameters& p);
void declare_newton(dealii::ParameterHandler& prm);
void read_newton(const Source& source, Parameters& p);
void declare_output(dealii::ParameterHandler& prm);
void read_output(const Source& source, Parameters& p);

}  // namespace dtwire::fem::prm_reading
