#include "studies/table.h"

#include "model/io/output_file.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "model/spec/errors.h"

namespace turbodyn::studies {

std::string table_number(double v) {
  if (!std::isfinite(v)) return "";
  std::ostringstream os;
  os << std::setprecision(12) << v;
  return os.str();
}

std::string value_text(double v, const std::string& unit) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  std::string s(buf, res.ptr);
  if (!unit.empty()) s += " " + unit;
  return s;
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

nlohmann::json json_number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json json_numbers(const std::vector<double>& v) {
  nlohmann::json a = nlohmann::json::array();
  for (double x : v) a.push_back(json_number(x));
  return a;
}

std::vector<double> from_json_numbers(const nlohmann::json& a) {
  std::vector<double> v;
  for (const auto& x : a) v.push_back(x.is_null() ? NAN : x.get<double>());
  return v;
}

CsvWriter::CsvWriter(const std::filesystem::path& file) {
  remove_symlink(file);  // a link at the path is replaced, not written through
  out_.open(file);
  if (!out_) throw ModelError(file.string() + ": cannot write");
}

void CsvWriter::separate() {
  if (row_started_) out_ << ',';
  row_started_ = true;
}

CsvWriter& CsvWriter::text(const std::string& s) {
  separate();
  out_ << csv_field(s);
  return *this;
}

CsvWriter& CsvWriter::texts(const std::vector<std::string>& s) {
  for (const std::string& x : s) text(x);
  return *this;
}

CsvWriter& CsvWriter::number(double v) {
  separate();
  out_ << table_number(v);
  return *this;
}

CsvWriter& CsvWriter::numbers(const std::vector<double>& v) {
  for (double x : v) number(x);
  return *this;
}

CsvWriter& CsvWriter::integer(std::size_t v) {
  separate();
  out_ << v;
  return *this;
}

void CsvWriter::end_row() {
  out_ << '\n';
  row_started_ = false;
}

}  // namespace turbodyn::studies
