// The command in pipelines: JSON for scripts, "-" for standard input and output.
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

TEST(CliStandardStreams, DashReadsStandardInputAndNamesIt) {
    TempDir t;
    auto f = t.write("p.l", kParametric);
    auto r = runGraftal("derive -", f);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out, "F(0.5)[+F(1)[+A(3)]B(2,-2.25)]B(1,-2.25)\n");
    r = runGraftal("stats -", f);
    EXPECT_EQ(nlohmann::json::parse(r.out)["file"], "<stdin>") << r.out;
    auto bad = t.write("bad.l", "Lsystem: 1\naxiom: F\nF --> F[+F\nendlsystem\n");
    r = runGraftal("derive -", bad);
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.err.rfind("<stdin>:3:", 0), 0u) << r.err;
    auto png = t.path() / "p.png";
    r = runGraftal("render - -o " + png.string(), f);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(readFile(png).substr(1, 3), "PNG");
}

TEST(CliStandardStreams, DashOutputWritesToStandardOutput) {
    TempDir t;
    auto f = t.write("p.l", kParametric);
    auto file = t.path() / "p.svg";
    auto r = runGraftal("render " + f.string() + " -o " + file.string());
    ASSERT_EQ(r.status, 0) << r.err;
    r = runGraftal("render " + f.string() + " -o -");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out, readFile(file)) << "SVG by default";
    r = runGraftal("render - -o - --format png", f);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out.substr(1, 3), "PNG");
    r = runGraftal("render " + f.string() + " -o - --format obj");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("\nv "), std::string::npos) << r.out.substr(0, 200);
    // A failed render writes nothing.
    r = runGraftal("render " + t.write("bad.l", "Lsystem: 1\naxiom: F[\nendlsystem\n").string() +
                   " -o -");
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.out, "");
    r = runGraftal("render " + f.string() + " -o x.png --format svg");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("--format applies to -o -"), std::string::npos) << r.err;
}

TEST(CliStandardStreams, BinaryOutputToATerminalIsRefused) {
    TempDir t;
    auto f = t.write("p.l", kParametric);
    auto log = t.path() / "typescript";
    // script(1) gives the command a terminal as standard output.
    const std::string cmd = "script -qfec \"" + std::string(GRAFTAL_EXE) + " render " + f.string() +
                            " -o - --format png\" " + log.string() +
                            " > /dev/null 2>&1 < /dev/null";
    const int raw = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(raw)) << raw;
    EXPECT_EQ(WEXITSTATUS(raw), 1);
    const std::string said = readFile(log);
    EXPECT_NE(said.find("PNG is binary and standard output is a terminal"), std::string::npos)
        << said;
    EXPECT_EQ(said.find("PNG\r\n"), std::string::npos);
}
