// Inputs that once crashed graftal, hung it or took memory without bound. Each must end in a
// clear error with its location or in a bounded result.
#include <gtest/gtest.h>

#include <string>

#include "process.hpp"
#include "test_helpers.hpp"

using namespace graftal;
using graftal::testing::parseError;
using graftal::testing::readFile;
using graftal::testing::runGraftal;
using graftal::testing::TempDir;

namespace {

std::string regression(const std::string& name) {
    return std::string(GRAFTAL_TESTS_DIR) + "/regressions/" + name;
}

}  // namespace

TEST(Regressions, AFormalMadeOfVerticalTabIsNotAName) {
    std::string text = readFile(regression("blank-formal.l"));
    ASSERT_EQ(text, "0(\v)->");
    EXPECT_EQ(
        parseError(text),
        "test.l:1:3: error: a predecessor names its parameters (e.g. A(x,y)); '' is not a name");
    auto r = runGraftal("derive " + regression("blank-formal.l"));
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("blank-formal.l:1:3"), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
}

TEST(Regressions, DeeplyNestedParenthesesAreAnErrorNotAStackOverflow) {
    auto nested = [](int depth) {
        return "Lsystem: 1\naxiom: F(" + std::string(depth, '(') + "1" + std::string(depth, ')') +
               ")\nendlsystem\n";
    };
    EXPECT_EQ(parseError(nested(200)), "");
    EXPECT_EQ(parseError(nested(10200)),
              "test.l:2:266: error: expression nested more than 256 levels deep");
    EXPECT_EQ(parseError("Lsystem: 1\naxiom: F(" + std::string(10000, '-') + "1)\nendlsystem\n"),
              "test.l:2:266: error: expression nested more than 256 levels deep");
    TempDir t;
    auto f = t.write("deep.l", nested(10200));
    auto r = runGraftal("derive " + f.string());
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("deep.l:2:266: error: expression nested"), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
}

TEST(Regressions, DeeplyNestedBranchesAreDerivedAndDrawn) {
    const int depth = 100000;
    TempDir t;
    auto f = t.write("branches.l", "Lsystem: 1\nderivation length: 1\naxiom: A" +
                                       std::string(depth, '[') + "F" + std::string(depth, ']') +
                                       "B\nF --> F[+F]\nA > B --> C\nendlsystem\n");
    auto r = runGraftal("stats " + f.string());
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("\"segments\": 2"), std::string::npos) << r.out.substr(0, 300);
    r = runGraftal("render -o " + (t.path() / "b.png").string() + " " + f.string());
    EXPECT_EQ(r.status, 0) << r.err;
}
