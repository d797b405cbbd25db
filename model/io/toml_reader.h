// Reading TOML input (model files, study files) with errors that point at the line: every value knows its
// file:line:column (or the --set override that put it there); a Reader remembers which keys of a table the
// program asked for and rejects all others with a "did you mean" suggestion.
#pragma once

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

#include "model/spec/enum_names.h"
#include "model/spec/errors.h"
#include "model/spec/limits.h"
#include "model/spec/units.h"

namespace turbodyn::input {

inline constexpr const char* kOverridePrefix = "--set ";

/// Parses TOML text; a syntax error is a ModelError naming source:line:column.
inline toml::table parse_toml(const std::string& text, const std::string& source_name) {
  try {
    return toml::parse(text, std::string_view(source_name));
  } catch (const toml::parse_error& e) {
    std::ostringstream os;
    os << source_name << ':' << e.source().begin.line << ':' << e.source().begin.column
       << ": TOML syntax error: " << e.description();
    throw ModelError(os.str());
  }
}

/// Reads the whole file (a ModelError "FILE: cannot open the WHAT" if it cannot, "FILE: is a directory" for one).
inline std::string read_text_file(const std::filesystem::path& file, const std::string& what) {
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec))
    throw ModelError(file.string() + ": is a directory, not a " + what);
  std::ifstream in(file, std::ios::binary);
  if (!in) throw ModelError(file.string() + ": cannot open the " + what);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Where values came from: the file, or the --set override that put a node into the tree.
struct Sources {
  std::string file;
  std::map<const toml::node*, std::string> overrides;
};

inline std::string where(const toml::source_region& src, const std::string& fallback) {
  if (!src.path || src.begin.line == 0) return fallback;
  std::ostringstream os;
  os << *src.path << ':' << src.begin.line << ':' << src.begin.column;
  return os.str();
}

// "file:line:column" of a node, or the override that created it.
inline std::string where(const toml::node& n, const Sources& sources, const std::string& fallback) {
  if (const auto it = sources.overrides.find(&n); it != sources.overrides.end()) return it->second;
  return where(n.source(), fallback);
}

// Position of a key (where a user looks for a misspelt name), else of its value.
inline std::string where_key(const toml::key& k, const toml::node& v, const Sources& sources, const std::string& fallback) {
  if (sources.overrides.count(&v)) return where(v, sources, fallback);
  return where(k.source(), where(v, sources, fallback));
}

inline std::string describe_node(const toml::node& n) {
  std::ostringstream os;
  switch (n.type()) {
    case toml::node_type::string: os << "'" << *n.value<std::string>() << "'"; break;
    case toml::node_type::table: os << "a table"; break;
    case toml::node_type::array: os << "an array"; break;
    case toml::node_type::boolean: os << (*n.value<bool>() ? "true" : "false"); break;
    case toml::node_type::floating_point: {
      // The shortest text that reads back as the same double: "-0.3", not toml++'s "-0.29999999999999999".
      char text[32];
      const auto end = std::to_chars(text, text + sizeof text, *n.value<double>()).ptr;
      os << std::string_view(text, static_cast<std::size_t>(end - text));
      break;
    }
    default: n.visit([&](auto&& v) { os << v; }); break;
  }
  return os.str();
}

enum class Bound { Any, Positive, NonNegative };

// Optional record of the key path of every key a Reader asks for (present or not), for the test that the
// documentation names every key the loader accepts (model_file.h: accepted_model_keys). Off unless a KeyRecording
// is alive on this thread; it costs one pointer test per key read, and keys are read only while loading.
inline thread_local std::vector<std::string>* key_record = nullptr;

// Same for the keys read as numbers (quantities, lists of them, whole numbers): the keys a study may vary
// (model_file.h: numeric_model_keys).
inline thread_local std::vector<std::string>* numeric_key_record = nullptr;

// While alive, points one of the record slots above at `out` (and restores the previous target after).
class Recording {
 public:
  Recording(std::vector<std::string>*& slot, std::vector<std::string>& out) : slot_(slot), previous_(slot) {
    slot_ = &out;
  }
  ~Recording() { slot_ = previous_; }
  Recording(const Recording&) = delete;
  Recording& operator=(const Recording&) = delete;

 private:
  std::vector<std::string>*& slot_;
  std::vector<std::string>* previous_;
};

struct KeyRecording : Recording {
  explicit KeyRecording(std::vector<std::string>& out) : Recording(key_record, out) {}
};

struct NumericKeyRecording : Recording {
  explicit NumericKeyRecording(std::vector<std::string>& out) : Recording(numeric_key_record, out) {}
};

// Reads the keys of one table, remembers which keys the program knows, and rejects all others in finish().
class Reader {
 public:
  Reader(const toml::table& table, std::string path, const Sources& sources)
      : table_(table), path_(std::move(path)), sources_(sources) {}

  const std::string& path() const { return path_; }
  const Sources& sources() const { return sources_; }
  std::string key_path(std::string_view key) const {
    return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
  }
  std::string location(std::string_view key) const {
    const toml::node* n = table_.get(key);
    const std::string table_loc = where(table_, sources_, sources_.file);
    return n ? where(*n, sources_, table_loc) : table_loc;
  }

  const toml::node* get(std::string_view key) {
    known_.emplace(key);
    if (key_record) key_record->push_back(key_path(key));
    return table_.get(key);
  }
  bool has(std::string_view key) { return get(key) != nullptr; }

  [[noreturn]] void fail(std::string_view key, const std::string& message) const {
    throw ModelError(location(key) + ": " + key_path(key) + ": " + message);
  }
  // A required key is absent: if an unknown key looks like a misspelling of it, that is the better message.
  [[noreturn]] void fail_missing(std::string_view key, const std::string& expected) const {
    for (auto&& [k, v] : table_) {
      const std::string other(k.str());
      if (known_.count(other)) continue;
      if (closest_match(other, {std::string(key)}) == key)
        throw ModelError(where_key(k, v, sources_, sources_.file) + ": " + key_path(other) +
                         ": unknown key; did you mean '" + std::string(key) + "'?");
    }
    fail(key, "missing required key (" + expected + ")");
  }
  [[noreturn]] void fail_table(const std::string& message) const {
    throw ModelError(where(table_, sources_, sources_.file) + ": " + (path_.empty() ? "(top level)" : path_) +
                     ": " + message);
  }

  double quantity(std::string_view key, const Dimension& d, Bound bound = Bound::Any) {
    record_numeric(key);
    const toml::node* n = get(key);
    if (!n) fail_missing(key, "expected " + describe(d));
    return convert(key, *n, d, bound);
  }
  double quantity_or(std::string_view key, const Dimension& d, double fallback, Bound bound = Bound::Any) {
    record_numeric(key);
    const toml::node* n = get(key);
    return n ? convert(key, *n, d, bound) : fallback;
  }
  // An array of quantities (a single value is taken as a list of one).
  std::vector<double> quantity_list(std::string_view key, const Dimension& d, Bound bound = Bound::Any) {
    record_numeric(key);
    std::vector<double> out;
    const toml::node* n = get(key);
    if (!n) return out;
    if (const toml::array* a = n->as_array()) {
      if (a->empty()) fail(key, "the list is empty");
      for (const toml::node& e : *a) out.push_back(convert(key, e, d, bound));
    } else {
      out.push_back(convert(key, *n, d, bound));
    }
    return out;
  }
  std::string text_or(std::string_view key, const std::string& fallback) {
    const toml::node* n = get(key);
    if (!n) return fallback;
    if (!n->is_string()) fail(key, "expected a string, got " + describe_node(*n));
    return *n->value<std::string>();
  }
  std::string choice(std::string_view key, const std::vector<std::string>& options, const std::string& fallback) {
    const std::string value = text_or(key, fallback);
    if (std::find(options.begin(), options.end(), value) != options.end()) return value;
    std::string list;
    for (const auto& o : options) list += (list.empty() ? "'" : ", '") + o + "'";
    std::string hint = closest_match(value, options);
    fail(key, "unknown value '" + value + "' (expected one of " + list + ")" +
                  (hint.empty() ? "" : "; did you mean '" + hint + "'?"));
  }
  // The enum value named by a string key, one of the names in `names` (enum_names.h); `fallback` when absent.
  template <class Enum, std::size_t N>
  Enum enumeration(std::string_view key, const EnumName<Enum> (&names)[N], Enum fallback) {
    Enum value = fallback;
    value_of(names, choice(key, names_of(names), name_of(names, fallback)), value);
    return value;
  }
  bool flag_or(std::string_view key, bool fallback) {
    const toml::node* n = get(key);
    if (!n) return fallback;
    if (!n->is_boolean()) fail(key, "expected true or false, got " + describe_node(*n));
    return *n->value<bool>();
  }
  // A whole number read as 64 bits and checked against [minimum, maximum], the range of what uses it (so a
  // value at or above 2^31 is refused, never cut to 32 bits).
  long integer_or(std::string_view key, long fallback, long minimum, long maximum) {
    record_numeric(key);
    const toml::node* n = get(key);
    if (!n) return fallback;
    if (!n->is_integer()) fail(key, "expected a whole number, got " + describe_node(*n));
    const std::int64_t v = *n->value<std::int64_t>();
    if (v < minimum || v > maximum)
      fail(key, "must be a whole number from " + std::to_string(minimum) + " to " + std::to_string(maximum) +
                    ", got " + std::to_string(v));
    return static_cast<long>(v);
  }
  const toml::table* table(std::string_view key) {
    const toml::node* n = get(key);
    if (!n) return nullptr;
    if (!n->is_table()) fail(key, "expected a table ([" + key_path(key) + "]), got " + describe_node(*n));
    return n->as_table();
  }
  const toml::array* array(std::string_view key) {
    const toml::node* n = get(key);
    if (!n) return nullptr;
    if (!n->is_array()) fail(key, "expected an array, got " + describe_node(*n));
    return n->as_array();
  }

  // Calls f(reader, i) for each entry of the array of tables `key` ([[key]] in TOML), whose reader has the path
  // "key[i]"; an entry that is not a table is an error. Returns the number of entries, 0 when the key is absent.
  template <class F>
  std::size_t each_table(std::string_view key, F&& f) {
    const toml::array* entries = array(key);
    if (!entries) return 0;
    for (std::size_t i = 0; i < entries->size(); ++i) {
      const toml::node& n = (*entries)[i];
      const std::string entry_path = key_path(key) + "[" + std::to_string(i) + "]";
      if (!n.is_table()) throw ModelError(where(n, sources_, sources_.file) + ": " + entry_path + ": expected a table");
      Reader r(*n.as_table(), entry_path, sources_);
      f(r, i);
    }
    return entries->size();
  }

  // A Reader of the table `key` ([key]), which must be there: `what` says what it holds, for the message.
  Reader required_table(std::string_view key, const std::string& what) {
    const toml::table* t = table(key);
    if (!t) fail(key, "missing: " + what);
    return Reader(*t, key_path(key), sources_);
  }
  // each_table for an array of tables that needs at least one entry (`what` says what one holds).
  template <class F>
  std::size_t required_tables(std::string_view key, const std::string& what, F&& f) {
    const toml::array* entries = array(key);
    if (!entries || entries->empty()) fail(key, "missing: " + what);
    return each_table(key, f);
  }

  void record_numeric(std::string_view key) const {
    if (numeric_key_record) numeric_key_record->push_back(key_path(key));
  }

  // A "PATH=VALUE" string of the list `key` read by `parse` (overrides.h: parse_override); its error is located at
  // the key.
  template <class Parse>
  auto parsed(std::string_view key, const std::string& text, Parse&& parse) {
    try {
      return parse(text);
    } catch (const ModelError& e) {
      fail(key, e.what());
    }
  }

  // Every key of the table must have been asked for.
  void finish() const {
    std::vector<std::string> known(known_.begin(), known_.end());
    for (auto&& [k, v] : table_) {
      const std::string key(k.str());
      if (known_.count(key)) continue;
      const std::string hint = closest_match(key, known);
      std::string message = "unknown key";
      if (!hint.empty()) message += "; did you mean '" + hint + "'?";
      else if (!known.empty()) {
        message += " (known here: ";
        for (std::size_t i = 0; i < known.size(); ++i) message += (i ? ", " : "") + known[i];
        message += ")";
      }
      throw ModelError(where_key(k, v, sources_, where(table_, sources_, sources_.file)) + ": " + key_path(key) +
                       ": " + message);
    }
  }

 private:
  double convert(std::string_view key, const toml::node& n, const Dimension& d, Bound bound) const {
    double v = 0.0;
    if (n.is_integer()) {
      v = static_cast<double>(*n.value<int64_t>());
    } else if (n.is_floating_point()) {
      v = *n.value<double>();
    } else if (n.is_string()) {
      try {
        v = parse_quantity(*n.value<std::string>(), d);
      } catch (const UnitError& e) {
        throw ModelError(where(n, sources_, location(key)) + ": " + key_path(key) + ": " + e.what());
      }
    } else {
      throw ModelError(where(n, sources_, location(key)) + ": " + key_path(key) + ": expected " + describe(d) +
                       " (a number in SI units or a string such as \"" + example_for(d) + "\"), got " +
                       describe_node(n));
    }
    if (const std::string why = limits::implausible(v, d); !why.empty())
      throw ModelError(where(n, sources_, location(key)) + ": " + key_path(key) + ": " + why);
    if (bound == Bound::Positive && !(v > 0.0))
      throw ModelError(where(n, sources_, location(key)) + ": " + key_path(key) + ": must be positive, got " +
                       describe_node(n));
    if (bound == Bound::NonNegative && v < 0.0)
      throw ModelError(where(n, sources_, location(key)) + ": " + key_path(key) + ": must not be negative, got " +
                       describe_node(n));
    return v;
  }
  static std::string example_for(const Dimension& d) {
    if (d == dim::length) return "15 um";
    if (d == dim::angular_speed) return "150000 rpm";
    if (d == dim::unbalance) return "390 mg*mm";
    if (d == dim::temperature) return "90 degC";
    if (d == dim::mass) return "0.119 kg";
    return "1 " + d.si_unit();
  }

  const toml::table& table_;
  std::string path_;
  const Sources& sources_;
  std::set<std::string> known_;
};


// A TOML file read whole, with a Reader over its top level (tree and sources live as long as this object).
class TomlFile {
 public:
  /// `what` names the kind of file in the "cannot open" message ("study file").
  TomlFile(const std::filesystem::path& file, const std::string& what)
      : root_(parse_toml(read_text_file(file, what), file.string())), sources_{file.string(), {}},
        top_(root_, "", sources_) {}
  TomlFile(const TomlFile&) = delete;
  TomlFile& operator=(const TomlFile&) = delete;
  const toml::table& root() const { return root_; }
  const Sources& sources() const { return sources_; }
  Reader& top() { return top_; }

 private:
  toml::table root_;
  Sources sources_;
  Reader top_;
};

}  // namespace turbodyn::input
