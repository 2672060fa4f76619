// The simulate CSV's numbers (io::trajectory_csv_rows, which formats them through a char
// pointer with a compiled format, for speed) against fmt's ordinary formatting of each number,
// and against the law that the text reads back to the same double.
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "heavytop/io/formats.hpp"

namespace heavytop {
namespace {

// The reference: every number as fmt::format("{}") prints it, -0 as 0, commas, a newline a row.
std::string reference_rows(const Trajectory& tr, std::size_t begin, std::size_t end) {
  std::string out;
  for (std::size_t i = begin; i < end; ++i) {
    for (std::size_t c = 0; c < kTrajectoryColumns.size() + tr.extra.size(); ++c) {
      if (c) out += ',';
      out += fmt::format("{}", tr.column(c)[i] + 0.0);
    }
    out += '\n';
  }
  return out;
}

// `values` laid out row by row over the five columns and `extra` more.
Trajectory trajectory_of(const std::vector<double>& values, std::size_t extra) {
  Trajectory tr;
  for (std::size_t e = 0; e < extra; ++e) tr.extra.emplace_back("extra" + std::to_string(e), std::vector<double>{});
  const std::size_t columns = kTrajectoryColumns.size() + extra;
  for (std::size_t i = 0; i + columns <= values.size(); i += columns)
    for (std::size_t c = 0; c < columns; ++c) tr.column(c).push_back(values[i + c]);
  return tr;
}

// The longest texts there are (24 characters), both notations' edges, and the odd values.
const std::vector<double> kEdgeCases = {
    0.0, -0.0, 1.0, -1.0, 0.1, 0.1 + 0.2, 1.0 / 3.0, -2.0 / 3.0,
    -2.2250738585072014e-308, -1.2345678901234567e-100, -1.7976931348623157e308,
    std::numeric_limits<double>::denorm_min(), -std::numeric_limits<double>::denorm_min(),
    1e-5, 1e-4, 0.00012345678901234567, -0.00012345678901234567, 1e15, 1e16, 1e17,
    9999999999999998.0, 1234567890123456.7, -123456789012345.67, 100000.0, 1e21, 1e22,
    std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
    std::numeric_limits<double>::quiet_NaN(), 5e-324, 4.35e-05, 0.05, 200.0, 1e-06};

TEST(CsvFormat, EdgeCasesPrintAsFmtPrintsThem) {
  std::vector<double> values;
  for (int r = 0; r < 11; ++r) values.insert(values.end(), kEdgeCases.begin(), kEdgeCases.end());
  for (std::size_t extra : {0u, 1u, 6u}) {
    const Trajectory tr = trajectory_of(values, extra);
    ASSERT_GT(tr.size(), 10u);
    EXPECT_EQ(io::trajectory_csv_rows(tr, 0, tr.size()), reference_rows(tr, 0, tr.size())) << extra << " extra";
    EXPECT_EQ(io::trajectory_csv_rows(tr, 3, 7), reference_rows(tr, 3, 7));
    EXPECT_EQ(io::trajectory_csv_rows(tr, 4, 4), "");
  }
}

TEST(CsvFormat, RandomDoublesPrintAsFmtPrintsThemAndReadBackExactly) {
  std::mt19937_64 bits(17);
  std::vector<double> values;
  while (values.size() < 110'000) {  // every finite bit pattern equally likely: all exponents
    const double x = std::bit_cast<double>(bits());
    if (std::isfinite(x)) values.push_back(x);
  }
  const Trajectory tr = trajectory_of(values, 6);
  const std::string csv = io::trajectory_csv_rows(tr, 0, tr.size());
  ASSERT_EQ(csv, reference_rows(tr, 0, tr.size()));

  std::istringstream lines(csv);
  std::string line, field;
  std::size_t i = 0, longest = 0;
  while (std::getline(lines, line)) {
    std::istringstream fields(line);
    for (std::size_t c = 0; std::getline(fields, field, ','); ++c) {
      longest = std::max(longest, field.size());
      EXPECT_EQ(std::strtod(field.c_str(), nullptr), tr.column(c)[i]) << field;
    }
    ++i;
  }
  EXPECT_EQ(i, tr.size());
  EXPECT_LE(longest, 24u);  // the room the formatter counts on (32 a number)
}

}  // namespace
}  // namespace heavytop
