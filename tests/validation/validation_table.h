// The validation table's data: each validation test states its figures here (what was measured,
// against which reference, with which tolerance and where that tolerance comes from) and the
// same call asserts them, so that a figure in docs/validation.md is always one a test asserted.
//
// A figure is written as one JSON line to CASCADE_BINARY_DIR/validation/<Suite.Test>.jsonl;
// scripts/render_validation.py renders docs/validation.md from every such file (scripts/test.sh
// runs it after the tests). A test's file is removed when the test starts, so a test that stops
// before its figures leaves no stale row. Tests whose name ends in KnownFailure are marked so in
// the table.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace cascade::testing {

enum class Bound {
  within,    // |measured − reference| ≤ tolerance
  at_most,   // measured ≤ reference (the reference is a limit; tolerance unused)
  at_least,  // measured ≥ reference
};

struct Figure {
  std::string case_name;         // e.g. "2D dam break (cases/dam_break_2d.yaml)"
  std::string reference;         // the reference with its citation
  std::string metric;            // what is compared, with its unit
  double measured = NAN;
  double reference_value = NAN;
  double tolerance = 0;          // absolute, or a fraction of |reference| when relative
  bool relative = false;
  Bound bound = Bound::within;
  std::string tolerance_source;  // where the tolerance comes from (scatter, truncation, convergence)
};

inline bool passes(const Figure& f) {
  if (!std::isfinite(f.measured)) return false;
  switch (f.bound) {
    case Bound::at_most:
      return f.measured <= f.reference_value;
    case Bound::at_least:
      return f.measured >= f.reference_value;
    case Bound::within:
      break;
  }
  const double allowed = f.relative ? f.tolerance * std::abs(f.reference_value) : f.tolerance;
  return std::abs(f.measured - f.reference_value) <= allowed;
}

// The larger of the two, NaN once either is: the worst case over a loop, which a NaN value must not
// pass (std::max(worst, NaN) keeps `worst`).
inline double worst_of(double worst, double value) { return std::isnan(value) || value > worst ? value : worst; }

namespace validation_detail {

inline std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (const unsigned char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c < 0x20) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\u%04x", c);
      out += escaped;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out + "\"";
}

inline std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";  // JSON has no NaN or infinity
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

inline const char* bound_name(Bound b) {
  switch (b) {
    case Bound::at_most:
      return "at_most";
    case Bound::at_least:
      return "at_least";
    case Bound::within:
      break;
  }
  return "within";
}

inline std::filesystem::path table_dir() { return std::filesystem::path(CASCADE_BINARY_DIR) / "validation"; }

// A test program that ctest runs in several configurations (tests/parallel: under mpirun at 1 to
// 4 processes) names each in CASCADE_VALIDATION_VARIANT, which the test's name in the table takes
// as a suffix, so that each configuration keeps its own figures.
inline std::string variant_suffix() {
  const char* variant = std::getenv("CASCADE_VALIDATION_VARIANT");
  return variant && *variant ? std::string(".") + variant : std::string();
}

inline std::string test_name(const ::testing::TestInfo& info) {
  return std::string(info.test_suite_name()) + "." + info.name() + variant_suffix();
}

inline std::string current_test_name() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  return info ? test_name(*info) : "unknown";
}

inline std::filesystem::path figures_file(const std::string& test) { return table_dir() / (test + ".jsonl"); }

// Removes a test's figures of an earlier run when the test starts.
class StaleFigureRemover : public ::testing::EmptyTestEventListener {
  void OnTestStart(const ::testing::TestInfo& info) override {
    std::error_code ignored;
    std::filesystem::remove(figures_file(test_name(info)), ignored);
  }
};

inline const bool stale_figure_remover_installed = [] {
  ::testing::UnitTest::GetInstance()->listeners().Append(new StaleFigureRemover);
  return true;
}();

inline std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

inline void append(const Figure& f, bool pass) {
  const std::string test = current_test_name();
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string name = info ? info->name() : "";
  const bool known_failure = name.size() >= 12 && name.compare(name.size() - 12, 12, "KnownFailure") == 0;
  std::ostringstream line;
  line << "{\"test\": " << json_string(test) << ", \"case\": " << json_string(f.case_name)
       << ", \"reference\": " << json_string(f.reference) << ", \"metric\": " << json_string(f.metric)
       << ", \"measured\": " << json_number(f.measured) << ", \"reference_value\": " << json_number(f.reference_value)
       << ", \"tolerance\": " << json_number(f.tolerance) << ", \"relative\": " << (f.relative ? "true" : "false")
       << ", \"bound\": \"" << bound_name(f.bound) << "\", \"tolerance_source\": " << json_string(f.tolerance_source)
       << ", \"pass\": " << (pass ? "true" : "false") << ", \"known_failure\": " << (known_failure ? "true" : "false")
       << ", \"measured_at\": \"" << utc_now() << "\"}\n";
  std::filesystem::create_directories(table_dir());
  std::ofstream(figures_file(test), std::ios::app) << line.str();
}

inline std::string describe(const Figure& f) {
  std::ostringstream text;
  text << f.case_name << ": " << f.metric << " = " << f.measured;
  switch (f.bound) {
    case Bound::at_most:
      text << ", limit ≤ " << f.reference_value;
      break;
    case Bound::at_least:
      text << ", limit ≥ " << f.reference_value;
      break;
    case Bound::within:
      text << " against " << f.reference_value << " ± " << (f.relative ? 100 * f.tolerance : f.tolerance)
           << (f.relative ? "%" : "");
      break;
  }
  return text.str() + " (" + f.reference + ")";
}

}  // namespace validation_detail

// Records the figure in the validation table and asserts it (a non-fatal EXPECT at the caller's
// line). Returns whether it passed.
#define CASCADE_VALIDATE(...)                                                                              \
  [&](const ::cascade::testing::Figure& f_) {                                                              \
    const bool pass_ = ::cascade::testing::passes(f_);                                                     \
    ::cascade::testing::validation_detail::append(f_, pass_);                                              \
    std::printf("validation: %s\n", ::cascade::testing::validation_detail::describe(f_).c_str());         \
    EXPECT_TRUE(pass_) << ::cascade::testing::validation_detail::describe(f_);                             \
    return pass_;                                                                                          \
  }(__VA_ARGS__)

}  // namespace cascade::testing
