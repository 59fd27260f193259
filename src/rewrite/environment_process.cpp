// The `process` environment: an external program answers the ?E modules over a line
// protocol on its standard input and output (docs/environments.md has the protocol).
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <thread>

#include "environment_detail.hpp"
#include "graftal/core/number_chars.hpp"
#include "graftal/lang/lsystem.hpp"
#include "graftal/rewrite/environment.hpp"

namespace graftal {

namespace {

using Clock = std::chrono::steady_clock;

constexpr double kDefaultTimeoutSeconds = 30;
constexpr double kMaxTimeoutSeconds = 1e6;
constexpr std::size_t kStderrKept = 600;  // the end of what the program said: its last words
constexpr auto kExitGrace = std::chrono::milliseconds(1000);
constexpr std::size_t kMaxAnswerLine = std::size_t(16) << 20;  // a runaway writer, not data

std::string formatNumber(double v) {
    // Rotations leave 1e-17-sized noise where a component is 0; the program should see 0.
    if (std::fabs(v) < 1e-12) v = 0;
    char buf[32];
    auto res = numberToChars(buf, buf + sizeof buf, v);
    return std::string(buf, res.ptr);
}

// Parses one answer line into numbers; false (with `bad` set) for a word that is not a
// finite number.
bool parseNumbers(std::string_view line, std::vector<double>& out, std::string& bad) {
    out.clear();
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
        std::size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
        if (i == start) break;
        std::string_view word = line.substr(start, i - start);
        std::string_view digits = word.front() == '+' ? word.substr(1) : word;
        double v = 0;
        auto res = numberFromChars(digits.data(), digits.data() + digits.size(), v);
        if (digits.empty() || res.ec != std::errc() || res.ptr != digits.data() + digits.size() ||
            !std::isfinite(v)) {
            bad = std::string(word);
            return false;
        }
        out.push_back(v);
    }
    return true;
}

// Quotes program output for a message; control bytes and non-ASCII (binary junk) are
// shown as '?' so that the message stays one readable line.
std::string quote(std::string_view text, std::size_t limit = 80) {
    std::string s(text.substr(0, limit));
    for (char& c : s)
        if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) > 0x7e) c = '?';
    if (text.size() > limit) s += "...";
    return "'" + s + "'";
}

class ProcessEnvironment : public Environment {
  public:
    ProcessEnvironment(std::string command, std::string directory, double timeoutSeconds,
                       SourceLocation where)
        : command_(std::move(command)),
          directory_(std::move(directory)),
          timeout_(timeoutSeconds),
          where_(std::move(where)) {}

    ~ProcessEnvironment() override { stop(); }

    std::string name() const override { return "process"; }

    void respond(int step, std::span<CommunicationRequest> requests) override {
        if (!failure_.empty()) throw Error(where_, failure_);
        if (pid_ < 0) start();
        step_ = step;
        if (!input_.empty())
            fail(who() + " wrote more answer lines than asked: " +
                 quote(input_.substr(0, input_.find('\n'))) +
                 " came after the last answer before step " + std::to_string(step));
        requests_ = requests;
        answered_ = 0;
        exchange(request(step, requests));
    }

  private:
    std::string who() const { return "the environment program " + quote(command_, 200); }

    static std::string request(int step, std::span<const CommunicationRequest> requests) {
        std::string s =
            "step " + std::to_string(step) + " " + std::to_string(requests.size()) + "\n";
        for (const auto& r : requests) {
            const TurtleFrame& f = r.frame;
            s += std::to_string(r.module);
            for (const Vec3* v : {&f.position, &f.heading, &f.left, &f.up})
                for (double c : {v->x, v->y, v->z}) s += ' ' + formatNumber(c);
            for (double p : r.params) s += ' ' + formatNumber(p);
            s += '\n';
        }
        return s;
    }

    void start() {
        int io[2], err[2];
        if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, io) != 0)
            fail("cannot start " + who() + ": " + std::strerror(errno));
        if (pipe2(err, O_CLOEXEC) != 0) {
            int e = errno;
            close(io[0]);
            close(io[1]);
            fail("cannot start " + who() + ": " + std::strerror(e));
        }
        // Everything the child needs is prepared before fork: between fork and exec a
        // multi-threaded parent's child may only make async-signal-safe calls.
        const char* argv[] = {"sh", "-c", command_.c_str(), nullptr};
        const char* dir = directory_.empty() ? nullptr : directory_.c_str();
        static const char kNoDir[] = "graftal: cannot enter the L-system's directory\n";
        static const char kNoShell[] = "graftal: cannot run /bin/sh\n";
        pid_t pid = fork();
        if (pid == 0) {
            setpgid(0, 0);  // its own process group, so that a timeout kills its children too
            dup2(io[1], 0);
            dup2(io[1], 1);
            dup2(err[1], 2);
            if (dir && chdir(dir) != 0) {
                (void)!write(2, kNoDir, sizeof kNoDir - 1);
                _exit(127);
            }
            execv("/bin/sh", const_cast<char* const*>(argv));
            (void)!write(2, kNoShell, sizeof kNoShell - 1);
            _exit(127);
        }
        int forkError = errno;
        close(io[1]);
        close(err[1]);
        if (pid < 0) {
            close(io[0]);
            close(err[0]);
            fail("cannot start " + who() + ": " + std::strerror(forkError));
        }
        setpgid(pid, pid);  // also here: whichever runs first, the group exists afterwards
        pid_ = pid;
        io_ = io[0];
        err_ = err[0];
        fcntl(io_, F_SETFL, fcntl(io_, F_GETFL) | O_NONBLOCK);
        fcntl(err_, F_SETFL, fcntl(err_, F_GETFL) | O_NONBLOCK);
    }

    // Uses every complete answer line received so far, so that a bad answer is reported
    // as soon as it arrives rather than after a wait for the rest.
    void takeAnswers() {
        std::vector<double> values;
        std::string bad;
        // `used` and `scanned_` keep the work linear in what arrives, however it is split.
        std::size_t used = 0;
        for (std::size_t eol;
             (eol = input_.find('\n', std::max(used, scanned_))) != std::string::npos;) {
            std::string_view line = std::string_view(input_).substr(used, eol - used);
            if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
            if (answered_ == requests_.size())
                fail(who() + " wrote more than " + std::to_string(requests_.size()) +
                     " answer lines in step " + std::to_string(step_) + ": " + quote(line) +
                     " is one too many");
            const CommunicationRequest& r = requests_[answered_];
            std::size_t n = r.params.size();
            std::string what = "answer line " + std::to_string(answered_ + 1) + " of step " +
                               std::to_string(step_) + " (for the ?E at module " +
                               std::to_string(r.module) + ", with " + std::to_string(n) +
                               " parameter" + (n == 1 ? "" : "s") + ")";
            if (!parseNumbers(line, values, bad))
                fail(who() + " wrote " + quote(line) + " as " + what + ": " + quote(bad) +
                     " is not a finite number");
            if (values.size() != n)
                fail(who() + " wrote " + quote(line) + " as " + what + ": expected " +
                     std::to_string(n) + " number" + (n == 1 ? "" : "s") +
                     ", one per parameter, found " + std::to_string(values.size()));
            std::copy(values.begin(), values.end(), r.params.begin());
            ++answered_;
            used = eol + 1;
        }
        input_.erase(0, used);
        scanned_ = input_.size();
        if (input_.size() > kMaxAnswerLine)
            fail(who() + " wrote an answer line longer than 16 MB in step " +
                 std::to_string(step_) + ", starting " + quote(input_));
    }

    // Sends the request and reads until every request is answered. Writing and
    // reading are interleaved so that a program answering while it reads cannot deadlock
    // against a full buffer.
    void exchange(const std::string& message) {
        auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                           std::chrono::duration<double>(timeout_));
        std::size_t sent = 0;
        while (sent < message.size() || answered_ < requests_.size()) {
            pollfd fds[2] = {{io_, short(POLLIN | (sent < message.size() ? POLLOUT : 0)), 0},
                             {err_, POLLIN, 0}};
            auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - Clock::now());
            if (left.count() <= 0) timedOut();
            int n = poll(fds, err_ >= 0 ? 2 : 1,
                         static_cast<int>(std::min<long long>(left.count(), 1 << 30)));
            if (n < 0 && errno == EINTR) continue;
            if (n < 0) fail("cannot talk to " + who() + ": " + std::strerror(errno));
            if (n == 0) timedOut();
            if (err_ >= 0 && fds[1].revents) drainStderr();
            if (fds[0].revents & POLLOUT) {
                ssize_t w = send(io_, message.data() + sent, message.size() - sent,
                                 MSG_NOSIGNAL | MSG_DONTWAIT);
                if (w > 0) {
                    sent += static_cast<std::size_t>(w);
                } else if (errno == EPIPE || errno == ECONNRESET) {
                    ended("stopped reading its input");
                } else if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
                    fail("cannot write to " + who() + ": " + std::strerror(errno));
                }
            }
            if (fds[0].revents & (POLLIN | POLLHUP | POLLERR)) {
                char buf[1 << 16];
                ssize_t r = recv(io_, buf, sizeof buf, MSG_DONTWAIT);
                if (r > 0) {
                    input_.append(buf, static_cast<std::size_t>(r));
                    takeAnswers();
                } else if (r == 0 || errno == ECONNRESET) {
                    ended("closed its output");
                } else if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
                    fail("cannot read from " + who() + ": " + std::strerror(errno));
                }
            }
        }
    }

    void drainStderr() {
        char buf[4096];
        for (;;) {
            ssize_t r = read(err_, buf, sizeof buf);
            if (r > 0) {
                stderr_.append(buf, static_cast<std::size_t>(r));
                if (stderr_.size() > 4 * kStderrKept)
                    stderr_.erase(0, stderr_.size() - kStderrKept);
                continue;
            }
            if (r < 0 && errno == EINTR) continue;
            if (r == 0) {
                close(err_);
                err_ = -1;
            }
            return;
        }
    }

    // What the program said on stderr, on one line, for the end of an error message.
    std::string lastWords() {
        if (err_ >= 0) drainStderr();
        std::string s =
            stderr_.size() > kStderrKept ? stderr_.substr(stderr_.size() - kStderrKept) : stderr_;
        while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
        while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.erase(0, 1);
        if (s.empty()) return "";
        for (std::size_t p; (p = s.find('\n')) != std::string::npos;) s.replace(p, 1, " | ");
        return "; its error output ends with: " + s;
    }

    // Waits up to `grace` for the program to exit; true when it has (status_ is then set).
    bool reap(Clock::duration grace) {
        if (pid_ < 0) return true;
        auto until = Clock::now() + grace;
        for (;;) {
            pid_t r = waitpid(pid_, &status_, WNOHANG);
            if (r == pid_ || (r < 0 && errno == ECHILD)) {
                pid_ = -1;
                return true;
            }
            if (Clock::now() >= until) return false;
            if (err_ >= 0) drainStderr();
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        }
    }

    std::string progress() const {
        return " in step " + std::to_string(step_) + " after " + std::to_string(answered_) +
               " of " + std::to_string(requests_.size()) + " answer lines";
    }

    // The program closed its end: say how it ended, if it did.
    [[noreturn]] void ended(const std::string& what) {
        std::string how = what;
        if (reap(kExitGrace)) {
            if (WIFEXITED(status_))
                how = "exited with status " + std::to_string(WEXITSTATUS(status_));
            else if (WIFSIGNALED(status_))
                how = "was killed by signal " + std::to_string(WTERMSIG(status_)) + " (" +
                      strsignal(WTERMSIG(status_)) + ")";
        }
        fail(who() + " " + how + progress() + lastWords());
    }

    [[noreturn]] void timedOut() {
        fail(who() + " did not answer within " + formatNumber(timeout_) + " s" + progress() +
             " (does it flush its output after each step? 'environment: timeout SECONDS' "
             "sets the limit)" +
             lastWords());
    }

    // The protocol is out of step after any failure: stop the program, and refuse every
    // later step with the same message.
    [[noreturn]] void fail(const std::string& message) {
        failure_ = message;
        terminate();
        throw Error(where_, message);
    }

    void terminate() {
        if (pid_ >= 0 && !reap(Clock::duration::zero())) {
            ::kill(-pid_, SIGKILL);
            ::kill(pid_, SIGKILL);
            while (waitpid(pid_, &status_, 0) < 0 && errno == EINTR) {
            }
            pid_ = -1;
        }
        closeAll();
    }

    void closeAll() {
        for (int* fd : {&io_, &err_})
            if (*fd >= 0) {
                close(*fd);
                *fd = -1;
            }
    }

    // End of input tells the program to finish; one that does not is killed.
    void stop() {
        if (pid_ < 0) return closeAll();
        shutdown(io_, SHUT_WR);
        auto until = Clock::now() + kExitGrace;
        while (pid_ >= 0 && Clock::now() < until) {
            char buf[4096];
            while (recv(io_, buf, sizeof buf, MSG_DONTWAIT) > 0) {
            }
            if (reap(std::chrono::milliseconds(20))) break;
        }
        terminate();
    }

    std::string command_, directory_;
    double timeout_ = kDefaultTimeoutSeconds;
    SourceLocation where_;
    pid_t pid_ = -1;
    int io_ = -1, err_ = -1;  // the program's stdin and stdout (one socket); its stderr
    int status_ = 0;
    int step_ = 0;
    std::span<CommunicationRequest> requests_;  // of the step being answered
    std::size_t answered_ = 0;
    std::string input_;        // received answer text not yet used
    std::size_t scanned_ = 0;  // input_ holds no '\n' before this
    std::string stderr_;       // the end of the program's error output
    std::string failure_;      // set once the program has failed
};

}  // namespace

std::unique_ptr<Environment> environment_detail::makeProcessEnvironment(const LSystem& lsystem) {
    const EnvironmentLine& first = lsystem.environment.front();
    auto words = splitWords(first);
    std::string command;
    if (words.size() > 1) {
        std::size_t start =
            static_cast<std::size_t>(words[1].location.column - first.location.column);
        command = first.text.substr(start);
        command.erase(command.find_last_not_of(" \t\r\n") + 1);
    }
    if (command.empty())
        throw Error(endOfLine(first),
                    "expected a command after 'process', e.g. "
                    "'environment: process python3 height_field.py'");
    double timeout = kDefaultTimeoutSeconds;
    bool timeoutSeen = false;
    for (std::size_t i = 1; i < lsystem.environment.size(); ++i) {
        const EnvironmentLine& line = lsystem.environment[i];
        auto option = splitWords(line);
        if (option.empty()) continue;
        if (option[0].text != "timeout")
            throw Error(option[0].location,
                        "expected 'timeout SECONDS' (the command is the rest of the 'process' "
                        "line), found '" +
                            option[0].text + "'");
        if (timeoutSeen) throw Error(option[0].location, "the timeout is given twice");
        timeoutSeen = true;
        if (option.size() < 2)
            throw Error(endOfLine(line),
                        "expected the timeout in seconds (a number) after 'timeout'");
        timeout = numberWord(option[1], "the timeout in seconds", lsystem);
        if (timeout <= 0 || timeout > kMaxTimeoutSeconds)
            throw Error(option[1].location, "the timeout must be > 0 and at most 1000000 seconds");
        if (option.size() > 2)
            throw Error(
                option[2].location,
                "expected the end of the line after the timeout, found '" + option[2].text + "'");
    }
    // Relative paths in the command are read from the L-system file's directory, so that a
    // model and its environment program can live side by side.
    std::string directory;
    if (!lsystem.file.empty())
        directory = std::filesystem::path(lsystem.file).parent_path().string();
    return std::make_unique<ProcessEnvironment>(command, directory, timeout, first.location);
}

std::unique_ptr<Environment> makeExternalProcessEnvironment(const std::string& command) {
    SourceLocation where{"<environment process>", 0, 0};
    if (command.find_first_not_of(" \t\r\n") == std::string::npos)
        throw Error(where, "expected a command for the external environment program");
    return std::make_unique<ProcessEnvironment>(command, "", kDefaultTimeoutSeconds, where);
}

}  // namespace graftal
