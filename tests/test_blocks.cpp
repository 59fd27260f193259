// Statement blocks, variables and printf, as cpfg runs them. The expected strings are
// what cpfg 6600 printed for the same files (the oracle cases named in each test).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "test_helpers.hpp"

using namespace graftal;
using graftal::testing::derived;
using graftal::testing::parse;
using graftal::testing::parseError;

namespace {

// Derives with `threads` threads and collects what printf wrote.
std::string deriveWith(const LSystem& ls, unsigned threads, std::string* printed = nullptr) {
    DerivationOptions o;
    o.threads = threads;
    std::string out;
    o.print = [&out](std::string_view text) { out += text; };
    std::string s = derive(ls, -1, o).toString(ls.symbols);
    if (printed) *printed = out;
    return s;
}

}  // namespace

// cpfg: C(1,100)B(5)B(7) (oracle s03_blocks).
TEST(Blocks, PreBlockConditionPostBlock) {
    LSystem ls = parse(
        "Lsystem: 1\nderivation length: 1\nAxiom: A(1) A(2) A(3)\n"
        "A(x) : { y = x*2; } y > 3 { z = y+1; } --> B(z)\n"
        "A(x) : * { w = x*100; } --> C(x,w)\nendlsystem\n");
    EXPECT_EQ(deriveWith(ls, 1), "C(1,100)B(5)B(7)");
}

// cpfg: S(10,1,5)S(3,2,3)D(6,60)D(10,90) (oracle s03_control_flow).
TEST(Blocks, IfElseWhileDoWhileOverSeveralLines) {
    LSystem ls = parse(
        "Lsystem: 1\nderivation length: 1\nAxiom: S(4) S(2) D(5) D(9)\n"
        "S(n) : {\n    s = 0;\n    i = 1;\n    while (i <= n) {\n        s = s + i;\n"
        "        i = i + 1;\n    }\n    if (s > 5) {\n        t = 1;\n    } else {\n"
        "        t = 2;\n    }\n} * --> S(s,t,i)\n"
        "D(n) : {\n    k = 0;\n    do {\n        k = k + 2;\n    } while (k < n);\n"
        "    if (k == 6) { u = 60; } else { if (k > 9) { u = 90; } else { u = 70; } }\n"
        "} * --> D(k,u)\nendlsystem\n");
    EXPECT_EQ(deriveWith(ls, 1), "S(10,1,5)S(3,2,3)D(6,60)D(10,90)");
}

// cpfg: A(11)D(1)A(22)D(2)B(22)E(5)E(6) (oracle s03_eval_order). Globals written while
// rewriting one module are seen by the modules to its right; a production's own variables
// keep their values between applications and steps; the result is the same for any
// number of threads.
TEST(Blocks, StringOrderAndPersistentVariablesForAnyThreadCount) {
    LSystem ls = parse(
        "Lsystem: 1\nderivation length: 3\nStart: { g = 0; }\nAxiom: A A B E(0) E(0)\n"
        "A : { g = g + 1; } g > 100 --> X\nA : * { g = g + 10; } --> A(g) C\n"
        "B --> B(g)\nC : { c = c + 1; } * --> D(c)\nE(k) : { e = e + 1; } * --> E(e)\n"
        "endlsystem\n");
    for (unsigned threads : {1u, 2u, 7u})
        EXPECT_EQ(deriveWith(ls, threads), "A(11)D(1)A(22)D(2)B(22)E(5)E(6)") << threads;
}

// The same with a string long enough for the parallel paths to split it: every module
// numbers itself from a global counter, so any reordering shows.
TEST(Blocks, GlobalCounterOverALongStringIsThreadCountIndependent) {
    LSystem ls = parse(
        "Lsystem: 1\nderivation length: 17\nStart: { n = 0; }\nAxiom: A(0)\n"
        "A(x) : * { n = n + 1; } --> A(n) A(x)\nendlsystem\n");
    std::string one = deriveWith(ls, 1);
    // The first module of step k is the 2^(k-1)-th application; the second is the first
    // module of step k - 1, unchanged.
    EXPECT_EQ(one.substr(0, 16), "A(65536)A(32768)");
    for (unsigned threads : {2u, 7u}) EXPECT_EQ(deriveWith(ls, threads), one) << threads;
}

// cpfg: XB(111) (oracle s03_stochastic_blocks): in a stochastic group every candidate's
// pre block runs, even one whose condition is false.
TEST(Blocks, StochasticGroupRunsEveryPreBlock) {
    LSystem ls = parse(
        "Lsystem: 1\nseed: 3\nderivation length: 1\nStart: { g = 0; }\nAxiom: A B\n"
        "A : { g = g + 1; } * --> X : 1\nA : { g = g + 10; } * --> Y : 0\n"
        "A : { g = g + 100; } 0 --> Z : 1\nB --> B(g)\nendlsystem\n");
    EXPECT_EQ(deriveWith(ls, 1), "XB(111)");
}

// cpfg: B(1,0)B(2,1)C(2,3,3,0) and the printed lines of oracle s04_global_blocks.
TEST(Blocks, StartStartEachEndEachEnd) {
    LSystem ls = parse(
        "Lsystem: 1\nderivation length: 4\n"
        "Start: { steps = 0; total = 0; ends = 0; printf(\"start\\n\"); }\n"
        "StartEach: { steps = steps + 1; printf(\"starteach %g\\n\", steps); }\n"
        "EndEach: { total = total + steps; printf(\"endeach %g %g\\n\", steps, total); }\n"
        "End: { ends = ends + 1; printf(\"end %g %g\\n\", total, ends); }\n"
        "Axiom: A(steps)\nA(n) : steps < 3 --> B(steps,total) A(n+1)\n"
        "A(n) : steps >= 3 --> C(n,steps,total,ends)\nendlsystem\n");
    std::string printed;
    EXPECT_EQ(deriveWith(ls, 2, &printed), "B(1,0)B(2,1)C(2,3,3,0)");
    EXPECT_EQ(printed,
              "start\nstarteach 1\nendeach 1 1\nstarteach 2\nendeach 2 3\nstarteach 3\n"
              "endeach 3 6\nstarteach 4\nendeach 4 10\nend 10 1\n");
}

// cpfg: A(7), printing only "start 7" (oracle s04_global_blocks_n0): Start: runs before
// the axiom's parameters are evaluated; no step, no End:.
TEST(Blocks, StartRunsBeforeTheAxiomAndEndNeedsAStep) {
    LSystem ls = parse(
        "Lsystem: 1\nderivation length: 0\nStart: { steps = 7; printf(\"start %g\\n\", steps); }\n"
        "End: { printf(\"end\\n\"); }\nAxiom: A(steps)\nA(n) --> B(steps)\nendlsystem\n");
    std::string printed;
    EXPECT_EQ(deriveWith(ls, 1, &printed), "A(7)");
    EXPECT_EQ(printed, "start 7\n");
}

// cpfg: S(3)W(2,3)W(1,3)W(0,3)T (oracle s04_step_globals).
TEST(Blocks, QIsTheStepAndZTheDerivationLength) {
    EXPECT_EQ(derived("Lsystem: 1\nderivation length: 3\nAxiom: S(0) T\n"
                      "S(k) --> S(Q) W(k,Z)\nendlsystem\n",
                      3),
              "S(3)W(2,3)W(1,3)W(0,3)T");
}

// cpfg printed these lines and A(4)P(0)P(0) (oracle s06_printf).
TEST(Blocks, PrintfFormatsAndGivesZero) {
    LSystem ls = parse(
        "Lsystem: 1\nderivation length: 2\nStart: { printf(\"start %g %g\\n\", 1.5, 2); }\n"
        "End: { printf(\"done\\n\"); }\nAxiom: A(1)\n"
        "A(x) : { printf(\"A(%g) at step %g\\n\", x, Q); } * --> A(x*2) "
        "P(printf(\"in param %.3f|%5.1f|%%\\t%g\\n\", x/3, x, -x))\nendlsystem\n");
    std::string printed;
    EXPECT_EQ(deriveWith(ls, 1, &printed), "A(4)P(0)P(0)");
    EXPECT_EQ(printed,
              "start 1.5 2\nA(1) at step 1\nin param 0.333|  1.0|%\t-1\nA(2) at step 2\n"
              "in param 0.667|  2.0|%\t-2\ndone\n");
}

TEST(Blocks, TernaryAndDiamondNotEqual) {
    EXPECT_EQ(derived("Lsystem: 1\nAxiom: A\nA --> B(3 > 2 ? 10 : 20, 2 <> 3, 2 <> 2)\n"
                      "endlsystem\n",
                      1),
              "B(10,1,0)");
}

TEST(Blocks, ErrorsNameTheConstructAndItsPlace) {
    EXPECT_EQ(parseError("Lsystem: 1\nAxiom: A\nA : {\n  y = 1;\n  while (y < 3 {\n"
                         "} * --> B\nendlsystem\n"),
              "test.l:3:5: error: expected '}' to close this block");
    EXPECT_EQ(parseError("Lsystem: 1\nAxiom: A\nA : {\n  y = 1;\n  while (y < 3 { }\n"
                         "} * --> B\nendlsystem\n"),
              "test.l:5:9: error: expected ')' to close the condition");
    EXPECT_EQ(parseError("Lsystem: 1\nStart: { y = 1 }\nAxiom: A\nA --> B\nendlsystem\n"),
              "test.l:2:10: error: expected ';' after the statement");
    EXPECT_EQ(parseError("Lsystem: 1\nStart: { for (;;) {} }\nAxiom: A\nA --> B\n"),
              "test.l:2:10: error: 'for' statements are not supported yet");
    EXPECT_EQ(parseError("Lsystem: 1\nStart: { f = fopen(\"out.txt\", \"r\"); }\nAxiom: A\n"),
              "test.l:2:31: error: fopen() opens files for writing: mode \"w\" or \"a\"");
}

// A loop that never ends is stopped with an error naming its condition.
TEST(Blocks, EndlessLoopIsAnError) {
    LSystem ls = parse(
        "Lsystem: 1\nStart: { i = 0; while (i >= 0) { i = i + 1; } }\n"
        "Axiom: A\nendlsystem\n");
    try {
        deriveWith(ls, 1);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(e.diagnostics().front().toString().find("i >= 0"), std::string::npos);
    }
}

// cpfg: L(1.5)M(4,10)L(2)M(5,20)L(2.5)M(6,30)K(30,2,1.5,30) and two warnings (oracle
// s05_arrays): row-major initial values, element assignment in Start: and in a block,
// truncated and clamped subscripts.
TEST(Blocks, GlobalArrays) {
    LSystem ls = parse(
        "Lsystem: 1\nderivation length: 4\ndefine: {\n"
        "    array len[4] = { 1.5, 2, 2.5, 3 },\n          m[2][3] = { 1, 2, 3,\n"
        "                      4, 5, 6 };\n}\nStart: {\n    len[3] = 30;\n}\nAxiom: A(0)\n"
        "A(i) : i < 3 { m[0][i] = m[0][i] * 10; } --> L(len[i]) M(m[1][i], m[0][i]) A(i+1)\n"
        "A(i) : i >= 3 --> K(len[i], len[1.7], len[-2], len[9])\nendlsystem\n");
    std::string printed;
    EXPECT_EQ(deriveWith(ls, 7, &printed), "L(1.5)M(4,10)L(2)M(5,20)L(2.5)M(6,30)K(30,2,1.5,30)");
    EXPECT_EQ(printed,
              "test.l:13:39: warning: subscript 1 of len is -2, out of range; using 0\n"
              "test.l:13:48: warning: subscript 1 of len is 9, out of range; using 3\n");
}

TEST(Blocks, ArrayErrorsNameTheirPlace) {
    EXPECT_EQ(parseError("Lsystem: 1\ndefine: { array a[0]; }\nAxiom: A\n"),
              "test.l:2:19: error: an array dimension is a whole number from 1 (at most "
              "10000000 elements in all)");
    EXPECT_EQ(parseError("Lsystem: 1\ndefine: { array a[2] = { 1, 2, 3 }; }\nAxiom: A\n"),
              "test.l:2:32: error: more initial values than 'a' has elements");
    EXPECT_EQ(parseError("Lsystem: 1\ndefine: { array a[2]; }\nAxiom: A\nA --> B(a[1][0])\n"),
              "test.l:4:13: error: 'a' has only 1 dimensions");
}

// cpfg: R(0,1,1)N(0)B(1)I(1,1)S(0,1) (oracle s06_random): only properties of the numbers
// are compared, they differ between implementations.
TEST(Blocks, RandomBuiltIns) {
    LSystem ls = parse(
        "Lsystem: 1\nseed: 7\nderivation length: 1\nAxiom: A\n"
        "A : {\n    r = ran(5);\n    n = nran(10,2);\n    b = bran(2,3);\n"
        "    i = biran(6,0.5);\n} * --> R(r*0, r >= 0 && r < 5, ran(1) != ran(1))\n"
        "\tN(n*0)\n\tB(b >= 0 && b <= 1)\n\tI(i == floor(i), i >= 0 && i <= 6)\n"
        "\tS(srand(3), srand(3) + ran(1) == srand(3) + ran(1))\nendlsystem\n");
    EXPECT_EQ(deriveWith(ls, 1), "R(0,1,1)N(0)B(1)I(1,1)S(0,1)");
}

// Productions that only read a global (written between steps by StartEach:) keep the
// parallel paths; the string is the same for any thread count.
TEST(Blocks, GlobalsReadByProductionsStayParallelAndDeterministic) {
    LSystem ls = parse(
        "Lsystem: 1\nderivation length: 17\nStart: { g = 0; }\nStartEach: { g = g + 1; }\n"
        "Axiom: A(0)\nA(x) : x < g --> A(g) B(x)\nB(x) --> B(x + g) B(x)\nendlsystem\n");
    std::string one = deriveWith(ls, 1);
    // 2^17 modules, enough for the step to be split between threads.
    EXPECT_EQ(one.substr(0, 20), "A(17)B(16)B(32)B(15)");
    for (unsigned threads : {2u, 7u}) EXPECT_EQ(deriveWith(ls, threads), one) << threads;
}

// fopen/fprintf/fclose write files in the model's folder (cpfg's file output).
TEST(Blocks, FprintfWritesAFileBesideTheModel) {
    namespace fs = std::filesystem;
    fs::path dir = fs::temp_directory_path() / "graftal-blocks-fprintf";
    fs::remove_all(dir);
    fs::create_directories(dir);
    {
        std::ofstream l(dir / "m.l");
        l << "Lsystem: 1\nderivation length: 2\nStart: { f = fopen(\"log.txt\", \"w\"); }\n"
             "End: { fprintf(f, \"end %g\\n\", Q); fclose(f); }\nAxiom: A(1)\n"
             "A(x) : { fprintf(f, \"A(%g)\\n\", x); fflush(f); } * --> A(x+1)\nendlsystem\n";
    }
    LSystem ls = loadLSystem(dir / "m.l");
    EXPECT_EQ(derive(ls).toString(ls.symbols), "A(3)");
    std::ifstream in(dir / "log.txt");
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_EQ(text.str(), "A(1)\nA(2)\nend 2\n");
    fs::remove_all(dir);
}

TEST(Blocks, FopenOutsideTheModelFolderIsRefused) {
    LSystem ls = parse(
        "Lsystem: 1\nStart: { f = fopen(\"/tmp/../etc/graftal-test.txt\", \"w\"); }\n"
        "Axiom: A\nendlsystem\n");
    try {
        derive(ls, 0);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_EQ(e.diagnostics().front().toString(),
                  "test.l:2:14: error: fopen(\"/tmp/../etc/graftal-test.txt\"): a model may only "
                  "write files inside its own folder or the working directory");
    }
}
