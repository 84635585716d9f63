#include "mjarm/plot/csv_table.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "mjarm/error.hpp"

namespace mjarm::plot {
namespace {

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(CsvTable, ReadsNamedColumnsAndQuotedCells) {
  const CsvTable table = CsvTable::parse(
      "t,kind,message\n0,phase,approach\n0.5,result,\"held, \"\"well\"\"\nat last\"\n1e-3,x,\n",
      "events.csv");
  ASSERT_EQ(table.rows(), 3u);
  EXPECT_EQ(table.header().size(), 3u);
  EXPECT_EQ(table.text("message")[1], "held, \"well\"\nat last");
  EXPECT_EQ(table.numbers("t")[2], 1e-3);
  EXPECT_TRUE(table.has("kind"));
  EXPECT_FALSE(table.has("kin"));
  EXPECT_EQ(table.find("message"), 2);
}

TEST(CsvTable, AcceptsNanAndEmptyCellsAsNumbers) {
  const CsvTable table = CsvTable::parse("a,b\nnan,\r\n-inf,2\n", "x.csv");
  const std::vector<double> a = table.numbers("a"), b = table.numbers("b");
  EXPECT_TRUE(std::isnan(a[0]));
  EXPECT_TRUE(std::isnan(b[0]));
  EXPECT_TRUE(std::isinf(a[1]));
  EXPECT_EQ(b[1], 2.0);
}

TEST(CsvTable, PrefixedColumns) {
  const CsvTable table = CsvTable::parse("t,force.a,force.b,forceful\n", "state.csv");
  EXPECT_EQ(table.columns_with_prefix("force."), (std::vector<std::string>{"force.a", "force.b"}));
  EXPECT_EQ(table.rows(), 0u);
}

TEST(CsvTable, ErrorsNameTheFileTheColumnAndTheLine) {
  const CsvTable table = CsvTable::parse("t,x\n0,1\n1,oops\n", "task.csv");
  const std::string missing = message_of([&] { table.numbers("err.vx"); });
  EXPECT_NE(missing.find("task.csv"), std::string::npos) << missing;
  EXPECT_NE(missing.find("'err.vx'"), std::string::npos) << missing;
  EXPECT_NE(missing.find("columns: t, x"), std::string::npos) << missing;
  const std::string bad = message_of([&] { table.numbers("x"); });
  EXPECT_NE(bad.find("line 3"), std::string::npos) << bad;
  EXPECT_NE(bad.find("'oops'"), std::string::npos) << bad;
  const std::string ragged = message_of([] { CsvTable::parse("a,b\n1,2\n3\n", "state.csv"); });
  EXPECT_NE(ragged.find("state.csv' line 3 has 1 cells, the header has 2"), std::string::npos)
      << ragged;
  EXPECT_NE(message_of([] { CsvTable::parse("", "e.csv"); }).find("is empty"), std::string::npos);
  EXPECT_NE(message_of([] {
              CsvTable::read("/nonexistent/q.csv");
            }).find("'/nonexistent/q.csv' does not exist"),
            std::string::npos);
  // through the one checked reader: a device is refused, not read forever
  EXPECT_NE(message_of([] { CsvTable::read("/dev/zero"); }).find("is a character device"),
            std::string::npos);
}

}  // namespace
}  // namespace mjarm::plot
