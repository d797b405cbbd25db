// report.html of every output directory (docs/output-format.md, "report.html"): one self-contained page with the
// model and the command that made the results, the key numbers, warnings and incomplete markers, and every picture.
// Each page is built from the result file the command has just written (summary.json, modal.json, ...), so that
// every number on it is one of that file (html_page.h), and `turbodyn plot` can rebuild a run's page from its
// summary.json alone.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace turbodyn::post {

/// What the command was and what else it wrote.
struct ReportInputs {
  std::string command;                ///< the command line that made the results
  std::vector<std::string> pictures;  ///< PNG files in the directory, in the order to show them
  std::vector<std::string> files;     ///< other result files in the directory, linked at the end
  std::vector<std::string> warnings;
};

/// `turbodyn run` (and `turbodyn plot`): from summary.json (its "command", "pictures", "warnings" are used; the
/// arguments' command, if not empty, is shown as the command that redrew the pictures).
void write_run_report(const std::filesystem::path& dir, const nlohmann::json& summary, const ReportInputs& in);
/// `turbodyn modal`: from modal.json.
void write_modal_report(const std::filesystem::path& dir, const nlohmann::json& modal, const ReportInputs& in);
/// `turbodyn response`: from response.json.
void write_response_report(const std::filesystem::path& dir, const nlohmann::json& response, const ReportInputs& in);
/// `turbodyn bearing`: from bearing.json.
void write_bearing_report(const std::filesystem::path& dir, const nlohmann::json& bearing, const ReportInputs& in);
/// `turbodyn stability`: from stability.json.
void write_stability_report(const std::filesystem::path& dir, const nlohmann::json& stability,
                            const ReportInputs& in);
/// `turbodyn sweep` and `turbodyn merge` (`kind`): from results.json.
void write_study_report(const std::filesystem::path& dir, const nlohmann::json& results, const std::string& kind,
                        const ReportInputs& in);
/// `turbodyn optimize`: from result.json.
void write_optimize_report(const std::filesystem::path& dir, const nlohmann::json& result, const ReportInputs& in);
/// `turbodyn identify`: from estimates.json.
void write_identify_report(const std::filesystem::path& dir, const nlohmann::json& estimates, const ReportInputs& in);

/// The PNG files among `files` (in their order) and the rest.
std::pair<std::vector<std::string>, std::vector<std::string>> split_pictures(const std::vector<std::string>& files);

}  // namespace turbodyn::post
