// CSV logs: round trip, and every malformed input gives an error naming file, line and column.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include <limits>

#include "ftsense/io/csv_log.hpp"

namespace ftsense::io {
namespace {

std::string temp_file(const std::string& name, const std::string& content) {
  const auto dir = std::filesystem::temp_directory_path() / "ftsense_csv_tests";
  std::filesystem::create_directories(dir);
  const auto path = (dir / name).string();
  std::ofstream(path) << content;
  return path;
}

TEST(CsvLog, WriteThenReadRoundTripsExactly) {
  const std::string path = temp_file("roundtrip.csv", "");
  const std::vector<double> row1{0.001, 1.0 / 3.0, -1e-300, 123456789.123456789};
  const std::vector<double> row2{0.002, std::nan(""), 2.5, -0.0};
  {
    CsvLogWriter w(path, {"time_s", "a/x_N", "b/y_m", "c"});
    w.write_row(row1);
    w.write_row(row2);
    w.commit();
  }
  CsvLogReader r(path);
  EXPECT_EQ(r.columns(), (std::vector<std::string>{"time_s", "a/x_N", "b/y_m", "c"}));
  std::vector<double> v;
  ASSERT_TRUE(r.next(v));
  EXPECT_EQ(v, row1);  // shortest round-trip formatting is exact
  ASSERT_TRUE(r.next(v));
  EXPECT_TRUE(std::isnan(v[1]));
  EXPECT_EQ(v[2], 2.5);
  EXPECT_FALSE(r.next(v));
}

TEST(CsvLog, EmptyCellIsADroppedSample) {
  CsvLogReader r(temp_file("empty_cell.csv", "time_s,a,b\n0.1,,2\n"));
  std::vector<double> v;
  ASSERT_TRUE(r.next(v));
  EXPECT_TRUE(std::isnan(v[1]));
  EXPECT_EQ(v[2], 2.0);
}

struct BadLogCase {
  const char* name;
  const char* content;
  LogError::Kind kind;
  const char* message_part;
};
std::ostream& operator<<(std::ostream& os, const BadLogCase& c) { return os << c.name; }

const BadLogCase kBadLogs[] = {
    {"empty_file", "", LogError::Kind::bad_header, ":1: the file is empty"},
    {"first_column_not_time", "t,a\n0,1\n", LogError::Kind::bad_header, ":1: the first column is 't'"},
    {"duplicate_column", "time_s,a,a\n", LogError::Kind::bad_header, "column 'a' appears twice"},
    {"unnamed_column", "time_s,,a\n", LogError::Kind::bad_header, "column 2 of the header has no name"},
    {"non_numeric_cell", "time_s,a,b\n0,1,2\n0.001,x1,2\n", LogError::Kind::bad_row,
     ":3: column 'a' (field 2) = 'x1' is not a number"},
    {"too_few_fields", "time_s,a,b\n0,1\n", LogError::Kind::bad_row, ":2: row has 2 fields but the header has 3"},
    {"too_many_fields", "time_s,a\n0,1,2\n", LogError::Kind::bad_row, ":2: row has more fields than the header's 2"},
    {"time_not_increasing", "time_s,a\n0.002,1\n0.001,1\n", LogError::Kind::bad_row,
     ":3: time_s = 0.001 s is not after the previous row's 0.002 s"},
    {"duplicated_timestamp", "time_s,a\n0.002,1\n0.002,1\n", LogError::Kind::bad_row, "is not after"},
    {"time_nan", "time_s,a\nnan,1\n", LogError::Kind::bad_row, ":2: time_s is not a finite number"},
    // from_chars reads "-1" after the explicit '+' was skipped: "+-1" used to load as -1.
    {"two_signs", "time_s,a\n0,+-1\n", LogError::Kind::bad_row, ":2: column 'a' (field 2) = '+-1' is not a number"},
};

class BadLog : public ::testing::TestWithParam<BadLogCase> {};

TEST_P(BadLog, IsReportedWithPosition) {
  const BadLogCase& c = GetParam();
  const std::string path = temp_file(std::string(c.name) + ".csv", c.content);
  try {
    CsvLogReader r(path);
    std::vector<double> v;
    while (r.next(v)) {
    }
    FAIL() << "expected a LogError";
  } catch (const LogError& e) {
    EXPECT_EQ(e.kind(), c.kind);
    EXPECT_NE(std::string(e.what()).find(c.message_part), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind(path, 0), 0u) << "message starts with the file: " << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Table, BadLog, ::testing::ValuesIn(kBadLogs),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(CsvLog, ReadsFromAStreamLikeFromAFile) {
  const std::string content = "\xEF\xBB\xBFtime_s, a ,b\r\n0.1,,2\r\n\r\n0.2,+3,-inf\r\n";
  CsvLogReader from_file(temp_file("stream.csv", content));
  std::istringstream in(content);
  CsvLogReader from_stream(in, "stream.csv");
  EXPECT_EQ(from_stream.columns(), from_file.columns());
  std::vector<double> a, b;
  while (from_file.next(a)) {
    ASSERT_TRUE(from_stream.next(b));
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_TRUE(a[i] == b[i] || (std::isnan(a[i]) && std::isnan(b[i])));
    EXPECT_EQ(from_stream.line(), from_file.line());
  }
  EXPECT_FALSE(from_stream.next(b));
  std::istringstream bad("time_s,a\n0,1\n0,2\n");
  CsvLogReader r(bad, "bad.csv");
  ASSERT_TRUE(r.next(b));
  try {
    r.next(b);
    FAIL() << "expected a LogError";
  } catch (const LogError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("bad.csv:3: time_s = ", 0), 0u) << e.what();
  }
}

TEST(CsvLog, NumbersBeyondDoubleAreInfinitiesAndBelowItZeros) {
  std::istringstream in("time_s,a,b,c,d,e\n0,1e400,-1e400,1e-400,-1e-400,4.9e-324\n");
  CsvLogReader r(in, "range.csv");
  std::vector<double> v;
  ASSERT_TRUE(r.next(v));
  EXPECT_EQ(v[1], std::numeric_limits<double>::infinity());
  EXPECT_EQ(v[2], -std::numeric_limits<double>::infinity());
  EXPECT_EQ(v[3], 0.0);
  EXPECT_FALSE(std::signbit(v[3]));
  EXPECT_EQ(v[4], 0.0);
  EXPECT_TRUE(std::signbit(v[4]));
  EXPECT_EQ(v[5], std::numeric_limits<double>::denorm_min());
}

TEST(CsvLog, ALastRowWithoutLineEndMayBeCutAndIsRefused) {
  std::istringstream in("time_s,a\n0,1.5\n0.001,1");  // "12.5" cut after its first digit?
  CsvLogReader r(in, "cut.csv");
  std::vector<double> v;
  ASSERT_TRUE(r.next(v));
  try {
    (void)r.next(v);
    FAIL() << "the cut row was accepted";
  } catch (const LogError& e) {
    EXPECT_NE(std::string(e.what()).find("cut.csv:3: the last row has no line end"), std::string::npos) << e.what();
  }
}

TEST(CsvLog, MissingFileSaysSo) {
  try {
    CsvLogReader r("/nonexistent/log.csv");
    FAIL();
  } catch (const LogError& e) {
    EXPECT_EQ(e.kind(), LogError::Kind::cannot_open);
    EXPECT_NE(std::string(e.what()).find("cannot open the log file"), std::string::npos);
  }
}

}  // namespace
}  // namespace ftsense::io
