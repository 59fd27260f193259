#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <random>

#include "engine_paths.hpp"
#include "rewrite/rewriting_engine.hpp"
#include "test_helpers.hpp"

using namespace graftal;
using graftal::testing::derived;
using graftal::testing::parse;

TEST(Context, BookExampleLeftContextOfGIsD) {
    EXPECT_EQ(derived("Lsystem: 1\naxiom: ABCD[EF][G[HI[JKL]M]NOPQ]\nD < G --> X\nendlsystem\n", 1),
              "ABCD[EF][X[HI[JKL]M]NOPQ]");
    EXPECT_EQ(derived("Lsystem: 1\naxiom: ABCD[EF][G[HI[JKL]M]NOPQ]\nF < G --> X\nendlsystem\n", 1),
              "ABCD[EF][G[HI[JKL]M]NOPQ]")
        << "a sibling branch is not context";
}

TEST(Context, BookExampleRightContextOfGIsN) {
    EXPECT_EQ(derived("Lsystem: 1\naxiom: ABCD[EF][G[HI[JKL]M]NOPQ]\nG > N --> X\nendlsystem\n", 1),
              "ABCD[EF][X[HI[JKL]M]NOPQ]");
    EXPECT_EQ(derived("Lsystem: 1\naxiom: ABCD[EF][G[HI[JKL]M]NOPQ]\nG > H --> X\nendlsystem\n", 1),
              "ABCD[EF][G[HI[JKL]M]NOPQ]")
        << "a lateral branch is not on the axis";
}

TEST(Context, RightContextFailsAtTheEndOfTheBranch) {
    EXPECT_EQ(derived("Lsystem: 1\naxiom: A[B]C\nB > C --> X\nendlsystem\n", 1), "A[B]C");
}

TEST(Context, LeftContextEntersTheParentAtTheBracket) {
    EXPECT_EQ(derived("Lsystem: 1\naxiom: A[B[C]D]\nA < D --> X\nB < C --> Y\nendlsystem\n", 1),
              "A[B[Y]D]")
        << "D's parent axis is B...A; B is the nearest, so A < D fails";
    EXPECT_EQ(derived("Lsystem: 1\naxiom: A[B[C]D]\nB < D --> X\nendlsystem\n", 1), "A[B[C]X]");
}

TEST(Context, IgnoredSymbolsAreSkippedBothWays) {
    EXPECT_EQ(
        derived("Lsystem: 1\nignore: +-F\naxiom: A+F-B-F+C\nA < B > C --> X\nendlsystem\n", 1),
        "A+F-X-F+C");
    EXPECT_EQ(derived("Lsystem: 1\naxiom: A+B\nA < B --> X\nendlsystem\n", 1), "A+B");
}

TEST(Context, ConsiderListsTheOnlySymbolsThatCount) {
    EXPECT_EQ(derived("Lsystem: 1\nconsider: AB\naxiom: AxyzB\nA < B --> X\nendlsystem\n", 1),
              "AxyzX");
}

TEST(Context, MultiModuleContexts) {
    EXPECT_EQ(derived("Lsystem: 1\naxiom: ABCDE\nAB < C > DE --> X\nendlsystem\n", 1), "ABXDE");
    EXPECT_EQ(derived("Lsystem: 1\naxiom: ABCDE\nBB < C --> X\nendlsystem\n", 1), "ABCDE");
}

TEST(Context, AcropetalSignalMatchesFigure312) {
    LSystem ls =
        graftal::testing::parse("Lsystem: 1\naxiom: J[I]I[I]I[I]I\nJ < I --> J\nendlsystem\n");
    EXPECT_EQ(derived(ls, 1), "J[J]J[I]I[I]I");
    EXPECT_EQ(derived(ls, 2), "J[J]J[J]J[I]I");
    EXPECT_EQ(derived(ls, 3), "J[J]J[J]J[J]J");
}

TEST(Context, BasipetalSignalMatchesFigure313) {
    LSystem ls =
        graftal::testing::parse("Lsystem: 1\naxiom: I[I]I[I]I[I]J\nI > J --> J\nendlsystem\n");
    EXPECT_EQ(derived(ls, 1), "I[I]I[I]J[I]J");
    EXPECT_EQ(derived(ls, 2), "I[I]J[I]J[I]J");
    EXPECT_EQ(derived(ls, 3), "J[I]J[I]J[I]J");
}

TEST(Context, ContextSearchCostDoesNotDependOnBranchSize) {
    // A[ huge branch ]B: B's left context is A across a branch of a million modules.
    // With a bracket index the whole step is linear; rescanning would be quadratic.
    std::string axiom = "A";
    for (int i = 0; i < 2000; ++i) axiom += "[" + std::string(500, 'x') + "]";
    axiom += "B";
    LSystem ls = graftal::testing::parse("Lsystem: 1\naxiom: " + axiom +
                                         "\nA < B --> C\nA < x --> y\nendlsystem\n");
    ModuleString s = derive(ls, 1);
    EXPECT_EQ(ls.symbols.name(s.symbol(s.size() - 1)), "C");
}

// ---- the context fast path (src/rewrite/context_rewriter.cpp) against the generic path ----

namespace {

// The engine against its generic path at 1, 2, 3 and 7 threads. Strings past 65536 modules
// are split into chunks, so that contexts cross chunk boundaries.
ModuleString expectSameAsGenericPath(const LSystem& ls, const ModuleString& start, int steps,
                                     const std::string& what, bool contextPath = true) {
    return graftal::testing::expectSameAsGenericPath(ls, start, steps, what, {1u, 2u, 3u, 7u},
                                                     contextPath);
}

ModuleString symbolsOf(const std::string& text) {
    ModuleString s;
    for (char c : text) s.push(static_cast<Symbol>(c));
    return s;
}

// A random string over `alphabet` of about n modules; brackets balanced unless `unbalanced`.
std::string randomString(std::mt19937& rng, std::size_t n, const std::string& alphabet,
                         bool unbalanced) {
    std::string s;
    int depth = 0;
    while (s.size() < n) {
        auto r = rng() % 100;
        if (r < 12) {
            s += '[';
            ++depth;
        } else if (r < 24 && (depth > 0 || unbalanced)) {
            s += ']';
            depth = std::max(0, depth - 1);
        } else {
            s += alphabet[rng() % alphabet.size()];
        }
    }
    if (!unbalanced) s.append(static_cast<std::size_t>(depth), ']');
    return s;
}

}  // namespace

TEST(ContextFastPath, HogewegHesperSystemsAgreeWithTheGenericPath) {
    // Steps at which the strings have grown past 100,000 modules.
    const std::pair<const char*, int> systems[] = {
        {"a", 43}, {"b", 36}, {"c", 41}, {"d", 36}, {"e", 41}};
    for (const auto& [figure, steps] : systems) {
        std::string file = std::string("fig3.11") + figure + "-hogeweg-hesper.l";
        LSystem ls = loadLSystem(std::filesystem::path(GRAFTAL_EXAMPLES_DIR) / file);
        ModuleString last = expectSameAsGenericPath(ls, ls.axiom, steps, file);
        EXPECT_GT(last.size(), 100000u) << file << " must be large enough to be split";
    }
}

TEST(ContextFastPath, RandomStringsAgreeAcrossChunkBoundaries) {
    // Left and right contexts, ignored and considered symbols, contexts that are themselves
    // ignored (they never match), modules with and without productions, deep and shallow
    // branches: one step on strings of 200,000 modules, whose chunk boundaries fall anywhere.
    const char* systems[] = {
        "Lsystem: 1\naxiom: A\nignore: +-\nA < B > A --> [+B]C\nA < B --> -B\nB > C --> BB\n"
        "C < A --> *\nB --> A\nendlsystem\n",
        "Lsystem: 1\naxiom: A\nconsider: ABD[]\nA < C --> D\nD > B --> [A]\n"
        "B < D > A --> C+C\nA > C --> B\nendlsystem\n",
        "Lsystem: 1\naxiom: A\nignore: C+\nA < A > A --> B\nB < A > B --> [A]A\nC < A --> D\n"
        "A > + --> C\n+ --> -\nendlsystem\n",
        "Lsystem: 1\naxiom: A\nD < B --> A\nA > A --> B\nB < A --> [B]A\nC --> D\nendlsystem\n",
    };
    std::mt19937 rng(2024);
    int k = 0;
    for (const char* text : systems) {
        LSystem ls = parse(text);
        for (bool unbalanced : {false, true}) {
            ModuleString start = symbolsOf(randomString(rng, 200000, "ABCD+-", unbalanced));
            expectSameAsGenericPath(
                ls, start, 3,
                "system " + std::to_string(k) + (unbalanced ? " on an unbalanced string" : ""));
        }
        ++k;
    }
}

TEST(ContextFastPath, BracketsAtTheEndsOfStringsAndChunks) {
    LSystem ls = parse("Lsystem: 1\naxiom: A\nA < B --> C\nB > A --> D\nA --> B\nendlsystem\n");
    for (const char* text : {"[", "]", "][", "B]A", "A[B", "[[[B]]]A", "]]]B[[[", "A]B[A"})
        expectSameAsGenericPath(ls, symbolsOf(text), 4, text);
    // Runs of brackets long enough to cover whole chunks, and branches that close in a
    // later chunk than they open in.
    std::string deep = std::string(70000, '[') + "AB" + std::string(70000, ']') + "BA";
    std::string shallow;
    for (int i = 0; i < 30000; ++i) shallow += "AB[A]B]";
    for (const auto& text : {deep, shallow, std::string(100000, ']') + "AB" + "[" + "BA"})
        expectSameAsGenericPath(ls, symbolsOf(text), 2, "long brackets");
}

TEST(ContextFastPath, StochasticProductionsWithContextsDrawAsTheGenericPath) {
    LSystem ls = parse(
        "Lsystem: 1\nseed: 11\nignore: F\naxiom: F[A]B[A]B[B]A\n"
        "A < B > A --> F[A]B : 1\nA < B > A --> B[B]A : 2\nA < B --> A : 3\n"
        "B --> BB : 0.25\nB --> [A]B : 0.75\nA > B --> A[B] : 1\nA > B --> BF : 4\n"
        "A --> AFB\nendlsystem\n");
    ModuleString last = expectSameAsGenericPath(ls, ls.axiom, 16, "stochastic");
    EXPECT_GT(last.size(), 70000u);
}

TEST(ContextFastPath, TablesAgreeWithTheGenericPath) {
    LSystem ls = parse(
        "Lsystem: 1\naxiom: AB\nA < A --> B\ntable: grow\nA < B --> BA\nB --> A[B]\n"
        "table: turn\nB > A --> AB\nA --> B\ntable schedule: grow 2, turn 1, repeat\n"
        "endlsystem\n");
    expectSameAsGenericPath(ls, ls.axiom, 12, "tables");
}

TEST(ContextFastPath, RightContextOnASkippedModuleTakesTheGenericPath) {
    // '+' is ignored, so it cannot wait on its axis for a right context: the generic path.
    LSystem ls = parse("Lsystem: 1\nignore: +\naxiom: A+B\n+ > B --> -\nA < B --> C\nendlsystem\n");
    expectSameAsGenericPath(ls, ls.axiom, 2, "ignored predecessor", false);
    EXPECT_EQ(derived(ls, 1), "A-C");
}

// cpfg: Y[Z]XV[W[X]]E[K]T (oracle s08_consider): with `consider:` not listing the
// brackets, a right context runs through branch ends; a left context still jumps over
// whole branches.
TEST(Context, ConsiderWithoutBracketsCrossesBranchEnds) {
    EXPECT_EQ(derived("Lsystem: 1\nconsider: XK\nAxiom: A[B]X C[D[X]] E[K]G\nA > X --> Y\n"
                      "B > X --> Z\nC > X --> V\nD > X --> W\nK < G --> U\nX < G --> T\n"
                      "endlsystem\n",
                      1),
              "Y[Z]XV[W[X]]E[K]T");
    // Listing them keeps the usual branch rules (oracle s08_consider_brackets).
    EXPECT_EQ(derived("Lsystem: 1\nconsider: X[]\nAxiom: A[B]X C[D[X]]\nA > X --> Y\n"
                      "B > X --> Z\nC > X --> V\nD > X --> W\nendlsystem\n",
                      1),
              "Y[B]XC[D[X]]");
}

// cpfg: X(1,2,3,4)[B(2)C][D(3)E]Y(4)Z[H]K[V[W]P]R (oracle s08_rcon_skip).
TEST(Context, EqualsSkipsTheBranchAndCloseBracketWalksOut) {
    EXPECT_EQ(derived("Lsystem: 1\nAxiom: A(1)[B(2)C][D(3)E]F(4) G[H]K [M[N]P]R\n"
                      "A(a) > [B(b)=][D(d)=]F(f) --> X(a,b,d,f)\nF(f) > G --> Y(f)\n"
                      "G > K --> Z\nM > =]R --> V\nN > ]P --> W\nH > K --> U\nendlsystem\n",
                      1),
              "X(1,2,3,4)[B(2)C][D(3)E]Y(4)Z[H]K[V[W]P]R");
}

// cpfg: A(3)CH after two steps (oracle s08_pred_brackets).
TEST(Context, BracketsInAPredecessorMatchLiterally) {
    EXPECT_EQ(derived("Lsystem: 1\nAxiom: A(1)[B(2)]C D[E]F\nA(x)[B(y)] --> A(x+y)\n"
                      "D[E] --> G\nG F --> H\nendlsystem\n",
                      2),
              "A(3)CH");
}

// cpfg: T(0)T(0)T(0)T(1) and ZBY (oracle s08_ring, s08_ring_context).
TEST(Context, RingLsystemWrapsContexts) {
    EXPECT_EQ(derived("Lsystem: 1\nring lsystem\nAxiom: T(1) T(0) T(0) T(0)\n"
                      "T(l) < T(x) --> T(l)\nendlsystem\n",
                      3),
              "T(0)T(0)T(0)T(1)");
    EXPECT_EQ(derived("Lsystem: 1\nRing Lsystem\nAxiom: A B C\nB C < A > B C --> Z\n"
                      "C > A --> Y\nA < B > A --> W\nendlsystem\n",
                      1),
              "ZBY");
}

// cpfg: F(1)[+F(0.5)]F(2)A (oracle s08_homomorphism): homomorphism productions may have
// contexts; `homomorphism: no warnings` is accepted.
TEST(Context, HomomorphismWithContext) {
    LSystem ls = parse(
        "Lsystem: 1\nderivation length: 2\nAxiom: A\nA --> S(1) A\n"
        "homomorphism: no warnings\nmaximum depth: 2\nS(x) > A --> F(x*2)\n"
        "S(x) --> F(x) L\nL --> [+F(0.5)]\nendlsystem\n");
    ModuleString s = derive(ls, 2);
    EXPECT_EQ(s.toString(ls.symbols), "S(1)S(1)A");
    EXPECT_EQ(applyHomomorphism(ls, s).toString(ls.symbols), "F(1)[+F(0.5)]F(2)A");
}

// Random 2L-systems: contexts on either side or both, symbols ignored or not, successors
// with brackets, deletions and stochastic choices; each derived on a random string by the
// context path (holding its choices beside the string, and writing them over it) on 1, 2,
// 3 and 7 threads, and by the generic path.
TEST(ContextFastPath, RandomSystemsAgreeWithTheGenericPath) {
    std::mt19937 rng(7);
    const std::string letters = "ABC+-";
    auto letter = [&] { return letters[rng() % letters.size()]; };
    int usedContextPath = 0;
    for (int k = 0; k < 24; ++k) {
        std::string text = "Lsystem: 1\nseed: " + std::to_string(k) + "\naxiom: A\n";
        if (rng() % 2) text += "ignore: +-\n";
        const int productions = 2 + static_cast<int>(rng() % 4);
        for (int p = 0; p < productions; ++p) {
            std::string left, right, successor;
            if (rng() % 3) left = std::string(1, letter()) + " < ";
            if (rng() % 3) right = std::string(" > ") + letter();
            const int length = static_cast<int>(rng() % 5);  // 0: the module is deleted
            for (int s = 0; s < length; ++s) {
                const auto r = rng() % 10;
                successor += r == 0 ? std::string("[") + letter() + "]" : std::string(1, letter());
            }
            text += left + letter() + right + " --> " + (successor.empty() ? "*" : successor);
            if (rng() % 4 == 0) text += " : " + std::to_string(1 + rng() % 3);
            text += "\n";
        }
        text += "endlsystem\n";
        LSystem ls;
        try {
            ls = parse(text);
        } catch (const Error&) {
            continue;  // a random file may mix probabilities in ways the language refuses
        }
        RewritingEngine probe(ls, ls.productions, ls.seed, 2);
        usedContextPath += probe.usesContextPath();
        // Past 65536 modules, so that the string is split into chunks.
        const ModuleString start = symbolsOf(randomString(rng, 70000, letters, rng() % 2 == 0));
        expectSameAsGenericPath(ls, start, 2, "random system " + std::to_string(k) + ":\n" + text,
                                probe.usesContextPath());
    }
    EXPECT_GE(usedContextPath, 12) << "too few random systems took the context path";
}

TEST(ContextFastPath, AGrowingStringIsRewrittenInItsOwnBuffer) {
    // Hogeweg and Hesper's 2L-system (ABOP fig. 1.31a): every successor has a module, the
    // longest 8, as long as the padded copies. With room in its buffer, the string of a
    // step becomes the next one where it is (ContextRewriter::writeOverItself), chunk by
    // chunk on several threads, and the other buffer is given back.
    const LSystem ls = parse(
        "Lsystem: 1\nignore: +-F\naxiom: F1F1F1\n"
        "0 < 0 > 0 --> 0\n0 < 0 > 1 --> 1[+F1F1]\n0 < 1 > 0 --> 1\n0 < 1 > 1 --> 1\n"
        "1 < 0 > 0 --> 0\n1 < 0 > 1 --> 1F1\n1 < 1 > 0 --> 0\n1 < 1 > 1 --> 0\n"
        "* < + > * --> -\n* < - > * --> +\nendlsystem\n");
    const std::size_t noLimit = std::size_t(1) << 40;
    RewritingEngine generic(ls, ls.productions, ls.seed, 1);
    generic.useGenericPathOnly();
    ModuleString expected = symbolsOf("F1F1F1"), next;
    for (int k = 1; k <= 45; ++k) {
        generic.step(expected, next, k, 0, noLimit);
        std::swap(expected, next);
    }
    ASSERT_GT(expected.size(), 200000u);  // past the threshold of parallel chunks
    for (unsigned threads : {1u, 2u, 3u, 5u}) {
        RewritingEngine engine(ls, ls.productions, ls.seed, threads);
        ASSERT_TRUE(engine.usesContextPath());
        ModuleString s = symbolsOf("F1F1F1"), other;
        s.rawSymbols().reserve(expected.size() + 8192);
        int inPlace = 0;
        for (int k = 1; k <= 45; ++k) {
            const Symbol* buffer = s.rawSymbols().data();
            engine.stepConsuming(s, other, k, 0, noLimit);
            if (other.rawSymbols().data() == buffer) {
                ++inPlace;
                EXPECT_EQ(s.rawSymbols().capacity(), 0u) << "the other buffer is kept";
            }
            std::swap(s, other);
        }
        EXPECT_EQ(inPlace, 45) << threads << " threads";
        EXPECT_TRUE(s == expected) << threads << " threads: " << s.size() << " modules, expected "
                                   << expected.size();
    }
}
