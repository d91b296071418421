#pragma once
// Per link type, what the links of a punch carry and how far they stretch (docs/dem_engine.md,
// "Outputs"): the state of every link at each output row is kept, so that at the end the links
// most loaded at the peak can be followed back along the whole push.
//   link_type_histograms.csv  per type, counts at the peak per axial force bin and per strain
//                             bin (total and plastic strain)
//   link_types_at_peak.csv    per type, link counts, summed tension and quantiles at the peak
//   link_paths.csv            force-strain path of the kPathsPerType links of each type with the
//                             largest axial force at the peak
// The elongation is the law's own axial displacement u (the length its last update saw minus the
// generated length, node centre to node centre); the strain is u over the generated length, the
// plastic strain the law's plastic elongation over the same length, for the laws that expose one
// (thesis, WirePM), empty otherwise.
#include <filesystem>
#include <string>
#include <vector>

#include "dtwire/dem/engine.hpp"
#include "dtwire/dem/hex_mesh.hpp"

namespace dtwire::dem {

class LinkRecorder {
 public:
  static constexpr std::size_t kPathsPerType = 10;

  explicit LinkRecorder(const HexMesh& mesh);
  void sample(const Engine& engine, double tool_displacement_mm);
  // The last sample is the peak of the run (the histograms and the path choice use it).
  void mark_peak() { peak_ = samples_.size() - 1; }
  void write(const std::filesystem::path& out, const std::string& run_id) const;

  static const std::vector<std::string>& file_names();

 private:
  struct Sample {
    double tool_displacement_mm;
    std::vector<double> force, elongation, plastic;  // [N], [m], [m] (NaN: not exposed or broken)
  };
  std::vector<double> length_;  // generated length of each link [m]
  std::vector<LinkTag> tag_;
  std::vector<Sample> samples_;
  std::size_t peak_ = 0;
};

}  // namespace dtwire::dem
