// The map L-system language: the book's listings as printed, and every bad input named
// with its file, line and column.
#include <gtest/gtest.h>

#include <filesystem>

#include "graftal/lang/model.hpp"
#include "graftal/maps/map_lsystem.hpp"

using namespace graftal;
namespace fs = std::filesystem;

namespace {

MapParseResult parseMap(const std::string& text, std::map<std::string, std::string> defines = {}) {
    ParseOptions o;
    o.fileName = "m.l";
    o.defines = std::move(defines);
    return parseMapLSystem(text, o);
}

// The first error, as the command prints it.
std::string firstError(const std::string& text) {
    MapParseResult r = parseMap(text);
    auto errors = r.errors();
    return errors.empty() ? "" : errors.front().toString();
}

const std::string kHead = "map L-system: 1\nderivation length: 1\naxiom: ab\nb --> b\n";

}  // namespace

TEST(MapParser, ReadsTheListingOfFig52AsPrinted) {
    MapParseResult r = loadMapLSystem(fs::path(GRAFTAL_EXAMPLES_DIR) / "fig5.2-cell-layer.l");
    ASSERT_TRUE(r.ok()) << r.diagnostics.front().toString();
    const MapLSystem& s = r.system;
    EXPECT_EQ(s.derivationLength, 5);
    ASSERT_EQ(s.axiom.size(), 3u);
    EXPECT_EQ(s.axiom[0].label, 'g');
    EXPECT_EQ(s.axiom[2].label, 'a');
    int productions = 0;
    for (const auto& p : s.productions) productions += p.has_value();
    EXPECT_EQ(productions, 23);
    EXPECT_EQ(successorText(*s.production('a')), "c[-~a]x[+~b]g");
    EXPECT_EQ(successorText(*s.production('v')), "~b");
    const MapProduction& a = *s.production('a');
    ASSERT_EQ(a.branches.size(), 2u);
    EXPECT_EQ(a.branches[0].vertex, 1u);
    EXPECT_FALSE(a.branches[0].left);
    EXPECT_TRUE(a.branches[0].towards);
    EXPECT_EQ(a.branches[1].vertex, 2u);
    EXPECT_TRUE(a.branches[1].left);
}

TEST(MapParser, ReadsTheListingOfFig53WithItsBranchBeforeTheAxis) {
    MapParseResult r = loadMapLSystem(fs::path(GRAFTAL_EXAMPLES_DIR) / "fig5.3-phascum-leaf.l");
    ASSERT_TRUE(r.ok()) << r.diagnostics.front().toString();
    const MapLSystem& s = r.system;
    EXPECT_EQ(s.derivationLength, 8);
    ASSERT_EQ(s.axiom.size(), 3u);
    EXPECT_FALSE(s.axiom[0].reversed);
    EXPECT_TRUE(s.axiom[1].reversed);
    EXPECT_TRUE(s.axiom[2].reversed);
    const MapProduction& c = *s.production('c');
    ASSERT_EQ(c.axis.size(), 1u);
    ASSERT_EQ(c.branches.size(), 1u);
    EXPECT_EQ(c.branches[0].vertex, 0u);
    EXPECT_EQ(successorText(c), "[+~y]e");
    EXPECT_EQ(successorText(*s.production('v')), "w[-~y][+y]d");
}

TEST(MapParser, AcceptsBothArrowsDefinesAndComments) {
    MapParseResult r = parseMap(
        "/* a comment */\n#define N 2+1\nmap L-system: 1\nderivation length: 2*N\n"
        "axiom: a~b // the axiom\na -> a[+b]a\nb \xE2\x86\x92 b\nendlsystem\n");
    ASSERT_TRUE(r.ok()) << r.diagnostics.front().toString();
    EXPECT_EQ(r.system.derivationLength, 6);
    EXPECT_EQ(successorText(*r.system.production('a')), "a[+b]a");
    EXPECT_TRUE(r.system.axiom[1].reversed);
    MapParseResult d = parseMap(
        "#define N 2\nmap L-system:\nderivation length: N\naxiom: a\n"
        "a --> a\n",
        {{"N", "4"}});
    ASSERT_TRUE(d.ok());
    EXPECT_EQ(d.system.derivationLength, 4) << "-D wins over #define";
}

TEST(MapParser, TellsMapFilesFromStringLSystems) {
    EXPECT_TRUE(isMapLSystemText("/* x */\n#define N 1\nmap L-system: 1\naxiom: a\n"));
    EXPECT_TRUE(isMapLSystemText("Map Lsystem:\n"));
    EXPECT_FALSE(isMapLSystemText("Lsystem: 1\naxiom: F\nF --> FF\nendlsystem\n"));
    EXPECT_FALSE(isMapLSystemText("axiom: F\nmap L-system: 1\n"));
    EXPECT_TRUE(isMapLSystemFile(fs::path(GRAFTAL_EXAMPLES_DIR) / "fig5.1-square-map.l"));
    EXPECT_FALSE(isMapLSystemFile(fs::path(GRAFTAL_EXAMPLES_DIR) / "fig3.4-plant.l"));
}

TEST(MapParser, UnknownLabelInASuccessor) {
    EXPECT_EQ(firstError(kHead + "a --> a[+b]z\n"),
              "m.l:5:12: error: unknown edge label 'z': no production has it as predecessor");
}

TEST(MapParser, UnknownLabelInTheAxiom) {
    EXPECT_EQ(firstError("map L-system:\naxiom: aq\na --> a\n"),
              "m.l:2:9: error: unknown edge label 'q': no production has it as predecessor");
}

TEST(MapParser, UnbalancedBrackets) {
    EXPECT_EQ(firstError(kHead + "a --> a[+b\n"),
              "m.l:5:8: error: unbalanced bracket: '[' is not closed");
    EXPECT_EQ(firstError(kHead + "a --> a+b]a\n"),
              "m.l:5:8: error: '+' belongs at the start of a branch, as in [+a]");
    EXPECT_EQ(firstError(kHead + "a --> ab]a\n"),
              "m.l:5:9: error: unbalanced bracket: ']' without '['");
}

TEST(MapParser, ABranchIsOneEdge) {
    EXPECT_EQ(firstError(kHead + "a --> a[+ba]a\n"),
              "m.l:5:11: error: a branch is one edge: expected ']' after its label");
    EXPECT_EQ(firstError(kHead + "a --> a[+[b]]a\n"),
              "m.l:5:10: error: a branch is one edge: no nested branch");
}

TEST(MapParser, PlusOrMinusBeforeABranch) {
    EXPECT_EQ(firstError(kHead + "a --> a[b]a\n"),
              "m.l:5:9: error: expected '+' or '-' at the start of a branch (which side of the "
              "axis it enters)");
    EXPECT_EQ(firstError(kHead + "a --> a[~b]a\n"),
              "m.l:5:9: error: expected '+' or '-' at the start of a branch (which side of the "
              "axis it enters)");
}

TEST(MapParser, OtherMistakes) {
    EXPECT_EQ(firstError("derivation length: 1\naxiom: a\na --> a\n"),
              "m.l:1:1: error: expected 'map L-system:' as the first statement");
    EXPECT_EQ(firstError(kHead + "a --> [+b]\n"),
              "m.l:5:7: error: a successor needs at least one edge on its main axis");
    EXPECT_EQ(firstError(kHead + "a --> a\na --> b\n"),
              "m.l:6:1: error: a second production for edge 'a'");
    EXPECT_EQ(firstError(kHead + "ab --> a\n"),
              "m.l:5:1: error: expected one edge label (a letter or digit) before the arrow");
    EXPECT_EQ(firstError("map L-system:\nderivation length: 1.5\naxiom: a\na --> a\n"),
              "m.l:2:20: error: the derivation length must be a whole number, 0 or more");
    EXPECT_EQ(firstError("map L-system:\naxiom: a\na --> a\nhello\n"),
              "m.l:4:1: error: expected a production 'a --> successor', 'derivation length:' "
              "or 'axiom:'");
}

TEST(MapParser, StringLSystemParserNamesMapFiles) {
    ParseResult r = loadModel(fs::path(GRAFTAL_EXAMPLES_DIR) / "fig5.2-cell-layer.l");
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.errors().front().message.find("map L-system"), std::string::npos)
        << r.errors().front().toString();
}
