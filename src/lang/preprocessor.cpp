// Runs mcpp on a .l file and maps its output back to the user's files (see the header).
//
// Three things stand between the .l language and a C preprocessor, and are dealt with
// before mcpp sees the text:
// - comments: the .l rules (source_text.cpp) blank them first, so that `F//&&leaf` keeps
//   its two roll modules instead of losing the rest of the line to a `//` comment;
// - `'` is a module, not the start of a character constant, and the `//` pairs left after
//   the comments are modules too: both are shielded as private-use characters, which mcpp
//   copies through untouched, and restored in its output;
// - #include: every included file gets the same treatment, so each file of the model is
//   copied, shielded, into a temporary folder and its #include lines are pointed at the
//   copies. The copies keep their lines, so mcpp's line markers (`#line N "copy"`) map
//   back to the user's file and line through the table of copies.
//
// mcpp keeps its state in globals and cannot be stopped from outside once it runs, while a
// macro such as `#define B A+A` nested a few dozen times expands without end in practice.
// So it runs in a child process, started once and kept for the next runs: the parent reads
// its output through pipes, stops it when the output passes the size limit or the time
// limit (the next run starts another), and the library's own globals never live in this
// process. A mutex serialises the runs.
#include "preprocessor.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>
#include <vector>

#include "graftal/core/file_reading.hpp"
#include "mcpp_server.hpp"
#ifdef GRAFTAL_PREPROCESSOR_PROGRAM
#include "../plugins/plugin_loader.hpp"
#endif

namespace graftal {

namespace fs = std::filesystem;

namespace {

constexpr std::size_t kMaxPreprocessedBytes = 64u << 20;   // 64 MiB
constexpr std::size_t kPreprocessedPerInputByte = 16;      // ... or 16 bytes per input byte
constexpr std::size_t kMinPreprocessedLimit = 256u << 10;  // ... plus 256 KiB
constexpr std::size_t kMaxMessageBytes = 1u << 20;         // mcpp's messages kept
constexpr auto kTimeLimit = std::chrono::seconds(60);

// U+E000 and U+E001 (private use): what `'` and a `/` before another `/` become for mcpp.
constexpr std::string_view kQuoteShield = "\xEE\x80\x80";
constexpr std::string_view kSlashShield = "\xEE\x80\x81";
constexpr std::string_view kHashShield = "\xEE\x80\x82";

std::mutex gMcppMutex;

bool isDirectiveName(std::string_view name) {
    static constexpr std::string_view kNames[] = {"define", "undef",  "include", "if",
                                                  "ifdef",  "ifndef", "elif",    "else",
                                                  "endif",  "line",   "error",   "pragma"};
    return std::find(std::begin(kNames), std::end(kNames), name) != std::end(kNames);
}

// A line that starts with `#` but is no directive (`#(0.06)F` continuing a successor: the
// turtle's width module). cpfg's preprocessor passes such lines through; mcpp would stop
// at them, so their `#` is shielded.
bool startsWithTurtleHash(std::string_view text, std::size_t lineStart) {
    std::size_t i = lineStart;
    while (i < text.size() && (text[i] == ' ' || text[i] == '\t')) ++i;
    if (i >= text.size() || text[i] != '#') return false;
    std::size_t j = i + 1;
    if (j >= text.size() || text[j] == '\n' || text[j] == ' ' || text[j] == '\t') return false;
    if (text[j] != '_' && !std::isalpha(static_cast<unsigned char>(text[j]))) return true;
    std::size_t e = j;
    while (e < text.size() && (std::isalnum(static_cast<unsigned char>(text[e])) || text[e] == '_'))
        ++e;
    return !isDirectiveName(text.substr(j, e - j));
}

std::string shield(std::string_view text) {
    std::string out;
    out.reserve(text.size() + text.size() / 8);
    bool lineStart = true;
    bool turtleLine = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        char c = text[i];
        if (lineStart) turtleLine = startsWithTurtleHash(text, i);
        lineStart = c == '\n';
        if (c == '#' && turtleLine) {
            out += kHashShield;
            turtleLine = false;
        } else if (c == '\'')
            out += kQuoteShield;
        else if (c == '/' && i + 1 < text.size() && text[i + 1] == '/')
            out += kSlashShield;
        else
            out += c;
    }
    return out;
}

void replaceAll(std::string& s, std::string_view from, std::string_view to) {
    for (std::size_t p = s.find(from); p != std::string::npos; p = s.find(from, p + to.size()))
        s.replace(p, from.size(), to);
}

std::string unshield(std::string s) {
    replaceAll(s, kQuoteShield, "'");
    replaceAll(s, kSlashShield, "/");
    replaceAll(s, kHashShield, "#");
    return s;
}

std::size_t skipBlanks(std::string_view s, std::size_t i) {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
    return i;
}

std::size_t identifierEnd(std::string_view s, std::size_t i) {
    while (i < s.size() && (std::isalnum(static_cast<unsigned char>(s[i])) || s[i] == '_')) ++i;
    return i;
}

// The directive of a line (`define`, `include`, ...) and where its operand starts; empty
// when the line is not a directive.
std::string_view directiveOf(std::string_view line, std::size_t& operand) {
    std::size_t i = skipBlanks(line, 0);
    if (i >= line.size() || line[i] != '#') return {};
    i = skipBlanks(line, i + 1);
    std::size_t e = identifierEnd(line, i);
    operand = skipBlanks(line, e);
    return line.substr(i, e - i);
}

// One file of the model, copied (comments blanked, shielded) for mcpp.
struct CopiedFile {
    fs::path copy;        // in the temporary folder
    std::string display;  // how locations name it
};

// The temporary folder and the copies in it; removed when the run ends.
class Workspace {
  public:
    explicit Workspace(const PreprocessOptions& options, DiagnosticList& diags)
        : options_(options), diags_(diags) {
        std::string pattern = (fs::temp_directory_path() / "graftal-cpp-XXXXXX").string();
        if (::mkdtemp(pattern.data())) dir_ = pattern;
    }
    ~Workspace() {
        std::error_code ec;
        if (!dir_.empty()) fs::remove_all(dir_, ec);
    }
    Workspace(const Workspace&) = delete;
    Workspace& operator=(const Workspace&) = delete;

    bool ready() const { return !dir_.empty(); }

    // Copies `text` (the contents of `display`, found at `path` when it is a file) and,
    // recursively, the files it includes. Returns the copy's path, or empty on failure.
    fs::path add(std::string_view text, const fs::path& path, const std::string& display,
                 bool isMain) {
        std::error_code ec;
        std::string key = path.empty() ? std::string() : fs::weakly_canonical(path, ec).string();
        if (!key.empty()) {
            if (auto it = byKey_.find(key); it != byKey_.end()) return files_[it->second].copy;
        }
        SourceText src;
        if (!prepareSource(text, display, src, diags_)) return {};
        std::size_t index = files_.size();
        fs::path copy = dir_ / (std::to_string(index) + (isMain ? ".l" : ".h"));
        files_.push_back({copy, display});
        if (!key.empty()) byKey_[key] = index;

        fs::path folder = path.empty() ? fs::path() : path.parent_path();
        fs::path displayFolder = fs::path(display).parent_path();
        std::string body;
        for (const auto& line : src.lines) {
            std::string text2 = shield(line.text);
            std::size_t operand = 0;
            std::string_view directive = directiveOf(text2, operand);
            if (directive == "define" || directive == "undef") {
                std::string name(text2.substr(operand, identifierEnd(text2, operand) - operand));
                if (options_.defines.count(name)) text2.clear();  // the command line wins
            } else if (directive == "include" && operand < text2.size() && text2[operand] == '"') {
                std::size_t close = text2.find('"', operand + 1);
                if (close != std::string::npos) {
                    std::string name = unshield(text2.substr(operand + 1, close - operand - 1));
                    fs::path target = fs::path(name).is_absolute() ? fs::path(name) : folder / name;
                    std::string problem;
                    std::optional<std::string> includedText;
                    if (fs::exists(target, ec) && !fs::is_directory(target, ec)) {
                        includedText = readUserFile(target, problem);
                        if (!includedText) {
                            // A device or an oversized file: mcpp would read it without end.
                            diags_.error({display, line.number, static_cast<int>(operand) + 1},
                                         "the included file '" + name + "' " + problem);
                            return {};
                        }
                    }
                    if (includedText) {
                        std::string shown =
                            fs::path(name).is_absolute()
                                ? name
                                : (displayFolder / name).lexically_normal().string();
                        fs::path included = add(*includedText, target, shown, false);
                        if (included.empty()) return {};
                        text2 = text2.substr(0, operand) + "\"" + included.string() + "\"" +
                                text2.substr(close + 1);
                    }
                    // A missing file is left to mcpp, which reports it where it is included
                    // (and only when the #include is not skipped by an #if).
                }
            }
            body += text2;
            body += '\n';
        }
        if (isMain) body += "#pragma MCPP put_defines\n";
        std::ofstream out(copy, std::ios::binary);
        out << body;
        if (!out) {
            diags_.error({display, 0, 0}, "cannot write the preprocessor's temporary copy");
            return {};
        }
        return copy;
    }

    // The user's name of a copy mcpp names in its output or messages; empty if unknown.
    const std::string* displayOf(std::string_view copyPath) const {
        for (const auto& f : files_)
            if (f.copy.string() == copyPath) return &f.display;
        return nullptr;
    }

  private:
    const PreprocessOptions& options_;
    DiagnosticList& diags_;
    fs::path dir_;
    std::vector<CopiedFile> files_;
    std::map<std::string, std::size_t> byKey_;
};

// ---- the preprocessor's process --------------------------------------------------------
//
// mcpp runs in a process started once and kept (mcpp_server.hpp): it reads each run's
// arguments from a socket, runs mcpp_lib_main (which resets mcpp's globals itself on entry:
// mcpp as a library is meant to be called again) and answers how many bytes it wrote.
// Starting one for every run cost more than many a derivation: fork and exit of a 90 MB
// process (a Dask worker, a Python with pandas) take 20-30 ms of CPU, a small sweep point
// 15 ms. A run stopped for its size or time, or a crash, ends the process; the next run
// starts another.

// The running preprocessor's process, guarded by gMcppMutex.
struct McppServer {
    pid_t pid = -1;
    pid_t owner = -1;  // the process that started it
    int control = -1;  // requests out, answers in
    int out = -1;      // mcpp's output
    int err = -1;      // mcpp's messages
    int runs = 0;
};
McppServer gServer;

// mcpp frees what it allocated, but a fresh process now and then bounds what it does not.
constexpr int kRunsPerServer = 1000;

void closeServerFds(McppServer& s) {
    for (int* fd : {&s.control, &s.out, &s.err}) {
        if (*fd >= 0) ::close(*fd);
        *fd = -1;
    }
}

// Ends the process (killed when `kill`, else it ends when its socket closes) and waits.
void stopServer(McppServer& s, bool kill, int* status = nullptr) {
    if (s.pid > 0 && kill) ::kill(s.pid, SIGKILL);
    closeServerFds(s);
    int st = 0;
    if (s.pid > 0) {
        while (::waitpid(s.pid, &st, 0) < 0 && errno == EINTR) {
        }
    }
    if (status) *status = st;
    s.pid = -1;
}

// The program the preprocessor's process runs (graftal-cpp beside the plugins), or empty
// where there is none (a static build, or a folder without it): then it is a fork of this
// process.
const std::string& serverProgram() {
    static const std::string program = [] {
#ifdef GRAFTAL_PREPROCESSOR_PROGRAM
        std::string path = (plugins::pluginFolder() / "graftal-cpp").string();
        if (::access(path.c_str(), X_OK) == 0) return path;
#endif
        return std::string();
    }();
    return program;
}

// Starts graftal-cpp with `ends` (its socket, output and messages) as 3, 4 and 5 and
// /dev/null as 0-2, and none of this process's other descriptors: a pipe the host writes to
// must reach its end when the host's does. -1 when it cannot be started.
pid_t spawnServer(const std::string& program, const int ends[3]) {
    // Moved above 5 first, so that no dup2 below overwrites an end not yet moved.
    int high[3] = {-1, -1, -1};
    for (int k = 0; k < 3; ++k) high[k] = ::fcntl(ends[k], F_DUPFD_CLOEXEC, 10);
    pid_t pid = -1;
    posix_spawn_file_actions_t actions;
    posix_spawnattr_t attributes;
    if (high[0] >= 0 && high[1] >= 0 && high[2] >= 0 &&
        ::posix_spawn_file_actions_init(&actions) == 0) {
        ::posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDWR, 0);
        ::posix_spawn_file_actions_adddup2(&actions, 0, 1);
        ::posix_spawn_file_actions_adddup2(&actions, 0, 2);
        ::posix_spawn_file_actions_adddup2(&actions, high[0], mcpp_server::kControlFd);
        ::posix_spawn_file_actions_adddup2(&actions, high[1], mcpp_server::kOutputFd);
        ::posix_spawn_file_actions_adddup2(&actions, high[2], mcpp_server::kMessagesFd);
        ::posix_spawn_file_actions_addclosefrom_np(&actions, mcpp_server::kMessagesFd + 1);
        if (::posix_spawnattr_init(&attributes) == 0) {
            // The host's handlers and blocked signals are not the program's: a crash in mcpp
            // ends it, and a host that ignores SIGPIPE (Python does) makes it ignored too.
            sigset_t all, none;
            ::sigfillset(&all);
            ::sigemptyset(&none);
            ::posix_spawnattr_setsigdefault(&attributes, &all);
            ::posix_spawnattr_setsigmask(&attributes, &none);
            ::posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK);
            char* argv[] = {const_cast<char*>(program.c_str()),
                            const_cast<char*>(mcpp_server::kProtocol), nullptr};
            if (::posix_spawn(&pid, program.c_str(), &actions, &attributes, argv, environ) != 0)
                pid = -1;
            ::posix_spawnattr_destroy(&attributes);
        }
        ::posix_spawn_file_actions_destroy(&actions);
    }
    for (int fd : high)
        if (fd >= 0) ::close(fd);
    return pid;
}

// The same process as a fork of this one, where there is no program to start.
pid_t forkServer(const int ends[3]) {
    pid_t pid = ::fork();
    if (pid != 0) return pid;
    // The process only runs mcpp: a crash there must end it, not run the handlers the
    // host installed (a fuzzer's or a sanitizer's would report the host's input).
    for (int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGTERM, SIGPIPE})
        ::signal(sig, SIG_DFL);
    ::signal(SIGINT, SIG_IGN);  // as graftal-cpp does (graftal_cpp_main.cpp)
    int keep[3];
    for (int k = 0; k < 3; ++k) {
        keep[k] = ::fcntl(ends[k], F_DUPFD, 10);
        if (keep[k] < 0) ::_exit(4);
    }
    int null = ::open("/dev/null", O_RDWR);
    for (int fd = 0; fd < 3; ++fd)
        if (null >= 0 && null != fd) ::dup2(null, fd);
    const int at[3] = {mcpp_server::kControlFd, mcpp_server::kOutputFd, mcpp_server::kMessagesFd};
    for (int k = 0; k < 3; ++k)
        if (::dup2(keep[k], at[k]) < 0) ::_exit(4);
    ::close_range(mcpp_server::kMessagesFd + 1, ~0u, 0);
    mcpp_server::serve(at[0], at[1], at[2]);
}

bool startServer(McppServer& s) {
    if (s.owner != ::getpid()) {
        // A copy of a process that had one (a fork of the host): the process is not this
        // one's child; close the copies of its descriptors so that it still sees its
        // parent go.
        closeServerFds(s);
        s.pid = -1;
    }
    if (s.pid > 0) return true;
    int control[2], outPipe[2], errPipe[2];
    if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, control) != 0) return false;
    if (::pipe2(outPipe, O_CLOEXEC) != 0) {
        ::close(control[0]), ::close(control[1]);
        return false;
    }
    if (::pipe2(errPipe, O_CLOEXEC) != 0) {
        ::close(control[0]), ::close(control[1]), ::close(outPipe[0]), ::close(outPipe[1]);
        return false;
    }
    const int ends[3] = {control[1], outPipe[1], errPipe[1]};
    pid_t pid = -1;
    if (!serverProgram().empty()) pid = spawnServer(serverProgram(), ends);
    if (pid < 0) pid = forkServer(ends);
    ::close(control[1]), ::close(outPipe[1]), ::close(errPipe[1]);
    if (pid < 0) {
        ::close(control[0]), ::close(outPipe[0]), ::close(errPipe[0]);
        return false;
    }
    s.pid = pid;
    s.owner = ::getpid();
    s.control = control[0];
    s.out = outPipe[0];
    s.err = errPipe[0];
    s.runs = 0;
    return true;
}

struct McppRun {
    std::string output, messages;
    bool tooLarge = false, tooSlow = false, failed = false;
};

bool sendRequest(int fd, const std::vector<std::string>& args) {
    std::string request;
    auto put = [&](std::uint32_t v) { request.append(reinterpret_cast<const char*>(&v), 4); };
    put(static_cast<std::uint32_t>(args.size()));
    for (const auto& a : args) {
        put(static_cast<std::uint32_t>(a.size()));
        request += a;
    }
    return mcpp_server::sendAll(fd, request.data(), request.size());
}

// Runs mcpp with `args` in the preprocessor's process (started when there is none), keeping
// at most maxOutput bytes of its output; stops it past that size or the time limit.
// The caller holds gMcppMutex.
McppRun runMcpp(const std::vector<std::string>& args, std::size_t maxOutput) {
    McppRun run;
    McppServer& s = gServer;
    if (s.pid > 0 && s.owner == ::getpid() && s.runs >= kRunsPerServer) stopServer(s, false);
    if (!startServer(s) || !sendRequest(s.control, args)) {
        // A process that died since its last run: one more try with a new one.
        if (s.pid > 0) stopServer(s, true);
        if (!startServer(s) || !sendRequest(s.control, args)) {
            if (s.pid > 0) stopServer(s, true);
            run.failed = true;
            return run;
        }
    }
    ++s.runs;

    auto deadline = std::chrono::steady_clock::now() + kTimeLimit;
    pollfd fds[3] = {{s.out, POLLIN, 0}, {s.err, POLLIN, 0}, {s.control, POLLIN, 0}};
    bool open[3] = {true, true, true};
    std::uint64_t received[2] = {0, 0};
    std::uint64_t answer[2] = {0, 0};
    bool answered = false;
    char buffer[65536];
    // Until the answer has come and its bytes are read, or the process is gone.
    auto finished = [&] {
        if (answered) return received[0] >= answer[0] && received[1] >= answer[1];
        return !open[0] && !open[1] && !open[2];
    };
    while (!finished()) {
        auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
            deadline - std::chrono::steady_clock::now());
        if (left.count() <= 0) {
            run.tooSlow = true;
            break;
        }
        for (int k = 0; k < 3; ++k)
            fds[k].fd = open[k] ? (k == 0 ? s.out : k == 1 ? s.err : s.control) : -1;
        int ready = ::poll(fds, 3, static_cast<int>(std::min<long long>(left.count(), 1000)));
        if (ready < 0 && errno != EINTR) {
            run.failed = true;
            break;
        }
        if (ready < 0) continue;
        for (int k = 0; k < 2; ++k) {
            if (!open[k] || !(fds[k].revents & (POLLIN | POLLHUP | POLLERR))) continue;
            ssize_t n = ::read(fds[k].fd, buffer, sizeof buffer);
            if (n <= 0) {
                if (n < 0 && errno == EINTR) continue;
                open[k] = false;
                continue;
            }
            received[k] += static_cast<std::uint64_t>(n);
            std::string& sink = k == 0 ? run.output : run.messages;
            std::size_t limit = k == 0 ? maxOutput : kMaxMessageBytes;
            std::size_t room = sink.size() < limit ? limit - sink.size() : 0;
            sink.append(buffer, std::min(room, static_cast<std::size_t>(n)));
            if (k == 0 && static_cast<std::size_t>(n) > room) run.tooLarge = true;
        }
        if (open[2] && (fds[2].revents & (POLLIN | POLLHUP | POLLERR))) {
            if (mcpp_server::readExactly(s.control, answer, sizeof answer))
                answered = true;
            else
                open[2] = false;  // the process ended (mcpp exited or crashed)
        }
        if (run.tooLarge) break;
    }
    if (run.tooLarge || run.tooSlow || run.failed) {
        stopServer(s, true);
    } else if (!answered) {
        // mcpp ended its process: as before, only a clean exit is no failure.
        int status = 0;
        stopServer(s, false, &status);
        if (!(WIFEXITED(status) && WEXITSTATUS(status) == 0)) run.failed = true;
    }
    return run;
}

// ---- reading mcpp's output back -------------------------------------------------------

// `#line 12 "/tmp/.../0.l"` (mcpp's form) or `# 12 "file"`.
bool parseLineMarker(std::string_view line, int& number, std::string& file) {
    std::size_t i = skipBlanks(line, 0);
    if (i >= line.size() || line[i] != '#') return false;
    i = skipBlanks(line, i + 1);
    if (line.compare(i, 4, "line") == 0) i = skipBlanks(line, i + 4);
    std::size_t d = i;
    while (d < line.size() && std::isdigit(static_cast<unsigned char>(line[d]))) ++d;
    if (d == i) return false;
    number = std::atoi(std::string(line.substr(i, d - i)).c_str());
    std::size_t q = line.find('"', d);
    if (q != std::string_view::npos) {
        std::size_t e = line.find('"', q + 1);
        if (e != std::string_view::npos) file = std::string(line.substr(q + 1, e - q - 1));
    }
    return true;
}

// `#define NAME body \t/* file:line\t*/` from put_defines: user-defined object-like macros.
void readDefinition(std::string_view line, std::map<std::string, std::string>& defines) {
    std::size_t operand = 0;
    if (directiveOf(line, operand) != "define") return;
    if (line.find("(predefined)") != std::string_view::npos) return;
    std::size_t nameEnd = identifierEnd(line, operand);
    if (nameEnd == operand || (nameEnd < line.size() && line[nameEnd] == '(')) return;
    std::string_view body = line.substr(nameEnd);
    std::size_t where = body.rfind("/*");
    if (where != std::string_view::npos) body = body.substr(0, where);
    std::size_t a = body.find_first_not_of(" \t");
    std::size_t b = body.find_last_not_of(" \t");
    std::string value = a == std::string_view::npos ? "" : std::string(body.substr(a, b - a + 1));
    defines[std::string(line.substr(operand, nameEnd - operand))] =
        value.empty() ? "1" : unshield(value);
}

// mcpp's messages: "path:line: error: text" followed by indented context lines.
void readMessages(const std::string& messages, const Workspace& ws, const std::string& mainName,
                  DiagnosticList& diags) {
    std::istringstream in(messages);
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == ' ' || line[0] == '\t') continue;
        Severity severity;
        std::size_t tag;
        if ((tag = line.find(": fatal error: ")) != std::string::npos ||
            (tag = line.find(": error: ")) != std::string::npos)
            severity = Severity::Error;
        else if ((tag = line.find(": warning: ")) != std::string::npos)
            severity = Severity::Warning;
        else
            continue;
        std::string where = line.substr(0, tag);
        std::string text = unshield(line.substr(line.find(": ", tag + 2) + 2));
        std::size_t colon = where.rfind(':');
        SourceLocation loc{mainName, 0, 0};
        if (colon != std::string::npos) {
            const std::string* shown = ws.displayOf(std::string_view(where).substr(0, colon));
            if (shown) loc.file = *shown;
            loc.line = std::atoi(where.c_str() + colon + 1);
            if (loc.line > 0) loc.column = 1;
        }
        if (text.rfind("Buffer overflow", 0) == 0 || text.rfind("Too many nested macros", 0) == 0)
            text = "a macro expands to more text than one line may hold (" + text +
                   "): is a macro defined in terms of another several times over?";
        else if (text.find("nesting of #include") != std::string::npos)
            text =
                "#include cycle: a file includes itself, directly or through others (" + text + ")";
        else if (text.rfind("#error", 0) != 0 && severity == Severity::Error)
            text = "preprocessor: " + text;
        bool repeated = false;  // mcpp may say the same thing twice
        for (const auto& d : diags.items())
            repeated = repeated || (d.message == text && d.location.file == loc.file &&
                                    d.location.line == loc.line);
        if (!repeated) diags.add({severity, loc, text});
    }
}

// One line of mcpp's output with its macro annotations (-K) taken out. Annotations mark
// every expansion (`/*<NAME l:c-l:c*/ ... /*>*/`, the call's place in the source), so the
// text outside expansions keeps its own columns and an expansion maps to its call.
// `endLine` receives the last source line a call on this line reaches (a call over
// several lines).
SourceLine stripAnnotations(const std::string& line, const std::string& file, int fileLine,
                            int& endLine) {
    SourceLine out;
    out.spans.push_back({1, file, fileLine, 1});
    endLine = fileLine;
    int depth = 0, l1 = 0, c1 = 0;
    for (std::size_t i = 0; i < line.size();) {
        if (line.compare(i, 2, "/*") == 0) {
            std::size_t close = line.find("*/", i + 2);
            if (close != std::string::npos) {
                std::string note = line.substr(i + 2, close - i - 2);
                int column = static_cast<int>(out.text.size()) + 1;
                int l0 = 0, c0 = 0;
                std::size_t space = note.find(' ');
                if (!note.empty() && note[0] == '<' && depth++ == 0 && space != std::string::npos &&
                    std::sscanf(note.c_str() + space + 1, "%d:%d-%d:%d", &l0, &c0, &l1, &c1) == 4) {
                    out.spans.push_back({column, file, l0, c0});
                    endLine = std::max(endLine, l1);
                } else if (note == ">" && depth > 0 && --depth == 0 && l1 > 0) {
                    out.spans.push_back({column, file, l1, c1});  // the text after the call
                }
                i = close + 2;
                continue;
            }
        }
        out.text += line[i++];
    }
    out.text = unshield(std::move(out.text));
    return out;
}

// The preprocessed lines, each mapped back through the last line marker, and the macros
// put_defines lists at the end.
void readOutput(const std::string& output, const Workspace& ws, const std::string& mainName,
                SourceText& out) {
    out.fileName = mainName;
    out.lines.clear();
    out.defines.clear();
    std::istringstream in(output);
    std::string line, file = mainName;
    int fileLine = 1, callEnd = 0;
    bool started = false, inDefinitions = false;
    while (std::getline(in, line)) {
        int number = 0;
        std::string copy;
        if (inDefinitions) {
            readDefinition(line, out.defines);
            continue;
        }
        if (parseLineMarker(line, number, copy)) {
            if (!copy.empty()) {
                const std::string* shown = ws.displayOf(copy);
                file = shown ? *shown : copy;
            }
            fileLine = number;
            started = true;
            continue;
        }
        if (!started) continue;  // notes on predefined macros
        if (line == "/* Currently defined macros. */") {
            inDefinitions = true;
            continue;
        }
        int endLine = 0;
        SourceLine sl = stripAnnotations(line, file, fileLine, endLine);
        if (!out.lines.empty() && fileLine <= callEnd &&
            out.lines.back().spans.front().file == file) {
            // the rest of a macro call that began on an earlier line: cpfg sees one line
            SourceLine& into = out.lines.back();
            int base = static_cast<int>(into.text.size()) + 1;
            into.text += sl.text;
            for (SourceSpan s2 : sl.spans) {
                s2.column += base - 1;
                into.spans.push_back(std::move(s2));
            }
        } else {
            sl.number = static_cast<int>(out.lines.size()) + 1;
            out.lines.push_back(std::move(sl));
        }
        if (endLine > fileLine)
            callEnd = endLine;
        else if (fileLine >= callEnd)
            callEnd = 0;
        ++fileLine;
    }
}

}  // namespace

bool mcppComparesWithinNames() {
    std::lock_guard<std::mutex> lock(gMcppMutex);
    return mcpp_server::shieldCompare();
}

bool preprocessSource(std::string_view text, const PreprocessOptions& options, SourceText& out,
                      DiagnosticList& diags) {
    const std::string& mainName = options.fileName;
    Workspace ws(options, diags);
    if (!ws.ready()) {
        diags.error({mainName, 0, 0}, "cannot create a temporary folder for the preprocessor");
        return false;
    }
    std::size_t errorsBefore = 0;
    for (const auto& d : diags.items()) errorsBefore += d.severity == Severity::Error;
    fs::path mainCopy =
        ws.add(text, mainName.empty() ? fs::path() : fs::path(mainName), mainName, true);
    if (mainCopy.empty()) return false;

    std::size_t limit = options.maxOutputBytes;
    if (limit == 0)
        limit = std::min(kMaxPreprocessedBytes,
                         kMinPreprocessedLimit + kPreprocessedPerInputByte * text.size());

    std::vector<std::string> args = {"graftal-cpp", "-e", "utf8", "-k", "-K", "-N", "-I-"};
    for (const auto& [name, value] : options.defines) {
        args.push_back("-D");
        args.push_back(name + "=" + shield(value));
    }
    args.push_back(mainCopy.string());

    McppRun run;
    {
        std::lock_guard<std::mutex> lock(gMcppMutex);
        mcpp_server::shieldCompare();  // for a forked process; graftal-cpp shields its own
        run = runMcpp(args, limit);
    }
    readMessages(run.messages, ws, mainName, diags);

    readOutput(run.output, ws, mainName, out);
    if (run.tooLarge) {
        SourceLocation at =
            out.lines.empty() ? SourceLocation{mainName, 1, 1} : out.at(out.lines.back().number, 1);
        diags.error(at, "the preprocessed text grows past " + std::to_string(limit >> 10) +
                            " KiB here: a macro expands to too much text (is it defined in "
                            "terms of another several times over?)");
    } else if (run.tooSlow) {
        diags.error({mainName, 0, 0}, "the preprocessor took longer than " +
                                          std::to_string(kTimeLimit.count()) +
                                          " seconds; stopped (macros expanding without end?)");
    } else if (run.failed) {
        diags.error({mainName, 0, 0}, "the preprocessor (mcpp) could not be run");
    }
    std::size_t errorsAfter = 0;
    for (const auto& d : diags.items()) errorsAfter += d.severity == Severity::Error;
    return errorsAfter == errorsBefore;
}

}  // namespace graftal
