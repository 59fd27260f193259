// The developmental plant models of examples/: every derivation printed in the seeds
// (the book, the lecture notes, the SIGGRAPH '88 paper) and the behaviour the text
// describes (switch times, delays, flowering sequences, variation between seeds).
//
// Some examples add turtle symbols (+ - / ...) to the book's productions so that
// branches can be drawn apart (see the comment at the top of each file); those tests
// compare the derived string with the book's after removing the turtle symbols.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "graftal/graftal.hpp"
#include "test_helpers.hpp"

using namespace graftal;
using graftal::testing::loadExample;
using graftal::testing::parseModel;
namespace fs = std::filesystem;

namespace {

Model example(const std::string& name, std::map<std::string, std::string> defines = {}) {
    ParseOptions o;
    o.defines = std::move(defines);
    return loadExample(fs::path(GRAFTAL_EXAMPLES_DIR) / name, o);
}

ModuleString deriveSeeded(const Model& ls, int n, std::uint64_t seed) {
    DerivationOptions o;
    o.seed = seed;
    return derive(ls, n, o);
}

std::string str(const Model& ls, int n) {
    return derive(ls, n).toString(ls.lsystem.symbols);
}

// The string without the turtle's turn/roll/pitch symbols (with or without a parameter):
// what the book prints for an example that adds turns to draw its branches apart.
std::string stripTurtle(const Model& ls, const ModuleString& s) {
    ModuleString out;
    for (std::size_t i = 0; i < s.size(); ++i) {
        Symbol sym = s.symbol(i);
        if (sym < 128 && sym != 0 && std::strchr("+-/\\&^|", static_cast<char>(sym))) continue;
        out.push(sym, s.params(i));
    }
    return out.toString(ls.lsystem.symbols);
}

std::string stripped(const Model& ls, int n) {
    return stripTurtle(ls, derive(ls, n));
}

Symbol sym(const Model& ls, const char* name) {
    int id = ls.lsystem.symbols.find(name);
    EXPECT_GE(id, 0) << name;
    return static_cast<Symbol>(id);
}

std::size_t countOf(const ModuleString& s, Symbol x) {
    std::size_t c = 0;
    for (Symbol y : s.symbols()) c += y == x;
    return c;
}

// The lateral branches of the main axis (bracket depth 1), from the base up: for each,
// the modules directly on its axis (not inside deeper branches).
std::vector<std::vector<std::size_t>> mainLaterals(const ModuleString& s) {
    std::vector<std::vector<std::size_t>> out;
    int depth = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
        Symbol x = s.symbol(i);
        if (x == '[') {
            if (depth++ == 0) out.emplace_back();
        } else if (x == ']') {
            --depth;
        } else if (depth == 1) {
            out.back().push_back(i);
        }
    }
    return out;
}

// The last module of the main axis whose symbol is one of `of`.
Symbol mainTerminal(const ModuleString& s, std::initializer_list<Symbol> of) {
    int depth = 0;
    Symbol last = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
        Symbol x = s.symbol(i);
        if (x == '[')
            ++depth;
        else if (x == ']')
            --depth;
        else if (depth == 0)
            for (Symbol o : of)
                if (x == o) last = x;
    }
    return last;
}

void expectDrawsAndIsSmall(const std::string& file) {
    SCOPED_TRACE(file);
    ParseResult parsed = loadModel(fs::path(GRAFTAL_EXAMPLES_DIR) / file);
    std::vector<Diagnostic> warnings = parsed.warnings();
    EXPECT_TRUE(warnings.empty()) << warnings.front().toString();
    Model ls = std::move(parsed).orThrow();
    ModuleString s = derive(ls);
    EXPECT_LT(s.size(), 2'000'000u) << "small enough to derive in well under a second";
    // As render() draws it: the kolams draw their f moves as one spline (`spline: path`).
    Scene scene = sceneForRender(ls, applyHomomorphism(ls.lsystem, s), RenderRequest{});
    EXPECT_GT(scene.segments.size() + scene.polygonCount(), 0u) << "draws a picture";
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Every model file: parses without warnings, stays small and quick, draws something.

TEST(Models, EveryModelFileDrawsAndStaysSmall) {
    for (const char* f : {"fig3.7-lily-of-the-valley.l",
                          "fig3.8-fern.l",
                          "fig3.9-lychnis-coronaria.l",
                          "fig3.10-capsella-delay.l",
                          "fig3.10-capsella-stochastic.l",
                          "fig3.10-capsella-table.l",
                          "sec3.3.4-compound-raceme.l",
                          "sec3.3.4-compound-raceme-terminal.l",
                          "fig3.14a-acropetal-signal.l",
                          "fig3.14b-basipetal-flowering.l",
                          "fig3.15-mycelis-muralis.l",
                          "fig3.16-stochastic-bush.l",
                          "fig3.17-flower-field.l",
                          "fig6.5-bag-of-candies.l",
                          "siggraph-a-branching-everywhere.l",
                          "siggraph-a-prime-branching-everywhere.l",
                          "siggraph-b-subapical.l",
                          "siggraph-c-prime-acropetal-signal.l",
                          "siggraph-d-basipetal-signal.l",
                          "siggraph-raceme-elongating-internodes.l",
                          "siggraph-lychnis-coronaria.l",
                          "siggraph-flower-field-stochastic-internodes.l",
                          "lecture-parametric-plant.l",
                          "lecture-stochastic-parametric-context.l",
                          "lecture-monopodial-branching.l",
                          "lecture-dichotomic-branching.l",
                          "honda-monopodial-tree.l",
                          "aono-kunii-sympodial-tree.l",
                          "abop-ternary-branching-tree.l"}) {
        expectDrawsAndIsSmall(f);
    }
}

// ---------------------------------------------------------------------------------------
// 3.3.1 Racemes: the lily-of-the-valley's printed developmental sequence.

TEST(Models, LilyOfTheValleyPrintedSequence) {
    Model ls = example("fig3.7-lily-of-the-valley.l");
    // LSFP, 3.3.1: A, I[IF0]A, I[IF1]I[IF0]A, I[IF2]I[IF1]I[IF0]A,
    // I[IF3]I[IF2]I[IF1]I[IF0]A (F_i is F(i)).
    EXPECT_EQ(str(ls, 0), "A");
    EXPECT_EQ(str(ls, 1), "I[IF(0)]A");
    EXPECT_EQ(str(ls, 2), "I[IF(1)]I[IF(0)]A");
    EXPECT_EQ(str(ls, 3), "I[IF(2)]I[IF(1)]I[IF(0)]A");
    EXPECT_EQ(str(ls, 4), "I[IF(3)]I[IF(2)]I[IF(1)]I[IF(0)]A");
    // ... and so on: at step n the flowers are F(n-1) at the base down to F(0) at the top.
    for (int n = 5; n <= 14; ++n) {
        std::string want;
        for (int k = n - 1; k >= 0; --k) want += "I[IF(" + std::to_string(k) + ")]";
        EXPECT_EQ(str(ls, n), want + "A") << n;
    }
    // The homomorphism draws: the book's flower F(i) becomes a polygon, I a segment.
    std::string drawn = applyHomomorphism(ls.lsystem, derive(ls, 1)).toString(ls.lsystem.symbols);
    EXPECT_EQ(drawn.find("F(0)"), std::string::npos);
    EXPECT_NE(drawn.find('{'), std::string::npos);
}

TEST(Models, SiggraphRacemeWithElongatingInternodesPrintedSequence) {
    Model ls = example("siggraph-raceme-elongating-internodes.l");
    // the SIGGRAPH '88 paper, 4.1: A, I0[I0F0]A, I1[I1F1]I0[I0F0]A, I2[I2F2]I1[I1F1]I0[I0F0]A,
    // I3[I3F3]I2[I2F2]I1[I1F1]I0[I0F0]A
    EXPECT_EQ(str(ls, 0), "A");
    EXPECT_EQ(str(ls, 1), "I(0)[I(0)F(0)]A");
    EXPECT_EQ(str(ls, 2), "I(1)[I(1)F(1)]I(0)[I(0)F(0)]A");
    EXPECT_EQ(str(ls, 3), "I(2)[I(2)F(2)]I(1)[I(1)F(1)]I(0)[I(0)F(0)]A");
    EXPECT_EQ(str(ls, 4), "I(3)[I(3)F(3)]I(2)[I(2)F(2)]I(1)[I(1)F(1)]I(0)[I(0)F(0)]A");
}

TEST(Models, FernHasNineFrondsGrowingSubapically) {
    Model ls = example("fig3.8-fern.l");
    std::string frond0 = "[A]", frond1 = "[I(0)[B]A]", frond2 = "[I(1)[I(0)[L(0)][L(0)]B]I(0)[B]A]";
    auto times9 = [](const std::string& s) {
        std::string r;
        for (int i = 0; i < 9; ++i) r += s;
        return r;
    };
    EXPECT_EQ(stripped(ls, 0), times9(frond0));
    EXPECT_EQ(stripped(ls, 1), times9(frond1));
    EXPECT_EQ(stripped(ls, 2), times9(frond2));
    // Leaves and first-order branches: the oldest at the base, the most leaves there.
    ModuleString s = derive(ls, 5);
    EXPECT_EQ(countOf(s, sym(ls, "A")), 9u);
    EXPECT_EQ(countOf(s, sym(ls, "B")), 9u * 5);  // 5 first-order apices per frond
    EXPECT_EQ(countOf(s, sym(ls, "L")), 9u * 2 * (4 + 3 + 2 + 1));  // 2 leaves per node
}

// ---------------------------------------------------------------------------------------
// 3.3.2 Lychnis coronaria: the delays of the two lateral apices.

TEST(Models, LychnisLateralApicesBranchAfterEightAndFourSteps) {
    Model ls = example("fig3.9-lychnis-coronaria.l");
    EXPECT_EQ(stripped(ls, 0), "A(7)");
    EXPECT_EQ(stripped(ls, 1), "I[A(0)][A(4)]IF(0)");
    EXPECT_EQ(stripped(ls, 4), "I[A(3)][A(7)]IF(3)");
    EXPECT_EQ(stripped(ls, 5), "I[A(4)][I[A(0)][A(4)]IF(0)]IF(4)");
    // The lateral created as A(0) needs eight steps, the one created as A(4) four.
    auto branchStep = [&](int lateral) {
        for (int n = 1; n <= 20; ++n) {
            ModuleString s = derive(ls, n);
            auto lat = mainLaterals(s);
            // the lateral's first module after its turn (+ or -) is I once it branched
            if (s.symbol(lat.at(lateral).at(1)) == 'I') return n - 1;  // steps after creation
        }
        return -1;
    };
    EXPECT_EQ(branchStep(0), 8);
    EXPECT_EQ(branchStep(1), 4);
    EXPECT_EQ(stripped(ls, 9), "I[I[A(0)][A(4)]IF(0)][I[A(4)][I[A(0)][A(4)]IF(0)]IF(4)]IF(8)");
    // The SIGGRAPH version has leaves and elongating internodes, same delays.
    Model sg = example("siggraph-lychnis-coronaria.l");
    EXPECT_EQ(stripped(sg, 1), "I(0)[L(0)][L(0)][A(0)][A(4)]I(0)F(0)");
    EXPECT_EQ(stripped(sg, 5),
              "I(4)[L(4)][L(4)][A(4)][I(0)[L(0)][L(0)][A(0)][A(4)]I(0)F(0)]I(4)F(4)");
}

// ---------------------------------------------------------------------------------------
// 3.3.3 Capsella: three mechanisms for the switch from leaves to flowers.

namespace {
// The step at which the apex is B for the first time (-1: never up to `maxSteps`).
int switchStep(const Model& ls, int maxSteps, std::optional<std::uint64_t> seed = {}) {
    DerivationOptions o;
    o.seed = seed;
    Derivation d(ls, o);
    Symbol b = static_cast<Symbol>(ls.lsystem.symbols.find("B"));
    for (int n = 0; n <= maxSteps; ++n) {
        if (n > 0) d.step();
        if (countOf(d.current(), b) > 0) return n;
    }
    return -1;
}
}  // namespace

TEST(Models, CapsellaDelaySwitchesAfterCountingTheLeaves) {
    for (int leaves : {3, 5, 8}) {
        SCOPED_TRACE(leaves);
        Model ls = example("fig3.10-capsella-delay.l", {{"NLEAVES", std::to_string(leaves)}});
        // A(0) ... A(n-1) make n leaves staying vegetative; A(n) makes one more and
        // becomes B: the switch is at step n+1, whatever happens.
        EXPECT_EQ(switchStep(ls, 30), leaves + 1);
        ModuleString atSwitch = derive(ls, leaves + 1);
        EXPECT_EQ(countOf(atSwitch, 'L'), static_cast<std::size_t>(leaves + 1));
        EXPECT_EQ(countOf(atSwitch, 'F'), 0u);
        ModuleString later = derive(ls, leaves + 6);
        EXPECT_EQ(countOf(later, 'L'), static_cast<std::size_t>(leaves + 1)) << "no more leaves";
        EXPECT_EQ(countOf(later, 'F'), 5u) << "one flower per step after the switch";
    }
    Model ls = example("fig3.10-capsella-delay.l");
    EXPECT_EQ(str(ls, 0), "A(0)");
    EXPECT_EQ(str(ls, 2), "I[L(1)]I[L(0)]A(2)");
    EXPECT_EQ(str(ls, 6), "I[L(5)]I[L(4)]I[L(3)]I[L(2)]I[L(1)]I[L(0)]B");
    EXPECT_EQ(str(ls, 8), "I[L(7)]I[L(6)]I[L(5)]I[L(4)]I[L(3)]I[L(2)]I[IF(1)]I[IF(0)]B");
}

TEST(Models, CapsellaTableSwitchesAtTheScheduledStep) {
    for (int days : {2, 6, 9}) {
        SCOPED_TRACE(days);
        Model ls = example("fig3.10-capsella-table.l", {{"DAYS", std::to_string(days)}});
        // Table 1 for `days` steps, table 2 from step days+1 on: its p1 A -> I[L0]B.
        EXPECT_EQ(switchStep(ls, 30), days + 1);
        EXPECT_EQ(ls.lsystem.tableForStep(days), 0);
        EXPECT_EQ(ls.lsystem.tableForStep(days + 1), 1);
        ModuleString before = derive(ls, days);
        EXPECT_EQ(before.symbol(before.size() - 1), 'A');
        EXPECT_EQ(countOf(derive(ls, days + 1), 'F'), 0u);
        EXPECT_EQ(countOf(derive(ls, days + 2), 'F'), 1u);
    }
    Model ls = example("fig3.10-capsella-table.l");
    EXPECT_EQ(str(ls, 7), "I[L(6)]I[L(5)]I[L(4)]I[L(3)]I[L(2)]I[L(1)]I[L(0)]B");
}

TEST(Models, CapsellaStochasticSwitchVariesWithTheSeedOnly) {
    Model ls = example("fig3.10-capsella-stochastic.l");
    std::set<int> steps;
    for (std::uint64_t seed = 1; seed <= 30; ++seed) {
        int s = switchStep(ls, 60, seed);
        ASSERT_GT(s, 0) << "seed " << seed;
        steps.insert(s);
        EXPECT_EQ(switchStep(ls, 60, seed), s) << "same seed, same switch step";
        // Whatever the step, the structure is that of the schema: one leaf per step
        // up to the switch, one flower per step after it.
        ModuleString m = deriveSeeded(ls, s + 3, seed);
        EXPECT_EQ(countOf(m, 'L'), static_cast<std::size_t>(s));
        EXPECT_EQ(countOf(m, 'F'), 3u);
    }
    EXPECT_GE(steps.size(), 4u) << "the switch step differs between seeds";
    EXPECT_EQ(deriveSeeded(ls, 20, 7), deriveSeeded(ls, 20, 7));
}

// ---------------------------------------------------------------------------------------
// 3.3.4 Compound racemes of order n.

namespace {
// For every flower F of the derived string: the order of the axis that bears it (the
// flower sits in a branch [IF] of that axis).
std::set<int> flowerAxisOrders(const ModuleString& s) {
    std::set<int> orders;
    int depth = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
        Symbol x = s.symbol(i);
        if (x == '[')
            ++depth;
        else if (x == ']')
            --depth;
        else if (x == 'F')
            orders.insert(depth - 1);
    }
    return orders;
}
}  // namespace

TEST(Models, CompoundRacemeOfOrderN) {
    {
        Model ls = example("sec3.3.4-compound-raceme.l");  // order 2
        EXPECT_EQ(stripped(ls, 1), "I[A(1)]A(0)");
        EXPECT_EQ(stripped(ls, 2), "I[I[A(2)]A(1)]I[A(1)]A(0)");
        EXPECT_EQ(stripped(ls, 3), "I[I[I[IF]A(2)]I[A(2)]A(1)]I[I[A(2)]A(1)]I[A(1)]A(0)");
    }
    for (int order = 0; order <= 4; ++order) {
        SCOPED_TRACE(order);
        Model ls = example("sec3.3.4-compound-raceme.l", {{"ORDER", std::to_string(order)}});
        // The first flower appears after order+1 steps, and every flower is borne by an
        // axis of order n: none on the axes of lower order.
        EXPECT_EQ(countOf(derive(ls, order), 'F'), 0u);
        EXPECT_EQ(countOf(derive(ls, order + 1), 'F'), 1u);
        ModuleString s = derive(ls, order + 4);
        EXPECT_EQ(flowerAxisOrders(s), std::set<int>{order});
    }
    // Order 0 is the simple raceme of 3.3.1 (with A(0) for A and a plain F).
    Model r = example("sec3.3.4-compound-raceme.l", {{"ORDER", "0"}});
    EXPECT_EQ(stripped(r, 3), "I[IF]I[IF]I[IF]A(0)");
}

TEST(Models, CompoundRacemeWithTerminalRacemesAfterTheSwitch) {
    Model ls = example("sec3.3.4-compound-raceme-terminal.l");  // order 2, switch after 4
    // Before the switch: as the plain compound raceme.
    Model plain = example("sec3.3.4-compound-raceme.l");
    for (int n = 0; n <= 4; ++n) EXPECT_EQ(stripped(ls, n), stripped(plain, n)) << n;
    // Step 5 uses p1': every apex of order < n makes a flower and becomes A(n).
    ModuleString s = derive(ls, 5);
    Symbol a = sym(ls, "A");
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (s.symbol(i) == a) {
            EXPECT_EQ(s.params(i)[0], 2.0);
        }
    }
    // From then on every axis, the main one included, ends in a raceme.
    EXPECT_EQ(flowerAxisOrders(derive(ls, 6)), (std::set<int>{0, 1, 2}));
    std::string s5 = stripped(ls, 5);
    ASSERT_GE(s5.size(), 9u);
    EXPECT_EQ(s5.substr(s5.size() - 9), "I[IF]A(2)");
}

// ---------------------------------------------------------------------------------------
// 3.5.2 The model with one acropetal signal: flowering times T_k.

namespace {

struct SignalModel {
    int m, n, u, v, d;
    // The book: T_k = k (un - vm)/(n - v) + d n/(n - v).
    double bookT(int k) const { return (k * (u * n - v * m) + d * n) / double(n - v); }
    // The book's l_k with its misprint corrected (LSFP prints -k/n (m-u)/(n-v) +
    // d/(n-v); solving its two equations gives (d - k(m-u))/(n-v)).
    double bookL(int k) const { return (d - k * (m - u)) / double(n - v); }
    // Exact discrete flowering step of lateral k in this L-system: S0 appears at the
    // base at step d+1 (p6 rewrites D_d), passes internode I_k at d+1+ku and segment J_j
    // of lateral k at d+1+ku+jv; lateral apex B (created at km, one J every n steps)
    // becomes F one step after S0 stands right before it, i.e. for the least j with
    // d+1+ku+jv < km+(j+1)n.
    int segmentsAtFlowering(int k) const {
        int x = d + 1 + k * (u - m) - n;
        return x < 0 ? 0 : x / (n - v) + 1;
    }
    int exactT(int k) const { return d + 2 + k * u + v * segmentsAtFlowering(k); }
};

struct Measured {
    std::vector<int> T, l;  // per lateral k = 1, 2, ... (index k-1)
    int mainApex = -1;
};

Measured measureFlowering(const Model& ls, int steps) {
    Measured r;
    Symbol F = 'F', J = 'J', A = 'A';
    Derivation d(ls);
    for (int n = 0; n <= steps; ++n) {
        if (n > 0) d.step();
        const ModuleString& s = d.current();
        auto lats = mainLaterals(s);
        for (std::size_t k = 0; k < lats.size(); ++k) {
            if (r.T.size() <= k) r.T.push_back(-1), r.l.push_back(-1);
            if (r.T[k] >= 0) continue;
            std::size_t js = 0;
            bool flowered = false;
            for (std::size_t i : lats[k]) {
                js += s.symbol(i) == J;
                flowered |= s.symbol(i) == F;
            }
            if (flowered) r.T[k] = n, r.l[k] = static_cast<int>(js);
        }
        if (r.mainApex < 0 && mainTerminal(s, {A, F}) == F) r.mainApex = n;
    }
    return r;
}

void checkSignalModel(const std::string& file, SignalModel p, int steps) {
    SCOPED_TRACE(file);
    Model ls = example(file);
    Measured r = measureFlowering(ls, steps);
    ASSERT_GE(r.T.size(), 8u);
    double slope = (p.u * p.n - p.v * p.m) / double(p.n - p.v);
    // Constant offset of this discrete model against the book's idealisation (one step
    // for D_d -> S_0, one for S_0 < B -> F, and the apex caught in mid-plastochron).
    double offset = (2.0 * p.n - p.v - double(p.v) * p.n) / (p.n - p.v);
    for (std::size_t i = 0; i < r.T.size(); ++i) {
        int k = static_cast<int>(i) + 1;
        SCOPED_TRACE("k=" + std::to_string(k));
        ASSERT_GE(r.T[i], 0) << "every lateral apex flowers";
        EXPECT_EQ(r.T[i], p.exactT(k));
        EXPECT_EQ(r.l[i], p.segmentsAtFlowering(k));
        // Where the lateral has segments when the signal comes (l_k >= 1, the case the
        // book's analysis covers), T_k is the book's value up to the constant offset and
        // the integer rounding of l_k (at most one segment: v steps).
        if (r.l[i] >= 1) {
            EXPECT_GT(r.T[i] - p.bookT(k), offset - 1e-9);
            EXPECT_LE(r.T[i] - p.bookT(k), offset + p.v + 1e-9);
            EXPECT_LE(std::abs(r.T[i] - p.bookT(k)), 2.5);
            EXPECT_LE(std::abs(r.l[i] - p.bookL(k)), 2.0);
        }
    }
    // The flowering sequence: over two laterals T changes by exactly 2 (un-vm)/(n-v).
    for (std::size_t i = 0; i + 2 < r.T.size(); ++i) {
        if (r.l[i + 2] >= 1) {
            EXPECT_EQ(r.T[i + 2] - r.T[i], std::lround(2 * slope)) << i;
        }
    }
}

}  // namespace

TEST(Models, AcropetalSignalFloweringTimesMatchTheBook) {
    // Fig 3.14 top: m = 2, n = 3, u = v = 1, d = 11: acropetal, T_k = k/2 + 16.5.
    SignalModel p{2, 3, 1, 1, 11};
    checkSignalModel("fig3.14a-acropetal-signal.l", p, 30);
    Measured r = measureFlowering(example("fig3.14a-acropetal-signal.l"), 30);
    EXPECT_EQ(r.T, (std::vector<int>{19, 19, 20, 20, 21, 21, 22, 22, 23, 23, 24}));
    EXPECT_EQ(r.l, (std::vector<int>{5, 4, 4, 3, 3, 2, 2, 1, 1, 0, 0}));
    EXPECT_EQ(r.mainApex, 24);
    // The figure's derivation lengths 15 - 19 - 21 - 23 - 26: no flower at 15, the
    // first at 19, all at 24.
    Model ls = example("fig3.14a-acropetal-signal.l");
    EXPECT_EQ(countOf(derive(ls, 15), 'F'), 0u);
    EXPECT_GT(countOf(derive(ls, 19), 'F'), 0u);
    EXPECT_EQ(countOf(derive(ls, 26), 'B') + countOf(derive(ls, 26), 'A'), 0u);
}

TEST(Models, BasipetalFloweringTimesMatchTheBook) {
    // Fig 3.14 bottom: m = 2, n = 5, u = 1, v = 3, d = 12: basipetal, T_k = -k/2 + 30.
    SignalModel p{2, 5, 1, 3, 12};
    checkSignalModel("fig3.14b-basipetal-flowering.l", p, 34);
    Measured r = measureFlowering(example("fig3.14b-basipetal-flowering.l"), 34);
    EXPECT_EQ(r.T, (std::vector<int>{27, 28, 26, 27, 25, 26, 24, 25, 23, 24, 25, 26}));
    EXPECT_EQ(r.l, (std::vector<int>{4, 4, 3, 3, 2, 2, 1, 1, 0, 0, 0, 0}));
    EXPECT_EQ(r.mainApex, 26);
    // Basipetal: the first flowers open near the top (step 23), the lowest last (28).
    EXPECT_EQ(*std::min_element(r.T.begin(), r.T.end()), 23);
    EXPECT_EQ(*std::max_element(r.T.begin(), r.T.end()), 28);
    EXPECT_LT(r.T[7], r.T[0]);
}

TEST(Models, SignalModelsWithOtherDelays) {
    // The exact discrete formula holds for other delays too (-D DELAY=...).
    for (int d : {6, 9, 14}) {
        SCOPED_TRACE(d);
        Model a = example("fig3.14a-acropetal-signal.l", {{"DELAY", std::to_string(d)}});
        Measured ra = measureFlowering(a, 3 * d + 4);
        SignalModel pa{2, 3, 1, 1, d};
        for (std::size_t i = 0; i < ra.T.size(); ++i) EXPECT_EQ(ra.T[i], pa.exactT(int(i) + 1));
        Model b = example("fig3.14b-basipetal-flowering.l", {{"DELAY", std::to_string(d)}});
        Measured rb = measureFlowering(b, 3 * d + 4);
        SignalModel pb{2, 5, 1, 3, d};
        for (std::size_t i = 0; i < rb.T.size(); ++i) EXPECT_EQ(rb.T[i], pb.exactT(int(i) + 1));
    }
}

TEST(Models, SignalModelSignalMovesOneInternodePerStepWhenUIsOne) {
    Model ls = example("fig3.14a-acropetal-signal.l");
    EXPECT_EQ(str(ls, 0), "D(0)A(0)");
    EXPECT_EQ(str(ls, 2), "D(2)I[+B(0)]A(0)");
    // D(11) -> S(0) at step 12; the signal is right after the first internode at 13,
    // after the second at 14.
    EXPECT_EQ(derive(ls, 12).symbol(0), 'S');
    std::string s13 = str(ls, 13), s14 = str(ls, 14);
    EXPECT_EQ(s13.substr(0, 5), "IS(0)");
    EXPECT_NE(s14.find("]IS(0)["), std::string::npos);
}

// ---------------------------------------------------------------------------------------
// 3.5.3 Mycelis muralis (written from the description): the sequence of events.

TEST(Models, MycelisSignalsReleaseAndFlowerTheLateralsFromTheTopDown) {
    Model ls = example("fig3.15-mycelis-muralis.l");
    Symbol X = sym(ls, "X"), A = sym(ls, "A"), F = 'F', D = sym(ls, "D");
    int mainFlower = -1;
    std::vector<int> released, flowered;
    Derivation d(ls);
    for (int n = 0; n <= 60; ++n) {
        if (n > 0) d.step();
        const ModuleString& s = d.current();
        if (mainFlower < 0 && mainTerminal(s, {A, F}) == F) mainFlower = n;
        auto lats = mainLaterals(s);
        released.resize(lats.size(), -1);
        flowered.resize(lats.size(), -1);
        for (std::size_t k = 0; k < lats.size(); ++k) {
            Symbol first = s.symbol(lats[k].front());
            if (mainFlower < 0) {
                EXPECT_EQ(first, D) << "apical dominance: laterals dormant before flowering";
            }
            if (released[k] < 0 && first == X) released[k] = n;
            Symbol last = 0;
            for (std::size_t i : lats[k])
                if (s.symbol(i) == A || s.symbol(i) == F) last = s.symbol(i);
            if (flowered[k] < 0 && last == F) flowered[k] = n;
        }
    }
    ASSERT_GT(mainFlower, 0);
    ASSERT_GE(released.size(), 5u);
    // S2 releases the laterals one node per step, the topmost first; S3 (slower) then
    // makes them flower, also from the top down: a basipetal flowering sequence.
    for (std::size_t k = 0; k < released.size(); ++k) {
        SCOPED_TRACE(k);
        ASSERT_GT(released[k], mainFlower);
        ASSERT_GT(flowered[k], released[k]);
        if (k + 1 < released.size()) {
            EXPECT_EQ(released[k] - released[k + 1], 1);
            EXPECT_GT(flowered[k], flowered[k + 1]);
            // the interval between release and flowering grows downwards (S2 faster
            // than S3): lower laterals have more time to grow
            EXPECT_GT(flowered[k] - released[k], flowered[k + 1] - released[k + 1]);
        }
    }
    // The process repeats on the laterals: second-order flowers exist at the end.
    std::set<int> depths;
    ModuleString s = d.current();
    int depth = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (s.symbol(i) == '[')
            ++depth;
        else if (s.symbol(i) == ']')
            --depth;
        else if (s.symbol(i) == F)
            depths.insert(depth);
    }
    EXPECT_TRUE(depths.count(0) && depths.count(1) && depths.count(2));
}

// ---------------------------------------------------------------------------------------
// 3.6 Variation: stochastic bushes and the flower field.

TEST(Models, StochasticBushesDifferBetweenSeeds) {
    Model ls = example("fig3.16-stochastic-bush.l");
    std::set<std::string> all;
    for (std::uint64_t seed = 1; seed <= 8; ++seed)
        all.insert(deriveSeeded(ls, 5, seed).toString(ls.lsystem.symbols));
    EXPECT_EQ(all.size(), 8u);
    // Every F is rewritten by one of the three productions: after one step the string
    // is one of the three successors.
    std::set<std::string> one;
    for (std::uint64_t seed = 0; seed < 40; ++seed)
        one.insert(deriveSeeded(ls, 1, seed).toString(ls.lsystem.symbols));
    EXPECT_EQ(one, (std::set<std::string>{"F[+F]F[-F]F", "F[+F]F", "F[-F]F"}));
}

TEST(Models, FlowerFieldSixteenSeedsSixteenPlants) {
    Model ls = example("fig3.17-flower-field.l");
    std::set<std::string> field;
    for (std::uint64_t seed = 1; seed <= 16; ++seed) {
        std::string s =
            deriveSeeded(ls, ls.lsystem.derivationLength, seed).toString(ls.lsystem.symbols);
        field.insert(s);
        EXPECT_EQ(deriveSeeded(ls, ls.lsystem.derivationLength, seed).toString(ls.lsystem.symbols),
                  s)
            << "same seed, same plant: " << seed;
    }
    EXPECT_EQ(field.size(), 16u);
    // The deterministic part is that of Fig 3.4: the first step has no seg yet.
    Model fig34 = example("fig3.4-plant.l");
    EXPECT_EQ(str(ls, 1), str(fig34, 1));
}

TEST(Models, SiggraphFlowerFieldStochasticInternodes) {
    Model ls = example("siggraph-flower-field-stochastic-internodes.l");
    EXPECT_EQ(str(ls, 1), "IIIK");
    std::set<std::string> field;
    for (std::uint64_t seed = 1; seed <= 16; ++seed)
        field.insert(deriveSeeded(ls, 5, seed).toString(ls.lsystem.symbols));
    EXPECT_GE(field.size(), 14u);
    // Every internode becomes I, II or I[L]L.
    std::set<std::string> one;
    Model single = graftal::testing::parseModel(
        "Lsystem: 1\naxiom: I\nI --> I : 1/3\nI --> II : 1/3\nI --> I[L]L : 1/3\nendlsystem\n");
    for (std::uint64_t seed = 0; seed < 40; ++seed)
        one.insert(deriveSeeded(single, 1, seed).toString(single.lsystem.symbols));
    EXPECT_EQ(one, (std::set<std::string>{"I", "II", "I[L]L"}));
}

// ---------------------------------------------------------------------------------------
// The SIGGRAPH '88 paper's L-systems (a)-(d), (a'), (c').

TEST(Models, SiggraphBranchingEverywhere) {
    Model a = example("siggraph-a-branching-everywhere.l");
    EXPECT_EQ(str(a, 0), "S");
    EXPECT_EQ(str(a, 1), "S[S]S[S]S");
    EXPECT_EQ(str(a, 2), "S[S]S[S]S[S[S]S[S]S]S[S]S[S]S[S[S]S[S]S]S[S]S[S]S");
    Model a1 = example("siggraph-a-prime-branching-everywhere.l");
    EXPECT_EQ(str(a1, 1), "S[-S]S[+S]S");
    EXPECT_EQ(stripTurtle(a1, derive(a1, 3)), str(a, 3));
    EXPECT_DOUBLE_EQ(a1.view.turtle.angleDegrees, 27.5);
}

TEST(Models, SiggraphSubapicalGrowth) {
    Model b = example("siggraph-b-subapical.l");
    EXPECT_EQ(stripped(b, 0), "A");
    EXPECT_EQ(stripped(b, 1), "S[A]S[A]A");
    EXPECT_EQ(stripped(b, 2), "SS[S[A]S[A]A]SS[S[A]S[A]A]S[A]S[A]A");
    // the paper's (b) itself, without the turns
    Model plain = graftal::testing::parseModel(
        "Lsystem: 1\naxiom: A\nA --> S[A]S[A]A\nS --> SS\nendlsystem\n");
    for (int n = 0; n <= 5; ++n)
        EXPECT_EQ(stripped(b, n), graftal::testing::derived(plain.lsystem, n)) << n;
}

TEST(Models, SiggraphSignalPropagation) {
    // (c), the topological system (LSFP 3.5.1; lost from the SIGGRAPH '88 paper's text)
    Model c =
        graftal::testing::parseModel("Lsystem: 1\naxiom: J[I]I[I]I[I]I\nJ < I --> J\nendlsystem\n");
    EXPECT_EQ(graftal::testing::derived(c.lsystem, 1), "J[J]J[I]I[I]I");
    EXPECT_EQ(graftal::testing::derived(c.lsystem, 2), "J[J]J[J]J[I]I");
    EXPECT_EQ(graftal::testing::derived(c.lsystem, 3), "J[J]J[J]J[J]J");
    // (c'), as printed: the same with turns, ignored in the context
    Model c1 = example("siggraph-c-prime-acropetal-signal.l");
    EXPECT_EQ(str(c1, 0), "J[+I]I[-I]I[+I]I");
    EXPECT_EQ(str(c1, 1), "J[+J]J[-I]I[+I]I");
    EXPECT_EQ(str(c1, 2), "J[+J]J[-J]J[+I]I");
    EXPECT_EQ(str(c1, 3), "J[+J]J[-J]J[+J]J");
    for (int n = 0; n <= 3; ++n)
        EXPECT_EQ(stripped(c1, n), graftal::testing::derived(c.lsystem, n));
    // (d): the basipetal signal moves down the main axis only
    Model d = example("siggraph-d-basipetal-signal.l");
    EXPECT_EQ(stripped(d, 0), "I[I]I[I]I[I]J");
    EXPECT_EQ(stripped(d, 1), "I[I]I[I]J[I]J");
    EXPECT_EQ(stripped(d, 2), "I[I]J[I]J[I]J");
    EXPECT_EQ(stripped(d, 3), "J[I]J[I]J[I]J");
    Model dplain =
        graftal::testing::parseModel("Lsystem: 1\naxiom: I[I]I[I]I[I]J\nI > J --> J\nendlsystem\n");
    for (int n = 0; n <= 3; ++n)
        EXPECT_EQ(stripped(d, n), graftal::testing::derived(dplain.lsystem, n));
}

// ---------------------------------------------------------------------------------------
// The lecture notes' examples (the L-systems lecture notes).

TEST(Models, LectureParametricPlantPrintedDerivation) {
    Model ls = example("lecture-parametric-plant.l");
    // A(0) => FA(1) => F[-L]FA(2) => F[-L]F[+L]FA(3) => F[-L]F[+L]FB
    EXPECT_EQ(str(ls, 0), "A(0)");
    EXPECT_EQ(str(ls, 1), "FA(1)");
    EXPECT_EQ(str(ls, 2), "F[-L]FA(2)");
    EXPECT_EQ(str(ls, 3), "F[-L]F[+L]FA(3)");
    EXPECT_EQ(str(ls, 4), "F[-L]F[+L]FB");
    EXPECT_EQ(str(ls, 7), "F[-L]F[+L]FB") << "B is final";
}

TEST(Models, LectureStochasticParametricContextExample) {
    Model ls = example("lecture-stochastic-parametric-context.l");
    // "A(1)B(3)A(5) => A(2)B(6)[A(3)]B(4)" with the file's seed
    EXPECT_EQ(str(ls, 0), "A(1)B(3)A(5)");
    EXPECT_EQ(str(ls, 1), "A(2)B(6)[A(3)]B(4)");
    // Every seed gives one of the four possible first steps, and all four occur.
    std::set<std::string> outcomes;
    for (std::uint64_t seed = 0; seed < 60; ++seed)
        outcomes.insert(deriveSeeded(ls, 1, seed).toString(ls.lsystem.symbols));
    EXPECT_EQ(outcomes, (std::set<std::string>{"A(2)B(6)[A(3)]B(4)", "A(2)B(6)[A(3)]A(6)",
                                               "B(0)B(6)[A(3)]B(4)", "B(0)B(6)[A(3)]A(6)"}));
}

TEST(Models, LectureMonopodialAndDichotomicBranching) {
    // The notes' "iteration k" is derivation step k-1.
    Model mono = example("lecture-monopodial-branching.l");
    EXPECT_EQ(stripped(mono, 0), "0");
    EXPECT_EQ(stripped(mono, 1), "1[0]0");
    EXPECT_EQ(stripped(mono, 2), "1[1[0]0]1[0]0");
    EXPECT_EQ(stripped(mono, 3), "1[1[1[0]0]1[0]0]1[1[0]0]1[0]0");
    Model dicho = example("lecture-dichotomic-branching.l");
    EXPECT_EQ(stripped(dicho, 0), "0");
    EXPECT_EQ(stripped(dicho, 1), "1[0][0]");
    EXPECT_EQ(stripped(dicho, 2), "1[1[0][0]][1[0][0]]");
    EXPECT_EQ(stripped(dicho, 3), "1[1[1[0][0]][1[0][0]]][1[1[0][0]][1[0][0]]]");
}

// ---------------------------------------------------------------------------------------
// Ch. 6: the bag of candies kolam, a table L-system.

TEST(Models, BagOfCandiesUsesTableOneForNMinusTwoSteps) {
    for (int n : {3, 4, 5}) {
        SCOPED_TRACE(n);
        Model ls = example("fig6.5-bag-of-candies.l", {{"N", std::to_string(n)}});
        EXPECT_EQ(ls.lsystem.derivationLength, n);
        for (int step = 1; step <= n - 2; ++step) EXPECT_EQ(ls.lsystem.tableForStep(step), 0);
        EXPECT_EQ(ls.lsystem.tableForStep(n - 1), 1);
        EXPECT_EQ(ls.lsystem.tableForStep(n), 1);
        ModuleString before = derive(ls, n - 2);
        EXPECT_EQ(countOf(before, 'A') + countOf(before, 'B'), 0u);
        ModuleString last = derive(ls, n);
        EXPECT_EQ(countOf(last, 'X') + countOf(last, 'A') + countOf(last, 'B'), 0u);
    }
    Model ls = example("fig6.5-bag-of-candies.l");
    EXPECT_EQ(str(ls, 1), "-XfX--XfX--XfX--XfX");
    EXPECT_EQ(str(ls, 2).substr(0, 11), "-BfA--BfAfB");
}
