// render(): the library makes the file `graftal render` makes; derivations and renders stop
// when cancelled from another thread and report their progress.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <thread>

#include "graftal/graftal.hpp"
#include "test_helpers.hpp"

using namespace graftal;
using graftal::testing::loadExample;
using graftal::testing::parseModel;

namespace {

std::filesystem::path scratch(const std::string& name) {
    std::filesystem::path dir = std::filesystem::temp_directory_path() / "graftal_pipeline_test";
    std::filesystem::create_directories(dir);
    std::filesystem::path p = dir / name;
    std::filesystem::remove(p);
    return p;
}

std::string bytesOf(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A linear growth whose every step walks the whole string: long enough to cancel.
const char* kLongGrowth = "Lsystem: 1\nderivation length: 200000\naxiom: A\nA --> AB\nendlsystem\n";

}  // namespace

TEST(Pipeline, RendersA3DPlantAsTheCommandDoes) {
    const std::filesystem::path plant =
        std::filesystem::path(GRAFTAL_EXAMPLES_DIR) / "fig4.1-generic-plant.l";
    std::filesystem::path fromLibrary = scratch("library.png"), fromCli = scratch("cli.png");
    RenderRequest request;
    request.output = fromLibrary;
    request.picture.width = request.picture.height = 120;
    RenderResult result = render(loadExample(plant), request);
    EXPECT_EQ(result.route, RenderRoute::RayTraced);
    EXPECT_TRUE(result.notes.empty());

    std::string command = std::string(GRAFTAL_EXE) + " render " + plant.string() + " -o " +
                          fromCli.string() + " --size 120x120";
    ASSERT_EQ(std::system(command.c_str()), 0);
    const std::string picture = bytesOf(fromLibrary);
    EXPECT_GT(picture.size(), 1000u);
    EXPECT_EQ(picture, bytesOf(fromCli)) << "the same PNG, byte for byte";
}

TEST(Pipeline, ChoosesLineArtAMeshAndTheDerivationDiagram) {
    Model koch = parseModel(
        "Lsystem: 1\nderivation length: 2\nangle increment: 90\naxiom: F-F-F-F\n"
        "F --> F-F+F+FF-F-F+F\nendlsystem\n");
    RenderRequest request;
    request.output = scratch("koch.svg");
    RenderResult svg = render(koch, request);
    EXPECT_EQ(svg.route, RenderRoute::LineArt);
    EXPECT_EQ(svg.steps, 2);
    EXPECT_NE(bytesOf(request.output).find("<svg"), std::string::npos);

    request.output = scratch("koch.obj");
    EXPECT_EQ(render(koch, request).route, RenderRoute::Mesh);
    EXPECT_NE(bytesOf(request.output).find("\nv "), std::string::npos);

    Model words = parseModel(
        "Lsystem: 1\nderivation length: 3\naxiom: b\na --> ab\nb --> a\n"
        "endlsystem\n");
    std::vector<std::string> told;
    request.output = scratch("words.svg");
    request.notify = [&](const Diagnostic& d) { told.push_back(d.message); };
    RenderResult diagram = render(words, request);
    EXPECT_EQ(diagram.route, RenderRoute::DerivationDiagram);
    ASSERT_EQ(diagram.notes.size(), 1u);
    EXPECT_EQ(diagram.notes[0].severity, Severity::Note);
    EXPECT_EQ(diagram.notes[0].message, "the string draws nothing; drawing its derivation instead");
    EXPECT_EQ(told, std::vector<std::string>{diagram.notes[0].message});
}

TEST(Pipeline, RefusesAnUnknownFormatBeforeDeriving) {
    RenderRequest request;
    request.output = scratch("plant.xyz");
    try {
        checkRenderRequest(request);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("unknown format"), std::string::npos) << e.what();
    }
}

TEST(Pipeline, ProgressReportsEveryStepInOrder) {
    Model m = parseModel("Lsystem: 1\nderivation length: 5\naxiom: A\nA --> AB\nendlsystem\n");
    std::vector<std::pair<int, std::size_t>> seen;
    RenderRequest request;
    request.output = scratch("progress.svg");
    request.progress = [&](int step, std::size_t modules) { seen.emplace_back(step, modules); };
    render(m, request);
    // The string draws nothing, so the diagram derives again: each run counts 1..5.
    ASSERT_GE(seen.size(), 5u);
    for (int k = 0; k < 5; ++k) {
        EXPECT_EQ(seen[k].first, k + 1);
        EXPECT_EQ(seen[k].second, static_cast<std::size_t>(k + 2)) << "A B...B: step + 1 B's";
    }
}

TEST(Cancellation, StopsALongDerivationFromAnotherThread) {
    Model m = parseModel(kLongGrowth);
    DerivationOptions options;
    std::atomic<int> lastStep{0};
    options.progress = [&](int step, std::size_t) { lastStep = step; };
    CancellationToken token = options.cancel;
    std::thread canceller([&] {
        while (lastStep < 100) std::this_thread::yield();
        token.cancel();
    });
    EXPECT_THROW(derive(m, 200000, options), Cancelled);
    canceller.join();
    EXPECT_GE(lastStep.load(), 100);
    EXPECT_LT(lastStep.load(), 200000) << "stopped long before the end";
}

TEST(Cancellation, ACancelledStepLeavesTheStringAsItWas) {
    Model m = parseModel(kLongGrowth);
    DerivationOptions options;
    CancellationToken token = options.cancel;
    Derivation d(m, options);
    d.run(3);
    token.cancel();
    EXPECT_THROW(d.step(), Cancelled);
    EXPECT_EQ(d.current().toString(m.lsystem.symbols), "ABBB");
}

TEST(Cancellation, ACancelledRenderLeavesNoFile) {
    Model m = parseModel("Lsystem: 1\nderivation length: 200000\naxiom: A\nA --> AF\nendlsystem\n");
    RenderRequest request;
    request.output = scratch("cancelled.png");
    request.stream = StreamPolicy::Auto;
    std::atomic<int> lastStep{0};
    request.progress = [&](int step, std::size_t) { lastStep = step; };
    CancellationToken token = request.cancel;
    std::thread canceller([&] {
        while (lastStep < 50) std::this_thread::yield();
        token.cancel();
    });
    try {
        render(m, request);
        ADD_FAILURE() << "not cancelled";
    } catch (const Cancelled& e) {
        EXPECT_EQ(e.messages(), "cancelled");
    }
    canceller.join();
    EXPECT_FALSE(std::filesystem::exists(request.output));
}
