// LilyPond source of a score, and the engraved score made by running the lilypond program.
#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <thread>
#include <vector>

#include "graftal/core/atomic_file.hpp"
#include "graftal/music/music.hpp"
#include "notation.hpp"

extern char** environ;

namespace graftal {

namespace fs = std::filesystem;

namespace {

constexpr std::size_t kMostEngravedBars = 1000;

// LilyPond's Dutch names: c cis d ... with ' for each octave above the one below middle C.
std::string lilyPitch(int midi) {
    static const char* names[] = {"c",   "cis", "d",   "dis", "e",   "f",
                                  "fis", "g",   "gis", "a",   "ais", "b"};
    std::string s = names[midi % 12];
    int marks = midi / 12 - 4;
    s += std::string(static_cast<std::size_t>(std::abs(marks)), marks > 0 ? '\'' : ',');
    return s;
}

std::string lilyDuration(int units) {
    bool dotted = false;
    int value = notation::noteValue(units, dotted);
    return std::to_string(value) + (dotted ? "." : "");
}

std::string quoted(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        out += c;
    }
    return out + "\"";
}

std::string formatTempo(double bpm) {
    std::ostringstream os;
    os << std::lround(bpm);
    return os.str();
}

// The lilypond program on the PATH.
fs::path findOnPath(const std::string& program) {
    const char* path = std::getenv("PATH");
    std::string dirs = path ? path : "/usr/bin:/bin";
    std::size_t start = 0;
    while (start <= dirs.size()) {
        std::size_t end = dirs.find(':', start);
        if (end == std::string::npos) end = dirs.size();
        fs::path candidate = fs::path(dirs.substr(start, end - start)) / program;
        if (end > start && ::access(candidate.c_str(), X_OK) == 0) return candidate;
        start = end + 1;
    }
    return {};
}

// A fresh private folder for lilypond's files, removed when done.
struct TemporaryFolder {
    fs::path path;
    TemporaryFolder() {
        static std::atomic<unsigned> counter{0};
        path = fs::temp_directory_path() /
               ("graftal-score-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
        fs::create_directories(path);
    }
    ~TemporaryFolder() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
};

struct RunResult {
    int status = -1;  // the exit status; -1 when it could not start or was killed
    bool timedOut = false;
};

// How long lilypond may take: $GRAFTAL_LILYPOND_SECONDS, else two minutes (a score of
// a few hundred bars takes seconds; thousands of bars on one page took minutes and
// gigabytes).
double lilyPondSeconds() {
    if (const char* env = std::getenv("GRAFTAL_LILYPOND_SECONDS"); env && *env) {
        char* end = nullptr;
        const double s = std::strtod(env, &end);
        if (end != env && s > 0 && s < 1e6) return s;
    }
    return 120;
}

// Runs `args` with its output in `log`, in a process group of its own that dies with this
// process (PR_SET_PDEATHSIG) and is killed whole after `seconds`: no lilypond (or the
// ghostscript it starts) is left running when graftal stops or gives up. Each of them may map
// at most `memoryBytes` (RLIMIT_AS): past it, its allocations fail and it exits.
RunResult run(const std::vector<std::string>& args, const fs::path& log, double seconds,
              std::size_t memoryBytes) {
    RunResult result;
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const int in = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
    const int out = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (in < 0 || out < 0) {
        if (in >= 0) ::close(in);
        if (out >= 0) ::close(out);
        return result;
    }
    const pid_t parent = ::getpid();
    const pid_t pid = ::fork();
    if (pid == 0) {
        // Only async-signal-safe calls between fork and exec.
        ::setpgid(0, 0);
        ::prctl(PR_SET_PDEATHSIG, SIGKILL);
        if (::getppid() != parent) ::_exit(127);  // the parent died before the line above
        const struct rlimit memory = {static_cast<rlim_t>(memoryBytes),
                                      static_cast<rlim_t>(memoryBytes)};
        ::setrlimit(RLIMIT_AS, &memory);
        ::dup2(in, 0);
        ::dup2(out, 1);
        ::dup2(out, 2);
        ::execve(argv[0], argv.data(), environ);
        ::_exit(127);
    }
    ::close(in);
    ::close(out);
    if (pid < 0) return result;
    ::setpgid(pid, pid);  // also here: whichever runs first, the group exists before a kill
    const auto deadline = std::chrono::steady_clock::now() +
                          std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                              std::chrono::duration<double>(seconds));
    // Until it is reaped, its pid (the group's id) cannot be reused: the group is killed
    // before that, on time out and after it ended (taking what it started with it).
    while (true) {
        siginfo_t info{};
        const int waited =
            ::waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT);
        if (waited < 0 && errno != EINTR) break;
        if (waited == 0 && info.si_pid == pid) break;
        if (std::chrono::steady_clock::now() >= deadline) {
            result.timedOut = true;
            break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    ::kill(-pid, SIGKILL);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    result.status = !result.timedOut && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
}

std::string tail(const fs::path& log) {
    std::ifstream in(log);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (text.size() > 600) text = "..." + text.substr(text.size() - 600);
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
    return text;
}

}  // namespace

std::string lilyPondSource(const Score& score, bool onePage) {
    double mean = 0;
    for (const Note& n : score.notes) mean += n.pitch;
    if (!score.notes.empty()) mean /= static_cast<double>(score.notes.size());

    std::ostringstream os;
    os << "% Made by graftal: a curve read as a score (LSFP ch. 6.3).\n";
    os << "\\version \"2.24.0\"\n";
    os << "\\header {\n";
    if (!score.title.empty()) os << "  title = " << quoted(score.title) << "\n";
    os << "  tagline = ##f\n}\n";
    if (onePage) os << "\\paper { page-breaking = #ly:one-page-breaking }\n";
    os << "\\score {\n  \\new Staff {\n";
    os << "    \\clef " << (mean < 57 ? "bass" : "treble") << "\n";
    os << "    \\time 4/4\n";
    os << "    \\tempo 4 = " << formatTempo(score.tempo) << "\n";
    for (const notation::Bar& bar : notation::bars(score)) {
        os << "   ";
        for (const notation::Piece& p : bar) {
            os << ' ' << (p.rest ? std::string("r") : lilyPitch(p.pitch)) << lilyDuration(p.units);
            if (p.tieToNext) os << " ~";
        }
        os << " |\n";
    }
    os << "    \\bar \"|.\"\n  }\n  \\layout { }\n}\n";
    return os.str();
}

void writeLilyPond(const Score& score, const Destination& destination) {
    std::string text = lilyPondSource(score);
    destination.write("LilyPond score", [&](std::ostream& out) { out << text; });
}

fs::path findLilyPond() {
    if (const char* env = std::getenv("GRAFTAL_LILYPOND"); env && *env) return env;
    return findOnPath("lilypond");
}

void engraveScore(const Score& score, const fs::path& path, std::size_t memoryLimit) {
    const std::optional<MusicFormat> format = musicFormatFor(path);
    if (!format || (*format != MusicFormat::Pdf && *format != MusicFormat::Png &&
                    *format != MusicFormat::Svg))
        throw fileError(path, "cannot engrave a score as '" + path.extension().string() +
                                  "': expected .pdf, .png or .svg");
    engraveScore(score, *format, Destination::file(path), memoryLimit);
}

void engraveScore(const Score& score, MusicFormat format, const Destination& destination,
                  std::size_t memoryLimit) {
    const fs::path& path = destination.path();
    const std::string ext = format == MusicFormat::Pdf   ? ".pdf"
                            : format == MusicFormat::Png ? ".png"
                            : format == MusicFormat::Svg ? ".svg"
                                                         : "";
    if (ext.empty()) throw fileError(path, "cannot engrave a score but as PDF, PNG or SVG");
    const std::string what = "score";
    fs::path lilypond = findLilyPond();
    if (lilypond.empty())
        throw fileError(path,
                        "cannot engrave the score: the lilypond program is not installed "
                        "(Debian: 'apt-get install lilypond', or 'make deps'); write a .ly "
                        "file instead and engrave it later with 'lilypond score.ly'");
    // LilyPond spends minutes and gigabytes on thousands of bars (on one page for a picture):
    // such a score is refused before it starts.
    const std::size_t bars = notation::bars(score).size();
    if (bars > kMostEngravedBars)
        throw fileError(path, "cannot engrave the score: it has " + std::to_string(bars) +
                                  " bars, more than the " + std::to_string(kMostEngravedBars) +
                                  " an engraved score may have: lower the steps or the unit "
                                  "(--unit, `music unit:`), or write a .ly (or .mid) file");
    TemporaryFolder tmp;
    const fs::path source = tmp.path / "score.ly";
    {
        std::ofstream out(source);
        out << lilyPondSource(score, ext != ".pdf");
        if (!out)
            throw fileError(path, "cannot engrave the score: cannot write its LilyPond source");
    }
    std::vector<std::string> args = {lilypond.string(), "-dno-point-and-click", "-s"};
    if (ext == ".pdf") args.push_back("--pdf");
    if (ext == ".png") args.insert(args.end(), {"--png", "-dresolution=110"});
    if (ext == ".svg") args.push_back("--svg");
    args.insert(args.end(), {"-o", (tmp.path / "score").string(), source.string()});
    const fs::path log = tmp.path / "lilypond.log";
    const double seconds = lilyPondSeconds();
    const RunResult ran = run(args, log, seconds, memoryLimit);
    if (ran.timedOut) {
        std::ostringstream limit;
        limit << seconds;
        throw fileError(path, "cannot engrave the score: lilypond took longer than " + limit.str() +
                                  " s on its " + std::to_string(bars) +
                                  " bars and was stopped: lower the steps or the unit, or "
                                  "write a .ly (or .mid) file instead");
    }
    const int status = ran.status;
    if (status != 0) {
        std::string detail = tail(log);
        throw fileError(path,
                        "cannot engrave the score: lilypond " +
                            (status < 0 ? std::string("could not be run")
                                        : "failed (exit status " + std::to_string(status) +
                                              "; it may map at most " +
                                              std::to_string(memoryLimit >> 20) +
                                              " MiB: --memory-limit)") +
                            (detail.empty() ? "" : ":\n" + detail));
    }
    fs::path made = tmp.path / ("score" + ext);
    if (!fs::exists(made)) made = tmp.path / ("score-page1" + ext);
    if (!fs::exists(made))
        throw fileError(path, "cannot engrave the score: lilypond wrote no " + ext + " file");
    std::ifstream in(made, std::ios::binary);
    destination.write(what, [&](std::ostream& out) { out << in.rdbuf(); });
}

}  // namespace graftal
