// The C ABI bundle: the contact-law shared library and its header (built by dtwire_contact),
// and the example program, copied next to a README with compile and link instructions.
#include <dlfcn.h>

#include <ostream>
#include <system_error>

#include "dtwire_contact.h"

#include "dtwire/core/atomic_file.hpp"
#include "dtwire/dem/export.hpp"

namespace dtwire::dem {
namespace {

std::filesystem::path find_header(const std::filesystem::path& include_dir) {
  std::error_code error;
  if (!std::filesystem::is_directory(include_dir, error)) return {};
  for (const auto& entry : std::filesystem::recursive_directory_iterator(include_dir, error))
    if (entry.path().filename() == "dtwire_contact.h") return entry.path();
  return {};
}

// The contact-law library this process has loaded (wherever it was built or installed).
std::filesystem::path loaded_library() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&dtwire_bond_create), &info) == 0 || !info.dli_fname) return {};
  return std::filesystem::canonical(info.dli_fname);
}

}  // namespace

std::vector<std::filesystem::path> export_c_abi(const std::filesystem::path& out,
                                                const std::filesystem::path& include_dir,
                                                const std::filesystem::path& example_dir) {
  const std::filesystem::path library = loaded_library();
  const std::filesystem::path header = find_header(include_dir);
  std::filesystem::create_directories(out);
  std::vector<std::filesystem::path> written;
  const auto copy = [&](const std::filesystem::path& from) {
    if (from.empty() || !std::filesystem::exists(from)) return false;
    std::filesystem::copy_file(from, out / from.filename(), std::filesystem::copy_options::overwrite_existing);
    written.push_back(out / from.filename());
    return true;
  };
  const bool have_library = copy(library);
  const bool have_header = copy(header);
  std::vector<std::string> examples;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(example_dir, error))
    if (entry.path().extension() == ".c" && copy(entry.path())) examples.push_back(entry.path().filename().string());
  const std::string library_name = library.filename().string();
  write_file_atomically(out / "README.md", [&](std::ostream& os) {
    os << "# dtwire contact laws: C ABI\n\n"
          "The contact laws (thesis macro-element, macro3d, WirePM, parallel bond) as a shared\n"
          "library with a C header, for any DEM code. Built by the `dtwire_contact` target.\n\n"
       << "- library: `" << library_name << "` " << (have_library ? "(copied here)" : "(NOT FOUND: build dtwire_contact)")
       << "\n- header: `dtwire_contact.h` "
       << (have_header ? "(copied here)" : "(NOT FOUND: this build has no C header yet)") << "\n\n"
       << "Compile and link a DEM code against it (from this folder):\n\n"
          "```sh\n"
          "cc -std=c11 -I. my_dem.c -L. -ldtwire_contact -Wl,-rpath,'$ORIGIN' -o my_dem\n";
    for (const std::string& example : examples)
      os << "cc -std=c11 -I. " << example << " -L. -ldtwire_contact -lm -Wl,-rpath,'$ORIGIN' -o "
         << std::filesystem::path(example).stem().string() << " && ./" << std::filesystem::path(example).stem().string()
         << "   # the example program\n";
    os << "```\n\n"
          "The header documents the functions (create a bond from a law name and named SI\n"
          "parameters, update it with a generalised displacement increment, read forces, energy\n"
          "and failure); see docs/dem_driver_export.md and the dem_export documentation of the\n"
          "dtwire repository for the parameter names of every law.\n";
  });
  written.push_back(out / "README.md");
  return written;
}

}  // namespace dtwire::dem
