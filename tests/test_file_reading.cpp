// Files named by user text are read only when they are files: a device would never end,
// a huge file would fill memory. Each case is what a user could write by mistake.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <chrono>
#include <fstream>
#include <thread>

#include "graftal/core/file_reading.hpp"
#include "graftal/geometry/surface.hpp"
#include "graftal/lang/model.hpp"
#include "process.hpp"

using graftal::testing::runGraftal;
using graftal::testing::TempDir;

namespace {

std::string messagesOf(const graftal::ParseResult& r) {
    std::string all;
    for (const auto& d : r.diagnostics)
        all += d.location.file + ":" + std::to_string(d.location.line) + ":" +
               std::to_string(d.location.column) + ": " + d.message + "\n";
    return all;
}

}  // namespace

TEST(FileReading, ARegularFileIsReadWhole) {
    TempDir t;
    auto f = t.write("a.l", std::string("axiom: F\n") + std::string(100000, ' '));
    std::string problem;
    auto bytes = graftal::readUserFile(f, problem);
    ASSERT_TRUE(bytes) << problem;
    EXPECT_EQ(bytes->size(), 100009u);
}

TEST(FileReading, DevicesDirectoriesAndMissingFilesAreNamedProblems) {
    TempDir t;
    std::string problem;
    EXPECT_FALSE(graftal::readUserFile("/dev/zero", problem));
    EXPECT_EQ(problem, "is a device, not a file");
    EXPECT_FALSE(graftal::readUserFile(t.path(), problem));
    EXPECT_EQ(problem, "is a directory, not a file");
    EXPECT_FALSE(graftal::readUserFile(t.path() / "none.l", problem));
    EXPECT_EQ(problem, "cannot be opened (does it exist?)");
}

TEST(FileReading, AFileOverTheLimitIsRefusedAndOneAtTheLimitRead) {
    TempDir t;
    auto f = t.write("big.s", std::string(2048, 'x'));
    std::string problem;
    EXPECT_FALSE(graftal::readUserFile(f, problem, 2047));
    EXPECT_EQ(problem, "is larger than 2047 bytes, more than any file graftal reads there");
    EXPECT_FALSE(graftal::readUserFile(f, problem, 1024));
    EXPECT_EQ(problem, "is larger than 1 KB, more than any file graftal reads there");
    auto bytes = graftal::readUserFile(f, problem, 2048);
    ASSERT_TRUE(bytes) << problem;
    EXPECT_EQ(bytes->size(), 2048u);
}

TEST(FileReading, APipeIsReadUpToTheLimit) {
    TempDir t;
    auto fifo = t.path() / "model.fifo";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    std::thread writer([&] {
        std::ofstream out(fifo, std::ios::binary);
        out << std::string(5000, 'F');
    });
    std::string problem;
    auto bytes = graftal::readUserFile(fifo, problem, 4096);
    writer.join();
    EXPECT_FALSE(bytes);
    EXPECT_EQ(problem, "is larger than 4 KB, more than any file graftal reads there");

    std::thread writer2([&] {
        std::ofstream out(fifo, std::ios::binary);
        out << "axiom: F\n";
    });
    bytes = graftal::readUserFile(fifo, problem, 4096);
    writer2.join();
    ASSERT_TRUE(bytes) << problem;
    EXPECT_EQ(*bytes, "axiom: F\n");
}

TEST(FileReading, AModelThatIsADeviceIsAnErrorNotAnEndlessRead) {
    auto r = graftal::loadModel("/dev/zero");
    EXPECT_FALSE(r.ok());
    EXPECT_EQ(messagesOf(r), "/dev/zero:0:0: is a device, not a file\n");
}

TEST(FileReading, AnIncludedDeviceIsAnErrorAtTheInclude) {
    TempDir t;
    auto f = t.write("inc.l", "axiom: F\n#include \"/dev/zero\"\nF --> FF\n");
    auto start = std::chrono::steady_clock::now();
    auto r = graftal::loadModel(f);
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
    EXPECT_FALSE(r.ok());
    EXPECT_EQ(messagesOf(r),
              f.string() + ":2:10: the included file '/dev/zero' is a device, not a file\n");
}

TEST(FileReading, ViewFilesNamingDevicesAreErrorsAtTheirLines) {
    TempDir t;
    auto l = t.write("m.l", "axiom: F\nF --> F\n");
    auto v = t.write("m.v", "angle increment: 30\ncontour: 1 /dev/zero\n");
    graftal::ParseOptions options;
    options.viewFile = v.string();
    auto r = graftal::loadModel(l, options);
    EXPECT_TRUE(r.ok()) << "cpfg forgives its view files: a warning";
    EXPECT_NE(messagesOf(r).find(v.string() +
                                 ":2:10: the contour file '/dev/zero' is a device, not a file"),
              std::string::npos)
        << messagesOf(r);

    options.viewFile = "/dev/zero";
    r = graftal::loadModel(l, options);
    EXPECT_EQ(messagesOf(r), "/dev/zero:0:0: the view file is a device, not a file\n");
}

TEST(FileReading, ASurfaceFileThatIsADeviceIsAnError) {
    try {
        (void)graftal::loadSurface("/dev/zero");
        FAIL() << "a device read as a surface";
    } catch (const graftal::Error& e) {
        EXPECT_STREQ(e.what(), "/dev/zero: error: the surface file is a device, not a file");
    }
}

TEST(FileReading, StandardInputRedirectedFromADeviceIsAnError) {
    auto r = runGraftal("derive -", "/dev/zero");
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.err.find("standard input is a device, not a file"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty());
}

TEST(FileReading, TheCommandLineSaysWhatTheModelIs) {
    auto r = runGraftal("derive /dev/zero");
    EXPECT_NE(r.status, 0);
    EXPECT_EQ(r.err, "/dev/zero: error: is a device, not a file\n");
}
