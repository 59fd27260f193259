// The command-line contract: what other tools and users rely on.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "process.hpp"

using graftal::testing::runGraftal;
using graftal::testing::TempDir;

namespace {

const char* kKoch =
    "Lsystem: 1\nangle factor: 4\nderivation length: 2\naxiom: F+F+F+F\n"
    "F --> F+F-F-FF+F+F-F\nendlsystem\n";

}  // namespace

TEST(Cli, DerivePrintsTheString) {
    TempDir t;
    auto f = t.write("fib.l",
                     "Lsystem: 1\nderivation length: 5\naxiom: b\na --> ab\nb --> a\nendlsystem\n");
    auto r = runGraftal("derive " + f.string());
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out, "abaababa\n");
    r = runGraftal("derive " + f.string() + " -n 2");
    EXPECT_EQ(r.out, "ab\n");
}

TEST(Cli, DefinesFromTheCommandLine) {
    TempDir t;
    auto f = t.write(
        "d.l", "#define N 1\nLsystem: 1\nderivation length: N\naxiom: A\nA --> AB\nendlsystem\n");
    auto r = runGraftal("derive " + f.string() + " -D N=3");
    EXPECT_EQ(r.out, "ABBB\n") << r.err;
}

TEST(Cli, StatsIsOneJsonObject) {
    TempDir t;
    auto f = t.write("koch.l", kKoch);
    auto r = runGraftal("stats " + f.string());
    ASSERT_EQ(r.status, 0) << r.err;
    auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["steps"], 2);
    EXPECT_EQ(j["modules"], 475);
    EXPECT_EQ(j["symbols"]["F"], 256);
    EXPECT_EQ(j["segments"], 256);
    EXPECT_EQ(j["polygons"], 0);
    ASSERT_EQ(j["bbox"]["min"].size(), 3u);
    double w = j["bbox"]["max"][0].get<double>() - j["bbox"]["min"][0].get<double>();
    double h = j["bbox"]["max"][1].get<double>() - j["bbox"]["min"][1].get<double>();
    EXPECT_NEAR(w, h, 1e-9);
    EXPECT_NEAR(w, 26, 1e-9) << "side 16 plus bumps of 4 + 1 on each side";
}

TEST(Cli, RenderWritesEachFormat) {
    TempDir t;
    auto f = t.write("koch.l", kKoch);
    for (const char* ext : {"svg", "png", "pdf"}) {
        auto out = t.path() / (std::string("k.") + ext);
        auto r = runGraftal("render " + f.string() + " -o " + out.string() + " --size 300x200");
        EXPECT_EQ(r.status, 0) << r.err;
        EXPECT_GT(std::filesystem::file_size(out), 100u) << ext;
    }
}

struct BadInput {
    const char* name;
    const char* content;   // nullptr: the file does not exist
    const char* args;      // extra arguments
    const char* expected;  // substring of stderr
    const char* outName = "out.png";
};

class CliBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(CliBadInput, OneClearMessageNonZeroStatusAndNoOutputFile) {
    const BadInput& b = GetParam();
    TempDir t;
    auto f = b.content ? t.write("bad.l", b.content) : t.path() / "missing.l";
    auto out = t.path() / b.outName;
    auto r = runGraftal("render " + f.string() + " -o " + out.string() + " " + b.args);
    EXPECT_NE(r.status, 0);
    EXPECT_LT(r.status, 128) << "no crash";
    EXPECT_NE(r.err.find(b.expected), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << "no output file left behind";
    for (auto& e : std::filesystem::directory_iterator(t.path()))
        EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

INSTANTIATE_TEST_SUITE_P(
    Cases, CliBadInput,
    ::testing::Values(
        BadInput{"UnknownKeyword", "Lsystem: 1\naxoim: F\n", "",
                 "bad.l:2:1: error: unknown keyword 'axoim:'"},
        BadInput{"MalformedProduction", "Lsystem: 1\naxiom: F\nF => FF\n", "",
                 "bad.l:3:1: error: expected a production"},
        BadInput{"UnbalancedBracket", "Lsystem: 1\naxiom: F\nF --> F[+F\n", "",
                 "bad.l:3:8: error: unbalanced '['"},
        BadInput{"MissingFile", nullptr, "", "missing.l: error: cannot open the file"},
        BadInput{"NegativeSteps", kKoch, "-n -3", "-n"},
        BadInput{"PopOnEmptyStack", "Lsystem: 1\naxiom: A\nA --> F]F\nendlsystem\n", "-n 1",
                 "bad.l:3:8: error: unbalanced ']' in the successor: no '[' is open here"},
        BadInput{"BinaryGarbage",
                 "\x7f"
                 "ELF\x02\x01\x01\x00\x00\x00",
                 "", "bad.l:1:1: error: this is not L-system text"},
        BadInput{"MemoryLimit", "Lsystem: 1\naxiom: F\nF --> FFFFFFFFFF\nendlsystem\n",
                 "-n 12 --memory-limit 64M",
                 "bad.l: error: derivation step 12 would make a string of 1000000000000 modules",
                 "out.svg"},  // an SVG holds every stroke: it cannot be drawn from summaries
        BadInput{"UnknownFormat", kKoch, "",
                 "x.bmp: unknown format (use .svg, .png, .pdf, .obj, .ply or .glb)", "x.bmp"}),
    [](const auto& param) { return std::string(param.param.name); });

TEST(Cli, NegativeStepCountIsRefused) {
    TempDir t;
    auto f = t.write("koch.l", kKoch);
    auto r = runGraftal("derive " + f.string() + " -n -3");
    EXPECT_NE(r.status, 0);
    EXPECT_FALSE(r.err.empty());
}

TEST(Cli, WarningsGoToStderrWithTheLine) {
    TempDir t;
    auto f = t.write("w.l", "Lsystem: 1\naxiom: ba\na --> c\nb < a --> b\nendlsystem\n");
    auto r = runGraftal("derive " + f.string() + " -n 1");
    EXPECT_EQ(r.status, 0);
    EXPECT_EQ(r.out, "bc\n");
    EXPECT_NE(r.err.find("w.l:4:1: warning:"), std::string::npos) << r.err;
}

TEST(Cli, EachWarningPrintsOnceForDeriveRenderAndStats) {
    TempDir t;
    auto f = t.write("w.l", "Lsystem: 1\naxiom: ba\na --> c\nb < a --> b\nendlsystem\n");
    auto count = [](const std::string& text, const std::string& what) {
        int n = 0;
        for (auto p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
        return n;
    };
    auto svg = (t.path() / "w.svg").string();
    for (const std::string& command :
         {"derive " + f.string() + " -n 1", "render " + f.string() + " -n 1 -o " + svg,
          "stats " + f.string() + " -n 1"}) {
        SCOPED_TRACE(command);
        auto r = runGraftal(command);
        EXPECT_EQ(r.status, 0) << r.err;
        EXPECT_EQ(count(r.err, "w.l:4:1: warning:"), 1) << r.err;
    }
}

// cpfg writes a side thinner than 1e-5 as max = min + 1e-5 (t09_slash: box 0 0 0 1e-05 2 1e-05).
TEST(Cli, StatsBoxGivesFlatSidesCpfgsThickness) {
    TempDir t;
    auto f = t.write("slash.l", "Lsystem: 1\nangle increment: 30\naxiom: F/F\nendlsystem\n");
    auto r = runGraftal("stats " + f.string());
    ASSERT_EQ(r.status, 0) << r.err;
    auto j = nlohmann::json::parse(r.out);
    const double want[2][3] = {{0, 0, 0}, {1e-5, 2, 1e-5}};
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(j["bbox"]["min"][c].get<double>(), want[0][c], 1e-12) << c;
        EXPECT_NEAR(j["bbox"]["max"][c].get<double>(), want[1][c], 1e-12) << c;
    }
}

// A phyllotaxis pattern made only of @c circles is a picture, not a blank page.
TEST(Cli, CirclesAloneRenderAsAPicture) {
    TempDir t;
    auto f = t.write("phyllo.l",
                     "Lsystem: 1\nderivation length: 30\naxiom: A(0)\n"
                     "A(n) --> [+(n*137.5)f(0.5*sqrt(n))@c(0.6)]A(n+1)\nendlsystem\n");
    auto svg = t.path() / "phyllo.svg";
    auto r = runGraftal("render " + f.string() + " -o " + svg.string());
    ASSERT_EQ(r.status, 0) << r.err;
    std::ifstream in(svg);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::size_t fills = 0;
    for (auto at = text.find("<path fill="); at != std::string::npos;
         at = text.find("<path fill=", at + 1))
        ++fills;
    EXPECT_EQ(fills, 30u) << "one filled circle per @c";
}

TEST(Cli, UsageMistakesNameWhatWasTypedAndWhatWasExpected) {
    TempDir t;
    auto f = t.write("koch.l", kKoch);
    struct Case {
        std::string args, message;
    };
    for (const Case& c : std::vector<Case>{
             {"frobnicate " + f.string(),
              "graftal: error: unknown subcommand 'frobnicate' (subcommands: derive, stats, "
              "render, music, studio, animate)\n"},
             {"render -x 3 " + f.string() + " -o k.png",
              "graftal: error: unknown option '-x' for render (see graftal render --help)\n"},
             {"derive -n abc " + f.string(),
              "graftal: error: -n abc: expected a whole number of steps\n"},
             {"derive --steps=2x " + f.string(),
              "graftal: error: --steps 2x: expected a whole number of steps\n"},
             {"render " + f.string() + " -o k.png --margin wide",
              "graftal: error: --margin wide: expected a number\n"},
             {"derive --precision half " + f.string(),
              "graftal: error: --precision half: expected single or double\n"},
             {"stats --random=mine " + f.string(),
              "graftal: error: --random mine: expected cpfg or graftal\n"}}) {
        auto r = runGraftal(c.args);
        EXPECT_EQ(r.status, 2) << c.args;
        EXPECT_EQ(r.err, c.message) << c.args;
        EXPECT_EQ(r.out, "");
    }
}

// Every subcommand's help is text: the choices of --precision and --random are named, not
// printed as the raw bytes of their enums (which made `grep` call the help binary).
TEST(Cli, HelpIsPlainText) {
    for (const char* sub : {"derive", "stats", "render", "music", "animate", "studio"}) {
        auto r = runGraftal(std::string(sub) + " --help");
        EXPECT_EQ(r.status, 0) << sub;
        for (unsigned char c : r.out)
            ASSERT_TRUE(c == '\n' || c >= 0x20) << sub << ": a control byte " << int(c);
    }
    EXPECT_NE(runGraftal("derive --help").out.find("--precision ENUM:{single, double}"),
              std::string::npos);
}

TEST(Cli, HelpPointsToSubcommandHelpDocsAndExamples) {
    auto r = runGraftal("--help");
    EXPECT_EQ(r.status, 0);
    EXPECT_NE(r.out.find("graftal SUBCOMMAND --help"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("docs/"), std::string::npos);
    EXPECT_NE(r.out.find("examples/"), std::string::npos);
}

TEST(Cli, MisspeltKeywordsSuggestTheClosestOne) {
    TempDir t;
    auto f = t.write("m.l", "Lsystem: 1\nderivaton length: 3\naxiom: F\nF --> FF\nendlsytem\n");
    auto r = runGraftal("derive " + f.string());
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("m.l:2:1: error: unknown keyword 'derivaton length:'; did you mean "
                         "'derivation length:'?\n"),
              std::string::npos)
        << r.err;
    EXPECT_NE(
        r.err.find("m.l:5:1: error: unknown keyword 'endlsytem'; did you mean 'endlsystem'?\n"),
        std::string::npos)
        << r.err;
    EXPECT_EQ(r.err.find("arrow"), std::string::npos) << "not taken for a production";
}
