#pragma once
// Strict reading of a .prm file before deal.II parses it: every subsection and entry must be
// declared (a misspelled name would otherwise leave the default in place without a word), and
// the file must set something. Errors name file:line and the closest declared name.
#include <deal.II/base/parameter_handler.h>

#include <map>
#include <string>

#include "dtwire/core/prm_document.hpp"

namespace dtwire::fem {

// "Section/Sub/Entry" -> line of its `set` in the file.
using EntryLines = std::map<std::string, int>;

// deal.II's listing of the declared subsections and entries, with their defaults.
PrmDocument declared_parameters(const dealii::ParameterHandler& declared);

// Throws InputError(file, line, ...) for an unknown subsection or entry, an unbalanced `end`, a
// line that is none of set/subsection/end/include, or a file without any `set`.
EntryLines check_prm_names(const dealii::ParameterHandler& declared, const std::string& file);

}  // namespace dtwire::fem
