#include "studies/table.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

namespace turbodyn::studies {
namespace {

TEST(Table, NumbersKeepTwelveDigitsAndLeaveUndefinedCellsEmpty) {
  EXPECT_EQ(table_number(0.1 + 0.2), "0.3");
  EXPECT_EQ(table_number(1.0 / 3.0), "0.333333333333");
  EXPECT_EQ(table_number(2.5e-5), "2.5e-05");
  EXPECT_EQ(table_number(NAN), "");
  EXPECT_EQ(table_number(INFINITY), "");
}

TEST(Table, OverrideValuesReadBackExactly) {
  EXPECT_EQ(value_text(51.0, "um"), "51 um");
  EXPECT_EQ(value_text(2.5e-5), "2.5e-05");
  const double v = 0.1 + 0.2;
  EXPECT_EQ(std::stod(value_text(v)), v);
}

TEST(Table, CsvFieldsAreQuotedOnlyWhenNeeded) {
  EXPECT_EQ(csv_field("max_x [m]"), "max_x [m]");
  EXPECT_EQ(csv_field("a,b"), "\"a,b\"");
  EXPECT_EQ(csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
}

TEST(Table, JsonNumbersRoundTripWithNullForUndefined) {
  const nlohmann::json j = json_numbers({1.5, NAN, -2.0});
  EXPECT_EQ(j.dump(), "[1.5,null,-2.0]");
  const std::vector<double> back = from_json_numbers(j);
  ASSERT_EQ(back.size(), 3u);
  EXPECT_EQ(back[0], 1.5);
  EXPECT_TRUE(std::isnan(back[1]));
  EXPECT_EQ(json_number(INFINITY), nlohmann::json(nullptr));
}

TEST(Table, CsvWriterSeparatesFieldsAndRows) {
  const auto f = std::filesystem::temp_directory_path() / "turbodyn_table_test.csv";
  {
    CsvWriter csv(f);
    csv.texts({"run", "a,b"}).text("value").end_row();
    csv.integer(3).numbers({0.5, NAN}).end_row();
  }
  std::ifstream in(f);
  std::ostringstream s;
  s << in.rdbuf();
  EXPECT_EQ(s.str(), "run,\"a,b\",value\n3,0.5,\n");
}

}  // namespace
}  // namespace turbodyn::studies
