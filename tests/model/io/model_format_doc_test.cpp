// docs/model-format.md names every key the model loader accepts, and no key it does not accept.
//
// The accepted keys come from the loader itself (accepted_model_keys: the key paths the TOML reader is asked for
// while it loads the examples and a built-in model), so a key added to model/io/model_file.cpp without a line in
// the documentation fails here. The documentation is read as sections: a heading that names a table in backticks
// (`[oil]`, `[[shaft]]`, `[bearings.NAME]` with `type = "ball"`) starts the section of that table, and every key
// in backticks in the first cell of a table row below it is documented there.
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "model/io/model_file.h"

namespace turbodyn {
namespace {

// The repository (docs/, examples/).
const std::string kSourceDir = TURBODYN_SOURCE_DIR;

std::string read_doc() {
  std::ifstream in(kSourceDir + "/docs/model-format.md");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The backticked tokens of a line, in order.
std::vector<std::string> code_spans(const std::string& line) {
  std::vector<std::string> out;
  std::size_t pos = 0;
  while (true) {
    const std::size_t a = line.find('`', pos);
    if (a == std::string::npos) break;
    const std::size_t b = line.find('`', a + 1);
    if (b == std::string::npos) break;
    out.push_back(line.substr(a + 1, b - a - 1));
    pos = b + 1;
  }
  return out;
}

// The table a heading documents: "" for the top level, "shaft[]" for `[[shaft]]`, "bearings.NAME[type=ball]" for
// `[bearings.NAME]` with `type = "ball"`; false if the heading names no table.
bool section_of_heading(const std::string& heading, std::string& section) {
  if (heading.find("Top level") != std::string::npos) {
    section = "";
    return true;
  }
  std::string table, type;
  for (const std::string& span : code_spans(heading)) {
    if (table.empty() && span.rfind("[[", 0) == 0 && span.size() > 4)
      table = span.substr(2, span.size() - 4) + "[]";
    else if (table.empty() && span.rfind("[", 0) == 0 && span.size() > 2)
      table = span.substr(1, span.size() - 2);
    else if (span.rfind("type = \"", 0) == 0 && span.back() == '"')
      type = span.substr(8, span.size() - 9);
  }
  if (table.empty()) return false;
  section = type.empty() ? table : table + "[type=" + type + "]";
  return true;
}

// Documented keys per section.
std::map<std::string, std::set<std::string>> documented_keys(const std::string& doc) {
  std::map<std::string, std::set<std::string>> out;
  std::istringstream in(doc);
  std::string line, section;
  bool in_section = false;
  while (std::getline(in, line)) {
    if (line.rfind("#", 0) == 0) {
      in_section = section_of_heading(line, section);
      if (in_section) out[section];
      continue;
    }
    if (!in_section || line.rfind("|", 0) != 0) continue;
    const std::size_t end = line.find('|', 1);
    if (end == std::string::npos) continue;
    for (const std::string& key : code_spans(line.substr(1, end - 1))) out[section].insert(key);
  }
  return out;
}

// Splits "bearings.NAME[type=ball].preload" into table "bearings.NAME[type=ball]" and key "preload".
std::pair<std::string, std::string> split_key(const std::string& path) {
  const std::size_t dot = path.rfind('.');
  if (dot == std::string::npos) return {"", path};
  return {path.substr(0, dot), path.substr(dot + 1)};
}

std::string without_type(const std::string& table) {
  const std::size_t t = table.find("[type=");
  if (t == std::string::npos) return table;
  return table.substr(0, t) + table.substr(table.find(']', t) + 1);
}

// Accepted keys that the documentation does not name in their table's section (for a bearing type: that type's
// section or the section of all bearings). A key that is itself a table counts as documented by its section.
std::vector<std::string> undocumented(const std::vector<std::string>& accepted, const std::string& doc) {
  const auto sections = documented_keys(doc);
  std::vector<std::string> missing;
  for (const std::string& path : accepted) {
    const auto [table, key] = split_key(path);
    bool found = false;
    for (const std::string& s : {table, without_type(table)})
      if (const auto it = sections.find(s); it != sections.end() && it->second.count(key)) found = true;
    const std::string as_table = without_type(path);
    for (const auto& [s, keys] : sections)
      if (s == as_table || s.rfind(as_table + ".", 0) == 0 || s.rfind(as_table + "[", 0) == 0) found = true;
    if (!found) missing.push_back(path);
  }
  return missing;
}

// Documented keys that the loader does not accept in that section (stale documentation, or a key that no model of
// accepted_model_keys visits).
std::vector<std::string> not_accepted(const std::vector<std::string>& accepted, const std::string& doc) {
  std::set<std::string> known;
  for (const std::string& path : accepted) {
    const auto [table, key] = split_key(path);
    known.insert(table + "|" + key);
    known.insert(without_type(table) + "|" + key);
  }
  std::vector<std::string> stale;
  for (const auto& [section, keys] : documented_keys(doc))
    for (const std::string& key : keys)
      if (!known.count(section + "|" + key)) stale.push_back((section.empty() ? "" : section + ".") + key);
  return stale;
}

std::string lines(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += "\n  " + x;
  return s;
}

TEST(ModelFormatDoc, EveryAcceptedKeyIsDocumented) {
  const std::vector<std::string> accepted = accepted_model_keys(kSourceDir + "/examples");
  const std::vector<std::string> missing = undocumented(accepted, read_doc());
  EXPECT_TRUE(missing.empty()) << "keys the loader accepts but docs/model-format.md does not document:"
                               << lines(missing);
}

TEST(ModelFormatDoc, EveryDocumentedKeyIsAccepted) {
  const std::vector<std::string> accepted = accepted_model_keys(kSourceDir + "/examples");
  const std::vector<std::string> stale = not_accepted(accepted, read_doc());
  EXPECT_TRUE(stale.empty()) << "keys docs/model-format.md documents but the loader does not accept there:"
                             << lines(stale);
}

// The recorded keys reach every kind of table: if the examples stop covering one, this says so instead of the
// check above passing on fewer keys.
TEST(ModelFormatDoc, RecordedKeysCoverEveryTableAndBearingType) {
  const std::vector<std::string> accepted = accepted_model_keys(kSourceDir + "/examples");
  std::set<std::string> tables;
  for (const std::string& path : accepted) tables.insert(split_key(path).first);
  for (const char* t : {"", "materials.NAME", "shaft[]", "mesh", "damping", "disks.NAME", "bearings.NAME[type=linear]",
                        "bearings.NAME[type=journal]", "bearings.NAME[type=floating-ring]", "bearings.NAME[type=ball]",
                        "bearings.NAME.damper", "oil", "speed", "solver", "output", "modal"})
    EXPECT_TRUE(tables.count(t)) << "no key recorded in table '" << t << "'";
  // Branches that only some models take.
  for (const char* k : {"speed.times", "disks.NAME.material", "disks.NAME.polar_inertia", "materials.NAME.G",
                        "bearings.NAME[type=ball].preload", "bearings.NAME[type=floating-ring].drill_holes"})
    EXPECT_THAT(accepted, ::testing::Contains(std::string(k)));
}

// The check fails when a key is taken out of the documentation: drop the row of the ball bearing's preload and
// the floating ring's drill-hole row, and the checker names exactly the keys of those rows.
TEST(ModelFormatDoc, RemovingARowFromTheDocumentationIsCaught) {
  const std::vector<std::string> accepted = accepted_model_keys(kSourceDir + "/examples");
  const std::string doc = read_doc();
  ASSERT_TRUE(undocumented(accepted, doc).empty());
  std::istringstream in(doc);
  std::string line, pruned;
  int removed = 0;
  while (std::getline(in, line)) {
    if (line.rfind("| `preload` ", 0) == 0 || line.rfind("| `drill_holes`", 0) == 0) {
      ++removed;
      continue;
    }
    pruned += line + "\n";
  }
  ASSERT_EQ(removed, 2);
  EXPECT_THAT(undocumented(accepted, pruned),
              ::testing::IsSupersetOf({std::string("bearings.NAME[type=ball].preload"),
                                       std::string("bearings.NAME[type=floating-ring].drill_holes")}));
}

}  // namespace
}  // namespace turbodyn
