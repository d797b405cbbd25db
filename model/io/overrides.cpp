#include "model/io/overrides.h"

#include <algorithm>
#include <charconv>
#include <fstream>
#include <sstream>

#include "model/io/model_file.h"
#include "model/io/overrides_toml.h"

namespace turbodyn {
namespace {

using input::kOverridePrefix;

// How messages name an override: as the user typed it.
std::string context_of(const Override& o) { return std::string(kOverridePrefix) + o.path + "=" + o.value; }

// The value of `o` as the node "v" of a table, read as TOML or else as a plain string; the nodes' source names the
// override, so messages about values inside it (an array, an inline table) point at the override.
toml::table read_value(const Override& o) {
  const std::string source = context_of(o);
  try {
    return toml::parse("v = " + o.value, std::string_view(source));
  } catch (const toml::parse_error&) {
    std::string escaped;
    for (char ch : o.value) {
      if (ch == '"' || ch == '\\') escaped += '\\';
      escaped += ch;
    }
    try {
      return toml::parse("v = \"" + escaped + "\"", std::string_view(source));
    } catch (const toml::parse_error& e) {
      throw ModelError(source + ": cannot read the value: " + std::string(e.description()));
    }
  }
}

void set_value(toml::table& root, const Override& o, const std::vector<OverrideStep>& steps, const toml::node& value,
               input::Sources* sources) {
  const std::string context = context_of(o);
  auto record = [&](const toml::node* n) {
    if (sources) sources->overrides[n] = context;
  };
  toml::table* table = &root;
  std::string walked;
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const OverrideStep& step = steps[i];
    const bool last = i + 1 == steps.size();
    walked += (walked.empty() ? "" : ".") + step.key;
    toml::node* n = table->get(step.key);
    if (step.index) {
      const std::size_t index = *step.index;
      if (!n || !n->is_array()) throw ModelError(context + ": '" + walked + "' is not an array in the model file");
      toml::array& arr = *n->as_array();
      if (index >= arr.size())
        throw ModelError(context + ": index " + std::to_string(index) + " is out of range ('" + walked + "' has " +
                         std::to_string(arr.size()) + " entries, counted from 0)");
      if (last) {
        value.visit([&](auto&& v) { arr.replace(arr.cbegin() + static_cast<std::ptrdiff_t>(index), v); });
        record(arr.get(index));
        return;
      }
      if (!arr[index].is_table()) throw ModelError(context + ": '" + walked + "[...]' is not a table");
      table = arr[index].as_table();
    } else if (last) {
      value.visit([&](auto&& v) { table->insert_or_assign(step.key, v); });
      record(table->get(step.key));
      return;
    } else {
      if (!n) {
        n = table->insert_or_assign(step.key, toml::table{}).first->second.as_table();
        record(n);
      }
      if (!n->is_table())
        throw ModelError(context + ": '" + walked + "' is a value, not a table, so it has no key '" +
                         steps[i + 1].key + "'");
      table = n->as_table();
    }
  }
}

// The node at the first `count` steps (nullptr if there is none).
const toml::node* find(const toml::table& root, const std::vector<OverrideStep>& steps, std::size_t count) {
  const toml::node* n = &root;
  for (std::size_t i = 0; i < count; ++i) {
    if (!n->is_table()) return nullptr;
    n = n->as_table()->get(steps[i].key);
    if (n && steps[i].index) n = n->is_array() ? n->as_array()->get(*steps[i].index) : nullptr;
    if (!n) return nullptr;
  }
  return n;
}

// TOML text of a single value: strings in double quotes (as the examples write them), anything else formatted by
// toml++ as {v = value}, keeping what follows "v = ".
std::string value_text(const toml::node& v) {
  if (const auto s = v.value<std::string>(); s && v.is_string()) {
    std::string q = "\"";
    for (char c : *s) {
      if (c == '"' || c == '\\') q += '\\';
      q += c;
    }
    return q + "\"";
  }
  toml::table t;
  v.visit([&](auto&& x) { t.insert("v", x); });
  std::ostringstream os;
  os << toml::toml_formatter(t);
  std::string s = os.str();
  s = s.substr(s.find('=') + 1);
  s.erase(0, s.find_first_not_of(' '));
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
  return s;
}

// Byte offset of a 1-based column (toml++ counts code points) in a UTF-8 line.
std::size_t byte_offset(const std::string& line, std::size_t column) {
  std::size_t cp = 1, i = 0;
  while (i < line.size() && cp < column) {
    const unsigned char c = static_cast<unsigned char>(line[i]);
    i += c < 0x80 ? 1 : c < 0xE0 ? 2 : c < 0xF0 ? 3 : 4;
    ++cp;
  }
  return i;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string s;
  for (const std::string& l : lines) s += l + "\n";
  return s;
}

// Edits `lines` so that they hold `o` (already applied to the tree `target`). False where a text edit cannot do it.
bool patch_lines(std::vector<std::string>& lines, const toml::table& tree, const std::vector<OverrideStep>& path,
                 const toml::node& value) {
  const toml::node* n = find(tree, path, path.size());
  if (!n) {
    // A key the file lacks: a new line in its table, if the table has a [header] of its own in the file.
    const toml::node* parent = path.size() > 1 && !path.back().index ? find(tree, path, path.size() - 1) : nullptr;
    const toml::table* t = parent ? parent->as_table() : nullptr;
    if (!t || t->is_inline() || t->source().begin.line == 0 || t->source().begin.line > lines.size()) return false;
    std::size_t after = t->source().begin.line;  // the header line, or the last line of a value of the table
    for (auto&& [k, child] : *t)
      if (!child.is_table() && !(child.is_array() && child.as_array()->is_array_of_tables()))
        after = std::max<std::size_t>(after, child.source().end.line);
    if (after > lines.size()) return false;
    lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(after), path.back().key + " = " + value_text(value));
    return true;
  }
  if (n->is_table() || n->is_array()) return false;
  const toml::source_region& r = n->source();
  if (r.begin.line == 0 || r.begin.line != r.end.line || r.begin.line > lines.size()) return false;
  std::string& line = lines[r.begin.line - 1];
  const std::size_t b = byte_offset(line, r.begin.column), e = byte_offset(line, r.end.column);
  line = line.substr(0, b) + value_text(value) + line.substr(e);
  return true;
}

}  // namespace

Override parse_override(const std::string& assignment) {
  const std::size_t eq = assignment.find('=');
  if (eq == std::string::npos)
    throw ModelError("--set " + assignment + ": expected PATH=VALUE, e.g. --set bearings.compressor.kxx=2e7");
  Override o{assignment.substr(0, eq), assignment.substr(eq + 1)};
  auto trim = [](std::string& s) {
    s.erase(0, s.find_first_not_of(" \t"));
    s.erase(s.find_last_not_of(" \t") + 1);
  };
  trim(o.path);
  trim(o.value);
  if (o.path.empty()) throw ModelError("--set " + assignment + ": the path before '=' is empty");
  if (o.value.empty()) throw ModelError("--set " + assignment + ": the value after '=' is empty");
  return o;
}

std::vector<OverrideStep> override_steps(const Override& o) {
  const std::string& path = o.path;
  auto fail = [&](const std::string& why) -> void { throw ModelError(context_of(o) + ": " + why); };
  std::vector<OverrideStep> steps;
  std::size_t pos = 0;
  while (true) {
    const std::size_t dot = path.find('.', pos);
    std::string part = path.substr(pos, dot == std::string::npos ? std::string::npos : dot - pos);
    OverrideStep step;
    if (const std::size_t bracket = part.find('['); bracket != std::string::npos) {
      if (part.back() != ']') fail("malformed index in '" + part + "' (expected NAME[INDEX])");
      const std::string idx = part.substr(bracket + 1, part.size() - bracket - 2);
      if (idx.empty()) fail("no index between the brackets in '" + part + "'");
      if (idx[0] == '-' && idx.size() > 1 && idx.find_first_not_of("0123456789", 1) == std::string::npos)
        fail("index " + idx + " is negative (entries are counted from 0)");
      if (idx.find_first_not_of("0123456789") != std::string::npos)
        fail("index '" + idx + "' is not a whole number");
      std::size_t index = 0;
      const auto [end, ec] = std::from_chars(idx.data(), idx.data() + idx.size(), index);
      if (ec != std::errc() || end != idx.data() + idx.size()) fail("index " + idx + " is out of range");
      step.index = index;
      part = part.substr(0, bracket);
    }
    if (part.empty()) fail("empty key in the path");
    step.key = part;
    steps.push_back(step);
    if (dot == std::string::npos) break;
    pos = dot + 1;
  }
  return steps;
}

void apply_override(toml::table& root, const Override& o, input::Sources* sources) {
  const std::vector<OverrideStep> steps = override_steps(o);
  const toml::table value = read_value(o);
  set_value(root, o, steps, *value.get("v"), sources);
}

std::string patched_model_text(const std::string& original, const std::string& source_name,
                               const std::vector<Override>& overrides, const std::string& header) {
  toml::table tree = input::parse_toml(original, source_name);
  toml::table target = tree;
  std::vector<std::string> lines;
  {
    std::istringstream ls(original);
    for (std::string l; std::getline(ls, l);) lines.push_back(l);
  }
  // Edits line by line; the same key twice: the last wins, as in the loader.
  bool in_place = true;
  for (const Override& o : overrides) {
    const std::vector<OverrideStep> path = override_steps(o);
    const toml::table value = read_value(o);
    set_value(target, o, path, *value.get("v"), nullptr);
    if (!in_place) continue;
    if (!patch_lines(lines, tree, path, *value.get("v"))) {
      in_place = false;
      continue;
    }
    // Later overrides of the same key find the new text at new columns: re-read the tree from the edited lines.
    try {
      tree = toml::parse(joined(lines), std::string_view(source_name));
    } catch (const toml::parse_error&) {
      in_place = false;
    }
  }
  std::string body;
  if (in_place) {
    body = joined(lines);
    try {
      in_place = toml::parse(body) == target;
    } catch (const toml::parse_error&) {
      in_place = false;
    }
  }
  if (!in_place) {
    std::ostringstream os;
    os << toml::toml_formatter(target) << "\n";
    body = os.str();
  }
  std::string out;
  std::istringstream hs(header);
  for (std::string l; std::getline(hs, l);) out += "# " + l + "\n";
  if (!header.empty()) out += "\n";
  out += body;
  (void)load_model_from_string(out, std::filesystem::path(source_name).filename().string());
  return out;
}

std::string patched_model(const std::filesystem::path& base, const std::vector<Override>& overrides,
                          const std::string& header) {
  return patched_model_text(input::read_text_file(base, "model file"), base.string(), overrides, header);
}

void write_patched_model(const std::filesystem::path& base, const std::vector<Override>& overrides,
                         const std::string& header, const std::filesystem::path& file) {
  write_patched_model_text(input::read_text_file(base, "model file"), base.string(), overrides, header, file);
}

void write_patched_model_text(const std::string& base_text, const std::string& source_name,
                              const std::vector<Override>& overrides, const std::string& header,
                              const std::filesystem::path& file) {
  const std::string text = patched_model_text(base_text, source_name, overrides, header);
  std::ofstream out(file, std::ios::binary);
  if (!out || !(out << text) || !out.flush()) throw ModelError(file.string() + ": cannot write");
}

}  // namespace turbodyn
