// The command in pipelines: JSON for scripts.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "process.hpp"

using graftal::testing::readFile;
using graftal::testing::runGraftal;
using graftal::testing::TempDir;

namespace {

const char* kParametric =
    "Lsystem: 1\nderivation length: 2\naxiom: A(1)\nA(x) --> F(x*0.5)[+A(x+1)]B(x,-2.25)\n"
    "endlsystem\n";

}  // namespace

TEST(CliStandardStreams, DeriveJsonListsEveryModuleWithItsParameters) {
    TempDir t;
    auto f = t.write("p.l", kParametric);
    auto text = runGraftal("derive " + f.string());
    auto r = runGraftal("derive --format json " + f.string());
    ASSERT_EQ(r.status, 0) << r.err;
    auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["file"], f.string());
    EXPECT_EQ(j["steps"], 2);
    ASSERT_TRUE(j["modules"].is_array());
    // F(0.5)[+F(1)[+A(3)]B(2,-2.25)]B(1,-2.25)
    EXPECT_EQ(text.out, "F(0.5)[+F(1)[+A(3)]B(2,-2.25)]B(1,-2.25)\n");
    ASSERT_EQ(j["modules"].size(), 11u);
    EXPECT_EQ(j["modules"][0]["symbol"], "F");
    EXPECT_EQ(j["modules"][0]["params"], nlohmann::json::array({0.5}));
    EXPECT_EQ(j["modules"][1]["symbol"], "[");
    EXPECT_EQ(j["modules"][1]["params"], nlohmann::json::array());
    EXPECT_EQ(j["modules"][10]["symbol"], "B");
    EXPECT_EQ(j["modules"][10]["params"], nlohmann::json::array({1, -2.25}));
    // Streamed, the same document.
    auto s = runGraftal("derive --format json --stream " + f.string());
    EXPECT_EQ(s.out, r.out) << s.err;
    // Symbols JSON must escape, and the empty string is an empty array.
    auto e = t.write("e.l", "Lsystem: 1\naxiom: \\\"\nendlsystem\n");
    r = runGraftal("derive --format json " + e.string());
    ASSERT_EQ(r.status, 0) << r.err;
    j = nlohmann::json::parse(r.out);
    ASSERT_EQ(j["modules"].size(), 2u);
    EXPECT_EQ(j["modules"][0]["symbol"], "\\");
    EXPECT_EQ(j["modules"][1]["symbol"], "\"");
    auto empty = t.write("empty.l", "Lsystem: 1\naxiom: *\nendlsystem\n");
    r = runGraftal("derive --format json " + empty.string());
    EXPECT_EQ(nlohmann::json::parse(r.out)["modules"].size(), 0u) << r.out;
    r = runGraftal("derive --format yaml " + f.string());
    EXPECT_EQ(r.status, 2);
}
