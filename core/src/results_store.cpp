#include "dtwire/core/results_store.hpp"

#include <hdf5.h>

#include <cmath>
#include <functional>
#include <sstream>
#include <stdexcept>

#include "dtwire/core/atomic_file.hpp"
#include "dtwire/core/error.hpp"
#include "hdf5_errors.hpp"

namespace dtwire {
namespace {

std::runtime_error hdf5_failure(const std::string& what) {
  const std::string stack = hdf5_error_text();
  return std::runtime_error("HDF5: " + what + " failed" + (stack.empty() ? "" : ": " + stack));
}

// Owns one HDF5 identifier. Closing never throws: after a failure the stack is already unwound
// into an exception, and a failed close only adds to HDF5's error stack, which is cleared.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t), const std::string& what) : id_(id), close_(close) {
    if (id_ < 0) throw hdf5_failure(what);
  }
  ~Handle() {
    if (id_ >= 0 && close_(id_) < 0) H5Eclear2(H5E_DEFAULT);
  }
  Handle(Handle&& other) noexcept : id_(other.id_), close_(other.close_) { other.id_ = -1; }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  operator hid_t() const { return id_; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

void check(herr_t status, const std::string& what) {
  if (status < 0) throw hdf5_failure(what);
}

Handle ordered_group_properties() {
  Handle plist(H5Pcreate(H5P_GROUP_CREATE), H5Pclose, "group properties");
  check(H5Pset_link_creation_order(plist, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED),
        "link order");
  check(H5Pset_attr_creation_order(plist, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED),
        "attribute order");
  return plist;
}

Handle create_group(hid_t parent, const std::string& name) {
  Handle plist = ordered_group_properties();
  return Handle(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, plist, H5P_DEFAULT), H5Gclose,
                "create group " + name);
}

void write_string_attribute(hid_t object, const std::string& name, const std::string& value) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "string type");
  check(H5Tset_size(type, value.empty() ? 1 : value.size()), "string size");
  check(H5Tset_strpad(type, H5T_STR_NULLPAD), "string padding");
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "scalar space");
  Handle attribute(H5Acreate2(object, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT),
                   H5Aclose, "create attribute " + name);
  const std::string padded = value.empty() ? std::string(1, '\0') : value;
  check(H5Awrite(attribute, type, padded.data()), "write attribute " + name);
}

void write_double_attribute(hid_t object, const std::string& name, double value) {
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "scalar space");
  Handle attribute(H5Acreate2(object, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT),
                   H5Aclose, "create attribute " + name);
  check(H5Awrite(attribute, H5T_NATIVE_DOUBLE, &value), "write attribute " + name);
}

std::string read_string_attribute(hid_t attribute) {
  Handle type(H5Aget_type(attribute), H5Tclose, "attribute type");
  if (H5Tget_class(type) != H5T_STRING) throw std::runtime_error("attribute is not a string");
  const std::size_t size = H5Tget_size(type);
  std::string value(size, '\0');
  Handle memtype(H5Tcopy(H5T_C_S1), H5Tclose, "string type");
  check(H5Tset_size(memtype, size), "string size");
  check(H5Tset_strpad(memtype, H5T_STR_NULLPAD), "string padding");
  check(H5Aread(attribute, memtype, value.data()), "read string attribute");
  value.resize(value.find('\0') == std::string::npos ? size : value.find('\0'));
  return value;
}

// Calls visit(name, attribute) for each attribute in creation order.
void for_each_attribute(hid_t object, const std::function<void(const std::string&, hid_t)>& visit) {
  H5O_info_t info;  // HDF5 1.10 API (Debian 12)
  check(H5Oget_info2(object, &info, H5O_INFO_NUM_ATTRS), "object info");
  for (hsize_t i = 0; i < info.num_attrs; ++i) {
    Handle attribute(H5Aopen_by_idx(object, ".", H5_INDEX_CRT_ORDER, H5_ITER_INC, i, H5P_DEFAULT,
                                    H5P_DEFAULT),
                     H5Aclose, "open attribute");
    const ssize_t length = H5Aget_name(attribute, 0, nullptr);
    std::string name(static_cast<std::size_t>(length), '\0');
    H5Aget_name(attribute, name.size() + 1, name.data());
    visit(name, attribute);
  }
}

std::vector<std::string> member_names(hid_t group) {
  H5G_info_t info;
  check(H5Gget_info(group, &info), "group info");
  std::vector<std::string> names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t length =
        H5Lget_name_by_idx(group, ".", H5_INDEX_CRT_ORDER, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    std::string name(static_cast<std::size_t>(length), '\0');
    H5Lget_name_by_idx(group, ".", H5_INDEX_CRT_ORDER, H5_ITER_INC, i, name.data(), name.size() + 1,
                       H5P_DEFAULT);
    names.push_back(name);
  }
  return names;
}

void write_vector(hid_t group, const std::string& name, const std::vector<double>& values) {
  const hsize_t dims[1] = {values.size()};
  Handle space(H5Screate_simple(1, dims, nullptr), H5Sclose, "data space");
  Handle dataset(H5Dcreate2(group, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT,
                            H5P_DEFAULT),
                 H5Dclose, "create dataset " + name);
  check(H5Dwrite(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
        "write dataset " + name);
}

std::vector<double> read_vector(hid_t dataset) {
  Handle space(H5Dget_space(dataset), H5Sclose, "data space");
  const hssize_t count = H5Sget_simple_extent_npoints(space);
  std::vector<double> values(static_cast<std::size_t>(count));
  check(H5Dread(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
        "read dataset");
  return values;
}

void require_finite(double value, const std::string& what) {
  if (!std::isfinite(value)) throw std::invalid_argument("refusing to write non-finite " + what);
}

void write_curve(hid_t curves, const std::string& name, const Curve& curve) {
  Handle group = create_group(curves, name);
  std::string order;
  for (const Channel& c : curve.channels()) order += (order.empty() ? "" : ",") + c.quantity;
  write_string_attribute(group, "channel_order", order);
  for (const auto& [key, value] : curve.metadata_entries())
    write_string_attribute(group, "meta:" + key, value);
  for (const Channel& c : curve.channels()) {
    for (double v : c.values) require_finite(v, "value in curve " + name + " channel " + c.quantity);
    write_vector(group, c.column_name(), c.values);
    Handle dataset(H5Dopen2(group, c.column_name().c_str(), H5P_DEFAULT), H5Dclose, "open dataset");
    write_string_attribute(dataset, "quantity", c.quantity);
    write_string_attribute(dataset, "unit", c.unit.symbol);
  }
}

Curve read_curve(hid_t group, const std::string& source) {
  Curve curve;
  for_each_attribute(group, [&](const std::string& name, hid_t attribute) {
    if (name.rfind("meta:", 0) == 0) curve.set_metadata(name.substr(5), read_string_attribute(attribute));
  });
  for (const std::string& dataset_name : member_names(group)) {
    Handle dataset(H5Dopen2(group, dataset_name.c_str(), H5P_DEFAULT), H5Dclose, "open dataset");
    std::string quantity, unit_symbol;
    for_each_attribute(dataset, [&](const std::string& name, hid_t attribute) {
      if (name == "quantity") quantity = read_string_attribute(attribute);
      if (name == "unit") unit_symbol = read_string_attribute(attribute);
    });
    const auto unit = find_unit(unit_symbol);
    if (quantity.empty() || !unit)
      throw InputError(source, "dataset " + dataset_name + " lacks a known quantity/unit attribute");
    curve.add_channel(quantity, *unit, read_vector(dataset));
  }
  return curve;
}

// The groups, datasets and attributes of the layout above, into an open file.
void write_contents(hid_t file, const Results& results) {
  Handle provenance = create_group(file, "provenance");
  write_string_attribute(provenance, "tool_version", results.provenance.tool_version);
  write_string_attribute(provenance, "git_hash", results.provenance.git_hash);
  write_string_attribute(provenance, "created_utc", results.provenance.created_utc);
  write_string_attribute(provenance, "command", results.provenance.command);
  write_string_attribute(provenance, "run_id", results.provenance.run_id);
  Handle inputs = create_group(provenance, "inputs");
  for (const auto& [input, digest] : results.provenance.input_sha256)
    write_string_attribute(inputs, input, digest);

  Handle curves = create_group(file, "curves");
  for (const auto& [name, curve] : results.curves) write_curve(curves, name, curve);

  Handle parameters = create_group(file, "parameters");
  for (const Parameter& p : results.parameters) {
    Handle space(H5Screate(H5S_SCALAR), H5Sclose, "scalar space");
    Handle dataset(H5Dcreate2(parameters, p.name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT,
                              H5P_DEFAULT, H5P_DEFAULT),
                   H5Dclose, "create parameter " + p.name);
    check(H5Dwrite(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &p.value),
          "write parameter");
    write_string_attribute(dataset, "unit", p.unit);
    if (p.sigma) write_double_attribute(dataset, "sigma", *p.sigma);
  }

  Handle fields = create_group(file, "fields");
  for (const auto& [key, value] : results.fields) write_string_attribute(fields, key, value);
}

}  // namespace

void write_results(const Results& results, const std::filesystem::path& path) {
  for (const Parameter& p : results.parameters) {
    require_finite(p.value, "parameter " + p.name);
    if (p.sigma) require_finite(*p.sigma, "sigma of parameter " + p.name);
  }
  // The file is built in memory (HDF5's core driver without a backing store) and written by the
  // same checked writer as every other result file: a full disk, a file-size limit or an I/O
  // error then surfaces as that writer's message (file name and the system's reason), and HDF5
  // never holds an identifier of a file whose writes failed.
  const Hdf5ErrorsSilenced silenced;
  std::string image;
  try {
    Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "file access properties");
    check(H5Pset_fapl_core(fapl, 1 << 20, 0), "in-memory file driver");
    Handle fcpl(H5Pcreate(H5P_FILE_CREATE), H5Pclose, "file properties");
    check(H5Pset_link_creation_order(fcpl, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED),
          "link order");
    const std::string memory_name = path.string() + ".in-memory";  // never on disk
    Handle file(H5Fcreate(memory_name.c_str(), H5F_ACC_TRUNC, fcpl, fapl), H5Fclose, "create in memory");
    write_contents(file, results);  // its objects are closed when it returns
    check(H5Fflush(file, H5F_SCOPE_GLOBAL), "flush");
    const ssize_t size = H5Fget_file_image(file, nullptr, 0);
    if (size < 0) throw hdf5_failure("file image size");
    image.resize(static_cast<std::size_t>(size));
    if (H5Fget_file_image(file, image.data(), image.size()) != size) throw hdf5_failure("file image");
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(path.string() + ": " + e.what());
  }
  write_bytes_atomically(path, image);
}

Results read_results(const std::filesystem::path& path) {
  const std::string source = path.string();
  if (std::filesystem::is_directory(path)) throw InputError(source, "is a directory, expected an HDF5 file");
  if (!std::filesystem::exists(path)) throw InputError(source, "no such file");
  if (H5Fis_hdf5(path.c_str()) <= 0) throw InputError(source, "not an HDF5 file");
  const Hdf5ErrorsSilenced silenced;  // errors become exceptions, not stderr noise

  Results results;
  try {
    Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "open " + source);
    for (const char* group : {"provenance", "curves", "parameters", "fields"})
      if (H5Lexists(file, group, H5P_DEFAULT) <= 0)
        throw InputError(source, std::string("not a dtwire results file: no /") + group + " group");
    Handle provenance(H5Gopen2(file, "provenance", H5P_DEFAULT), H5Gclose, "open /provenance");
    for_each_attribute(provenance, [&](const std::string& name, hid_t attribute) {
      const std::string value = read_string_attribute(attribute);
      if (name == "tool_version") results.provenance.tool_version = value;
      if (name == "git_hash") results.provenance.git_hash = value;
      if (name == "created_utc") results.provenance.created_utc = value;
      if (name == "command") results.provenance.command = value;
      if (name == "run_id") results.provenance.run_id = value;
    });
    Handle inputs(H5Gopen2(provenance, "inputs", H5P_DEFAULT), H5Gclose, "open inputs");
    for_each_attribute(inputs, [&](const std::string& name, hid_t attribute) {
      results.provenance.input_sha256.emplace_back(name, read_string_attribute(attribute));
    });

    Handle curves(H5Gopen2(file, "curves", H5P_DEFAULT), H5Gclose, "open /curves");
    for (const std::string& name : member_names(curves)) {
      Handle group(H5Gopen2(curves, name.c_str(), H5P_DEFAULT), H5Gclose, "open curve " + name);
      results.curves.emplace_back(name, read_curve(group, source));
    }

    Handle parameters(H5Gopen2(file, "parameters", H5P_DEFAULT), H5Gclose, "open /parameters");
    for (const std::string& name : member_names(parameters)) {
      Handle dataset(H5Dopen2(parameters, name.c_str(), H5P_DEFAULT), H5Dclose, "open " + name);
      Parameter p;
      p.name = name;
      check(H5Dread(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &p.value), "read");
      for_each_attribute(dataset, [&](const std::string& attr, hid_t attribute) {
        if (attr == "unit") p.unit = read_string_attribute(attribute);
        if (attr == "sigma") {
          double sigma = 0;
          check(H5Aread(attribute, H5T_NATIVE_DOUBLE, &sigma), "read sigma");
          p.sigma = sigma;
        }
      });
      results.parameters.push_back(p);
    }

    Handle fields(H5Gopen2(file, "fields", H5P_DEFAULT), H5Gclose, "open /fields");
    for_each_attribute(fields, [&](const std::string& name, hid_t attribute) {
      results.fields.emplace_back(name, read_string_attribute(attribute));
    });
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(source, std::string("unreadable results file: ") + e.what());
  }
  return results;
}

}  // namespace dtwire
