// How the batch-of-runs layers write numbers and tables (sweep results, optimisation history, identified features),
// so that every table of a study reads alike and a number means the same in each.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace turbodyn::studies {

/// A number in a table: 12 significant digits, "" for NaN and infinities (an empty cell, not a string that a
/// spreadsheet would read as text).
std::string table_number(double v);

/// The shortest text that reads back as the same double, then " <unit>" if `unit` is not empty: the value of a
/// --set override ("51 um", "0.0001", "2.5e-05 m"), exact so that a run can be repeated from its overrides.
std::string value_text(double v, const std::string& unit = "");

/// A CSV field as written: quoted (quotes doubled) only when it holds a comma, a quote or a line break.
std::string csv_field(const std::string& s);

/// JSON null for NaN and infinities, which JSON cannot hold; JSON numbers round-trip doubles exactly.
nlohmann::json json_number(double v);
nlohmann::json json_numbers(const std::vector<double>& v);
/// Inverse of json_numbers (null -> NaN).
std::vector<double> from_json_numbers(const nlohmann::json& a);

/// A CSV file written row by row; fields are separated and quoted as needed.
class CsvWriter {
 public:
  /// Throws ModelError when the file cannot be written.
  explicit CsvWriter(const std::filesystem::path& file);

  CsvWriter& text(const std::string& s);
  CsvWriter& texts(const std::vector<std::string>& s);
  CsvWriter& number(double v);                ///< table_number
  CsvWriter& numbers(const std::vector<double>& v);
  CsvWriter& integer(std::size_t v);
  void end_row();

 private:
  void separate();
  std::ofstream out_;
  bool row_started_ = false;
};

}  // namespace turbodyn::studies
