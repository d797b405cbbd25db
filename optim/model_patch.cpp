#include "optim/model_patch.h"

#include <fstream>
#include <sstream>

#include <toml++/toml.h>

#include "model/io/toml_reader.h"

namespace turbodyn::optim {
namespace {

struct Segment {
  std::string key;
  long index = -1;
};

// The --set path syntax of docs/model-format.md: dotted keys, name[i] for an entry of an array of tables.
std::vector<Segment> split_path(const std::string& path) {
  std::vector<Segment> out;
  std::stringstream ss(path);
  std::string part;
  while (std::getline(ss, part, '.')) {
    Segment s;
    const std::size_t b = part.find('[');
    if (b != std::string::npos && part.back() == ']') {
      s.index = std::stol(part.substr(b + 1, part.size() - b - 2));
      part = part.substr(0, b);
    }
    s.key = part;
    out.push_back(s);
  }
  return out;
}

// The override's value as a TOML node, read like the model loader reads it (TOML, else a plain string).
toml::table value_table(const Override& o) {
  try {
    return toml::parse("v = " + o.value);
  } catch (const toml::parse_error&) {
    toml::table t;
    t.insert("v", o.value);
    return t;
  }
}

// The node at `path` (nullptr if absent); with `create`, missing tables are made and the value is set.
toml::node* walk(toml::table& root, const std::vector<Segment>& path, const toml::node* set) {
  toml::table* t = &root;
  for (std::size_t i = 0; i < path.size(); ++i) {
    const bool last = i + 1 == path.size();
    toml::node* n = t->get(path[i].key);
    if (path[i].index >= 0) {
      if (!n || !n->is_array() || static_cast<std::size_t>(path[i].index) >= n->as_array()->size()) return nullptr;
      toml::array& a = *n->as_array();
      if (last) {
        if (set) set->visit([&](auto&& v) { a.replace(a.cbegin() + path[i].index, v); });
        return a.get(static_cast<std::size_t>(path[i].index));
      }
      n = a.get(static_cast<std::size_t>(path[i].index));
    } else if (last) {
      if (set) set->visit([&](auto&& v) { t->insert_or_assign(path[i].key, v); });
      return t->get(path[i].key);
    } else if (!n) {
      if (!set) return nullptr;
      n = &t->insert_or_assign(path[i].key, toml::table{}).first->second;
    }
    if (!n->is_table()) return nullptr;
    t = n->as_table();
  }
  return nullptr;
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

}  // namespace

std::string patched_model(const std::filesystem::path& base, const std::vector<Override>& overrides,
                          const std::string& header) {
  const std::string original = input::read_text_file(base, "model file");
  toml::table tree = input::parse_toml(original, base.string());
  toml::table target = tree;
  // In-place edits, line by line; the same override twice: the last wins, as in the loader.
  std::vector<std::string> lines;
  {
    std::istringstream ls(original);
    std::string l;
    while (std::getline(ls, l)) lines.push_back(l);
  }
  bool in_place = true;
  for (const Override& o : overrides) {
    const std::vector<Segment> path = split_path(o.path);
    const toml::table v = value_table(o);
    walk(target, path, v.get("v"));
    const toml::node* n = walk(tree, path, nullptr);
    if (!n) {
      // A key the file lacks: a new line in its table, if the table has a [header] of its own in the file.
      const toml::node* parent =
          path.size() > 1 && path.back().index < 0 ? walk(tree, {path.begin(), path.end() - 1}, nullptr) : nullptr;
      const toml::table* t = parent ? parent->as_table() : nullptr;
      if (!t || t->is_inline() || t->source().begin.line == 0 || t->source().begin.line > lines.size()) {
        in_place = false;
        continue;
      }
      std::size_t after = t->source().begin.line;  // the header line, or the last line of a value of the table
      for (auto&& [k, child] : *t)
        if (!child.is_table() && !(child.is_array() && child.as_array()->is_array_of_tables()))
          after = std::max<std::size_t>(after, child.source().end.line);
      if (after > lines.size()) {
        in_place = false;
        continue;
      }
      lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(after),
                   path.back().key + " = " + value_text(*v.get("v")));
    } else if (n->is_table() || n->is_array()) {
      in_place = false;
      continue;
    } else {
      const toml::source_region& r = n->source();
      if (r.begin.line == 0 || r.begin.line != r.end.line || r.begin.line > lines.size()) {
        in_place = false;
        continue;
      }
      std::string& line = lines[r.begin.line - 1];
      const std::size_t b = byte_offset(line, r.begin.column), e = byte_offset(line, r.end.column);
      line = line.substr(0, b) + value_text(*v.get("v")) + line.substr(e);
    }
    // Later overrides of the same key find the new text at new columns: re-read the tree from the edited lines.
    std::string joined;
    for (const std::string& l : lines) joined += l + "\n";
    try {
      tree = toml::parse(joined, std::string_view(base.string()));
    } catch (const toml::parse_error&) {
      in_place = false;
      break;
    }
  }
  std::string body;
  if (in_place) {
    for (const std::string& l : lines) body += l + "\n";
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
  (void)load_model_from_string(out, base.filename().string());
  return out;
}

}  // namespace turbodyn::optim
