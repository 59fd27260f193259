#include <gtest/gtest.h>

#include "test_helpers.hpp"

using namespace graftal;
using graftal::testing::derived;
using graftal::testing::parse;
using graftal::testing::parseError;

namespace {

const char* kCapsella =
    "Lsystem: 1\naxiom: A\n"
    "L(i) --> L(i+1)\n"
    "table: vegetative\nA --> I[L(0)]A\n"
    "table: flowering\nA --> I[L(0)]B\nB --> I[IF(0)]B\nF(i) --> F(i+1)\n"
    "table schedule: vegetative 2, flowering\nendlsystem\n";

}  // namespace

TEST(Tables, ScheduleSwitchesTablesAtTheGivenStep) {
    LSystem ls = parse(kCapsella);
    ASSERT_EQ(ls.tableNames.size(), 2u);
    EXPECT_EQ(ls.tableForStep(1), 0);
    EXPECT_EQ(ls.tableForStep(2), 0);
    EXPECT_EQ(ls.tableForStep(3), 1);
    EXPECT_EQ(ls.tableForStep(100), 1);
    EXPECT_EQ(derived(ls, 2), "I[L(1)]I[L(0)]A");
    EXPECT_EQ(derived(ls, 3), "I[L(2)]I[L(1)]I[L(0)]B");
    EXPECT_EQ(derived(ls, 4), "I[L(3)]I[L(2)]I[L(1)]I[IF(0)]B");
}

TEST(Tables, ProductionsBeforeTheFirstTableBelongToAll) {
    LSystem ls = parse(kCapsella);
    EXPECT_EQ(ls.productions[0].table, -1);
    EXPECT_EQ(ls.productions[1].table, 0);
    EXPECT_EQ(ls.productions[2].table, 1);
}

TEST(Tables, RepeatingScheduleCycles) {
    LSystem ls = parse(
        "Lsystem: 1\naxiom: X\ntable: day\nX --> XD\ntable: night\nX --> XN\n"
        "table schedule: day 2, night 1, repeat\nendlsystem\n");
    EXPECT_EQ(derived(ls, 6), "XNDDNDD");
}

TEST(Tables, ScheduleCountsMayBeExpressions) {
    LSystem ls = parse(
        "#define N 5\nLsystem: 1\naxiom: X\ntable: a\nX --> XA\ntable: b\nX --> XB\n"
        "table schedule: a N-2, b\nendlsystem\n");
    EXPECT_EQ(derived(ls, 5), "XBBAAA");
}

TEST(Tables, ErrorsNameTheLine) {
    EXPECT_EQ(
        parseError("Lsystem: 1\naxiom: X\ntable: a\nX --> Y\ntable schedule: b 2\nendlsystem\n"),
        "test.l:5:17: error: unknown table 'b' (tables: a)");
    EXPECT_NE(parseError("Lsystem: 1\naxiom: X\ntable: a\nX --> Y\nendlsystem\n")
                  .find("has tables but no 'table schedule:'"),
              std::string::npos);
    EXPECT_EQ(parseError("Lsystem: 1\naxiom: X\ntable: a\nX --> Y\ntable: b\nX --> Z\n"
                         "table schedule: a, b 3\nendlsystem\n"),
              "test.l:7:17: error: only the last table of a schedule may omit its step count");
}
