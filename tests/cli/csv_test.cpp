// The strict CSV reader and the 17-digit writer behind the CLI (core/io/csv.h).
#include "core/io/csv.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <string>

namespace glintlab::io {
namespace {

std::string error_of(const std::string& text) {
  try {
    parse_csv(text, "t.csv");
  } catch (const CsvError& e) {
    return e.what();
  }
  return "";
}

TEST(CsvReader, ReadsNamedColumns) {
  const CsvTable t = parse_csv(
      "\xEF\xBB\xBF"
      "a, b ,c\r\n1,-2.5e3, x \n+0.25,1e-300,y\n\n",
      "t.csv");
  EXPECT_EQ(t.header(), (std::vector<std::string>{"a", "b", "c"}));
  ASSERT_EQ(t.num_rows(), 2u);
  EXPECT_EQ(t.number(0, t.column("b")), -2500.0);
  EXPECT_EQ(t.number(1, 0), 0.25);
  EXPECT_EQ(t.number(1, 1), 1e-300);
  EXPECT_EQ(t.text(0, 2), "x");
  EXPECT_FALSE(t.find_column("d").has_value());
}

TEST(CsvReader, ErrorsNameFileRowAndColumn) {
  EXPECT_EQ(error_of(""), "'t.csv': the file is empty (expected a header row of column names)");
  EXPECT_EQ(error_of("a,b\n1,2\n3\n"),
            "'t.csv' data row 2: has 1 field, expected 2 (one per header column)");
  EXPECT_EQ(error_of("a,b\n1,\n"),
            "'t.csv' data row 1, column b: empty field (valid: a value in every column)");
  EXPECT_EQ(error_of("a,a\n"), "'t.csv' header row: column 'a' appears more than once");
  EXPECT_EQ(error_of("a,b\n1,\"2\"\n"),
            "'t.csv' data row 1: contains a quote character (quoted fields are not supported)");
  const CsvTable t = parse_csv("a,b\n1,2\n3,4x\n", "t.csv");
  try {
    t.number(1, 1);
    FAIL() << "no error";
  } catch (const CsvError& e) {
    EXPECT_STREQ(
        e.what(),
        "'t.csv' data row 2, column b: '4x' is not a number (valid: a finite decimal number)");
  }
  try {
    (void)t.column("z");
    FAIL() << "no error";
  } catch (const CsvError& e) {
    EXPECT_STREQ(e.what(), "'t.csv': missing column 'z' in the header");
  }
}

TEST(CsvReader, NumbersMustBeFiniteAndWhole) {
  for (const char* bad :
       {"nan", "inf", "-inf", "1e999", "0x10", "1.5.2", "1 2", "++1", "+-1", "+", "-", "."}) {
    EXPECT_FALSE(parse_finite_double(bad).has_value()) << bad;
  }
  EXPECT_EQ(number_problem("nan"), "is not finite");
  EXPECT_EQ(number_problem("-inf"), "is not finite");
  EXPECT_EQ(number_problem("1e999"), "is outside the range of a double");
  EXPECT_EQ(number_problem("1e-999"), "is outside the range of a double");
  EXPECT_EQ(number_problem("1.5.2"), "is not a number");
  EXPECT_EQ(parse_finite_double("1e-310").value(), 1e-310);  // subnormal: fine
  EXPECT_EQ(parse_finite_double("-0").value(), 0.0);
  EXPECT_EQ(parse_finite_double(".5").value(), 0.5);
  EXPECT_EQ(parse_finite_double("5.").value(), 5.0);
  EXPECT_EQ(parse_finite_double("1E2").value(), 100.0);
}

TEST(CsvWriter, SeventeenDigitsRoundTrip) {
  std::ostringstream out;
  {
    CsvWriter w(out, {"x", "name", "k"});
    w.cell(0.1).cell("ggx").cell_int(1);
    w.end_row();
    w.cell(std::numeric_limits<double>::quiet_NaN()).cell("b").cell_int(0);
    w.end_row();
    w.cell(1.0 / 3.0);
    EXPECT_THROW(w.end_row(), std::logic_error);
  }
  EXPECT_EQ(out.str().substr(0, 45), "x,name,k\n0.10000000000000001,ggx,1\nnan,b,0\n0.");
  EXPECT_EQ(format_double(1.0 / 3.0), "0.33333333333333331");
  EXPECT_EQ(std::stod(format_double(1.0 / 3.0)), 1.0 / 3.0);
  EXPECT_EQ(format_double(1e-310), "9.9999999999999694e-311");
}

}  // namespace
}  // namespace glintlab::io
