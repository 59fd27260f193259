// `graftal studio`: runs the server (studio_command.cpp declares the options). The page
// comes from share/graftal/studio beside the program (built by `make` from studio/).
#include <fcntl.h>
#include <malloc.h>
#include <pthread.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "graftal/studio/studio_server.hpp"
#include "studio_command.hpp"

namespace graftal::cli {

namespace fs = std::filesystem;

namespace {

// The folder of the page: $GRAFTAL_STUDIO_ASSETS, else share/graftal/studio beside the
// program (the build tree) or one folder up (an installed bin/).
fs::path studioAssets() {
    if (const char* env = std::getenv("GRAFTAL_STUDIO_ASSETS")) return env;
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (ec) return {};
    for (const fs::path& candidate : {exe.parent_path() / "share/graftal/studio",
                                      exe.parent_path().parent_path() / "share/graftal/studio"})
        if (fs::exists(candidate / "index.html")) return candidate;
    return {};
}

}  // namespace

int runStudio(const StudioCommandOptions& options) {
    studio::StudioOptions server;
    server.root = options.path.empty() ? fs::path(".") : fs::path(options.path);
    server.assets = studioAssets();
    server.requireToken = !options.noToken;
    if (options.noToken)
        std::cerr << "graftal: warning: --no-token: every program and every user of this "
                     "machine can use this studio (read, write and derive its models)\n";
    if (server.assets.empty())
        std::cerr << "graftal: warning: the studio's page was not built (make builds it); "
                     "only its API is served\n";

    // SIGINT and SIGTERM are taken by this thread, so that the server stops cleanly
    // (its scratch folder removed) instead of dying mid-write.
    sigset_t signals;
    sigemptyset(&signals);
    sigaddset(&signals, SIGINT);
    sigaddset(&signals, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &signals, nullptr);

    // Every keystroke allocates and frees buffers of megabytes (a million segments are some
    // 100 MB). Kept in one heap instead of handed back to the system, they return without
    // page faults, which on a loaded virtual machine cost more than the turtle itself. The
    // price: the server keeps the memory of its largest picture until it stops.
    mallopt(M_ARENA_MAX, 1);  // a buffer freed by one thread serves the next
    mallopt(M_MMAP_MAX, 0);   // large buffers from the heap too, never mapped one by one
    mallopt(M_TRIM_THRESHOLD, 1 << 30);

    studio::StudioServer studio(server);
    const int port = studio.start(options.port);
    // As Jupyter does: the secret goes in the address the browser opens; the page keeps it
    // as a cookie.
    const std::string address = "http://127.0.0.1:" + std::to_string(port) + "/" +
                                (studio.token().empty() ? "" : "?token=" + studio.token());
    std::cout << "graftal studio: " << address << " (Ctrl-C stops it)" << std::endl;
    // The browser is given a file only this user can read, which leads to the address: the
    // token is never on a command line that other users can list (Jupyter's redirect file).
    const fs::path redirect =
        fs::temp_directory_path() / ("graftal-studio-" + std::to_string(::getpid()) + ".html");
    if (!options.noOpen) {
        const int fd = ::open(redirect.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
        const std::string page =
            "<!doctype html><meta http-equiv=\"refresh\" content=\"0;url=" + address +
            "\"><a href=\"" + address + "\">graftal studio</a>\n";
        const bool written =
            fd >= 0 && ::write(fd, page.data(), page.size()) == static_cast<ssize_t>(page.size());
        if (fd >= 0) ::close(fd);
        const std::string command = "xdg-open '" + redirect.string() + "' >/dev/null 2>&1 &";
        if (!written || std::system(command.c_str()) != 0)
            std::cerr << "graftal: note: open " << address << " in a browser\n";
    }
    int received = 0;
    sigwait(&signals, &received);
    studio.stop();
    std::error_code ec;
    if (!options.noOpen) fs::remove(redirect, ec);
    return 0;
}

}  // namespace graftal::cli
