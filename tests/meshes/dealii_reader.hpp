#pragma once
// What deal.II sees in a .msh file (built in its own library so only it needs deal.II flags).
#include <cstddef>
#include <set>
#include <string>

struct DealIIView {
  std::size_t cells = 0;
  std::set<int> material_ids;
  std::set<int> boundary_ids;  // of faces at the boundary
  double min_jxw = 0;          // over every cell and 2x2x2 Gauss point (Q1 mapping)
  double volume = 0;
};

DealIIView read_with_dealii(const std::string& msh_file);
