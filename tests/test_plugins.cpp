// The heavy writers are plugins (src/plugins/plugin_loader.hpp): a command that makes no
// picture, animation, sound or studio never loads their libraries (read from the dynamic
// loader's own report, LD_DEBUG=libs), and a missing or broken plugin is an error that names
// the format and the file looked for. A static build links the writers and has no plugins.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "process.hpp"
#include "test_helpers.hpp"

namespace {

namespace fs = std::filesystem;
using graftal::testing::readFile;
using graftal::testing::RunResult;
using graftal::testing::TempDir;

const fs::path kExamples = GRAFTAL_EXAMPLES_DIR;
const std::string kFibonacci = (kExamples / "fig1.3-fibonacci.l").string();
const std::string kKoch = (kExamples / "fig2.2-quadratic-koch-island.l").string();

// The libraries of Cairo, Embree, the animation encoders, FFmpeg, libsmf, FluidSynth and
// the studio's server.
const char* const kHeavy[] = {"libcairo",      "libembree",      "libtbb", "libgif",
                              "libwebp",       "libavcodec",     "libavformat", "libsmf",
                              "libfluidsynth", "libcpp-httplib", "libssl", "libcrypto"};

bool pluginsBuilt() {
    return fs::is_directory(fs::path(GRAFTAL_EXE).parent_path() / "graftal-plugins");
}

// graftal with `environment` (VAR=value ...) added to its own.
RunResult runWith(const std::string& environment, const std::string& args) {
    TempDir dir;
    const fs::path out = dir.path() / "out", err = dir.path() / "err";
    const std::string command = "env " + environment + " " + GRAFTAL_EXE + " " + args + " > " +
                                out.string() + " 2> " + err.string() + " < /dev/null";
    const int raw = std::system(command.c_str());
    RunResult r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
    r.out = readFile(out);
    r.err = readFile(err);
    return r;
}

// The shared libraries the run initialised, as the dynamic loader reports them.
std::vector<std::string> librariesOf(const std::string& args) {
    const RunResult r = runWith("LD_DEBUG=libs", args);
    EXPECT_EQ(r.status, 0) << args << "\n" << r.err.substr(0, 2000);
    std::vector<std::string> libraries;
    std::istringstream lines(r.err);
    const std::string marker = "calling init: ";
    for (std::string line; std::getline(lines, line);)
        if (auto at = line.find(marker); at != std::string::npos)
            libraries.push_back(line.substr(at + marker.size()));
    return libraries;
}

bool loads(const std::vector<std::string>& libraries, const std::string& name) {
    for (const std::string& library : libraries)
        if (fs::path(library).filename().string().starts_with(name)) return true;
    return false;
}

TEST(Plugins, CommandsThatMakeNoPictureLoadNoHeavyLibrary) {
    if (!pluginsBuilt()) GTEST_SKIP() << "a static build links the writers";
    TempDir dir;
    const std::string svg = (dir.path() / "x.svg").string();
    const std::vector<std::string> commands = {
        "--version",      "derive " + kFibonacci,           "stats " + kFibonacci,
        "derive " + kKoch, "stats " + kKoch,                 "render " + kKoch + " -o " + svg,
        "render -q " + kFibonacci + " -o " + svg};
    for (const std::string& args : commands) {
        const std::vector<std::string> libraries = librariesOf(args);
        ASSERT_TRUE(loads(libraries, "libgraftal_core")) << "no loader report for " << args;
        for (const char* heavy : kHeavy)
            EXPECT_FALSE(loads(libraries, heavy)) << args << ": " << heavy;
    }
}

// This process's children, as the folders of /proc that describe them.
std::vector<fs::path> children() {
    std::vector<fs::path> found;
    for (const auto& entry : fs::directory_iterator("/proc")) {
        std::ifstream stat(entry.path() / "stat");
        std::string line;
        if (!std::getline(stat, line)) continue;
        // pid (name) state ppid ...: the name may hold spaces and parentheses.
        const std::size_t close = line.rfind(')');
        if (close == std::string::npos) continue;
        std::istringstream rest(line.substr(close + 1));
        std::string state;
        long parent = 0;
        rest >> state >> parent;
        if (parent == ::getpid()) found.push_back(entry.path());
    }
    return found;
}

TEST(Plugins, ThePreprocessorRunsAsASmallProgramOfItsOwnOrElseAsAFork) {
    // A fork of a large host (Python, a Dask worker) would make its every page copy-on-write.
    if (!pluginsBuilt()) GTEST_SKIP() << "a static build forks its preprocessor";
    const std::string model = "#define N 3\nLsystem: 1\naxiom: A(N)\nendlsystem\n";
    EXPECT_EQ(graftal::testing::derived(graftal::testing::parse(model), 0), "A(3)");
    int programs = 0;
    for (const fs::path& child : children()) {
        std::error_code ec;
        if (fs::read_symlink(child / "exe", ec).filename() != "graftal-cpp") continue;
        ++programs;
        // It maps libmcpp and libc, and none of graftal's libraries.
        std::ifstream maps(child / "maps");
        const std::string mapped{std::istreambuf_iterator<char>(maps), {}};
        EXPECT_NE(mapped.find("libmcpp"), std::string::npos);
        EXPECT_EQ(mapped.find("libgraftal"), std::string::npos);
        EXPECT_EQ(mapped.find("libstdc++"), std::string::npos);
    }
    EXPECT_EQ(programs, 1) << "one child process runs graftal-plugins/graftal-cpp";

    // Without the program (another plugin folder), the preprocessor is a fork: same result.
    TempDir dir;
    const fs::path file = dir.path() / "n.l";
    std::ofstream(file) << model;
    const RunResult r =
        runWith("GRAFTAL_PLUGIN_DIR=" + dir.path().string(), "derive -n 0 " + file.string());
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out, "A(3)\n");
}

TEST(Plugins, APngLoadsCairoThroughItsPlugin) {
    if (!pluginsBuilt()) GTEST_SKIP() << "a static build links the writers";
    TempDir dir;
    const fs::path png = dir.path() / "koch.png";
    const std::vector<std::string> libraries =
        librariesOf("render " + kKoch + " -o " + png.string());
    EXPECT_TRUE(loads(libraries, "graftal_plugin_cairo.so"));
    EXPECT_TRUE(loads(libraries, "libcairo"));
    EXPECT_FALSE(loads(libraries, "libembree"));
    EXPECT_FALSE(loads(libraries, "libavcodec"));
    EXPECT_EQ(readFile(png).substr(1, 3), "PNG");
}

TEST(Plugins, AMissingPluginNamesTheFormatAndTheFileLookedFor) {
    if (!pluginsBuilt()) GTEST_SKIP() << "a static build links the writers";
    TempDir empty, out;
    const std::string environment = "GRAFTAL_PLUGIN_DIR=" + empty.path().string();
    // What needs no plugin still works.
    EXPECT_EQ(runWith(environment, "stats " + kKoch).status, 0);
    EXPECT_EQ(runWith(environment, "render " + kKoch + " -o " + (out.path() / "k.svg").string())
                  .status,
              0);
    struct Case {
        std::string args, format, plugin;
    };
    const Case cases[] = {
        {"render " + kKoch + " -o " + (out.path() / "k.png").string(), "PNG",
         "graftal_plugin_cairo.so"},
        {"animate " + kKoch + " --size 64x64 -o " + (out.path() / "k.mp4").string(), "MP4",
         "graftal_plugin_video.so"},
        {"animate " + kKoch + " --size 64x64 -o " + (out.path() / "k.gif").string(), "GIF",
         "graftal_plugin_animation.so"},
        {"music " + (kExamples / "fig6.9-hilbert-music.l").string() + " -o " +
             (out.path() / "h.wav").string(),
         "WAV", "graftal_plugin_audio.so"},
    };
    for (const Case& c : cases) {
        const RunResult r = runWith(environment, c.args);
        EXPECT_EQ(r.status, 1) << c.args << "\n" << r.err;
        EXPECT_NE(r.err.find(c.format), std::string::npos) << r.err;
        EXPECT_NE(r.err.find((empty.path() / c.plugin).string()), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("missing"), std::string::npos) << r.err;
    }
    EXPECT_FALSE(fs::exists(out.path() / "k.png"));
}

TEST(Plugins, ABrokenPluginIsAnErrorNotACrash) {
    if (!pluginsBuilt()) GTEST_SKIP() << "a static build links the writers";
    TempDir plugins, out;
    plugins.write("graftal_plugin_cairo.so", "not a shared library\n");
    const RunResult r = runWith("GRAFTAL_PLUGIN_DIR=" + plugins.path().string(),
                                "render " + kKoch + " -o " + (out.path() / "k.png").string());
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find("PNG"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("graftal_plugin_cairo.so, which cannot be loaded"), std::string::npos)
        << r.err;
}

}  // namespace
