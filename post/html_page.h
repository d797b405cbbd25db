// A self-contained HTML page of results (report.html): inline style, no script libraries, relative links only, so
// it opens offline from the output directory and moves with it.
//
// Every number shown that comes from a result file carries where it comes from:
//   <span class="num" data-file="summary.json" data-pointer="/probes/disk.compressor.x/max_abs"
//         data-value="0.000283" data-scale="1000000" data-digits="4">283.0 µm</span>
// data-value is the JSON number as the file holds it, data-pointer an RFC 6901 JSON pointer into data-file, and the
// text shows data-value x data-scale to data-digits significant digits. tests/cli/report_browser_test.py checks
// every such number against the file. A small inline script marks <body> once the page has loaded
// (data-rendered="yes", data-images-total, data-images-loaded, data-images-broken: the sources of images that did
// not load); the page does not need it to be read.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace turbodyn::post {

/// `s` with &, <, >, " and ' replaced by entities (safe as element text and as a quoted attribute value).
std::string html_escape(const std::string& s);

/// `v` to `digits` significant digits the way an engineer reads it: plain decimals from 0.001 to 1e7
/// ("283.0", "150000", "0.04871"), else scientific ("2.830e-07").
std::string display_number(double v, int digits = 4);

class HtmlPage {
 public:
  /// `kind`: the command that wrote the page (run, modal, ...), shown and stored as <body data-kind>.
  HtmlPage(std::string title, std::string kind);

  /// A heading of a section.
  void heading(const std::string& text);
  /// A paragraph of plain text.
  void paragraph(const std::string& text);
  /// A paragraph of ready HTML (built from html_escape and number()).
  void paragraph_html(const std::string& html);
  /// A command line shown as code.
  void command(const std::string& text);
  /// A marked box (class "warn"): the run is incomplete, a constraint is violated, ...
  void alert(const std::string& text);
  /// The warnings of the command, as a list (nothing when empty).
  void warnings(const std::vector<std::string>& list);
  /// A table; cells are ready HTML. `label` names the table for tests (data-table).
  void table(const std::string& label, const std::vector<std::string>& header,
             const std::vector<std::vector<std::string>>& rows);
  /// Two-column table of (name, ready HTML) pairs.
  void key_values(const std::string& label, const std::vector<std::pair<std::string, std::string>>& rows);
  /// Every picture, in the given order, each with its file name as caption and a link to the full size.
  void pictures(const std::vector<std::string>& files);
  /// Links to the other files of the directory.
  void files(const std::vector<std::string>& names);

  /// The number at `pointer` in `root` (the content of `file`), shown x `scale` to `digits` significant digits
  /// followed by `unit`, with the data attributes above. Not a number there (null, missing): "–" without them.
  static std::string number(const std::string& file, const nlohmann::json& root, const std::string& pointer,
                            double scale = 1.0, const std::string& unit = "", int digits = 4);

  /// The page as HTML text.
  std::string html() const;
  /// Writes `dir`/report.html (atomically, model/io/output_file.h).
  void write(const std::filesystem::path& dir) const;

 private:
  std::string title_, kind_, body_;
};

/// A JSON pointer to member `key` of the object at `parent` ("/probes" + "disk.x" -> "/probes/disk.x"; '~' and '/'
/// in the key escaped).
std::string json_pointer(const std::string& parent, const std::string& key);
std::string json_pointer(const std::string& parent, std::size_t index);

}  // namespace turbodyn::post
