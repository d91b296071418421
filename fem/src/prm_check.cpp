#include "prm_check.hpp"

#include <sstream>

#include "dtwire/core/error.hpp"
#include "dtwire/core/prm_document.hpp"

namespace dtwire::fem {

PrmDocument declared_parameters(const dealii::ParameterHandler& declared) {
  std::ostringstream listing;
  declared.print_parameters(listing, dealii::ParameterHandler::ShortPRM);
  return PrmDocument::parse(listing.str(), "the solver's declared parameters");
}

EntryLines check_prm_names(const dealii::ParameterHandler& declared, const std::string& file) {
  const PrmDocument document = PrmDocument::read(file);
  check_declared(document, declared_parameters(declared));
  if (document.entries().empty())
    throw InputError(file, "no 'set' line: an empty parameter file would run on the defaults alone");
  EntryLines lines;
  for (const auto& entry : document.entries()) lines[entry.path] = entry.line;  // the last `set` wins, as in deal.II
  return lines;
}

}  // namespace dtwire::fem
