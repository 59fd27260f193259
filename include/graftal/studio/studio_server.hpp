// graftal studio's HTTP server: the page, its assets, and the JSON and binary endpoints
// docs/studio.md lists. Bound to 127.0.0.1 only; every path is checked by StudioRoot.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

#include "graftal/studio/studio_model.hpp"
#include "graftal/studio/studio_root.hpp"

namespace graftal::studio {

struct StudioOptions {
    std::filesystem::path root;    // a folder or one .l file
    std::filesystem::path assets;  // index.html, studio.js, studio.css (empty: none served)
    StudioLimits limits;
    int watchMilliseconds = 20'000;  // the longest a file-change poll waits
    // Every request but the page's script and style must carry this run's secret: in the
    // address's ?token= (then kept as a cookie), the cookie, or an X-Graftal-Token header.
    // Empty with requireToken: a random one (token() tells it).
    bool requireToken = true;
    std::string token;
    // Derivations (live view, mesh, export, thumbnail) under way at once, and the memory
    // their limits may hold together: each gets what is left of the budget, up to
    // limits.memoryLimit and at least a quarter of it. Past these a request waits up to
    // busyWaitMilliseconds, then is answered 503.
    int maxDerivations = 4;
    std::size_t memoryBudget = std::size_t(3) << 29;  // 1.5 GiB
    int busyWaitMilliseconds = 15'000;
};

class StudioServer {
  public:
    // Throws Error when the root does not exist.
    explicit StudioServer(StudioOptions options);
    ~StudioServer();  // stops the server
    StudioServer(const StudioServer&) = delete;
    StudioServer& operator=(const StudioServer&) = delete;

    // Binds 127.0.0.1:port (0: a free port) and serves on a thread of its own; returns the
    // port. Throws Error when the port cannot be bound.
    int start(int port = 0);
    // Blocks until stop() (from another thread or a signal handler's thread).
    void wait();
    void stop();
    // Answers one HTTP request given as its bytes, through every check and route a
    // connection's request meets, and returns the answer's bytes: for the fuzz target that
    // drives the handlers. Before start() the server's own host is 127.0.0.1:0.
    std::string answer(std::string_view request);
    // The secret a request must carry (empty when none is required).
    const std::string& token() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace graftal::studio
