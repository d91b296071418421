#include "gap_model_runner.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <regex>
#include <sstream>

#include "dtwire/calibrate/command_simulator.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/provenance.hpp"
#include "dtwire/core/region_ids.hpp"
#include "msh_area.hpp"

namespace dtwire::app {
namespace {

const std::regex& set_line() {
  static const std::regex r(R"(^(\s*set\s+)([^=]*?)(\s*=\s*)([^#]*?)(\s*(#.*)?)$)");
  return r;
}

std::string number_text(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

// Calls `edit(name, value)` on every `set name = value` line; a non-empty result replaces value.
std::string edit_entries(const std::string& text,
                         const std::function<std::string(const std::string&, const std::string&)>& edit) {
  std::istringstream in(text);
  std::ostringstream out;
  std::string line;
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_match(line, m, set_line())) {
      const std::string replaced = edit(m[2].str(), m[4].str());
      if (!replaced.empty()) line = m[1].str() + m[2].str() + m[3].str() + replaced + m[5].str();
    }
    out << line << "\n";
  }
  return out.str();
}

// Sets `name` inside `subsection section` (one level deep) to value; adds the line at the end of
// the subsection when it is missing there.
std::string set_in_subsection(const std::string& text, const std::string& section, const std::string& name,
                              const std::string& value) {
  std::istringstream in(text);
  std::ostringstream out;
  std::string line;
  bool inside = false, done = false;
  const std::regex open("^\\s*subsection\\s+(.*?)\\s*$"), close("^\\s*end\\s*$");
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_match(line, m, open)) inside = m[1].str() == section;
    if (inside && std::regex_match(line, m, set_line()) && m[2].str() == name) {
      line = m[1].str() + m[2].str() + m[3].str() + value + m[5].str();
      done = true;
    }
    if (inside && std::regex_match(line, close)) {
      if (!done) out << "  set " << name << " = " << value << "\n";
      inside = false;
      done = true;
    }
    out << line << "\n";
  }
  return out.str();
}

// Whether `subsection Wire contact` enables the contact between the wires of a DT mesh.
bool wire_contact_enabled(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  bool inside = false;
  const std::regex open("^\\s*subsection\\s+(.*?)\\s*$"), close("^\\s*end\\s*$");
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_match(line, m, open)) inside = m[1].str() == "Wire contact";
    else if (std::regex_match(line, close)) inside = false;
    else if (inside && std::regex_match(line, m, set_line()) && m[2].str() == "Enabled") return m[4].str() == "true";
  }
  return false;
}

std::map<std::string, std::string> entries(const std::string& text) {
  std::map<std::string, std::string> out;
  edit_entries(text, [&](const std::string& name, const std::string& value) {
    out[name] = value;
    return std::string();
  });
  return out;
}

double to_number(const std::string& text) {
  try {
    return std::stod(text);
  } catch (const std::exception&) {
    return 0.0;
  }
}

// Hardening table "e:s, ..." shifted by a plastic pre-strain a0: sigma'(e) = sigma(e + a0).
std::string shifted_table(const std::string& table, double a0) {
  std::vector<std::pair<double, double>> points;
  std::stringstream s(table);
  std::string item;
  while (std::getline(s, item, ',')) {
    const auto colon = item.find(':');
    if (colon != std::string::npos)
      points.emplace_back(to_number(item.substr(0, colon)), to_number(item.substr(colon + 1)));
  }
  if (points.size() < 2) throw ComputationError("residual_stress: the hardening table needs two points");
  auto stress_at = [&](double e) {  // piecewise linear, last slope continued
    std::size_t k = 1;
    while (k + 1 < points.size() && points[k].first < e) ++k;
    const auto& [e0, s0] = points[k - 1];
    const auto& [e1, s1] = points[k];
    return s0 + (s1 - s0) * (e - e0) / (e1 - e0);
  };
  std::string out = "0:" + number_text(stress_at(a0));
  int kept = 0;
  for (const auto& [e, sigma] : points)
    if (e > a0) {
      out += ", " + number_text(e - a0) + ":" + number_text(sigma);
      ++kept;
    }
  if (kept == 0) out += ", 1:" + number_text(stress_at(a0 + 1.0));
  return out;
}

std::vector<unsigned> id_list(const std::string& text) {
  std::vector<unsigned> ids;
  std::stringstream s(text);
  std::string item;
  while (std::getline(s, item, ','))
    if (item.find_first_not_of(" \t") != std::string::npos) ids.push_back(static_cast<unsigned>(to_number(item)));
  return ids;
}

// coating_slip: the bonded area of the top grips (m^2) when the .prm holds the wire by the grips'
// lateral surfaces of its mesh file (ids 10 w + 4 and 10 w + 5 of `dtwire mesh sw|dt`,
// docs/meshes.md) with clamped ends under displacement control; otherwise 0 and why not.
double grip_area(const std::map<std::string, std::string>& values, const std::filesystem::path& directory,
                 std::string& reason) {
  const auto value = [&](const char* name, const char* fallback) {
    return values.count(name) ? values.at(name) : std::string(fallback);
  };
  if (value("Mesh file", "").empty()) {
    reason = "the .prm has no mesh file with grip surfaces (`dtwire mesh sw|dt --grip-length`)";
    return 0.0;
  }
  if (value("Bottom end", "clamped") != "clamped" || value("Top end", "clamped") != "clamped" ||
      value("Control", "displacement") != "displacement") {
    reason = "the bonded grip needs clamped ends under displacement control";
    return 0.0;
  }
  const auto top = id_list(value("Top boundary ids", "2")), bottom = id_list(value("Bottom boundary ids", "1"));
  for (const auto& ids : {top, bottom})
    for (unsigned id : ids)
      if (!regions::is_grip_lateral_boundary(static_cast<int>(id))) {
        reason = "the grips are not held by their lateral surfaces (Bottom / Top boundary ids " +
                 std::to_string(regions::kWireAStartGrip) + ", " + std::to_string(regions::kWireAEndGrip) + ", " +
                 std::to_string(regions::kWireBStartGrip) + ", " + std::to_string(regions::kWireBEndGrip) + ")";
        return 0.0;
      }
  const double area = msh_surface_area(directory / value("Mesh file", ""), top);
  if (!(area > 0.0)) reason = "no face of the mesh file carries the Top boundary ids";
  return area;
}

}  // namespace

std::string edit_prm(const std::string& text, const std::vector<gap::AppliedEffect>& effects,
                     const std::filesystem::path& prm_directory, const GripBond& grip) {
  std::string out = edit_entries(text, [&](const std::string& name, const std::string& value) {
    if (name == "Fields") return std::string("false");  // no VTU output in fits
    if (name == "Mesh file" && !value.empty() && std::filesystem::path(value).is_relative())
      return (prm_directory / value).string();
    return std::string();
  });
  const auto values = entries(text);
  for (const gap::AppliedEffect& a : effects) {
    const std::string& effect = a.effect->name;
    const double p = a.params.at(0);
    if (effect == "geometry_imperfection") {
      out = edit_entries(out, [&](const std::string& name, const std::string& value) {
        if (name == "Bow imperfection (mm)" || name == "Imperfection") return number_text(p * to_number(value));
        return std::string();
      });
    } else if (effect == "residual_stress") {
      const double a0 = p * kTwistingPlasticStrain;
      const std::string law = values.count("Hardening law") ? values.at("Hardening law") : "linear";
      out = edit_entries(out, [&](const std::string& name, const std::string& value) {
        if (law == "table" && name == "Hardening table") return shifted_table(value, a0);
        if (law == "linear" && name == "Yield stress (MPa)") {
          const double h = values.count("Hardening modulus (MPa)") ? to_number(values.at("Hardening modulus (MPa)")) : 0.0;
          return number_text(to_number(value) + h * a0);
        }
        return std::string();
      });
    } else if (effect == "wire_friction") {  // the DT model's Coulomb coefficient between the wires
      out = set_in_subsection(out, "Wire contact", "Friction coefficient", number_text(p));
    } else if (effect == "twist_tightening") {  // extra clearance of the interweavement (mm)
      out = set_in_subsection(out, "Wire contact", "Gap offset (mm)", number_text(p));
    } else if (effect == "shear_failure") {  // shear branch of the failure locus (docs/fem.md)
      out = set_in_subsection(out, "Material", "Failure shear ductility ratio", number_text(p));
    } else if (effect == "coating_slip") {
      // The top grips' bond slides at a force of p x the clamped model's peak force; at the
      // neutral value (1: it would carry the peak) the grips stay as the .prm has them.
      if (p >= a.effect->neutral) continue;
      if (!(grip.top_area > 0.0 && grip.reference_force > 0.0))
        throw ComputationError("gap --model: coating_slip needs the grips' area and the model's peak force");
      // Penalty 10 E / h: below its strength the bond is the clamp within 0.5 % of the stiffness
      // (docs/fem.md) at the cost of factor 1; a .prm with bonded grips keeps its own.
      if (!values.count("Grip interface") || values.at("Grip interface") != "bonded") {
        out = set_in_subsection(out, "Boundary conditions", "Grip interface", "bonded");
        out = set_in_subsection(out, "Boundary conditions", "Grip bond stiffness factor", "10");
      }
      out = set_in_subsection(out, "Boundary conditions", "Grip bond strength (MPa)",
                              number_text(p * grip.reference_force / grip.top_area * 1e-6));
    } else {
      throw ComputationError("gap --model: effect " + effect + " cannot be switched on in a .prm");
    }
  }
  return out;
}

FeModel make_fe_model(const std::filesystem::path& prm, std::filesystem::path work) {
  std::ifstream in(prm);
  if (!in) throw InputError(prm.string(), "cannot read the model .prm");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  const auto values = entries(text);

  FeModel model;
  const auto has_amplitude = [&](const char* name) {
    return values.count(name) && std::abs(to_number(values.at(name))) > 0;
  };
  if (!has_amplitude("Bow imperfection (mm)") && !has_amplitude("Imperfection"))
    model.unsupported["geometry_imperfection"] = "the .prm has no imperfection amplitude to scale";
  const std::string law = values.count("Hardening law") ? values.at("Hardening law") : "linear";
  if (law != "table" && law != "linear")
    model.unsupported["residual_stress"] = "plastic pre-strain only for table and linear hardening";
  if (!wire_contact_enabled(text))
    for (const char* name : {"wire_friction", "twist_tightening"})
      model.unsupported[name] = "the .prm has no enabled `subsection Wire contact` (a DT model, docs/fem_dt.md)";
  if (!has_amplitude("Failure d1") && !has_amplitude("Failure d2"))
    model.unsupported["shear_failure"] = "the .prm has no failure locus (Failure d1, d2) whose shear branch to lower";
  std::string no_grip;
  GripBond grip;
  grip.top_area = grip_area(values, std::filesystem::absolute(prm).parent_path(), no_grip);
  if (!(grip.top_area > 0.0)) model.unsupported["coating_slip"] = no_grip;

  if (work.empty())
    work = std::filesystem::temp_directory_path() / ("dtwire_gap_model_" + std::to_string(::getpid()));
  std::filesystem::create_directories(work);
  auto cache = std::make_shared<std::map<std::string, gap::ForceCurve>>();
  auto runs = std::make_shared<int>(0);
  const std::filesystem::path directory = std::filesystem::absolute(prm).parent_path();
  const std::string source = prm.string();
  model.runs = runs.get();
  model.work = work;
  // One FE run of an edited .prm (cached by its text).
  const auto run = [=, keep = runs](const std::string& edited, const std::string& label) {
    const std::string key = sha256_text(edited);
    if (const auto hit = cache->find(key); hit != cache->end()) return hit->second;
    calibrate::CommandSpecification spec;
    // $DTWIRE_FE_EXECUTABLE: a dtwire built with fem, when this one was built without it.
    const char* fe_executable = std::getenv("DTWIRE_FE_EXECUTABLE");
    spec.program = fe_executable ? std::filesystem::path(fe_executable) : calibrate::dtwire_executable();
    spec.arguments = {"run", "{input}", "--out", "{output}", "--quiet"};
    spec.input_template = edited;
    spec.work_directory = work;
    std::cout << "  FE run: " << label << std::flush;
    const Curve curve = calibrate::CommandSimulator(spec).simulate({});
    gap::ForceCurve c;
    c.u = curve.si("displacement");
    c.f = curve.si("force");
    c.source = label;
    ++*keep;
    std::cout << " (done)\n";
    (*cache)[key] = c;
    return c;
  };
  model.run = [=](const std::vector<gap::AppliedEffect>& effects) {
    std::string label = source;
    GripBond bond = grip;
    for (const gap::AppliedEffect& a : effects) {
      label += " " + a.effect->name + "=" + number_text(a.params[0]);
      if (a.effect->name == "coating_slip") {  // capacity relative to the clamped model's peak force
        for (const double f : run(edit_prm(text, {}, directory), source).f)
          bond.reference_force = std::max(bond.reference_force, std::abs(f));
      }
    }
    return run(edit_prm(text, effects, directory, bond), label);
  };
  return model;
}

}  // namespace dtwire::app
