// The parallel streamed derivation gives the held string, its text, its counts and its
// turtle measures, for every example that can be streamed and any thread count.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "graftal/output/string_text_writer.hpp"
#include "graftal/pipeline/export.hpp"
#include "graftal/pipeline/statistics.hpp"
#include "graftal/rewrite/parallel_stream.hpp"
#include "graftal/rewrite/streamed_runs.hpp"
#include "graftal/rewrite/streaming.hpp"
#include "graftal/turtle/streamed_interpretation.hpp"
#include "test_helpers.hpp"

using namespace graftal;
using graftal::testing::loadExample;
using graftal::testing::parseModel;

namespace {

using Collect = graftal::testing::ModuleCollector;

// The examples the parallel stream applies to, each with a step count whose string has
// between a few hundred and about 200,000 modules (so that several chunks are made).
struct Case {
    std::string name;
    Model model;
    int steps;
};

std::vector<Case> streamableExamples() {
    std::vector<Case> cases;
    const std::filesystem::path dir = std::filesystem::path(GRAFTAL_EXAMPLES_DIR);
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(dir))
        if (e.path().extension() == ".l") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    for (const auto& f : files) {
        Model m;
        try {
            m = loadExample(f);
        } catch (const Error&) {
            continue;
        }
        if (!streamsInParallel(m.lsystem)) continue;
        int steps = 0;
        for (int n = 1; n <= std::min(m.lsystem.derivationLength, 12); ++n) {
            if (derive(m, n).size() > 200000) break;
            steps = n;
        }
        cases.push_back({f.filename().string(), std::move(m), steps});
    }
    return cases;
}

const std::vector<Case>& examples() {
    static const std::vector<Case> cases = streamableExamples();
    return cases;
}

ModuleString parallelString(const LSystem& ls, int steps, unsigned threads,
                            Precision precision = Precision::Single) {
    DerivationOptions options;
    options.threads = threads;
    options.precision = precision;
    ModuleString all(precision);
    streamDerivationParallel(ls, steps, nullptr,
                             [&](const StreamBlock& b) { all.append(b.modules); }, options);
    return all;
}

}  // namespace

TEST(ParallelStream, ManyParametricAndD0LExamplesApply) {
    std::size_t parametric = 0, plain = 0;
    for (const Case& c : examples()) (c.model.lsystem.isParametric() ? parametric : plain)++;
    EXPECT_GE(parametric, 5u);
    EXPECT_GE(plain, 5u);
}

TEST(ParallelStream, SameStringAsTheHeldDerivationForAnyThreadCount) {
    for (const Case& c : examples()) {
        for (Precision precision : {Precision::Single, Precision::Double}) {
            DerivationOptions held;
            held.precision = precision;
            const ModuleString expected = derive(c.model, c.steps, held);
            for (unsigned threads : {1u, 2u, 4u}) {
                EXPECT_TRUE(parallelString(c.model.lsystem, c.steps, threads, precision) ==
                            expected)
                    << c.name << " n=" << c.steps << " threads=" << threads;
                // streamDerivation() hands the same modules to a sink, on one thread or many.
                Collect sink;
                DerivationOptions options = held;
                options.threads = threads;
                streamDerivation(c.model.lsystem, c.steps, sink, options);
                ModuleString got = sink.s;
                got.setPrecision(precision);
                EXPECT_TRUE(got == expected) << c.name << " threads=" << threads;
            }
        }
    }
}

TEST(ParallelStream, CountsAreTheHeldStringsCounts) {
    for (const Case& c : examples()) {
        const ModuleString held = derive(c.model, c.steps);
        const auto expected = countSymbols(held, c.model.lsystem.symbols.size(), 1);
        for (unsigned threads : {1u, 2u, 4u}) {
            DerivationOptions options;
            options.threads = threads;
            EXPECT_EQ(countStreamedParallel(c.model.lsystem, c.steps, options), expected)
                << c.name << " threads=" << threads;
            // Through `graftal stats --no-geometry`, streamed or not.
            for (StreamPolicy policy : {StreamPolicy::Auto, StreamPolicy::Always}) {
                DeriveRequest request;
                request.steps = c.steps;
                request.threads = threads;
                request.stream = policy;
                const ModelStatistics stats = measured(c.model, request, false);
                EXPECT_EQ(stats.symbolCounts, expected) << c.name;
                EXPECT_EQ(stats.modules, held.size()) << c.name;
            }
        }
    }
}

TEST(ParallelStream, DeriveWritesTheHeldStringsTextForAnyThreadCount) {
    for (const Case& c : examples()) {
        std::ostringstream held;
        writeStringText(derive(c.model, c.steps), c.model.lsystem.symbols, held, 1);
        for (unsigned threads : {1u, 2u, 4u}) {
            for (StreamPolicy policy : {StreamPolicy::Auto, StreamPolicy::Always}) {
                std::string text;
                ExportRequest request;
                request.steps = c.steps;
                request.threads = threads;
                request.stream = policy;
                exportModel(c.model, Destination::memory(text, "a.txt"), request);
                EXPECT_EQ(text, held.str()) << c.name << " threads=" << threads;
            }
        }
    }
}

TEST(ParallelStream, TheStreamedTurtleMeasuresTheHeldString) {
    for (const Case& c : examples()) {
        const ModuleString held = derive(c.model, c.steps);
        const StreamedMeasure expected = measureModules(c.model, held);
        const Bounds volume = cpfgViewVolume(c.model, held);
        for (unsigned threads : {1u, 2u, 4u}) {
            DerivationOptions options;
            options.threads = threads;
            const StreamedMeasure m = measureStreamed(c.model, c.steps, options, true, true);
            EXPECT_EQ(m.modules, held.size()) << c.name;
            EXPECT_EQ(m.symbolCounts, expected.symbolCounts) << c.name;
            EXPECT_EQ(m.segments, expected.segments) << c.name;
            EXPECT_EQ(m.polygons, expected.polygons) << c.name;
            EXPECT_EQ(m.bounds.min, volume.min) << c.name << " threads=" << threads;
            EXPECT_EQ(m.bounds.max, volume.max) << c.name << " threads=" << threads;
        }
    }
}

TEST(ParallelStream, AStringOfMillionsOfModulesIsCountedDrawnAndWrittenAsWhenHeld) {
    // Honda's tree of the bench at n = 18 (1.8 million modules): the automatic choice takes
    // the parallel stream there.
    const Model m = loadExample(std::filesystem::path(GRAFTAL_EXAMPLES_DIR) /
                                "../bench/cpfg/honda-2.6a.l");
    ASSERT_TRUE(parallelStreamPays(m.lsystem, 18, 2));
    const ModuleString held = derive(m, 18);
    ASSERT_GT(held.size(), 1000000u);
    DeriveRequest request;
    request.steps = 18;
    request.threads = 2;
    const ModelStatistics counted = measured(m, request, false);
    EXPECT_EQ(counted.symbolCounts, countSymbols(held, m.lsystem.symbols.size(), 1));
    const ModelStatistics drawn = measured(m, request, true);
    const StreamedMeasure expected = measureModules(m, held);
    EXPECT_EQ(drawn.segments, expected.segments);
    EXPECT_EQ(drawn.bounds.min, cpfgViewVolume(m, held).min);
    EXPECT_EQ(drawn.bounds.max, cpfgViewVolume(m, held).max);
    std::ostringstream text;
    writeStringText(held, m.lsystem.symbols, text, 1);
    std::string streamed;
    ExportRequest exportRequest;
    exportRequest.steps = 18;
    exportRequest.threads = 2;
    exportModel(m, Destination::memory(streamed, "a.txt"), exportRequest);
    // Compared as a whole: a difference in megabytes of text is not worth printing.
    const std::string expectedText = text.str();
    std::size_t at = 0;
    while (at < std::min(streamed.size(), expectedText.size()) && streamed[at] == expectedText[at])
        ++at;
    EXPECT_TRUE(streamed == expectedText)
        << "sizes " << streamed.size() << " and " << expectedText.size() << ", first difference at "
        << at << ": " << streamed.substr(at > 40 ? at - 40 : 0, 80) << " / "
        << expectedText.substr(at > 40 ? at - 40 : 0, 80);
}

TEST(ParallelStream, ACancelledStreamStops) {
    const Case* big = nullptr;
    for (const Case& c : examples())
        if (c.model.lsystem.isParametric()) big = &c;
    ASSERT_NE(big, nullptr);
    DerivationOptions options;
    options.threads = 2;
    options.cancel.cancel();
    EXPECT_THROW(streamDerivationParallel(big->model.lsystem, big->steps, nullptr,
                                          [](const StreamBlock&) {}, options),
                 Error);
}

TEST(ParallelStream, ErrorsOfTheConsumerStopTheWorkers) {
    for (const Case& c : examples()) {
        if (c.steps < 3) continue;
        DerivationOptions options;
        options.threads = 4;
        EXPECT_THROW(streamDerivationParallel(
                         c.model.lsystem, c.steps, nullptr,
                         [](const StreamBlock&) { throw Error(SourceLocation{}, "stop"); },
                         options),
                     Error)
            << c.name;
    }
}

// A first chunk far larger than the others (C triples at every step, A grows as the
// Fibonacci words), chunks of many blocks, and a consumer slower than the workers: while
// the consumer still reads the first chunk, the other workers fill all the blocks they may
// queue and wait; the first chunk's worker must never wait for them. The string is the held
// one, in order.
TEST(ParallelStream, WorkersAheadOfASlowConsumerWaitAndGoOn) {
    const LSystem ls = graftal::testing::parse("Lsystem: 1\naxiom: C" + std::string(16383, 'A') +
                                               "\nC --> CCC\nA --> AB\nB --> A\nendlsystem\n");
    ASSERT_TRUE(streamsInParallel(ls));
    // On two threads: 64 chunks; the first 4.8 M modules (146 blocks), each other one
    // 256 As of 987 modules (7 blocks or more), nine of them in the window.
    const ModuleString held = derive(ls, 14);
    ASSERT_GT(held.size(), 20000000u);
    for (unsigned threads : {2u, 3u}) {
        DerivationOptions options;
        options.threads = threads;
        ModuleString all;
        std::size_t blocks = 0;
        streamDerivationParallel(
            ls, 14, nullptr,
            [&](const StreamBlock& b) {
                all.append(b.modules);
                if (++blocks % 2 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
            },
            options);
        EXPECT_GT(blocks, 600u);
        EXPECT_TRUE(all == held) << threads << " threads: " << all.size() << " modules, expected "
                                 << held.size();
    }
}
