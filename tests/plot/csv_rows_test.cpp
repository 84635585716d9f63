// The streaming CSV reader (include/mjarm/plot/csv_rows.hpp): rows as CsvTable reads them, one at a
// time across its read buffer, and the damaged files a recording can be — cut in the middle of a
// row, binary, of other columns — refused naming the line.

#include "mjarm/plot/csv_rows.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "mjarm/error.hpp"
#include "sim/sim_test_support.hpp"
#include "support/error_message.hpp"

namespace mjarm::plot {
namespace {

namespace fs = std::filesystem;

fs::path write(const test::TempDir& dir, const std::string& name, const std::string& text) {
  const fs::path path = dir.path() / name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// reads every row; returns the error, or "rows N"
std::string read_all(const fs::path& path) {
  return test::error_of([&] {
    CsvRowReader reader(path, "recorded table");
    while (reader.next()) {
    }
    throw Error("rows " + std::to_string(reader.rows()));
  });
}

TEST(CsvRowReader, ReadsRowsAndQuotedCellsOneAtATime) {
  const test::TempDir dir("csv_rows");
  const fs::path path = write(
      dir, "events.csv",
      "t,kind,message\n0,phase,approach\n\n0.5,result,\"held, \"\"well\"\"\nat last\"\r\nnan,x,\n");
  CsvRowReader reader(path, "recorded table");
  ASSERT_EQ(reader.header().size(), 3u);
  EXPECT_EQ(reader.require("message"), 2u);
  EXPECT_EQ(reader.find("nope"), -1);
  EXPECT_NE(test::error_of([&] { reader.require("nope"); }).find("t, kind, message"),
            std::string::npos);
  ASSERT_TRUE(reader.next());
  EXPECT_EQ(reader.cell(2), "approach");
  EXPECT_EQ(reader.line(), 2u);
  ASSERT_TRUE(reader.next());  // the blank line skipped
  EXPECT_EQ(reader.line(), 4u);
  EXPECT_EQ(reader.number(0), 0.5);
  EXPECT_EQ(reader.cell(2), "held, \"well\"\nat last");
  ASSERT_TRUE(reader.next());
  EXPECT_TRUE(std::isnan(reader.number(0)));
  EXPECT_TRUE(std::isnan(reader.number(2)));  // an empty cell
  EXPECT_NE(
      test::error_of([&] { reader.number(1); }).find("column 'kind' line 6: 'x' is not a number"),
      std::string::npos);
  EXPECT_FALSE(reader.next());
  EXPECT_EQ(reader.rows(), 3u);
}

TEST(CsvRowReader, RowsAcrossManyReadBuffersAreReadWhole) {
  // 3 MiB of rows: the 1 MiB buffer is refilled in the middle of rows
  const test::TempDir dir("csv_rows");
  std::string text = "t,a,b\n";
  constexpr int kRows = 100000;
  for (int i = 0; i < kRows; ++i)
    text += std::to_string(i) + ",0.123456789012345678," + std::to_string(-i) + "\n";
  const fs::path path = write(dir, "long.csv", text);
  CsvRowReader reader(path, "recorded table");
  int row = 0;
  while (reader.next()) {
    ASSERT_EQ(reader.number(0), row) << row;
    ASSERT_EQ(reader.number(2), -row) << row;
    ++row;
  }
  EXPECT_EQ(row, kRows);
}

TEST(CsvRowReader, ATruncatedBinaryOrForeignFileIsRefusedNamingTheLine) {
  const test::TempDir dir("csv_rows");
  // cut in the middle of a row: fewer cells, or the last number cut (no line end after it)
  EXPECT_NE(read_all(write(dir, "cut.csv", "t,a,b\n0,1,2\n0.1,1")).find("line 3"),
            std::string::npos);
  EXPECT_NE(read_all(write(dir, "cut2.csv", "t,a,b\n0,1,2\n0.1,1,2.5")).find("truncated"),
            std::string::npos);
  EXPECT_NE(read_all(write(dir, "cells.csv", "t,a,b\n0,1,2\n0.1,1\n0.2,1,2\n"))
                .find("line 3 has 2 cells, the header has 3"),
            std::string::npos);
  std::string binary =
      "\x7f"
      "ELF\x02\x01\x01";
  binary += std::string(3, '\0') + "more";
  EXPECT_NE(read_all(write(dir, "binary.csv", binary)).find("NUL byte"), std::string::npos);
  EXPECT_NE(read_all(write(dir, "empty.csv", "")).find("is empty"), std::string::npos);
  EXPECT_NE(read_all(dir.path() / "missing.csv").find("does not exist"), std::string::npos);
  EXPECT_NE(read_all(dir.path()).find("directory"), std::string::npos);
  EXPECT_EQ(read_all(write(dir, "good.csv", "t,a\n0,1\n1,2\n")), "rows 2");
}

}  // namespace
}  // namespace mjarm::plot
