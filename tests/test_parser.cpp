#include <gtest/gtest.h>

#include "test_helpers.hpp"

using namespace graftal;
using graftal::testing::loadExample;
using graftal::testing::parse;
using graftal::testing::parseError;
using graftal::testing::parseModel;

TEST(Parser, ReadsTheCpfgForm) {
    Model m = parseModel(
        "/* Koch island */\n"
        "#define N 3\n"
        "Lsystem: 1\n"
        "derivation length: N\n"
        "angle factor: 4\n"
        "Axiom: F+F+F+F\n"
        "F --> F+F-F-FF+F+F-F\n"
        "endlsystem\n");
    const LSystem& ls = m.lsystem;
    EXPECT_EQ(ls.derivationLength, 3);
    EXPECT_DOUBLE_EQ(m.view.turtle.angleDegrees, 90);
    EXPECT_FALSE(ls.legacyPfg);
    EXPECT_FALSE(m.view.turtle.clockwisePlus);
    EXPECT_EQ(ls.axiom.toString(ls.symbols), "F+F+F+F");
    ASSERT_EQ(ls.productions.size(), 1u);
    EXPECT_EQ(ls.productions[0].successor.size(), 14u);
}

TEST(Parser, AFileWithoutLsystemHeaderIsAPfgDataFile) {
    Model m = parseModel(
        "derivation length: 30\n"
        "angle factor: 16\n"
        "scale factor: 100\n"
        "axiom: F1F1F1\n"
        "ignore: +-F\n"
        "0 < 0 > 0 --> 0\n"
        "* < + > * --> -\n");
    const LSystem& ls = m.lsystem;
    EXPECT_TRUE(ls.legacyPfg);
    EXPECT_TRUE(m.view.turtle.clockwisePlus);
    EXPECT_DOUBLE_EQ(m.view.turtle.angleDegrees, 22.5);
    EXPECT_TRUE(ls.ignored['+']);
    EXPECT_TRUE(ls.ignored['F']);
    EXPECT_FALSE(ls.ignored['0']);
    ASSERT_EQ(ls.productions.size(), 2u);
    EXPECT_EQ(ls.productions[0].left.size(), 1u);
    EXPECT_EQ(ls.productions[1].left.size(), 0u) << "* is the empty context";
    EXPECT_EQ(ls.productions[1].predecessor[0].symbol, '+');
}

TEST(Parser, MultiLetterModulesTokeniseLongestFirst) {
    LSystem ls = parse(
        "module a, ab, abc;\n"
        "Lsystem: 1\n"
        "axiom: abcaba F\n"
        "endlsystem\n");
    EXPECT_EQ(ls.axiom.size(), 4u);
    EXPECT_EQ(ls.symbols.name(ls.axiom.symbol(0)), "abc");
    EXPECT_EQ(ls.symbols.name(ls.axiom.symbol(1)), "ab");
    EXPECT_EQ(ls.symbols.name(ls.axiom.symbol(2)), "a");
    EXPECT_EQ(ls.symbols.name(ls.axiom.symbol(3)), "F");
}

TEST(Parser, SeveralModulePredecessorsAndContexts) {
    LSystem ls = parse("axiom: X\nAB < CDE > FG --> A[B]A\n");
    const Production& p = ls.productions.at(0);
    EXPECT_EQ(p.left.size(), 2u);
    EXPECT_EQ(p.predecessor.size(), 3u);
    EXPECT_EQ(p.right.size(), 2u);
    EXPECT_EQ(p.successor.size(), 5u);
}

TEST(Parser, CommentsKeepColumnsAndRollSymbolsSurvive) {
    LSystem ls = parse(
        "Lsystem: 1 // the name\n"
        "/* a\n   multi-line comment */ axiom: A\n"
        "A --> F//&&A   // two rolls, two pitches\n"
        "endlsystem\n");
    EXPECT_EQ(ls.productions[0].successor.size(), 6u);
    EXPECT_EQ(parseError("Lsystem: 1\n/* open */ axiom: A\nA --> $\n"), "")
        << "a $ is a plain module";
}

TEST(Parser, ParametricProductionsCompile) {
    LSystem ls = parse(
        "Lsystem: 1\n"
        "axiom: A(1)B(2)C(3)\n"
        "A(x) < B(y) > C(z) : y < 4 --> B(x+z)[A(y)]\n"
        "endlsystem\n");
    const Production& p = ls.productions.at(0);
    EXPECT_EQ(p.slotCount, 3);
    ASSERT_TRUE(p.condition.has_value());
    EXPECT_EQ(p.condition->text(), "y < 4");
    EXPECT_EQ(ls.axiom.toString(ls.symbols), "A(1)B(2)C(3)");
}

TEST(Parser, CommandLineDefinesWin) {
    ParseOptions o;
    o.defines["N"] = "7";
    LSystem ls =
        parseLSystem("#define N 3\nLsystem: 1\nderivation length: N\naxiom: F\nendlsystem\n", o);
    EXPECT_EQ(ls.derivationLength, 7);
}

TEST(Parser, ConsiderIsTheComplementOfIgnore) {
    LSystem ls = parse("Lsystem: 1\nconsider: AB\naxiom: A\nendlsystem\n");
    EXPECT_FALSE(ls.ignored['A']);
    EXPECT_TRUE(ls.ignored['F']);
    EXPECT_TRUE(ls.ignored['+']);
}

TEST(Parser, WarnsWhenAContextFreeProductionShadowsAContextSensitiveOne) {
    ParseOptions o;
    o.fileName = "test.l";
    ParseResult r = graftal::parse("Lsystem: 1\naxiom: ba\na --> c\nb < a --> b\nendlsystem\n", o);
    ASSERT_TRUE(r.ok());
    std::vector<Diagnostic> warnings = r.warnings();
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0].location.line, 4);
    EXPECT_EQ(warnings[0].location.endLine, 4);
    EXPECT_EQ(warnings[0].location.endColumn, 12) << "the end of the production 'b < a --> b'";
    EXPECT_NE(warnings[0].message.find("line 3"), std::string::npos);
}

TEST(ParserErrors, UnknownKeywordNamesTheKeyword) {
    EXPECT_EQ(parseError("Lsystem: 1\nderivation lenght: 4\naxiom: F\n").substr(0, 44),
              "test.l:2:1: error: unknown keyword 'derivati");
}

TEST(ParserErrors, MissingArrow) {
    EXPECT_EQ(parseError("Lsystem: 1\naxiom: F\nF F+F\n"),
              "test.l:3:1: error: expected a production such as 'F --> F+F' (the arrow '-->' "
              "is missing) or a keyword line such as 'axiom: F'");
}

TEST(ParserErrors, UnbalancedBrackets) {
    EXPECT_EQ(parseError("Lsystem: 1\naxiom: F\nF --> F[+F\n"),
              "test.l:3:8: error: unbalanced '[' in the successor: expected a matching ']'");
    EXPECT_EQ(parseError("Lsystem: 1\naxiom: F]F\n"),
              "test.l:2:9: error: unbalanced ']' in the axiom: no '[' is open here");
}

TEST(ParserErrors, MissingAxiom) {
    EXPECT_EQ(parseError("Lsystem: 1\nF --> FF\nendlsystem\n"),
              "test.l:3:1: error: no axiom: expected a line such as 'axiom: F'");
}

TEST(ParserErrors, BadValues) {
    EXPECT_EQ(
        parseError("Lsystem: 1\nderivation length: -3\naxiom: F\n"),
        "test.l:2:20: error: derivation length must be a whole number from 0 to 1000000, not -3");
    EXPECT_EQ(parseError("Lsystem: 1\nangle factor: 0\naxiom: F\n"),
              "test.l:2:15: error: angle factor must be positive (delta = 360 / factor)");
    EXPECT_EQ(parseError("Lsystem: 1\nderivation length: M\naxiom: F\n"),
              "test.l:2:20: error: unknown name 'M'");
}

TEST(ParserErrors, BinaryGarbage) {
    std::string bin = "Lsystem: 1\nax\x01\x02\xff";
    EXPECT_EQ(parseError(bin),
              "test.l:2:3: error: this is not L-system text: found a binary byte 0x01 (expected "
              "a .l file in ASCII or UTF-8)");
}

TEST(ParserErrors, ParametersAndExpressions) {
    EXPECT_EQ(parseError("Lsystem: 1\naxiom: A(1)\nA(x) --> A(y)\n"),
              "test.l:3:12: error: unknown name 'y' (not a parameter of this production)");
    EXPECT_EQ(parseError("Lsystem: 1\naxiom: A(1\n"),
              "test.l:2:9: error: unclosed '(': expected ')' to end the parameter list");
    EXPECT_EQ(
        parseError("Lsystem: 1\naxiom: A\nA(1) --> B\n"),
        "test.l:3:3: error: a predecessor names its parameters (e.g. A(x,y)); '1' is not a name");
}

TEST(ParserErrors, NonAsciiModule) {
    EXPECT_EQ(parseError("Lsystem: 1\naxiom: \xCF\x89\n")
                  .rfind("test.l:2:8: error: unexpected character '\xCF\x89'", 0),
              0u);
}

TEST(ParserErrors, ReportsSeveralErrorsInOnePass) {
    try {
        parse("Lsystem: 1\nfoo: 1\naxiom: F\nF F\nbar: 2\n");
        FAIL() << "expected errors";
    } catch (const Error& e) {
        EXPECT_EQ(e.diagnostics().size(), 3u);
    }
}

TEST(ParserErrors, UnterminatedComment) {
    EXPECT_EQ(parseError("Lsystem: 1\naxiom: F /* no end\n"),
              "test.l:2:10: error: unterminated comment: expected '*/' before the end of the file");
}

TEST(ParserErrors, TooManyModuleNamesIsAnErrorWithItsPlace) {
    // Symbols are one byte: 123 multi-letter names fit beside ASCII and ?E ?P ?H ?L ?U.
    std::string names;
    for (int i = 0; i < 123; ++i) names += (i ? ", m" : "module m") + std::to_string(i);
    std::string ok = names + ";\nLsystem: 1\naxiom: m122 F\nendlsystem\n";
    EXPECT_EQ(graftal::testing::parse(ok).symbols.size(), 256u);
    std::string e = parseError(names + ", extra;\nLsystem: 1\naxiom: F\nendlsystem\n");
    EXPECT_NE(e.find("test.l:1:"), std::string::npos) << e;
    EXPECT_NE(e.find("too many module names: at most 123"), std::string::npos) << e;
    e = parseError(names + ";\nLsystem: 1\naxiom: ~leaf\nendlsystem\n");
    EXPECT_NE(e.find("test.l:3:8"), std::string::npos) << e;
    EXPECT_NE(e.find("too many module names"), std::string::npos) << e;
}

// cpfg: R(1)[S(2)]R(2)[S(3)]P(3)T(20,21) (oracle s01_continuation): a line starting with
// a TAB continues the line before it.
TEST(Parser, TabContinuesTheLineBefore) {
    EXPECT_EQ(graftal::testing::derived(
                  "Lsystem: 1\nderivation length: 2\nAxiom: P(1)\n\tQ(2)\n"
                  "P(n) : n < 3 -->\n\tR(n)\n\t[S(n+1)]\n\tP(n+1)\n"
                  "Q(m) : {\n    k = m*10;\n    j = k + 1;\n} * --> T(k,\n\tj)\nendlsystem\n",
                  2),
              "R(1)[S(2)]R(2)[S(3)]P(3)T(20,21)");
    // cpfg rejects a production glued to the one above (oracle s01_tab_joins_lines).
    EXPECT_EQ(graftal::testing::parseError("Lsystem: 1\nAxiom: A B\nA --> X\n\tB --> Y\n"),
              "test.l:4:4: error: a second arrow '-->' in this production (a line starting "
              "with a TAB continues the line before it)");
}

// cpfg: E[E[E[E[E[C]]]]]DE[E[C]]DA (oracle s08_decomposition): `decomposition:` with a
// colon and `no warnings`.
TEST(Parser, DecompositionWithColonAndNoWarnings) {
    EXPECT_EQ(graftal::testing::derived(
                  "Lsystem: 1\nderivation length: 2\nAxiom: A\nA --> B A\n"
                  "decomposition: no warnings\nmaximum depth: 3\nB --> C D\nC --> E [C]\n"
                  "endlsystem\n",
                  2),
              "E[E[E[E[E[C]]]]]DE[E[C]]DA");
}
