// cpfg's ~ is a module of its own followed by the module that names the surface: the
// strings below are what cpfg 6.6 (built from vlab's cpfg/ sources) derives for these
// files, and the surfaces are placed where the turtle is when it reads ~.
#include <gtest/gtest.h>

#include <string>

#include "graftal/turtle/turtle.hpp"
#include "test_helpers.hpp"

namespace {

using graftal::Model;
using graftal::Scene;
using graftal::testing::derived;
using graftal::testing::parse;

Scene drawn(const std::string& text) {
    Model m = graftal::testing::parseModel(text);
    return graftal::interpret(m, graftal::deriveWithQueries(m.lsystem, 0));
}

// vlab's raceme writes its flowers as ~l(0.5,t) and grows them with l(s,t) --> ...:
// cpfg F~l(0.75,1)[~b]; graftal left l(0.5,0) as it was.
TEST(CpfgSurfacePrefix, ProductionsRewriteTheModuleAfterTilde) {
    EXPECT_EQ(derived("Lsystem: 1\nderivation length: 2\nAxiom: A\n"
                      "A --> F~l(0.5,0)[~b]\nl(s,t) --> l(s*1.5,t+1)\nendlsystem\n",
                      2),
              "F~l(0.75,1)[~b]");
}

// cpfg B~l(2)XB~: ~ is the right context of A and the left context of l.
TEST(CpfgSurfacePrefix, TildeIsAModuleInContexts) {
    EXPECT_EQ(derived("Lsystem: 1\nderivation length: 1\nAxiom: A~l(1)XA~\n"
                      "A > ~ --> B\n~ < l(s) --> l(s+1)\nendlsystem\n",
                      1),
              "B~l(2)XB~");
    // cpfg A~l(1): the ~ stands between A and l.
    EXPECT_EQ(derived("Lsystem: 1\nderivation length: 1\nAxiom: A~l(1)\n"
                      "A < l(s) --> l(9)\nendlsystem\n",
                      1),
              "A~l(1)");
    // cpfg A~l(9) once ~ is ignored.
    EXPECT_EQ(derived("Lsystem: 1\nderivation length: 1\nignore: ~\nAxiom: A~l(1)\n"
                      "A < l(s) --> l(9)\nendlsystem\n",
                      1),
              "A~l(9)");
}

TEST(CpfgSurfacePrefix, TildeAndTheNameAreTwoModules) {
    graftal::LSystem ls = parse("Lsystem: 1\nAxiom: ~l(2)~leaf F\nendlsystem\n");
    ASSERT_EQ(ls.axiom.size(), 5u);
    EXPECT_EQ(ls.axiom.symbols()[0], '~');
    EXPECT_EQ(ls.axiom.symbols()[1], 'l');
    EXPECT_EQ(ls.axiom.symbols()[2], '~');
    EXPECT_EQ(ls.symbols.name(ls.axiom.symbols()[3]), "leaf");
    // An undeclared long surface name is one module only after ~: elsewhere its letters
    // stay modules of their own.
    graftal::LSystem letters = parse("Lsystem: 1\nAxiom: ~leaf leaf\nendlsystem\n");
    EXPECT_EQ(letters.axiom.size(), 6u);
    EXPECT_EQ(derived("Lsystem: 1\nAxiom: leaf~leaf(2)\nendlsystem\n", 0), "leaf~leaf(2)");
}

TEST(CpfgSurfacePrefix, TheSurfaceIsNamedByTheNextModuleAndScaledByItsParameter) {
    Scene s = drawn("Lsystem: 1\nAxiom: F~l(0.5,3)F~leaf\nendlsystem\n");
    ASSERT_EQ(s.surfaces.size(), 2u);
    EXPECT_EQ(s.surfaceNames[s.surfaces[0].surface], "l");
    EXPECT_DOUBLE_EQ(s.surfaces[0].origin.y, 1);
    EXPECT_DOUBLE_EQ(s.surfaces[0].scale, 0.5);
    EXPECT_EQ(s.surfaceNames[s.surfaces[1].surface], "leaf");
    EXPECT_DOUBLE_EQ(s.surfaces[1].origin.y, 2);
    EXPECT_DOUBLE_EQ(s.surfaces[1].scale, 1);
    EXPECT_EQ(s.segments.size(), 2u);
}

// A lone ~ before a turtle command or at the end places nothing; the command still acts.
TEST(CpfgSurfacePrefix, ALoneTildeDrawsNothing) {
    Scene s = drawn("Lsystem: 1\nAxiom: F~[+F]~F~\nendlsystem\n");
    EXPECT_TRUE(s.surfaces.empty());
    EXPECT_EQ(s.segments.size(), 3u);
}

}  // namespace
