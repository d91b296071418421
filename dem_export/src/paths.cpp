// Prescribed load paths of the two-node driver and path CSV files.
#include "dtwire/dem/paths.hpp"

#include <cmath>
#include <fstream>
#include <stdexcept>

#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"

namespace dtwire::dem {
namespace {

// Unload-reload levels of the cycles path, as fractions of the peak elongation; the last leg
// pulls to the peak (past the break of a typical wire).
constexpr double kCycleLevels[] = {0.1, 0.25, 0.5, 0.75};

// 1-based line of the CSV header (the first line that is neither blank nor a '#' line).
int header_line(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const auto first = line.find_first_not_of(" \t\r");
    if (first != std::string::npos && line[first] != '#') return number;
  }
  return 1;
}

void check_options(const PathOptions& o) {
  if (!(o.reference_length > 0.0)) throw std::invalid_argument("path: reference length must be > 0");
  if (!(o.duration > 0.0)) throw std::invalid_argument("path: duration must be > 0");
  if (o.steps < 1) throw std::invalid_argument("path: steps must be >= 1");
  if (!(o.max_axial_strain >= 0.0 && o.max_compression_strain >= 0.0 && o.max_rotation >= 0.0))
    throw std::invalid_argument("path: magnitudes must be >= 0");
}

}  // namespace

std::vector<std::string> prescribed_path_names() {
  return {"axial_pull", "compression", "bending_spin", "pull_spin", "cycles"};
}

std::vector<Breakpoint> path_breakpoints(const std::string& name, const PathOptions& o) {
  check_options(o);
  const double pull = o.max_axial_strain * o.reference_length;
  if (name == "axial_pull") return {{0.0, 0.0}, {pull, 0.0}};
  if (name == "compression") return {{0.0, 0.0}, {-o.max_compression_strain * o.reference_length, 0.0}};
  if (name == "bending_spin") return {{0.0, 0.0}, {0.0, o.max_rotation}};
  if (name == "pull_spin") return {{0.0, 0.0}, {pull, o.max_rotation}};
  if (name == "cycles") {
    std::vector<Breakpoint> points{{0.0, 0.0}};
    for (const double level : kCycleLevels) {
      points.push_back({level * pull, 0.0});
      points.push_back({0.0, 0.0});
    }
    points.push_back({pull, 0.0});
    return points;
  }
  std::string known;
  for (const auto& n : prescribed_path_names()) known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown path '" + name + "', expected one of: " + known +
                              ", free_oscillation, all, or a .csv file");
}

std::vector<std::size_t> leg_steps(const std::vector<Breakpoint>& points, double reference_length,
                                   std::size_t steps) {
  std::vector<double> lengths;
  double total = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) {
    lengths.push_back(std::abs(points[i].axial - points[i - 1].axial) +
                      reference_length * std::abs(points[i].rotation - points[i - 1].rotation));
    total += lengths.back();
  }
  std::vector<std::size_t> result;
  for (const double length : lengths) {
    const double share = total > 0.0 ? length / total : 1.0 / static_cast<double>(lengths.size());
    result.push_back(std::max<std::size_t>(1, static_cast<std::size_t>(std::llround(share * static_cast<double>(steps)))));
  }
  return result;
}

LoadPath make_path(const std::string& name, const PathOptions& options) {
  const std::vector<Breakpoint> points = path_breakpoints(name, options);
  const std::vector<std::size_t> steps = leg_steps(points, options.reference_length, options.steps);
  std::size_t total_steps = 0;
  for (const std::size_t n : steps) total_steps += n;
  const double time_step = options.duration / static_cast<double>(total_steps);

  LoadPath path;
  path.name = name;
  path.samples.push_back(PathSample{});
  std::size_t step = 0;
  for (std::size_t leg = 0; leg < steps.size(); ++leg) {
    const Breakpoint& a = points[leg];
    const Breakpoint& b = points[leg + 1];
    const std::size_t n = steps[leg];
    for (std::size_t k = 1; k <= n; ++k) {
      const double fraction = static_cast<double>(k) / static_cast<double>(n);
      PathSample sample;
      sample.time = static_cast<double>(++step) * time_step;
      sample.displacement(0) = a.axial + (b.axial - a.axial) * fraction;
      sample.displacement(4) = a.rotation + (b.rotation - a.rotation) * fraction;
      path.samples.push_back(sample);
    }
  }
  return path;
}

LoadPath read_path_csv(const std::filesystem::path& file) {
  const Curve curve = read_csv(file);
  const std::string source = file.string();
  if (!curve.has("time")) throw InputError(source, 1, 1, "path CSV needs a time column (e.g. time_s)");
  struct Component {
    const char* quantity;
    Dimension dimension;
    int index;
  };
  const Component components[] = {{"axial_displacement", Dimension::Length, 0},
                                  {"shear_displacement_y", Dimension::Length, 1},
                                  {"shear_displacement_z", Dimension::Length, 2},
                                  {"rotation_x", Dimension::Angle, 3},
                                  {"rotation_y", Dimension::Angle, 4},
                                  {"rotation_z", Dimension::Angle, 5}};
  const auto column_of = [&](std::string_view quantity) {
    int column = 1;
    for (const Channel& c : curve.channels()) {
      if (c.quantity == quantity) return column;
      ++column;
    }
    return 0;
  };
  bool any = false;
  for (const Channel& c : curve.channels()) {
    bool known = c.quantity == "time";
    for (const Component& component : components) known = known || c.quantity == component.quantity;
    if (!known)
      throw InputError(source, 1, column_of(c.quantity),
                       "unknown path column '" + c.column_name() +
                           "', expected time, axial_displacement, shear_displacement_y, "
                           "shear_displacement_z, rotation_x, rotation_y, rotation_z with units");
    any = any || c.quantity != "time";
  }
  if (!any) throw InputError(source, 1, 1, "path CSV has no displacement or rotation column");
  const Channel& time_channel = curve.channel("time");
  if (time_channel.unit.dimension != Dimension::Time)
    throw InputError(source, 1, column_of("time"), "time column must have a time unit (s, min)");
  for (const Component& component : components) {
    const Channel* c = curve.find(component.quantity);
    if (c && c->unit.dimension != component.dimension)
      throw InputError(source, 1, column_of(component.quantity),
                       std::string("column ") + component.quantity + " must have a " +
                           std::string(dimension_name(component.dimension)) + " unit");
  }

  LoadPath path;
  path.name = file.stem().string();
  const std::vector<double> time = time_channel.si();
  const int first_data_line = header_line(file) + 1;
  path.samples.resize(curve.size());
  for (std::size_t i = 0; i < curve.size(); ++i) {
    path.samples[i].time = time[i];
    if (i > 0 && !(time[i] > time[i - 1]))
      throw InputError(source, first_data_line + static_cast<int>(i), column_of("time"),
                       "time must increase strictly");
  }
  for (const Component& component : components) {
    if (const Channel* c = curve.find(component.quantity)) {
      const std::vector<double> values = c->si();
      for (std::size_t i = 0; i < values.size(); ++i) path.samples[i].displacement(component.index) = values[i];
    }
  }
  return path;
}

}  // namespace dtwire::dem
