// Overrides: the --set grammar, its errors, and the model file written with overrides applied (comments kept,
// loading to the same machine as load_model with the overrides).
#include "model/io/overrides.h"

#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "model/io/model_file.h"
#include "tests/support/test_support.h"

namespace turbodyn {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::Not;
using testing::example;

// The message of the ModelError `f` throws ("" if none).
template <class F>
std::string override_error_of(F&& f) {
  try {
    f();
  } catch (const ModelError& e) {
    return e.what();
  }
  return "";
}

// The values an override can reach in the examples used here, in a fixed order (names compared apart).
std::vector<double> values_of(const MachineSpec& m) {
  std::vector<double> v;
  for (const ShaftSection& s : m.shaft) v.insert(v.end(), {s.length, s.outer_diameter, s.inner_diameter});
  for (const DiskSpec& d : m.disks) v.insert(v.end(), {d.z, d.mass, d.unbalance, d.unbalance_phase});
  for (const BearingSpec& b : m.bearings) {
    v.insert(v.end(), {b.z, b.damper.clearance, b.damper.length, static_cast<double>(b.damper.n_circ),
                       static_cast<double>(b.damper.enabled)});
    for (const std::vector<double>& k : b.linear.k) v.insert(v.end(), k.begin(), k.end());
    for (const std::vector<double>& c : b.linear.c) v.insert(v.end(), c.begin(), c.end());
  }
  v.insert(v.end(), {m.damping.alpha, m.damping.beta, m.speed.start, m.speed.end, m.speed.duration, m.solver.rtol,
                     m.output.sample_rate});
  v.insert(v.end(), m.modal.orders.begin(), m.modal.orders.end());
  return v;
}

std::vector<std::string> names_of(const MachineSpec& m) {
  std::vector<std::string> n = {m.name};
  for (const ShaftSection& s : m.shaft) n.push_back(s.material);
  for (const DiskSpec& d : m.disks) n.push_back(d.name);
  for (const BearingSpec& b : m.bearings) n.push_back(b.name);
  return n;
}

TEST(Overrides, GrammarDottedKeysAndIndices) {
  const Override o = parse_override("  shaft[2].outer_diameter =  12 mm ");
  EXPECT_EQ(o.path, "shaft[2].outer_diameter");
  EXPECT_EQ(o.value, "12 mm");
  const std::vector<OverrideStep> s = override_steps(o);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].key, "shaft");
  ASSERT_TRUE(s[0].index.has_value());
  EXPECT_EQ(*s[0].index, 2u);
  EXPECT_EQ(s[1].key, "outer_diameter");
  EXPECT_FALSE(s[1].index.has_value());
  const std::vector<OverrideStep> d = override_steps({"bearings.compressor.damper.clearance", "60 um"});
  ASSERT_EQ(d.size(), 4u);
  EXPECT_EQ(d[3].key, "clearance");
  EXPECT_THAT(override_error_of([] { parse_override("no-equals-sign"); }), HasSubstr("expected PATH=VALUE"));
  EXPECT_THAT(override_error_of([] { parse_override("=1"); }), HasSubstr("path before '=' is empty"));
  EXPECT_THAT(override_error_of([] { parse_override("speed.end="); }), HasSubstr("value after '=' is empty"));
}

TEST(Overrides, BadIndicesNameTheOverrideAndTheCause) {
  auto steps_error = [](const std::string& path) { return override_error_of([&] { override_steps({path, "1"}); }); };
  EXPECT_THAT(steps_error("shaft[x].length"), AllOf(HasSubstr("--set shaft[x].length=1"), HasSubstr("not a whole number")));
  EXPECT_THAT(steps_error("shaft[-1].length"), AllOf(HasSubstr("--set shaft[-1].length=1"), HasSubstr("negative")));
  EXPECT_THAT(steps_error("shaft[].length"), HasSubstr("no index"));
  EXPECT_THAT(steps_error("shaft[0.length"), HasSubstr("malformed index"));
  EXPECT_THAT(steps_error("shaft[99999999999999999999999999].length"), HasSubstr("out of range"));
  EXPECT_THAT(steps_error("shaft..length"), HasSubstr("empty key"));
  for (const char* p : {"shaft[x].length", "shaft[-1].length", "shaft[99999999999999999999999999].length"})
    EXPECT_THAT(steps_error(p), Not(HasSubstr("stol")));

  // Out of range and not an array: known only against the model file, from the loader and the writer alike.
  const std::string f = example("reference_linear.toml");
  for (auto&& run : {std::function<void()>([&] { load_model(f, {{"shaft[1].length", "1"}}); }),
                     std::function<void()>([&] { patched_model(f, {{"shaft[1].length", "1"}}, ""); })})
    EXPECT_THAT(override_error_of(run), AllOf(HasSubstr("--set shaft[1].length=1"),
                                              HasSubstr("index 1 is out of range"), HasSubstr("has 1 entries")));
  EXPECT_THAT(override_error_of([&] { patched_model(f, {{"speed[0].end", "1"}}, ""); }),
              AllOf(HasSubstr("--set speed[0].end=1"), HasSubstr("'speed' is not an array")));
  EXPECT_THAT(override_error_of([&] { load_model(f, {{"shaft[x].length", "1"}}); }), HasSubstr("not a whole number"));
}

TEST(Overrides, WriterKeepsCommentsAndLayout) {
  const std::string base = example("reference_damper.toml");
  const std::vector<Override> o = {{"bearings.compressor.damper.clearance", "60 um"},
                                   {"shaft[0].outer_diameter", "11 mm"},
                                   {"bearings.turbine.damper.n_circ", "40"},
                                   {"speed.end", "90000 rpm"}};
  const std::string text = patched_model(base, o, "written by a test");
  EXPECT_EQ(text.rfind("# written by a test\n\n# The reference turbocharger rotor", 0), 0u);
  EXPECT_THAT(text, HasSubstr("clearance = \"60 um\"                # radial clearance"));
  EXPECT_THAT(text, HasSubstr("outer_diameter = \"11 mm\"\n"));
  EXPECT_THAT(text, HasSubstr("[[shaft]]                          # solid Ø 10 mm over the full length"));
  EXPECT_THAT(text, HasSubstr("oil_temperature = \"90 degC\"\nn_circ = 40\n\n[speed]"));
  // Apart from the header and the four edits, the file is unchanged line for line.
  std::ifstream in(base);
  const std::string original((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t body = text.find("# The reference");
  std::size_t changed = 0;
  std::istringstream a(original), b(text.substr(body));
  for (std::string la, lb; std::getline(a, la) && std::getline(b, lb);) {
    if (la == lb) continue;
    ++changed;
    if (lb == "n_circ = 40") std::getline(b, lb);  // the added line: the rest follows one line later
  }
  EXPECT_EQ(changed, 4u);
}

TEST(Overrides, PatchedFileLoadsToTheSameMachine) {
  const std::string base = example("reference_damper.toml");
  const std::vector<std::vector<Override>> cases = {
      {{"bearings.compressor.damper.clearance", "60 um"}, {"disks.turbine.unbalance", "1 g*mm"}},
      {{"shaft[0].outer_diameter", "11 mm"}, {"speed.end", "1000 rad/s"}, {"speed.end", "90000 rpm"}},
      {{"bearings.turbine.damper.n_circ", "40"}, {"name", "patched"}},
      {{"damping.beta", "1e-6"}, {"modal.orders", "[1.0, 0.5]"}},  // new tables: written out whole
      {{"bearings.compressor.k", "[2e7]"}, {"solver.rtol", "1e-7"}},
  };
  const auto dir = std::filesystem::temp_directory_path() / "turbodyn_overrides_test";
  std::filesystem::create_directories(dir);
  for (const std::vector<Override>& o : cases) {
    SCOPED_TRACE(o.front().path);
    write_patched_model(base, o, "round trip", dir / "patched.toml");
    const MachineSpec patched = load_model(dir / "patched.toml"), direct = load_model(base, o);
    EXPECT_EQ(values_of(patched), values_of(direct));
    EXPECT_EQ(names_of(patched), names_of(direct));
  }
  EXPECT_THAT(override_error_of([&] { write_patched_model(base, {}, "", dir / "no_such_dir" / "x.toml"); }),
              HasSubstr("cannot write"));
}

}  // namespace
}  // namespace turbodyn
