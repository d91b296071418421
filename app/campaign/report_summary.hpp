#pragma once
// The one-minute summary at the top of the campaign report: the calibrated parameter sets, the
// mesh-scale validation, the gap verdicts and what to distrust, each linking to its step.
//
// What a step contributes is found generically: its `summary` files if it declares them, else
// the files of its outputs and report that the summary knows how to read, chosen by the step's
// command: `fit` -> parameters.json (values, sigma, unit, NRMSE per curve, warnings);
// `gap` -> the verdict JSON (cause, shrink, region); `dem run` -> its figures and curves (the
// mesh-scale validation). Warnings in every step's console log are listed too.
#include <filesystem>
#include <string>
#include <vector>

#include "campaign_file.hpp"
#include "campaign_runner.hpp"

namespace dtwire::app {

// Markdown, starting with "## Summary"; image and file links are relative to `out`.
std::string summary_markdown(const Campaign& campaign, const std::vector<StepOutcome>& outcomes,
                             const std::filesystem::path& out);

// The anchor of a Markdown heading (GitHub's rule: lower case, spaces to '-', punctuation dropped).
std::string heading_anchor(const std::string& heading);

}  // namespace dtwire::app
