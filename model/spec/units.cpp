#include "model/spec/units.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <tuple>
#include <vector>

namespace turbodyn {
namespace {

constexpr double two_pi = 2.0 * std::numbers::pi;

// ----------------------------------------------------------------------------------------------------------------
// Dimension names

struct DimensionName {
  Dimension dim;
  std::string_view description;  // with its article
  std::string_view si_unit;      // preferred spelling; empty: built from the base units
};

constexpr DimensionName dimension_names[] = {
    {dim::dimensionless, "a dimensionless number", "1"},
    {dim::length, "a length", ""},
    {dim::mass, "a mass", ""},
    {dim::time, "a time", ""},
    {dim::temperature, "a temperature", ""},
    {dim::angle, "an angle", ""},
    {dim::area, "an area", ""},
    {dim::velocity, "a velocity", ""},
    {dim::acceleration, "an acceleration", ""},
    {dim::frequency, "a frequency", "Hz"},
    {dim::angular_speed, "an angular speed", ""},
    {dim::angular_acceleration, "an angular acceleration", ""},
    {dim::force, "a force", "N"},
    {dim::pressure, "a pressure", "Pa"},
    {dim::stiffness, "a stiffness", "N/m"},
    {dim::damping, "a damping coefficient", "N*s/m"},
    {dim::density, "a density", ""},
    {dim::inertia, "a moment of inertia", ""},
    {dim::unbalance, "an unbalance", ""},
    {dim::viscosity, "a dynamic viscosity", "Pa*s"},
    {dim::moment, "a moment", "N*m"},
    {dim::rotational_stiffness, "a rotational stiffness", "N*m/rad"},
    {dim::rotational_damping, "a rotational damping coefficient", "N*m*s/rad"},
    {dim::power, "a power", "W"},
    {dim::thermal_conductance, "a thermal conductance", "W/K"},
    {dim::thermal_conductivity, "a thermal conductivity", "W/m/K"},
    {dim::specific_heat, "a specific heat capacity", "J/kg/K"},
};

const DimensionName* find_name(const Dimension& d) {
  const auto it = std::ranges::find(dimension_names, d, &DimensionName::dim);
  return it == std::ranges::end(dimension_names) ? nullptr : &*it;
}

// "kg*m^2/s^2": positive exponents first, then each negative one as a division, so that the result reads
// left to right exactly as parse_quantity evaluates it.
std::string base_unit_expression(const Dimension& d) {
  const std::pair<std::string_view, int> factors[] = {{"kg", d.kg}, {"m", d.m}, {"s", d.s}, {"K", d.K}, {"rad", d.rad}};
  const auto term = [](std::string_view symbol, int exponent) {
    std::string t(symbol);
    if (exponent != 1) t += "^" + std::to_string(exponent);
    return t;
  };
  std::string numerator, denominator;
  for (const auto& [symbol, exponent] : factors) {
    if (exponent > 0) numerator += (numerator.empty() ? "" : "*") + term(symbol, exponent);
    if (exponent < 0) denominator += "/" + term(symbol, -exponent);
  }
  return (numerator.empty() ? "1" : numerator) + denominator;
}

Dimension scaled(const Dimension& d, int n) { return {d.kg * n, d.m * n, d.s * n, d.K * n, d.rad * n}; }

Dimension without_angle(Dimension d) {
  d.rad = 0;
  return d;
}

// ----------------------------------------------------------------------------------------------------------------
// Units

// The SI value of a unit: mul / div * 10^pow10 * (2*pi)^turns. Keeping decimal prefixes and full turns apart
// from the rest means "15 um" gives exactly the double 15e-6 and "150000 rpm" as a frequency exactly 2500,
// instead of something an ulp away.
struct Scale {
  double mul = 1, div = 1;
  int pow10 = 0;
  int turns = 0;
};

Scale operator*(const Scale& a, const Scale& b) {
  return {a.mul * b.mul, a.div * b.div, a.pow10 + b.pow10, a.turns + b.turns};
}

Scale power(const Scale& s, int n) {
  const double mul = std::pow(s.mul, std::abs(n)), div = std::pow(s.div, std::abs(n));
  return {n >= 0 ? mul : div, n >= 0 ? div : mul, s.pow10 * n, s.turns * n};
}

// Multiplying by an exact power of ten (dividing for negative exponents) rounds only once.
double times_power_of_ten(double x, int exponent) {
  constexpr int max_exact = 22;  // 1e22 is the largest power of ten a double holds exactly
  constexpr double big = 1e22;
  for (; exponent > max_exact; exponent -= max_exact) x *= big;
  for (; exponent < -max_exact; exponent += max_exact) x /= big;
  double p = 1;
  for (int i = 0; i < std::abs(exponent); ++i) p *= 10;
  return exponent >= 0 ? x * p : x / p;
}

double to_si(double value, const Scale& s) {
  double x = times_power_of_ten(value * s.mul / s.div, s.pow10);
  for (int i = 0; i < s.turns; ++i) x *= two_pi;
  for (int i = 0; i > s.turns; --i) x /= two_pi;
  return x;
}

struct UnitDef {
  std::string_view name;
  Dimension dim;
  Scale scale;
  bool prefixable;       // metric units take SI prefixes: "mm", "kN", "MPa"
  bool celsius = false;  // offset scale, value + 273.15 K
};

constexpr double celsius_offset = 273.15;

constexpr UnitDef unit_table[] = {
    {"m", dim::length, {}, true},
    {"in", dim::length, {254, 1, -4}, false},
    {"inch", dim::length, {254, 1, -4}, false},
    {"g", dim::mass, {1, 1, -3}, true},
    {"s", dim::time, {}, true},
    {"min", dim::time, {60}, false},
    {"h", dim::time, {3600}, false},
    {"N", dim::force, {}, true},
    {"Pa", dim::pressure, {}, true},
    {"bar", dim::pressure, {1, 1, 5}, true},
    {"J", dim::moment, {}, true},  // energy has the dimension of a moment
    {"W", dim::moment / dim::time, {}, true},
    {"Hz", dim::angular_speed, {1, 1, 0, 1}, true},  // one cycle per second, see the angle rule in units.h
    {"K", dim::temperature, {}, true},
    {"degC", dim::temperature, {}, false, true},
    {"rad", dim::angle, {}, true},
    {"deg", dim::angle, {1, 360, 0, 1}, false},
    {"rev", dim::angle, {1, 1, 0, 1}, false},
    {"rpm", dim::angular_speed, {1, 60, 0, 1}, false},
    {"P", dim::viscosity, {1, 1, -1}, false},  // poise; prefixed only as cP, listed on its own
    {"cP", dim::viscosity, {1, 1, -3}, false},
};

struct Prefix {
  std::string_view symbol;
  int pow10;
  std::string_view only_for = {};  // "c" makes sense only in "cm"
};

// Unit names are looked up after normalisation, which spells both micro signs as 'u'.
constexpr Prefix prefixes[] = {{"G", 9}, {"M", 6}, {"k", 3}, {"c", -2, "m"}, {"m", -3}, {"u", -6}, {"n", -9}};

struct Unit {
  Dimension dim;
  Scale scale;
  bool celsius = false;
};

std::optional<Unit> find_unit(std::string_view name) {
  // Whole names first, so that "min" is minutes and "cP" centipoise.
  for (const auto& u : unit_table) {
    if (u.name == name) return Unit{u.dim, u.scale, u.celsius};
  }
  for (const auto& p : prefixes) {
    if (!name.starts_with(p.symbol)) continue;
    const std::string_view rest = name.substr(p.symbol.size());
    if (!p.only_for.empty() && rest != p.only_for) continue;
    for (const auto& u : unit_table) {
      if (u.prefixable && u.name == rest) return Unit{u.dim, u.scale * Scale{1, 1, p.pow10}};
    }
  }
  return std::nullopt;
}

std::string known_units() {
  std::string list;
  for (const auto& u : unit_table) list += (list.empty() ? "" : ", ") + std::string(u.name);
  list += "; prefixes";
  for (const auto& p : prefixes) {
    list += " " + std::string(p.symbol);
    if (p.symbol == "u") list += "/\xC2\xB5";
  }
  return list + " (c only in cm)";
}

// ----------------------------------------------------------------------------------------------------------------
// Suggestions for unknown units

// Optimal string alignment distance in half edits: insertions, deletions, substitutions and swaps of neighbours
// ("rmp" vs "rpm") cost 2, a change of case only ("HZ" vs "Hz") costs 1.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  const auto lower = [](char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; };
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = 2 * i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = 2 * j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const char x = a[i - 1], y = b[j - 1];
      const std::size_t substitution = x == y ? 0 : lower(x) == lower(y) ? 1 : 2;
      d[i][j] = std::min({d[i - 1][j] + 2, d[i][j - 1] + 2, d[i - 1][j - 1] + substitution});
      if (i > 1 && j > 1 && x == b[j - 2] && a[i - 2] == y) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 2);
    }
  }
  return d[a.size()][b.size()];
}

// Every spelling find_unit accepts (with 'u' for micro), in table order, unprefixed first.
const std::vector<std::string>& all_unit_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const auto& u : unit_table) out.emplace_back(u.name);
    for (const auto& p : prefixes) {
      for (const auto& u : unit_table) {
        if (u.prefixable && (p.only_for.empty() || p.only_for == u.name)) {
          out.push_back(std::string(p.symbol) + std::string(u.name));
        }
      }
    }
    return out;
  }();
  return names;
}

// The known spellings nearest to an unknown unit name, with units of the expected dimension first among equally
// near ones. Two units run together ("Nm") count as one edit away from their product ("N*m") and are suggested
// when that product has the expected dimension.
std::vector<std::string> suggestions(std::string_view unknown, const Dimension& expected) {
  struct Candidate {
    std::string name;
    std::size_t distance;  // half edits
    bool expected_dimension;
  };
  const auto matches = [&](const Dimension& d) { return without_angle(d) == without_angle(expected); };

  std::vector<Candidate> candidates;
  const std::size_t max_distance = unknown.size() <= 2 ? 2 : 4;  // one edit for short names, else two
  for (const auto& name : all_unit_names()) {
    const std::size_t distance = edit_distance(unknown, name);
    if (distance <= max_distance) candidates.push_back({name, distance, matches(find_unit(name)->dim)});
  }
  for (std::size_t i = 1; i < unknown.size(); ++i) {
    const auto left = find_unit(unknown.substr(0, i)), right = find_unit(unknown.substr(i));
    if (left && right && matches(left->dim * right->dim)) {
      candidates.push_back({std::string(unknown.substr(0, i)) + "*" + std::string(unknown.substr(i)), 2, true});
    }
  }

  // Keep the group the fewest whole edits away and, if some of it has the expected dimension, only those.
  const auto edits = [](const Candidate& c) { return (c.distance + 1) / 2; };
  std::ranges::stable_sort(candidates, [&](const Candidate& a, const Candidate& b) {
    return std::tuple(edits(a), !a.expected_dimension, a.distance) <
           std::tuple(edits(b), !b.expected_dimension, b.distance);
  });
  constexpr std::size_t max_suggestions = 5;
  std::vector<std::string> out;
  for (const auto& c : candidates) {
    const Candidate& best = candidates.front();
    if (out.size() == max_suggestions || edits(c) > edits(best) || (best.expected_dimension && !c.expected_dimension))
      break;
    out.push_back(c.name);
  }
  return out;
}

// ----------------------------------------------------------------------------------------------------------------
// Parsing

// UTF-8 spellings accepted besides ASCII.
constexpr std::string_view micro_sign = "\xC2\xB5";   // U+00B5 MICRO SIGN
constexpr std::string_view greek_mu = "\xCE\xBC";     // U+03BC GREEK SMALL LETTER MU
constexpr std::string_view degree_sign = "\xC2\xB0";  // U+00B0 DEGREE SIGN, "°" and "°C"
constexpr std::string_view middle_dot = "\xC2\xB7";   // U+00B7 MIDDLE DOT, multiplication
constexpr std::string_view superscript_two = "\xC2\xB2";
constexpr std::string_view superscript_three = "\xC2\xB3";
constexpr std::string_view whitespace[] = {" ", "\t", "\r", "\n", "\xC2\xA0" /* U+00A0 NO-BREAK SPACE */};

std::size_t whitespace_length(std::string_view s) {
  for (const auto w : whitespace) {
    if (s.starts_with(w)) return w.size();
  }
  return 0;
}

std::string_view trim(std::string_view s) {
  while (const std::size_t n = whitespace_length(s)) s.remove_prefix(n);
  while (!s.empty()) {
    // Check the one- and two-byte endings that whitespace_length knows.
    if (whitespace_length(s.substr(s.size() - 1)) == 1) {
      s.remove_suffix(1);
    } else if (s.size() >= 2 && whitespace_length(s.substr(s.size() - 2)) == 2) {
      s.remove_suffix(2);
    } else {
      break;
    }
  }
  return s;
}

// The whole UTF-8 character starting s, for messages.
std::string_view first_character(std::string_view s) {
  const auto lead = static_cast<unsigned char>(s.front());
  const std::size_t length = lead >= 0xF0 ? 4 : lead >= 0xE0 ? 3 : lead >= 0xC0 ? 2 : 1;
  return s.substr(0, length);
}

bool is_ascii_letter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }
bool is_digit(char c) { return c >= '0' && c <= '9'; }

// The input and the expected dimension, for error messages.
class Context {
 public:
  Context(std::string_view text, const Dimension& expected) : text_(text), expected_(expected) {}

  const Dimension& expected() const { return expected_; }
  std::string quoted() const { return "'" + std::string(text_) + "'"; }

  // Throws "<problem>, expected <dimension>[; <hint>]"; `problem` should quote the input.
  [[noreturn]] void fail(const std::string& problem, const std::string& hint = {}) const {
    throw UnitError(problem + ", expected " + describe(expected_) + (hint.empty() ? "" : "; " + hint));
  }

 private:
  std::string_view text_;
  const Dimension& expected_;
};

struct ParsedUnit {
  Dimension dim;
  Scale scale;
  bool celsius = false;
};

// Parses a unit expression (the part after the number, trimmed) left to right.
class UnitExpressionParser {
 public:
  UnitExpressionParser(const Context& context, std::string_view expression) : context_(context), expr_(expression) {}

  ParsedUnit parse() {
    ParsedUnit result;
    // A leading "1" or a bare '/' is the empty product, as in "1/s".
    if (consume("1")) {
      skip_whitespace();
      if (!at("/")) context_.fail("a leading 1 must be followed by '/' in " + context_.quoted());
    } else if (!at("/")) {
      multiply(result, parse_factor(), 1);
    }
    while (true) {
      skip_whitespace();
      if (at_end()) break;
      const bool divide = consume("/");
      if (!divide && !consume("*") && !consume(middle_dot)) {
        if (!at_name())
          context_.fail("unexpected '" + std::string(first_character(rest())) + "' in " + context_.quoted());
        context_.fail("missing '*' or '/' before '" + std::string(rest()) + "' in " + context_.quoted());
      }
      skip_whitespace();
      if (at_end())
        context_.fail(std::string("unit missing after '") + (divide ? "/" : "*") + "' in " + context_.quoted());
      multiply(result, parse_factor(), divide ? -1 : 1);
    }
    if (celsius_token_ && *celsius_token_ != expr_) {
      context_.fail("'" + std::string(*celsius_token_) + "' is only allowed as the whole unit in " + context_.quoted(),
                    "it is an offset scale; write temperature differences and rates in K");
    }
    return result;
  }

 private:
  struct Factor {
    Unit unit;
    int exponent = 1;
  };

  void multiply(ParsedUnit& result, const Factor& factor, int sign) {
    const int n = sign * factor.exponent;
    result.dim = result.dim * scaled(factor.unit.dim, n);
    result.scale = result.scale * power(factor.unit.scale, n);
    result.celsius = result.celsius || factor.unit.celsius;
  }

  Factor parse_factor() {
    const std::size_t start = pos_;
    const std::string name = read_name();
    const std::string_view raw = expr_.substr(start, pos_ - start);
    if (name.empty()) {
      const std::string what = at_end() ? "unit missing" : "unexpected '" + std::string(first_character(rest())) + "'";
      context_.fail(what + " in " + context_.quoted());
    }
    const std::optional<Unit> unit = find_unit(name);
    if (!unit) unknown_unit(name, raw);
    if (unit->celsius) celsius_token_ = raw;

    Factor factor{*unit};
    if (consume("^")) {
      factor.exponent = read_exponent(raw);
    } else if (consume(superscript_two)) {
      factor.exponent = 2;
    } else if (consume(superscript_three)) {
      factor.exponent = 3;
    } else if (!at_end() && is_digit(expr_[pos_])) {
      context_.fail("number directly after '" + std::string(raw) + "' in " + context_.quoted(),
                    "write powers with '^', e.g. '" + std::string(raw) + "^2'");
    }
    return factor;
  }

  // Letters and the micro and degree signs, normalised for find_unit: both micro signs become 'u', '°' becomes
  // "deg" (so "°C" is "degC").
  std::string read_name() {
    std::string name;
    while (!at_end()) {
      if (is_ascii_letter(expr_[pos_])) {
        name += expr_[pos_++];
      } else if (consume(micro_sign) || consume(greek_mu)) {
        name += 'u';
      } else if (consume(degree_sign)) {
        name += "deg";
      } else {
        break;
      }
    }
    return name;
  }

  int read_exponent(std::string_view base) {
    const auto fail = [&] {
      context_.fail("exponent of '" + std::string(base) + "' must be an integer in " + context_.quoted());
    };
    if (at("+") && rest().size() > 1 && is_digit(rest()[1])) ++pos_;  // from_chars takes '-' but not '+'
    int exponent = 0;
    const char* first = expr_.data() + pos_;
    const auto [end, ec] = std::from_chars(first, expr_.data() + expr_.size(), exponent);
    if (ec != std::errc()) fail();
    pos_ += static_cast<std::size_t>(end - first);
    // "m^2.5", "m^2,5"; a large bound keeps the dimension arithmetic far from overflow.
    constexpr int max_exponent = 99;
    if (at(".") || at(",") || std::abs(exponent) > max_exponent) fail();
    return exponent;
  }

  [[noreturn]] void unknown_unit(const std::string& name, std::string_view raw) const {
    const std::vector<std::string> similar = suggestions(name, context_.expected());
    std::string hint;
    if (!similar.empty()) {
      hint = "did you mean ";
      for (std::size_t i = 0; i < similar.size(); ++i) hint += (i == 0 ? "'" : ", '") + similar[i] + "'";
      hint += "? ";
    }
    hint += "known units: " + known_units();
    context_.fail("unknown unit '" + std::string(raw) + "' in " + context_.quoted(), hint);
  }

  bool at_end() const { return pos_ >= expr_.size(); }
  bool at_name() const {
    return (!at_end() && is_ascii_letter(expr_[pos_])) || at(micro_sign) || at(greek_mu) || at(degree_sign);
  }
  std::string_view rest() const { return expr_.substr(pos_); }
  bool at(std::string_view token) const { return rest().starts_with(token); }
  bool consume(std::string_view token) {
    if (!at(token)) return false;
    pos_ += token.size();
    return true;
  }
  void skip_whitespace() {
    while (const std::size_t n = whitespace_length(rest())) pos_ += n;
  }

  const Context& context_;
  std::string_view expr_;
  std::size_t pos_ = 0;
  std::optional<std::string_view> celsius_token_;
};

struct Number {
  double value;
  std::size_t length;  // characters used
};

// Locale-independent; a leading '+' is accepted (std::from_chars does not take it), "+-1" is not.
std::optional<Number> read_number(std::string_view s, const Context& context) {
  std::size_t start = 0;
  if (s.starts_with("+")) {
    if (s.size() < 2 || !(is_digit(s[1]) || s[1] == '.')) return std::nullopt;
    start = 1;
  }
  double value = 0;
  const char* first = s.data() + start;
  const auto [end, ec] = std::from_chars(first, s.data() + s.size(), value);
  if (ec == std::errc::invalid_argument) return std::nullopt;
  if (ec == std::errc::result_out_of_range) context.fail("number out of range in " + context.quoted());
  if (!std::isfinite(value)) context.fail(context.quoted() + " is not a finite number");
  return Number{value, static_cast<std::size_t>(end - s.data())};
}

bool is_unit_expression(std::string_view s, const Context& context) {
  try {
    UnitExpressionParser(context, s).parse();
    return true;
  } catch (const UnitError&) {
    return false;
  }
}

}  // namespace

std::string Dimension::si_unit() const {
  const DimensionName* name = find_name(*this);
  return name && !name->si_unit.empty() ? std::string(name->si_unit) : base_unit_expression(*this);
}

std::string describe(const Dimension& d) {
  const DimensionName* name = find_name(d);
  if (!name) return "a quantity in " + d.si_unit();
  return std::string(name->description) + " (" + d.si_unit() + ")";
}

std::optional<std::string> quantity_unit(std::string_view text) {
  const std::string_view s = trim(text);
  const Context context(text, dim::dimensionless);
  try {
    const std::optional<Number> number = read_number(s, context);
    if (!number) return std::nullopt;
    return std::string(trim(s.substr(number->length)));
  } catch (const UnitError&) {
    return std::nullopt;  // out of range or not finite: parse_quantity reports it
  }
}

double parse_quantity(std::string_view text, const Dimension& expected) {
  const Context context(text, expected);
  const std::string_view s = trim(text);
  if (s.empty()) context.fail("empty quantity " + context.quoted());

  const std::optional<Number> number = read_number(s, context);
  if (!number) {
    const std::string form = "write '<number> <unit>' or a bare number in SI units";
    if (is_unit_expression(s, context)) context.fail("missing number in " + context.quoted(), form);
    context.fail(context.quoted() + " does not start with a number", form);
  }

  const std::string_view unit_text = trim(s.substr(number->length));
  if (unit_text.empty()) return number->value;  // bare numbers are SI

  ParsedUnit unit = UnitExpressionParser(context, unit_text).parse();
  // Angle rule (see units.h): between frequencies and angular speeds (or accelerations), an angle exponent
  // missing on one side counts full turns of 2*pi rad. Elsewhere ("1 N*m" for N*m/rad, "90 deg" for a plain
  // number) a missing angle is more likely a mistake than a count of turns, so it is an error.
  const Dimension bare = without_angle(expected);
  const bool time_rate = bare.kg == 0 && bare.m == 0 && bare.K == 0 && bare.s < 0;
  if (without_angle(unit.dim) != bare || (unit.dim.rad != expected.rad && !time_rate)) {
    throw UnitError(context.quoted() + " is " + describe(unit.dim) + ", expected " + describe(expected));
  }
  unit.scale.turns += expected.rad - unit.dim.rad;

  double value = to_si(number->value, unit.scale);
  if (unit.celsius) value += celsius_offset;
  if (!std::isfinite(value)) context.fail(context.quoted() + " is out of range");
  return value;
}

}  // namespace turbodyn
