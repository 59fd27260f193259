// graftal studio's HTTP server: the page, its assets, and the JSON and binary endpoints
// docs/studio.md lists. Bound to 127.0.0.1 only; every path is checked by StudioRoot.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "studio/studio_model.hpp"
#include "studio/studio_root.hpp"

namespace graftal::studio {

struct StudioOptions {
    std::filesystem::path root;    // a folder or one .l file
    std::filesystem::path assets;  // index.html, studio.js, studio.css (empty: none served)
    StudioLimits limits;
    int watchMilliseconds = 20'000;  // the longest a file-change poll waits
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

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace graftal::studio
