#include <gtest/gtest.h>

#include <filesystem>
#include <iterator>

#include "engine_paths.hpp"
#include "rewrite/rewriting_engine.hpp"
#include "test_helpers.hpp"

using namespace graftal;
using graftal::testing::derived;
using graftal::testing::parse;

TEST(Derivation, AnabaenaMatchesTheBook) {
    LSystem ls = parse(
        "module ar, al, br, bl;\nLsystem: 1\naxiom: ar\n"
        "ar --> al br\nal --> bl ar\nbr --> ar\nbl --> al\nendlsystem\n");
    EXPECT_EQ(derived(ls, 0), "ar");
    EXPECT_EQ(derived(ls, 1), "albr");
    EXPECT_EQ(derived(ls, 2), "blarar");
    EXPECT_EQ(derived(ls, 3), "alalbralbr");
    EXPECT_EQ(derived(ls, 4), "blarblararblarar");
}

TEST(Derivation, FibonacciWordLengths) {
    LSystem ls = parse("Lsystem: 1\naxiom: b\na --> ab\nb --> a\nendlsystem\n");
    EXPECT_EQ(derived(ls, 5), "abaababa");
    const std::size_t fib[] = {1, 1, 2, 3, 5, 8, 13, 21, 34, 55, 89, 144};
    for (int n = 0; n < 12; ++n) EXPECT_EQ(derive(ls, n).size(), fib[n]) << "n=" << n;
}

TEST(Derivation, KochIslandModuleCounts) {
    LSystem ls = parse("Lsystem: 1\naxiom: F+F+F+F\nF --> F+F-F-FF+F+F-F\nendlsystem\n");
    // modules(n) = 7 + 13 * 4 * (8^n - 1) / 7
    std::size_t expected[] = {7, 59, 475, 3803, 30427, 243419};
    for (int n = 0; n < 6; ++n) EXPECT_EQ(derive(ls, n).size(), expected[n]);
}

TEST(Derivation, EmptySuccessorDeletes) {
    EXPECT_EQ(derived("Lsystem: 1\naxiom: ABAB\nA --> *\nendlsystem\n", 1), "BB");
}

TEST(Derivation, FirstApplicableProductionInFileOrderWins) {
    EXPECT_EQ(derived("Lsystem: 1\naxiom: A\nA --> B\nA --> C\nendlsystem\n", 1), "B");
}

TEST(Derivation, HormoneDiffusionMatchesTheBook) {
    LSystem ls = parse("Lsystem: 1\naxiom: baaaaaaaa\nb < a --> b\nendlsystem\n");
    EXPECT_EQ(derived(ls, 1), "bbaaaaaaa");
    EXPECT_EQ(derived(ls, 2), "bbbaaaaaa");
    EXPECT_EQ(derived(ls, 3), "bbbbaaaaa");
    EXPECT_EQ(derived(ls, 4), "bbbbbaaaa");
}

TEST(Derivation, PfgMultiModulePredecessorReplacesTheWholeSubword) {
    LSystem ls = parse("axiom: ABCDEFG\nAB < CDE > FG --> A[B]A\n");
    EXPECT_EQ(derived(ls, 1), "ABA[B]AFG");
}

TEST(Derivation, ParametersBindFromPredecessorAndBothContexts) {
    LSystem ls = parse(
        "Lsystem: 1\naxiom: A(1)B(2)C(3)\n"
        "A(x) < B(y) > C(z) : y < 4 --> B(x+z)[A(y)]\nendlsystem\n");
    EXPECT_EQ(derived(ls, 1), "A(1)B(4)[A(2)]C(3)");
    EXPECT_EQ(derived(ls, 2), "A(1)B(4)[A(2)]C(3)") << "y=4 fails the condition";
}

TEST(Derivation, LectureNotesParametricSequence) {
    LSystem ls = parse(
        "Lsystem: 1\naxiom: A(0)\n"
        "A(i) : i < 3 --> F[-L]FA(i+1)\n"
        "A(i) : i == 3 --> FB\nendlsystem\n");
    EXPECT_EQ(derived(ls, 1), "F[-L]FA(1)");
    EXPECT_EQ(derived(ls, 4), "F[-L]FF[-L]FF[-L]FFB");
}

TEST(Derivation, RunTimeModuloByZeroNamesModuleAndStep) {
    LSystem ls = parse("Lsystem: 1\naxiom: A(2)\nA(x) --> A(x-1)B(1%(x-1))\nendlsystem\n");
    try {
        derive(ls, 3);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        std::string m = e.diagnostics().front().toString();
        EXPECT_NE(m.find("test.l:3:"), std::string::npos) << m;
        EXPECT_NE(m.find("modulo by zero"), std::string::npos) << m;
        EXPECT_NE(m.find("'A(1)' in derivation step 2"), std::string::npos) << m;
    }
}

// The first error of deriving `text` for `steps` steps. (x/0 is 1, as in cpfg; x%0 is an
// error.)
Diagnostic runTimeError(const std::string& text, int steps) {
    LSystem ls = parse(text);
    try {
        derive(ls, steps);
    } catch (const Error& e) {
        return e.diagnostics().front();
    }
    ADD_FAILURE() << "expected an error";
    return {};
}

TEST(Derivation, RunTimeErrorInASuccessorCarriesTheProductionsSpan) {
    Diagnostic d =
        runTimeError("Lsystem: 1\naxiom: A(2)\nA(x) --> A(x-1)B(1%(x-1))\nendlsystem\n", 3);
    EXPECT_EQ(d.toString(),
              "test.l:3:1: error: modulo by zero in '1%(x-1)' (while rewriting module 0 "
              "'A(1)' in derivation step 2)");
    EXPECT_EQ(d.location.endLine, 3);
    EXPECT_EQ(d.location.endColumn, 26) << "just past 'A(x) --> A(x-1)B(1%(x-1))'";
}

TEST(Derivation, RunTimeErrorInAConditionNamesItsProductionNotTheFirstCandidate) {
    Diagnostic d = runTimeError(
        "Lsystem: 1\naxiom: F A(3)\nA(x) : x > 5 --> B\n  A(x) : (x-1)%(x-2) >= 0 --> A(x-1)\n"
        "endlsystem\n",
        3);
    EXPECT_EQ(d.toString(),
              "test.l:4:3: error: modulo by zero in '(x-1)%(x-2) >= 0' (while rewriting module 1 "
              "'A(2)' in derivation step 2)");
    EXPECT_EQ(d.location.endLine, 4);
    EXPECT_EQ(d.location.endColumn, 37);
}

TEST(Derivation, RunTimeErrorInADecompositionNamesItsProduction) {
    Diagnostic d = runTimeError(
        "Lsystem: 1\naxiom: C(1)\nC(x) --> C(x-1)A(x-1)\ndecomposition\nA(x) --> B(1%x)\n"
        "endlsystem\n",
        1);
    EXPECT_EQ(d.location.line, 5);
    EXPECT_EQ(d.location.column, 1);
    EXPECT_EQ(d.location.endColumn, 16);
    EXPECT_NE(d.message.find("'A(0)' in derivation step 1"), std::string::npos) << d.message;
}

TEST(Derivation, MemoryLimitRefusesBeforeAllocating) {
    LSystem ls = parse("Lsystem: 1\naxiom: F\nF --> FFFFFFFFFF\nendlsystem\n");
    DerivationOptions o;
    o.memoryLimit = 1 << 20;
    Derivation d(ls, o);
    d.run(5);  // 100000 modules: fits
    EXPECT_EQ(d.current().size(), 100000u);
    try {
        d.step();
        FAIL() << "expected the limit to refuse step 6";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("1000000 modules"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("memory limit"), std::string::npos) << e.what();
    }
    EXPECT_EQ(d.current().size(), 100000u) << "a refused step leaves the string as it was";
}

// The context path notes its choices over the string it rewrites: a step the limit refuses
// must give the string back as it was, module for module, also on several threads.
TEST(Derivation, ARefusedContextStepLeavesTheStringAsItWas) {
    LSystem ls = parse(
        "Lsystem: 1\naxiom: A[B]AB\nignore: +\nA < B --> [+A]B\nB > A --> AB\n"
        "A --> BA\nendlsystem\n");
    for (unsigned threads : {1u, 3u}) {
        DerivationOptions o;
        o.threads = threads;
        Derivation grown(ls, o);
        int steps = 0;
        while (grown.current().size() < 300000) {
            grown.step();
            ++steps;
        }
        const ModuleString before = grown.current();
        const std::size_t next = derive(ls, steps + 1).size();
        o.memoryLimit = next - 1;  // one byte a module: the next string does not fit
        Derivation d(ls, o);
        d.run(steps);
        ASSERT_TRUE(d.current() == before);
        EXPECT_THROW(d.step(), Error);
        EXPECT_TRUE(d.current() == before) << threads << " threads: the string was changed";
        EXPECT_EQ(d.stepsDone(), steps);
    }
}

TEST(Derivation, SameResultForAnyThreadCount) {
    const char* systems[] = {
        "Lsystem: 1\naxiom: F+F+F+F\nF --> F+F-F-FF+F+F-F\nendlsystem\n",
        // Hogeweg and Hesper's Fig 3.11a: context-sensitive, bracketed
        "Lsystem: 1\nignore: +-F\naxiom: F1F1F1\n0 < 0 > 0 --> 0\n0 < 0 > 1 --> 1[+F1F1]\n"
        "0 < 1 > 0 --> 1\n0 < 1 > 1 --> 1\n1 < 0 > 0 --> 0\n1 < 0 > 1 --> 1F1\n"
        "1 < 1 > 0 --> 0\n1 < 1 > 1 --> 0\n* < + > * --> -\n* < - > * --> +\nendlsystem\n",
        "Lsystem: 1\naxiom: A(1)\nA(x) --> A(x+1)F(x)[+A(x/2)]F(x)\nendlsystem\n",
        "Lsystem: 1\nseed: 7\naxiom: F\nF --> F[+F]F[-F]F : 1\nF --> F[+F]F : 1\n"
        "F --> F[-F]F : 1\nendlsystem\n",
    };
    int steps[] = {5, 42, 14, 8};
    for (int k = 0; k < 4; ++k) {
        LSystem ls = parse(systems[k]);
        DerivationOptions one;
        one.threads = 1;
        ModuleString a = derive(ls, steps[k], one);
        EXPECT_GT(a.size(), 70000u) << "system " << k << " must be large enough to be split";
        for (unsigned threads : {2u, 7u}) {
            DerivationOptions many;
            many.threads = threads;
            EXPECT_TRUE(a == derive(ls, steps[k], many)) << "system " << k << ", " << threads;
        }
    }
}

// ---- parametric steps: the quick choice and direct binding against the generic path ----

namespace {

// The axiom rewritten by the engine and by the generic path alone (choose() and matches()
// for every module), at 1 and 3 threads: the same modules and doubles after every step.
void expectParametricSameAsGenericPath(const LSystem& ls, int steps, const std::string& what) {
    ModuleString start = ls.axiom;
    if (!start.hasParameters()) start.rawParamStart().assign(start.size() + 1, 0);
    graftal::testing::expectSameAsGenericPath(ls, start, steps, what, {1u, 3u});
}

}  // namespace

TEST(Derivation, ParametricStepsAgreeWithTheGenericPath) {
    LSystem honda =
        loadLSystem(std::filesystem::path(GRAFTAL_EXAMPLES_DIR) / "honda-monopodial-tree.l");
    expectParametricSameAsGenericPath(honda, 15, "Honda");
    const char* systems[] = {
        // productions told apart by their number of parameters, and copies in between
        "Lsystem: 1\naxiom: A(1)F(2)A(1,2)B[A(3)]\nA(x) --> A(x+1)F(x)[+A(x/2,x)]F(x)\n"
        "A(x,y) --> B(x*y)A(y-x)\nB(x) --> B(x)\nB --> A(1)\nendlsystem\n",
        // conditions, ran(), a context and a stochastic choice among parametric productions
        "Lsystem: 1\nseed: 5\naxiom: A(1)B(3)A(5)C\nA(x) < B(y) > A(z) : y < 40 --> "
        "B(x+z)[A(y)]\nA(x) : x > 3 --> A(x-ran(2))C\nA(x) --> A(x+1) : 0.4\n"
        "A(x) --> B(x-1)A(x) : 0.6\nC --> CA(2)\nendlsystem\n",
        // the first of several productions with the same predecessor wins
        "Lsystem: 1\naxiom: A(1)BA(2)\nA(x) --> B(x)A(x+1)\nA(x) --> C(x*2)\nB --> BA(0)\n"
        "B --> D\nendlsystem\n",
        // pfg's multi-module predecessors next to parametric modules
        "Lsystem: 1\naxiom: A(1)BC(2)\nA(x) --> A(x*2)B\nB C(y) --> C(y+1)B\nendlsystem\n",
    };
    int k = 0;
    for (const char* text : systems)
        expectParametricSameAsGenericPath(parse(text), 12, "system " + std::to_string(k++));
}

TEST(Derivation, SimpleArgumentsGiveTheSameDoublesAsTheirPrograms) {
    LSystem ls = parse(
        "Lsystem: 1\naxiom: A(0.7,-2)\nA(x,y) --> B(x+1.5, 2-x, x*0.1, x/3, 3/x, y, 7, "
        "1.5+x, 2*x, x-0.1, 0.1-y)\nendlsystem\n");
    DerivationOptions doubles;  // the doubles as computed, not rounded to floats
    doubles.precision = Precision::Double;
    ModuleString s = derive(ls, 1, doubles);
    const double x = 0.7, y = -2;
    const double expected[] = {x + 1.5, 2 - x,   x * 0.1, x / 3,   3 / x,  y,
                               7,       1.5 + x, 2 * x,   x - 0.1, 0.1 - y};
    auto got = s.params(0);
    ASSERT_EQ(got.size(), std::size(expected));
    for (std::size_t i = 0; i < got.size(); ++i) EXPECT_EQ(got[i], expected[i]) << "argument " << i;
}

// cpfg divides by 1 instead (oracle s06_math: K(1/0) is K(1)), on every engine path.
TEST(Derivation, DivisionByZeroDividesByOne) {
    EXPECT_EQ(derived("Lsystem: 1\naxiom: A(3)\nA(x) --> B(x/0)\nendlsystem\n", 1), "B(3)");
    EXPECT_EQ(derived("Lsystem: 1\naxiom: A(2)\nA(x) --> A(x-1)B(6/(x-1))\nendlsystem\n", 2),
              "A(0)B(6)B(6)");
}
