// The findings of the second fuzzing campaign (docs/reliability.md) and the studio's guards
// against other sites' pages and bursts of requests: each ends in a clear error or a bounded
// result, never a crash, a hang, an orphan process or memory past the limit.
#include <gtest/gtest.h>
#include <httplib.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "graftal/core/diagnostics.hpp"
#include "graftal/geometry/mesh.hpp"
#include "graftal/lang/source_text.hpp"
#include "graftal/music/music.hpp"
#include "graftal/output/render3d.hpp"
#include "graftal/studio/studio_server.hpp"
#include "lang/preprocessor.hpp"
#include "process.hpp"

namespace fs = std::filesystem;
using graftal::testing::runGraftal;
using graftal::testing::TempDir;
using nlohmann::json;

namespace {

std::string regression(const std::string& name) {
    return std::string(GRAFTAL_TESTS_DIR) + "/regressions/" + name;
}
std::string example(const std::string& name) {
    return std::string(GRAFTAL_EXAMPLES_DIR) + "/" + name;
}

// --- 1: libmcpp's macro lookup ---------------------------------------------------------

TEST(Reliability, PreprocessorComparesMacroNamesWithinTheirLength) {
    // 01-mcpp-macro-lookup-overread.l: an identifier in __FILE__'s hash chain, longer than
    // it; the lookup read 26 bytes past a 66-byte block (ASan, in the fuzz build's replay
    // of fuzz/regressions/parse/mcpp-*.l).
    graftal::PreprocessOptions options;
    options.fileName = "overread.l";
    graftal::SourceText out;
    graftal::DiagnosticList diags;
    graftal::preprocessSource("kkkkkkkkkkkkkkkkkkosition\n#define A 1\nA\n", options, out, diags);
    EXPECT_TRUE(graftal::mcppComparesWithinNames());
    // The text is preprocessed as before: the macro expands, the long name stays.
    std::string text;
    for (const auto& line : out.lines) text += line.text + "\n";
    EXPECT_NE(text.find("kkkkkkkkkkkkkkkkkkosition"), std::string::npos) << text;
    EXPECT_NE(text.find("1"), std::string::npos) << text;
}

// --- 3: the WAV writer ----------------------------------------------------------------

TEST(Reliability, WavOfALongScoreIsRefusedWithinTheMemoryLimit) {
    TempDir dir;
    graftal::Score score;
    score.tempo = 60;
    score.notes.push_back({60, 0, 10000, 80});  // 10,000 beats: 2.8 hours at 60 bpm
    graftal::AudioOptions audio;
    audio.memoryLimit = std::size_t(64) << 20;
    const auto started = std::chrono::steady_clock::now();
    try {
        graftal::writeWav(score, dir.path() / "long.wav", audio);
        FAIL() << "a 2.8-hour sound was written under a 64 MiB limit";
    } catch (const graftal::Error& e) {
        const std::string m = e.messages();
        EXPECT_NE(m.find("memory limit of 64 MiB"), std::string::npos) << m;
        EXPECT_NE(m.find("lower the steps"), std::string::npos) << m;
    }
    EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(5));
    EXPECT_FALSE(fs::exists(dir.path() / "long.wav"));
}

TEST(Reliability, MusicCommandHonoursTheMemoryLimitAndRefusesAnAbsurdTempo) {
    TempDir dir;
    const auto started = std::chrono::steady_clock::now();
    auto r =
        runGraftal("music -q --memory-limit 64M " + regression("music-wav-unbounded-buffer.l") +
                   " -o " + (dir.path() / "x.wav").string());
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find("over the memory limit of 64 MiB"), std::string::npos) << r.err;
    EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(30));
    r = runGraftal("music -q --tempo 1e-300 " + example("fig6.9-hilbert-music.l") + " -o " +
                   (dir.path() / "y.wav").string());
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find("tempo"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("vector"), std::string::npos) << r.err;
}

// --- 4: LilyPond ----------------------------------------------------------------------

bool alive(pid_t pid) {
    return ::kill(pid, 0) == 0;
}

pid_t readPid(const fs::path& file) {
    std::ifstream in(file);
    pid_t pid = 0;
    in >> pid;
    return pid;
}

// A lilypond that never ends: it writes its pid and sleeps.
fs::path sleepyLilyPond(const TempDir& dir) {
    const fs::path script = dir.write(
        "lilypond", "#!/bin/sh\necho $$ > " + (dir.path() / "pid").string() + "\nexec sleep 300\n");
    fs::permissions(script, fs::perms::owner_all);
    return script;
}

graftal::Score shortScore() {
    graftal::Score score;
    for (int i = 0; i < 8; ++i) score.notes.push_back({60 + i, double(i), 1, 80});
    return score;
}

TEST(Reliability, LilyPondIsStoppedAfterItsTimeLimit) {
    TempDir dir;
    ::setenv("GRAFTAL_LILYPOND", sleepyLilyPond(dir).c_str(), 1);
    ::setenv("GRAFTAL_LILYPOND_SECONDS", "1", 1);
    const auto started = std::chrono::steady_clock::now();
    try {
        graftal::engraveScore(shortScore(), dir.path() / "score.png");
        ADD_FAILURE() << "a lilypond that never ends gave a score";
    } catch (const graftal::Error& e) {
        EXPECT_NE(e.messages().find("lilypond took longer than 1 s"), std::string::npos)
            << e.messages();
    }
    ::unsetenv("GRAFTAL_LILYPOND");
    ::unsetenv("GRAFTAL_LILYPOND_SECONDS");
    EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(10));
    const pid_t pid = readPid(dir.path() / "pid");
    ASSERT_GT(pid, 0);
    EXPECT_FALSE(alive(pid)) << "lilypond " << pid << " still runs";
}

// LilyPond runs under the writer's memory limit: a lilypond that writes the address-space
// limit it was given (ulimit -v, in KiB) and fails.
TEST(Reliability, LilyPondRunsUnderTheMemoryLimit) {
    TempDir dir;
    const fs::path script =
        dir.write("lilypond", "#!/bin/sh\nulimit -v > " + (dir.path() / "limit").string() +
                                  "\necho 'not enough memory' >&2\nexit 1\n");
    fs::permissions(script, fs::perms::owner_all);
    ::setenv("GRAFTAL_LILYPOND", script.c_str(), 1);
    try {
        graftal::engraveScore(shortScore(), dir.path() / "score.pdf", std::size_t(64) << 20);
        ADD_FAILURE() << "a failed lilypond gave a score";
    } catch (const graftal::Error& e) {
        EXPECT_NE(e.messages().find("at most 64 MiB: --memory-limit"), std::string::npos)
            << e.messages();
        EXPECT_NE(e.messages().find("not enough memory"), std::string::npos) << e.messages();
    }
    ::unsetenv("GRAFTAL_LILYPOND");
    std::ifstream limit(dir.path() / "limit");
    long kib = 0;
    limit >> kib;
    EXPECT_EQ(kib, 64 * 1024);
    EXPECT_FALSE(fs::exists(dir.path() / "score.pdf"));
}

TEST(Reliability, LilyPondDiesWithGraftal) {
    TempDir dir;
    const std::string command = "GRAFTAL_LILYPOND=" + sleepyLilyPond(dir).string() + " " +
                                GRAFTAL_EXE + " music -q " + example("fig6.9-hilbert-music.l") +
                                " -o " + (dir.path() / "s.png").string() +
                                " > /dev/null 2>&1 & echo $!";
    FILE* shell = ::popen(command.c_str(), "r");
    ASSERT_NE(shell, nullptr);
    pid_t graftal = 0;
    ASSERT_EQ(std::fscanf(shell, "%d", &graftal), 1);
    ::pclose(shell);
    pid_t lily = 0;
    for (int i = 0; i < 200 && lily <= 0; ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        lily = readPid(dir.path() / "pid");
    }
    ASSERT_GT(lily, 0) << "lilypond never started";
    ::kill(graftal, SIGTERM);
    bool gone = false;
    for (int i = 0; i < 100 && !gone; ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        gone = !alive(lily);
    }
    EXPECT_TRUE(gone) << "lilypond " << lily << " outlived graftal";
    if (!gone) ::kill(lily, SIGKILL);
}

TEST(Reliability, AScoreTooLongToEngraveIsRefusedAtOnce) {
    TempDir dir;
    graftal::Score score;
    for (int i = 0; i < 2049; ++i) score.notes.push_back({60, 4.0 * i, 4, 80});  // 2049 bars
    try {
        graftal::engraveScore(score, dir.path() / "long.png");
        FAIL() << "a 2049-bar score was engraved";
    } catch (const graftal::Error& e) {
        const std::string m = e.messages();
        // Refused for its length, or for lilypond missing: never run for minutes.
        EXPECT_TRUE(m.find("2049 bars") != std::string::npos ||
                    m.find("not installed") != std::string::npos)
            << m;
    }
}

// --- 6: the camera --------------------------------------------------------------------

TEST(Reliability, AFarViewpointIsAnErrorNotAnAbort) {
    TempDir dir;
    const std::string model = example("fig3.8-fern-3d.l");
    for (const std::string& camera :
         {std::string("--viewpoint 1e308,1e308,1e308"), std::string("--viewpoint 1e19,0,0")}) {
        auto r = runGraftal("render -q " + model + " " + camera + " -n 3 --size 64x64 -o " +
                            (dir.path() / "x.png").string());
        EXPECT_EQ(r.status, 1) << camera << ": " << r.err;
        EXPECT_NE(r.err.find("viewpoint"), std::string::npos) << camera << ": " << r.err;
        EXPECT_FALSE(fs::exists(dir.path() / "x.png")) << camera;
    }
    // From a view file, the value is refused where the file gives it (file:line:column);
    // a view file's value graftal cannot use may leave the setting's default, with that
    // message as a warning, as cpfg does: either way no abort, and no picture from there.
    const std::string view = regression("raytrace-huge-viewpoint.v");
    auto v = runGraftal("render " + model + " " + view + " -n 3 --size 64x64 -o " +
                        (dir.path() / "v.png").string());
    EXPECT_TRUE(v.status == 0 || v.status == 1) << v.err;
    EXPECT_NE(v.err.find("raytrace-huge-viewpoint.v:1:"), std::string::npos) << v.err;
    EXPECT_NE(v.err.find("viewpoint must be a finite point within 1e15"), std::string::npos)
        << v.err;
    EXPECT_EQ(fs::exists(dir.path() / "v.png"), v.status == 0);
    // A near one still draws.
    auto r = runGraftal("render -q " + model + " --viewpoint 0,12,22 -n 3 --size 64x64 -o " +
                        (dir.path() / "y.png").string());
    EXPECT_EQ(r.status, 0) << r.err;
}

TEST(Reliability, RayTracerRefusesCameraValuesOutOfRange) {
    graftal::Mesh triangle;
    triangle.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    triangle.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    triangle.indices = {0, 1, 2};
    triangle.triangleColor = {0};
    triangle.palette = {{0.2f, 0.6f, 0.2f}};
    graftal::RaytraceOptions o;
    o.width = o.height = 8;
    o.threads = 1;
    EXPECT_EQ(graftal::renderRaytracedPixels(triangle, o).size(), 8u * 8u * 3u);
    for (const graftal::Vec3 far :
         {graftal::Vec3{1e300, 0, 0}, graftal::Vec3{0, 2e15, 0}, graftal::Vec3{0, 0, 1e19}}) {
        o.camera.viewpoint = far;
        EXPECT_THROW(graftal::renderRaytracedPixels(triangle, o), graftal::Error) << far.z;
    }
    o.camera.viewpoint = graftal::Vec3{0, 0, 5};
    o.camera.target = graftal::Vec3{0, 0, -1e16};
    EXPECT_THROW(graftal::renderRaytracedPixels(triangle, o), graftal::Error);
}

// --- 2, 5 and the studio's guards -------------------------------------------------------

class StudioGuardTest : public ::testing::Test {
  protected:
    void start(int maxDerivations = 4, int busyWait = 15'000) {
        root = dir.path() / "models";
        fs::create_directories(root);
        std::ofstream(root / "koch.l") << "Lsystem: 1\nderivation length: 2\nangle factor: 4\n"
                                          "axiom: F\nF --> F+F-F-F+F\nendlsystem\n";
        graftal::studio::StudioOptions options;
        options.root = root;
        options.assets = dir.path() / "assets";
        fs::create_directories(options.assets);
        std::ofstream(options.assets / "index.html") << "<!doctype html><title>studio</title>";
        options.limits.maxSteps = 2000;
        options.maxDerivations = maxDerivations;
        options.busyWaitMilliseconds = busyWait;
        server = std::make_unique<graftal::studio::StudioServer>(options);
        port = server->start(0);
    }
    httplib::Client client(bool withToken = true) {
        httplib::Client c("127.0.0.1", port);
        c.set_read_timeout(120, 0);
        if (withToken) c.set_default_headers({{"X-Graftal-Token", server->token()}});
        return c;
    }
    static json parse(const httplib::Result& r) { return json::parse(r->body); }

    TempDir dir;
    fs::path root;
    std::unique_ptr<graftal::studio::StudioServer> server;
    int port = 0;
};

const char* kSlow =
    "Lsystem: 1\nderivation length: 2000\nAxiom: A(0)\n"
    "A(n) : n < 20 --> A(n+1)A(n+1)\nA(n) : n >= 20 --> A(n+1)\nendlsystem\n";

TEST_F(StudioGuardTest, RequestsNeedTheRunsToken) {
    start();
    ASSERT_EQ(server->token().size(), 32u);
    auto bare = client(false);
    auto refused = bare.Get("/api/files");
    ASSERT_TRUE(refused);
    EXPECT_EQ(refused->status, 403);
    EXPECT_NE(refused->body.find("token"), std::string::npos);
    auto wrong = bare.Get("/api/files", {{"X-Graftal-Token", std::string(32, '0')}});
    ASSERT_TRUE(wrong);
    EXPECT_EQ(wrong->status, 403);
    // The address printed opens the page, which keeps the token as a cookie.
    auto page = bare.Get(("/?token=" + server->token()).c_str());
    ASSERT_TRUE(page);
    EXPECT_EQ(page->status, 200);
    const std::string cookie = page->get_header_value("Set-Cookie");
    EXPECT_NE(cookie.find(server->token()), std::string::npos) << cookie;
    EXPECT_NE(cookie.find("SameSite=Strict"), std::string::npos) << cookie;
    EXPECT_NE(cookie.find("HttpOnly"), std::string::npos) << cookie;
    auto withCookie = bare.Get("/api/files", {{"Cookie", cookie.substr(0, cookie.find(';'))}});
    ASSERT_TRUE(withCookie);
    EXPECT_EQ(withCookie->status, 200);
    EXPECT_EQ(client().Get("/api/files")->status, 200);
}

TEST_F(StudioGuardTest, AnotherSitesPageIsRefused) {
    start();
    auto c = client();
    // A cross-site form post needs no preflight: its Origin gives it away.
    auto evil = c.Post("/api/derive", {{"Origin", "http://evil.example"}},
                       json{{"text", "axiom: F\n"}}.dump(), "text/plain");
    ASSERT_TRUE(evil);
    EXPECT_EQ(evil->status, 403);
    EXPECT_NE(evil->body.find("evil.example"), std::string::npos);
    auto own = c.Post("/api/parse", {{"Origin", "http://127.0.0.1:" + std::to_string(port)}},
                      json{{"text", "axiom: F\n"}}.dump(), "application/json");
    ASSERT_TRUE(own);
    EXPECT_EQ(own->status, 200);
}

TEST_F(StudioGuardTest, AChunkedBodyIsNotRead) {
    start();
    auto c = client();
    std::size_t sent = 0;
    // 64 MB offered in pieces without a length: refused before it is read.
    auto res = c.Post(
        "/api/parse",
        [&](std::size_t, httplib::DataSink& sink) {
            const std::string piece(1 << 20, ' ');
            if (sent >= (std::size_t(64) << 20)) {
                sink.done();
                return true;
            }
            sent += piece.size();
            return sink.write(piece.data(), piece.size());
        },
        "application/json");
    if (res) {
        EXPECT_EQ(res->status, 411);
        EXPECT_NE(res->body.find("Content-Length"), std::string::npos);
    }
    EXPECT_LT(sent, std::size_t(64) << 20) << "the whole chunked body was taken";
    // The server lives on.
    EXPECT_EQ(client().Get("/api/info")->status, 200);
}

TEST_F(StudioGuardTest, NumbersAreRangeChecked) {
    start();
    auto c = client();
    for (const json& steps : {json(4294967297ull), json(-1), json(99999999999ll), json(2.5),
                              json(18446744073709551615ull), json("3")}) {
        auto r =
            c.Post("/api/derive", json{{"text", "axiom: F\nF --> FF\n"}, {"steps", steps}}.dump(),
                   "application/json");
        ASSERT_TRUE(r);
        EXPECT_EQ(r->status, 400) << steps.dump();
        EXPECT_NE(parse(r)["error"].get<std::string>().find("\"steps\""), std::string::npos)
            << r->body;
    }
    auto ok =
        c.Post("/api/parse", json{{"text", "axiom: F\n"}, {"steps", 3}}.dump(), "application/json");
    EXPECT_EQ(ok->status, 200);
    auto watch = c.Get("/api/watch?path=koch.l&since=abc");
    ASSERT_TRUE(watch);
    EXPECT_EQ(watch->status, 400);
    EXPECT_NE(watch->body.find("since"), std::string::npos) << watch->body;
}

// A view file's value graftal cannot use is a warning at its line and the setting's default,
// as in cpfg: the far viewpoint never reaches the ray tracer, the picture is made with the
// default camera, and the page's report says where the value was refused.
TEST_F(StudioGuardTest, AFarViewpointInAViewFileIsAWarningAndTheServerLives) {
    start();
    std::ofstream(root / "fern.l") << std::ifstream(example("fig3.8-fern-3d.l")).rdbuf();
    std::ofstream(root / "fern.v") << "viewpoint: 1e200 0 0\n";
    std::ifstream in(root / "fern.l");
    const std::string text((std::istreambuf_iterator<char>(in)), {});
    auto c = client();
    auto r =
        c.Post("/api/export",
               json{{"text", text}, {"path", "fern.l"}, {"steps", 3}, {"format", "png"}}.dump(),
               "application/json");
    ASSERT_TRUE(r) << "the server died";
    EXPECT_EQ(r->status, 200) << r->body;
    EXPECT_EQ(r->body.substr(0, 4), "\x89PNG");
    auto report = c.Post("/api/parse", json{{"text", text}, {"path", "fern.l"}}.dump(),
                         "application/json");
    ASSERT_TRUE(report);
    EXPECT_NE(report->body.find("viewpoint must be a finite point within 1e15"), std::string::npos)
        << report->body;
    EXPECT_NE(report->body.find("fern.v"), std::string::npos) << report->body;
    EXPECT_EQ(c.Get("/api/info")->status, 200);
}

TEST_F(StudioGuardTest, OverItsDerivationsTheServerAnswers503AndLivesOn) {
    start(/*maxDerivations=*/1, /*busyWait=*/300);
    auto slow = std::async(std::launch::async, [&] {
        auto c = client();
        return c
            .Post("/api/derive", json{{"text", kSlow}, {"session", "a"}}.dump(), "application/json")
            ->status;
    });
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    auto c = client();
    auto busy = c.Post("/api/derive", json{{"text", "axiom: F\n"}, {"session", "b"}}.dump(),
                       "application/json");
    ASSERT_TRUE(busy);
    EXPECT_EQ(busy->status, 503);
    EXPECT_NE(busy->body.find("busy"), std::string::npos) << busy->body;
    // The page's newer request replaces the slow one, which frees the slot.
    auto newer = c.Post("/api/derive", json{{"text", "axiom: F\n"}, {"session", "a"}}.dump(),
                        "application/json");
    ASSERT_TRUE(newer);
    EXPECT_EQ(newer->status, 200) << newer->body;
    EXPECT_EQ(slow.get(), 409);
}

// The load test: a burst of 20 heavy derivations of one page (127.0.0.1 only, bounded in
// count and time). The newest is answered with its picture, the older ones are cancelled
// or refused, at most the gate's derivations run at once, and the server lives on.
TEST_F(StudioGuardTest, ABurstOfOnePageIsBoundedAndAnswersTheNewest) {
    start(/*maxDerivations=*/2, /*busyWait=*/20'000);
    const auto started = std::chrono::steady_clock::now();
    std::vector<std::future<int>> older;
    for (int i = 0; i < 19; ++i) {
        older.push_back(std::async(std::launch::async, [&] {
            auto c = client();
            auto r = c.Post("/api/derive", json{{"text", kSlow}, {"session", "page"}}.dump(),
                            "application/json");
            return r ? r->status : -1;
        }));
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    auto c = client();
    auto newest =
        c.Post("/api/derive", json{{"text", "axiom: F\nF --> FF\n"}, {"session", "page"}}.dump(),
               "application/json");
    ASSERT_TRUE(newest);
    EXPECT_EQ(newest->status, 200) << newest->body;
    for (auto& f : older) {
        const int status = f.get();
        EXPECT_TRUE(status == 409 || status == 503) << status;
    }
    EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(60));
    EXPECT_EQ(c.Get("/api/info")->status, 200);
    // The server runs in this process: its peak resident memory stayed under 2 GB.
    std::ifstream status("/proc/self/status");
    std::string line;
    long peakKiB = 0;
    while (std::getline(status, line))
        if (line.rfind("VmHWM:", 0) == 0) peakKiB = std::atol(line.c_str() + 6);
    EXPECT_GT(peakKiB, 0);
    EXPECT_LT(peakKiB, 2'000'000) << "peak " << peakKiB << " KiB";
}

}  // namespace

// --- Saving through the studio ----------------------------------------------------------

namespace {

// `graftal studio DIR --no-open --no-token` in the background: its pid and port.
std::pair<pid_t, int> startStudio(const fs::path& dir, const fs::path& log) {
    const std::string command = std::string(GRAFTAL_EXE) + " studio " + dir.string() +
                                " --no-open --no-token > " + log.string() +
                                " 2>/dev/null & echo $!";
    FILE* shell = ::popen(command.c_str(), "r");
    pid_t pid = 0;
    if (!shell || std::fscanf(shell, "%d", &pid) != 1) return {0, 0};
    ::pclose(shell);
    for (int i = 0; i < 200; ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(25));
        const std::string out = graftal::testing::readFile(log);
        const auto at = out.find("http://127.0.0.1:");
        if (at != std::string::npos) return {pid, std::atoi(out.c_str() + at + 17)};
    }
    return {pid, 0};
}

}  // namespace

TEST(Reliability, ASaveKilledMidwayLeavesTheOldOrTheNewText) {
    TempDir dir;
    const fs::path models = dir.path() / "models";
    fs::create_directories(models);
    const std::string oldText(900'000, 'o'), newText(900'000, 'n');
    int sawOld = 0, sawNew = 0;
    for (int round = 0; round < 5; ++round) {
        std::ofstream(models / "m.l", std::ios::binary) << oldText;
        const auto [pid, port] = startStudio(models, dir.path() / "log");
        ASSERT_GT(port, 0) << "the studio did not start";
        auto save = std::async(std::launch::async, [port = port, &newText] {
            httplib::Client c("127.0.0.1", port);
            c.Put("/api/file?path=m.l", newText, "text/plain");
        });
        // Killed at another moment of the save each round.
        std::this_thread::sleep_for(std::chrono::microseconds(500 + 2500 * round));
        ::kill(pid, SIGKILL);
        save.get();
        for (int i = 0; i < 200 && alive(pid); ++i)
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        const std::string text = graftal::testing::readFile(models / "m.l");
        ASSERT_TRUE(text == oldText || text == newText)
            << "round " << round << ": " << text.size() << " bytes";
        (text == oldText ? sawOld : sawNew)++;
    }
    EXPECT_EQ(sawOld + sawNew, 5);
}
