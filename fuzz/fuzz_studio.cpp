// Fuzz target: the studio server's request handling, driven directly (no socket): the
// checks every request meets (host, origin, token, body length, chunked bodies) and every
// route's reading of its query and JSON body. An input that begins with a method is sent as
// it is; any other input is a route chosen by its first byte with the rest as the body, the
// headers a page would send added, so that the fuzzer reaches the handlers' JSON at once.
// The server runs over a scratch folder with two models and tight limits. A finding: an
// answer that is not HTTP, or a 500 (an error no handler words: "stoll", a raw std::vector
// message), besides the sanitizers' own.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <string_view>

#include <unistd.h>

#include "graftal/studio/studio_server.hpp"

namespace {

namespace fs = std::filesystem;

constexpr std::string_view kToken = "fuzz-token";

struct Route {
    std::string_view method;
    std::string_view target;
};

// The routes of docs/studio.md, with the queries the page sends.
constexpr Route kRoutes[] = {
    {"POST", "/api/parse"},
    {"POST", "/api/derive"},
    {"POST", "/api/mesh"},
    {"POST", "/api/export"},
    {"PUT", "/api/file?path=scratch.l"},
    {"GET", "/api/file?path=koch.l"},
    {"GET", "/api/files"},
    {"GET", "/api/info"},
    {"GET", "/api/watch?path=koch.l&since=0"},
    {"GET", "/api/thumbnail?path=koch.l"},
};

graftal::studio::StudioServer& server() {
    static std::unique_ptr<graftal::studio::StudioServer> instance = [] {
        const fs::path root = fs::temp_directory_path() /
                              ("graftal-fuzz-studio-" + std::to_string(::getpid()));
        fs::create_directories(root);
        // Each fuzzing process (libFuzzer's fork mode starts many) removes its own folder.
        static const fs::path removed = root;
        std::atexit([] {
            std::error_code ec;
            fs::remove_all(removed, ec);
        });
        std::ofstream(root / "koch.l") << "#define N 2\nlsystem: 1\nderivation length: N\n"
                                          "axiom: F-F-F-F\nF --> F-F+F+FF-F-F+F\nendlsystem\n";
        std::ofstream(root / "koch.v") << "angle factor: 4\n";
        std::ofstream(root / "tree.l")
            << "lsystem: 1\nderivation length: 3\naxiom: A(1)\n"
               "A(x) --> F(x)[+(30)A(x*0.6)][-(30)A(x*0.6)]\nendlsystem\n";
        graftal::studio::StudioOptions options;
        options.root = root;
        options.token = std::string(kToken);
        options.watchMilliseconds = 10;
        options.busyWaitMilliseconds = 10;
        options.maxDerivations = 1;
        options.memoryBudget = std::size_t(64) << 20;
        options.limits.memoryLimit = std::size_t(64) << 20;
        options.limits.streamLimit = 2'000'000;
        options.limits.segmentBudget = 20'000;
        options.limits.meshSegmentBudget = 5'000;
        options.limits.maxSteps = 12;
        options.limits.deriveSeconds = 2;
        return std::make_unique<graftal::studio::StudioServer>(options);
    }();
    return *instance;
}

std::string requestOf(std::string_view input) {
    for (std::string_view method : {"GET ", "POST ", "PUT ", "HEAD ", "OPTIONS ", "DELETE "})
        if (input.substr(0, method.size()) == method) return std::string(input);
    const Route& route = kRoutes[input.empty() ? 0 : static_cast<unsigned char>(input[0]) %
                                                         std::size(kRoutes)];
    const std::string_view body = input.empty() ? input : input.substr(1);
    std::string request = std::string(route.method) + " " + std::string(route.target) +
                          " HTTP/1.1\r\nHost: 127.0.0.1:0\r\nX-Graftal-Token: " +
                          std::string(kToken) + "\r\nContent-Type: application/json\r\n";
    if (route.method != "GET")
        request += "Content-Length: " + std::to_string(body.size()) + "\r\n";
    request += "\r\n";
    if (route.method != "GET") request += body;
    return request;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string request = requestOf({reinterpret_cast<const char*>(data), size});
    // Engraved scores run LilyPond for seconds a request (it has a time limit of its own,
    // tested elsewhere): left out so that the campaign's time goes to the handlers.
    if (request.find("score-") != std::string::npos) return 0;
    const std::string answer = server().answer(request);
    // httplib answers a request it cannot read with 400 and nothing when the bytes end
    // before the request line: both are its own, not a route's.
    if (answer.empty()) return 0;
    // GRAFTAL_FUZZ_SHOW=1: each answer's status line, to see which routes an input reaches.
    static const bool show = std::getenv("GRAFTAL_FUZZ_SHOW") != nullptr;
    if (show) std::fprintf(stderr, "%.*s\n", int(answer.find('\r')), answer.c_str());
    if (answer.rfind("HTTP/1.1 ", 0) != 0) {
        std::fprintf(stderr, "graftal fuzz check failed: an answer that is not HTTP: %.80s\n",
                     answer.c_str());
        std::abort();
    }
    if (answer.compare(9, 3, "500") == 0) {
        std::fprintf(stderr, "graftal fuzz check failed: a 500 answer:\n%.600s\n",
                     answer.c_str());
        std::abort();
    }
    return 0;
}
