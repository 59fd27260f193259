// What cpfg accepts in its models and graftal now reads the same way: one-letter surface
// names after ~, lines starting with the turtle's #(w) in a continued successor, stop() in
// a block, a predecessor that is a whole branch, model folders described by vlab's
// `specifications` file. The models are our own; the expected strings follow cpfg's
// reading of each construct (cpfg/lsys_input.l and .y, generate.c).
#include <gtest/gtest.h>

#include <string>

#include "graftal/lang/vlab_specifications.hpp"
#include "process.hpp"
#include "test_helpers.hpp"

using namespace graftal;
using namespace graftal::testing;

namespace {

std::string messages(const std::vector<Diagnostic>& ds) {
    std::string s;
    for (const auto& d : ds) s += d.toString() + "\n";
    return s;
}

std::string derivedFrom(const ParseResult& r, int steps = -1) {
    const Model m = ParseResult(r).orThrow();
    return deriveWithQueries(m.lsystem, steps).toString(m.lsystem.symbols);
}

}  // namespace

// cpfg reads one character after ~: with `surface: L ...` in the view file, ~LF is the
// surface L, then a segment F.
TEST(CpfgModels, AOneLetterSurfaceIsFollowedByTheNextModule) {
    const std::string l = "Lsystem: 1\nderivation length: 1\nAxiom: A\nA --> F~LF~Lx\nendlsystem\n";
    ParseResult withSurface = parse(l, "surface: L leaf.s 2\n", "m.v", ParseOptions{});
    ASSERT_TRUE(withSurface.ok()) << messages(withSurface.diagnostics);
    const LSystem& ls = withSurface.model.lsystem;
    ASSERT_EQ(ls.productions.size(), 1u);
    const auto& succ = ls.productions[0].successor;
    ASSERT_EQ(succ.size(), 7u) << "F ~ L F ~ L x";
    EXPECT_EQ(succ[1].symbol, '~');
    EXPECT_EQ(succ[2].symbol, 'L');
    EXPECT_EQ(succ[3].symbol, 'F');
    EXPECT_EQ(succ[5].symbol, 'L');
    EXPECT_EQ(succ[6].symbol, 'x');

    // A surface declared in the .l before the production counts too.
    LSystem inL = parse("Lsystem: 1\nsurface: L leaf.s 2\nAxiom: ~LF\nendlsystem\n");
    ASSERT_EQ(inL.axiom.size(), 3u);
    EXPECT_EQ(inL.axiom.symbols()[2], 'F');

    // Without such a surface a longer name after ~ stays graftal's one module.
    ParseResult without = parse(l, "angle increment: 30\n", "m.v", ParseOptions{});
    ASSERT_TRUE(without.ok());
    EXPECT_EQ(without.model.lsystem.productions[0].successor.size(), 5u) << "F ~ LF ~ Lx";
}

// A line of a continued successor may start with the turtle's #(w): cpfg's preprocessor
// passes it through, and so does graftal's (it is no directive).
TEST(CpfgModels, ALineStartingWithTheWidthModulePassesThePreprocessor) {
    const std::string text =
        "#define W 0.5\n"
        "Lsystem: 1\nderivation length: 1\nAxiom: A\n"
        "A --> F(1)\n"
        "\t#(W)F(2) #F\n"
        "\t#(0.06)\tf(0.1)\n"
        "endlsystem\n";
    EXPECT_EQ(derived(text, 1), "F(1)#(0.5)F(2)#F#(0.06)f(0.1)");
}

// cpfg's stop(x) stops its animation; in a derivation it is x and does nothing else.
TEST(CpfgModels, StopInABlockIsAccepted) {
    const std::string text =
        "Lsystem: 1\nderivation length: 3\nStart: {d = 0;}\n"
        "EndEach: {d = d + 1; if (d == 2) {stop(1);}}\n"
        "Axiom: A(0)\nA(x) --> A(x + 1 + stop(0))\nendlsystem\n";
    EXPECT_EQ(derived(text, 3), "A(3)");
}

// A predecessor may be a whole branch, brackets included: it is replaced as a whole.
TEST(CpfgModels, APredecessorThatIsAWholeBranch) {
    const std::string text =
        "Lsystem: 1\nderivation length: 1\n"
        "Axiom: A[f(1)-f(2)P(3)]B[f(1)-f(2)P(0)]\n"
        "[f(y)-f(z)P(r)] : r == 0 --> *\n"
        "endlsystem\n";
    EXPECT_EQ(derived(text, 1), "A[f(1)-f(2)P(3)]B");
}

TEST(CpfgModels, TheSpecificationsCpfgCommandNamesTheFiles) {
    const auto c = cpfgCommandOf(
        "plant.l\npanel.l\nplant.v\nignore:\n*\nmodel:\n\tgenerate:\n"
        "\t\tcpfg -w 300 500 -M plant.mat -e plant.e plant.l plant.v plant.a\n"
        "\tother:\n\t\tcpfg other.l other.v\n");
    ASSERT_TRUE(c.has_value());
    EXPECT_EQ(c->lFile, "plant.l");
    EXPECT_EQ(c->viewFile, "plant.v");
    EXPECT_EQ(c->materials, "plant.mat");
    EXPECT_EQ(c->environment, "plant.e");
    EXPECT_FALSE(cpfgCommandOf("plant.l\nignore:\n*\nL-system:\n\tEDIT plant.l\n").has_value());
}

// `graftal derive FOLDER` on a vlab folder with several .l and .v files: its
// specifications say which make the model.
TEST(CpfgModels, AFolderIsReadAsItsSpecificationsSay) {
    TempDir dir;
    dir.write("panel.l", "this is a control panel, not an L-system\n");
    dir.write("plant.l", "Lsystem: 1\nderivation length: 1\nAxiom: A\nA --> F+F\nendlsystem\n");
    dir.write("other.v", "angle increment: 10\n");
    dir.write("plant.v", "angle increment: 45\n");
    dir.write("plant.map", std::string(768, '\0'));
    dir.write("specifications",
              "plant.l\npanel.l\nplant.v\nother.v\nignore:\n*\nmodel:\n\tgenerate:\n"
              "\t\tcpfg -m plant.map plant.l plant.v plant.a\n");
    ParseResult r = loadModel(dir.path());
    ASSERT_TRUE(r.ok()) << messages(r.diagnostics);
    EXPECT_EQ(r.model.view.turtle.angleDegrees, 45);
    EXPECT_EQ(derivedFrom(r), "F+F");
    EXPECT_EQ(r.model.view.materials.colorMap, "plant.map");

    // The command line works the same way.
    RunResult p = runGraftal("derive '" + dir.path().string() + "'");
    EXPECT_EQ(p.status, 0) << p.err;
    EXPECT_EQ(p.out, "F+F\n");
}

// cpfg's lexer passes over a backslash in an expression: a macro continued with `\\` keeps
// one in its body, and a block's line may end with one.
TEST(CpfgModels, ABackslashInAnExpressionOrABlockIsPassedOver) {
    const std::string text =
        "#define twice(x) \\\\\n"
        "\t(2 * (x))\n"
        "Lsystem: 1\nderivation length: 1\nAxiom: A(1)\n"
        "A(x) : {y = twice(x) + \\\n"
        "\t1;} --> B(y, twice(3))\n"
        "endlsystem\n";
    EXPECT_EQ(derived(text, 1), "B(3,6)");
}

// cpfg preprocesses the L-system with -DNAME=i for the i-th item of the view file's
// function set, so models call func(NAME, t); a gallery file begins `funcgalleryver 1 1`.
TEST(CpfgModels, FunctionSetItemsAreCalledByName) {
    TempDir dir;
    dir.write("shapes.fset",
              "funcgalleryver 1 1\nitems: 2\n"
              "fver 1 1\nname: RISE\nsamples: 0\nflip: off\npoints: 4\n"
              "0.000000 0.000000\n0.333333 0.333333\n0.666667 0.666667\n1.000000 1.000000\n"
              "fver 1 1\nname: FLAT.func\nsamples: 0\nflip: off\npoints: 4\n"
              "0.000000 2.000000\n0.333333 2.000000\n0.666667 2.000000\n1.000000 2.000000\n");
    dir.write("m.v", "angle increment: 30\nfunction set: shapes.fset\n");
    dir.write("m.l",
              "#define OWN 7\n"
              "Lsystem: 1\nderivation length: 1\nAxiom: A\n"
              "A --> B(RISE, FLAT, OWN, func(FLAT, 0.5), func(RISE, 0.5))\nendlsystem\n");
    ParseResult r = loadModel(dir.path());
    ASSERT_TRUE(r.ok()) << messages(r.diagnostics);
    EXPECT_EQ(derivedFrom(r), "B(1,2,7,2,0.5)");
}

// A right context may leave a branch open: `A > [B` asks only how the next branch begins.
TEST(CpfgModels, ARightContextMayLeaveABranchOpen) {
    EXPECT_EQ(derived("Lsystem: 1\nderivation length: 1\nAxiom: A[BC]A[CB]\n"
                      "A > [B --> X\nendlsystem\n",
                      1),
              "X[BC]A[CB]");
}
