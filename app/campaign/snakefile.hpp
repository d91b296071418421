#pragma once
// A campaign as a Snakemake workflow (`dtwire campaign FILE -o DIR --snakefile Snakefile`), so
// that `snakemake --cores 16` or a cluster profile (Slurm) runs its steps and writes into DIR
// what the campaign runner would: one rule per step with the same dtwire command (console output
// to DIR/steps/<step>/output.log), its declared inputs and outputs, `threads:` from the step, a
// marker DIR/steps/<step>/command.txt (written as the runner writes it) through which a step
// waits for every step campaign_graph.hpp says it waits for; and a last rule that writes the
// report from the outputs (`dtwire campaign FILE -o DIR --report-only`).
#include <filesystem>
#include <string>
#include <vector>

#include "campaign_file.hpp"

namespace dtwire::app {

struct SnakefileOptions {
  std::filesystem::path out;         // DIR, made absolute
  std::filesystem::path executable;  // the dtwire binary the rules run, absolute
  std::vector<std::string> variables;  // the --var settings, repeated in the report rule
};

// The workflow's text.
std::string snakefile_text(const Campaign& campaign, const SnakefileOptions& options);

}  // namespace dtwire::app
