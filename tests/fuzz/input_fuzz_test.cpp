// A deterministic mutation fuzzer of everything a user types: model files, study, optimisation and
// identification files, and --set overrides (issue 20). Each input is mutated from an example (a value replaced by
// an extreme, a wrong unit or a wrong type; a line deleted, doubled or renamed; the file cut short or sprinkled with
// bytes) and read the way the commands read it: a model is loaded, its rotor built and its run-up model made (what
// `check` and the start of `run` do); a study file is loaded with its base model.
//
// The oracle: the input is accepted, or refused with a ModelError whose message names where the fault is (the
// mutated file, or the --set override). A crash (signal) or an endless loop fails the test through CTest; any other
// exception, or a ModelError that names no place, is a "raw message" and fails it here.
//
// TURBODYN_FUZZ_INPUTS=N sets the number of inputs (default 5,000: about 10 s); the long mode of
// docs/validation.md runs 100,000.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "identification/identify_study.h"
#include "model/engine/runup.h"
#include "model/io/model_file.h"
#include "model/io/toml_reader.h"
#include "model/io/overrides.h"
#include "model/rotor/rotor.h"
#include "optim/optimization.h"
#include "studies/study.h"
#include "tests/support/temp_dir.h"

namespace turbodyn {
namespace {

namespace fs = std::filesystem;

enum class FileKind { Model, Study, Optimization, Identification };

FileKind kind_of(const std::string& text) {
  if (text.find("[study]") != std::string::npos) return FileKind::Study;
  if (text.find("[optimize]") != std::string::npos) return FileKind::Optimization;
  if (text.find("[identify]") != std::string::npos) return FileKind::Identification;
  return FileKind::Model;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const std::string& l : lines) out += l + "\n";
  return out;
}

// The lines of `mutant` that `original` does not have (the mutation, for a failure message).
std::string changed_lines(const std::string& original, const std::string& mutant) {
  const std::vector<std::string> a = lines_of(original), b = lines_of(mutant);
  std::string out;
  for (std::size_t i = 0; i < b.size(); ++i)
    if (i >= a.size() || a[i] != b[i]) {
      out += "  line " + std::to_string(i + 1) + ": " + b[i] + "\n";
      if (out.size() > 400) break;
    }
  return out.empty() ? "  (cut short after " + std::to_string(mutant.size()) + " bytes)\n" : out;
}

// Values a hostile or careless user writes in place of a good one.
const std::vector<std::string> kBadValues = {
    "0", "-1", "1e308", "-1e308", "1e-308", "nan", "inf", "-inf", "2147483648", "4294967304",
    "9223372036854775807", "-9223372036854775808", "3.5", "\"\"", "\"abc\"", "\"1e999 m\"", "\"15 kg\"",
    "\"-15 um\"", "\"nan um\"", "\"1e300 mm\"", "\"1e-300 mm\"", "\"15 uum\"", "\"90 degC\"", "\"-300 degC\"",
    "\"150000 rpm\"", "\"2147483648\"", "true", "[]", "[1, 2]", "{}", "\"x\"", "1e-12", "1e12", "-0.0",
};

struct Mutator {
  std::mt19937_64 rng;
  explicit Mutator(std::uint64_t seed) : rng(seed) {}
  std::size_t pick(std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng); }

  // The index of a random "key = value" line, or lines.size() if there is none.
  std::size_t assignment(const std::vector<std::string>& lines) {
    std::vector<std::size_t> idx;
    for (std::size_t i = 0; i < lines.size(); ++i)
      if (lines[i].find('=') != std::string::npos && lines[i].rfind('#', 0) != 0) idx.push_back(i);
    return idx.empty() ? lines.size() : idx[pick(idx.size())];
  }

  std::string mutate(const std::string& text) {
    std::vector<std::string> lines = lines_of(text);
    const std::size_t i = assignment(lines);
    const int op = static_cast<int>(pick(10));
    if (i == lines.size() || op == 9) {  // cut the file short
      return text.substr(0, pick(text.size() + 1));
    }
    std::string& l = lines[i];
    const std::size_t eq = l.find('=');
    switch (op) {
      case 0: case 1: case 2: case 3:  // an extreme or wrongly typed value
        l = l.substr(0, eq + 1) + " " + kBadValues[pick(kBadValues.size())];
        break;
      case 4:  // one element of an array, or a number inside a string, replaced
        for (std::size_t k = eq + 1; k < l.size(); ++k)
          if (std::isdigit(static_cast<unsigned char>(l[k]))) {
            std::size_t e = k;
            while (e < l.size() && (std::isalnum(static_cast<unsigned char>(l[e])) || l[e] == '.' || l[e] == '-' || l[e] == '+')) ++e;
            const std::string v = kBadValues[pick(kBadValues.size())];
            l = l.substr(0, k) + (v.front() == '"' ? v.substr(1, v.size() - 2) : v) + l.substr(e);
            break;
          }
        break;
      case 5: lines.erase(lines.begin() + static_cast<long>(i)); break;        // a key left out
      case 6: lines.insert(lines.begin() + static_cast<long>(i), l); break;    // a key written twice
      case 7: l.insert(eq > 1 ? pick(eq - 1) + 1 : 0, "x"); break;             // a misspelt key
      case 8: l.insert(pick(l.size() + 1), std::string(1, "\"[]{}=#\\,.\x01\xff"[pick(12)])); break;  // a stray byte
    }
    return joined(lines);
  }
};

// What reading one input leads to.
struct Outcome {
  bool raw = false;       // refused without a usable message
  std::string message;
};

Outcome read_as_user(const std::function<void()>& load, const std::string& place) {
  Outcome o;
  try {
    load();
  } catch (const ModelError& e) {
    o.message = e.what();
    o.raw = o.message.find(place) == std::string::npos;
  } catch (const std::exception& e) {
    o.message = std::string("[") + typeid(e).name() + "] " + e.what();
    o.raw = true;
  }
  return o;
}

void load_model_file(const fs::path& file, const std::vector<Override>& overrides) {
  const MachineSpec spec = load_model(file, overrides);
  const Rotor rotor = build_rotor(spec);
  (void)make_runup_model(spec);
}

void load_any(FileKind kind, const fs::path& file) {
  switch (kind) {
    case FileKind::Model: load_model_file(file, {}); break;
    case FileKind::Study: (void)studies::load_study(file); break;
    case FileKind::Optimization: (void)optim::load_optimization(file); break;
    case FileKind::Identification: (void)identification::load_identify_study(file); break;
  }
}

std::size_t fuzz_inputs() {
  const char* n = std::getenv("TURBODYN_FUZZ_INPUTS");
  return n ? static_cast<std::size_t>(std::strtoul(n, nullptr, 10)) : 5000;
}

// The examples, copied to a scratch directory so that the mutants sit beside the files they refer to, and read once.
struct Corpus {
  fs::path dir;
  std::vector<fs::path> files;
  std::vector<std::string> texts;  // of each file
  explicit Corpus(const std::string& name) {
    dir = testing::fresh_temp_dir("input_fuzz_" + name);  // one per test: CTest runs them in parallel
    fs::copy(fs::path(TURBODYN_SOURCE_DIR) / "examples", dir, fs::copy_options::recursive);
    for (const fs::directory_entry& e : fs::directory_iterator(dir))
      if (e.path().extension() == ".toml") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    for (const fs::path& f : files) texts.push_back(input::read_text_file(f, "example"));
  }
};

TEST(InputFuzz, MutatedFilesAreReadOrRefusedWithALocatedMessage) {
  const Corpus corpus("files");
  ASSERT_GE(corpus.files.size(), 10u);
  Mutator m(20261202);
  const std::size_t n = fuzz_inputs();
  std::size_t refused = 0, raw = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const fs::path& base = corpus.files[k % corpus.files.size()];
    const std::string& text = corpus.texts[k % corpus.files.size()];
    const std::string mutant = m.mutate(text);
    const fs::path file = corpus.dir / ("mutant_" + base.filename().string());
    std::ofstream(file, std::ios::binary) << mutant;
    const Outcome o = read_as_user([&] { load_any(kind_of(text), file); }, file.filename().string());
    refused += !o.message.empty();
    if (o.raw && ++raw <= 20)
      ADD_FAILURE() << "input " << k << " (from " << base.filename().string() << "): raw message: " << o.message
                    << "\n" << changed_lines(text, mutant);
    fs::remove(file);
  }
  std::cout << "[ fuzz ] " << n << " mutated files: " << refused << " refused, " << raw << " raw messages\n";
  EXPECT_EQ(raw, 0u);
  EXPECT_GT(refused, n / 4);  // the mutations do break most files: the oracle is exercised
}

TEST(InputFuzz, MutatedOverridesAreAppliedOrRefusedNamingTheOverride) {
  const Corpus corpus("overrides");
  Mutator m(42);
  const std::size_t n = fuzz_inputs() / 2;
  std::size_t refused = 0, raw = 0;
  std::vector<std::pair<fs::path, std::vector<std::string>>> models;
  for (std::size_t i = 0; i < corpus.files.size(); ++i)
    if (kind_of(corpus.texts[i]) == FileKind::Model)
      models.push_back({corpus.files[i], numeric_model_keys(corpus.files[i], {})});
  ASSERT_FALSE(models.empty());
  for (std::size_t k = 0; k < n; ++k) {
    const auto& [file, keys] = models[k % models.size()];
    if (keys.empty()) continue;
    std::string path = keys[m.pick(keys.size())];
    if (m.pick(8) == 0) path.insert(m.pick(path.size() + 1), "x");   // a misspelt path
    if (m.pick(8) == 0) path += "[" + kBadValues[m.pick(9)] + "]";   // an index that is no index
    std::string value = kBadValues[m.pick(kBadValues.size())];
    if (value.front() == '"') value = value.substr(1, value.size() - 2);
    const std::string assignment = path + "=" + value;
    const Outcome o = read_as_user([&] { load_model_file(file, {parse_override(assignment)}); }, "--set");
    // An override that is read fine but makes the model file itself invalid may name the file instead.
    const bool located = !o.raw || o.message.find(file.filename().string()) != std::string::npos;
    refused += !o.message.empty();
    if (!located && ++raw <= 20)
      ADD_FAILURE() << "--set " << assignment << " on " << file.filename().string() << ": raw message: " << o.message;
  }
  std::cout << "[ fuzz ] " << n << " mutated overrides: " << refused << " refused, " << raw << " raw messages\n";
  EXPECT_EQ(raw, 0u);
}

}  // namespace
}  // namespace turbodyn
