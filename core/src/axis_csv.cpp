#include "dtwire/core/axis_csv.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "dtwire/core/error.hpp"
#include "dtwire/core/prm_document.hpp"

namespace dtwire {

std::vector<std::vector<AxisStation>> read_axis_csv(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string(), "cannot open the axis file (`dtwire mesh ... -o X.msh` writes X.axis.csv)");
  std::vector<std::vector<AxisStation>> wires;
  std::string line;
  int number = 0;
  bool header = false;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line[0] == '#') continue;
    if (!header) {
      if (line.rfind("wire,arc_length_mm,x_mm", 0) != 0)
        throw InputError(file.string(), number, 0, "expected the header 'wire,arc_length_mm,x_mm,...'");
      header = true;
      continue;
    }
    std::stringstream s(line);
    std::vector<double> v;
    for (std::string item; std::getline(s, item, ',');) {
      const auto value = parse_number(item);
      if (!value || !std::isfinite(*value))
        throw InputError(file.string(), number, 0, "expected 11 numbers, found '" + item + "'");
      v.push_back(*value);
    }
    if (v.size() != 11) throw InputError(file.string(), number, 0, "expected 11 columns, found " + std::to_string(v.size()));
    if (v[0] != 0.0 && v[0] != 1.0) throw InputError(file.string(), number, 0, "wire must be 0 or 1");
    const auto wire = static_cast<std::size_t>(v[0]);
    if (wire > wires.size()) throw InputError(file.string(), number, 0, "wire 1 before wire 0");
    if (wire == wires.size()) wires.emplace_back();
    AxisStation st;
    st.wire = static_cast<unsigned>(wire);
    st.arc_length = 1e-3 * v[1];
    for (unsigned c = 0; c < 3; ++c) {
      st.point[c] = 1e-3 * v[2 + c];
      st.tangent[c] = v[5 + c];
      st.curvature[c] = 1e3 * v[8 + c];
    }
    if (std::abs(std::hypot(st.tangent[0], st.tangent[1], st.tangent[2]) - 1.0) > 1e-6)
      throw InputError(file.string(), number, 0, "the tangent is not a unit vector");
    wires[wire].push_back(st);
  }
  if (!header) throw InputError(file.string(), "no header line 'wire,arc_length_mm,x_mm,...'");
  for (const auto& w : wires)
    if (w.size() < 2) throw InputError(file.string(), "a wire with fewer than two stations");
  return wires;
}

}  // namespace dtwire
