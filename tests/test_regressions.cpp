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
