// Runs the graftal executable the way a user would and captures what it says.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace graftal::testing {

struct RunResult {
    int status = -1;
    std::string out, err;
};

inline std::string readFile(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// `args` is passed through the shell; quote paths with spaces yourself. Standard input is
// `input` (by default nothing).
inline RunResult runGraftal(const std::string& args,
                            const std::filesystem::path& input = "/dev/null") {
    static int counter = 0;
    auto dir = std::filesystem::temp_directory_path();
    auto tag = std::to_string(::getpid()) + "-" + std::to_string(counter++);
    auto outPath = dir / ("graftal-out-" + tag), errPath = dir / ("graftal-err-" + tag);
    std::string cmd = std::string(GRAFTAL_EXE) + " " + args + " > " + outPath.string() + " 2> " +
                      errPath.string() + " < " + input.string();
    int raw = std::system(cmd.c_str());
    RunResult r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
    r.out = readFile(outPath);
    r.err = readFile(errPath);
    std::filesystem::remove(outPath);
    std::filesystem::remove(errPath);
    return r;
}

// A scratch directory removed at the end of the test.
class TempDir {
  public:
    TempDir() {
        static int n = 0;
        path_ = std::filesystem::temp_directory_path() /
                ("graftal-test-" + std::to_string(::getpid()) + "-" + std::to_string(n++));
        std::filesystem::create_directories(path_);
    }
    ~TempDir() { std::filesystem::remove_all(path_); }
    const std::filesystem::path& path() const { return path_; }
    std::filesystem::path write(const std::string& name, const std::string& content) const {
        auto p = path_ / name;
        std::ofstream(p, std::ios::binary) << content;
        return p;
    }

  private:
    std::filesystem::path path_;
};

}  // namespace graftal::testing
