#pragma once
// Helpers of the FE tests that run the dtwire executable's mesher (DTWIRE_EXE) into scratch
// folders under the system's temporary directory.
#include <cstdlib>
#include <filesystem>
#include <string>

namespace dtwire::fem::testing {

// A fresh, empty folder `<tmp>/<prefix><name>`.
inline std::filesystem::path scratch_dir(const std::string& prefix, const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / (prefix + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// `dtwire mesh KIND OPTIONS -o DIR/KIND.msh`; the mesh path, empty if the mesher failed.
inline std::filesystem::path make_mesh(const std::string& kind, const std::filesystem::path& dir,
                                       const std::string& options) {
  const auto mesh = dir / (kind + ".msh");
  const std::string command = std::string(DTWIRE_EXE) + " mesh " + kind + " " + options + " -o " + mesh.string() +
                              " > /dev/null 2>&1";
  return std::system(command.c_str()) == 0 ? mesh : std::filesystem::path();
}

}  // namespace dtwire::fem::testing
