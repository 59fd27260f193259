// `stats --no-geometry` counts the last step without writing it. For strings without
// parameters that count comes from the fast path's successor table or from the context
// path's choices; either must give exactly the counts of the string the step writes.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "graftal/rewrite/derivation.hpp"
#include "test_helpers.hpp"

using namespace graftal;
using graftal::testing::parse;

namespace {

// Counts the next step of `ls` after `before` steps, then does it, and compares.
void expectCountsOfTheStep(const LSystem& ls, int before, unsigned threads,
                           const std::string& what) {
    DerivationOptions o;
    o.threads = threads;
    Derivation d(ls, o);
    d.run(before);
    const std::vector<std::uint64_t> counted = d.countNextStep();
    ASSERT_FALSE(counted.empty()) << what << ": nothing counted";
    EXPECT_EQ(d.stepsDone(), before) << what << ": counting leaves the derivation as it was";
    d.step();
    EXPECT_EQ(counted, countSymbols(d.current(), ls.symbols.size(), 1))
        << what << " after " << before << " steps with " << threads << " threads";
}

std::string benchModel(const std::string& name) {
    return std::string(GRAFTAL_TESTS_DIR) + "/../bench/lsystems/" + name;
}

}  // namespace

// The D0L fast path and the context path, on strings past the parallel threshold (2^16
// modules) so that several threads really split the count.
TEST(CountNextStep, BenchModelsWithoutParametersAgreeWithTheWrittenStep) {
    struct Case {
        const char* file;
        int before;
    };
    for (const Case c : {Case{"koch-island.l", 5}, Case{"abop-1.24d.l", 9},
                         Case{"hogeweg-1.31a.l", 40}}) {
        const LSystem ls = loadLSystem(benchModel(c.file));
        ASSERT_FALSE(ls.isParametric()) << c.file;
        for (unsigned threads : {1u, 2u, 5u}) expectCountsOfTheStep(ls, c.before, threads, c.file);
    }
}

// Tables pick a different successor table per step; ignored symbols and brackets shape the
// contexts; a module left unchanged by every production is copied.
TEST(CountNextStep, TablesAndContextsAgreeWithTheWrittenStep) {
    const LSystem tables = parse(
        "Lsystem: 1\nderivation length: 6\naxiom: a\n"
        "table: one\na --> ab\nb --> a\n"
        "table: two\na --> b\nb --> bab\n"
        "table schedule: one 2, two 1, one\nendlsystem\n");
    for (int before = 0; before < 5; ++before) expectCountsOfTheStep(tables, before, 2, "tables");
    const LSystem context = parse(
        "Lsystem: 1\nderivation length: 8\nignore: +F\naxiom: bF[+a]aa+c\n"
        "b < a --> b\nb --> a[+b]c\na > c --> ca\nc --> F\nendlsystem\n");
    for (int before = 0; before < 7; ++before)
        expectCountsOfTheStep(context, before, 3, "context");
}

// Every example without parameters whose first steps derive: the count of each step equals
// the written step.
TEST(CountNextStep, ExamplesWithoutParametersAgreeWithTheWrittenStep) {
    int checked = 0;
    for (const auto& entry :
         std::filesystem::directory_iterator(std::string(GRAFTAL_TESTS_DIR) + "/../examples")) {
        if (entry.path().extension() != ".l") continue;
        LSystem ls;
        try {
            ls = loadLSystem(entry.path().string());
        } catch (const Error&) {
            continue;  // a map L-system or a model folder's part
        }
        if (ls.isParametric()) continue;
        const int steps = std::min(ls.derivationLength, 5);
        for (int before = 0; before < steps; ++before) {
            DerivationOptions o;
            o.threads = 2;
            Derivation d(ls, o);
            d.run(before);
            if (d.current().size() > 200'000) break;
            const std::vector<std::uint64_t> counted = d.countNextStep();
            if (counted.empty()) break;  // blocks, cuts, decompositions: done in full
            d.step();
            EXPECT_EQ(counted, countSymbols(d.current(), ls.symbols.size(), 1))
                << entry.path().filename() << " step " << before + 1;
            ++checked;
        }
    }
    EXPECT_GT(checked, 50) << "the examples without parameters were not found";
}
