// The derivation alone, timed inside one process (bench/run.sh, the "in-process" column):
//
//   derive_timing FILE STEPS [REPEATS] [single|double]
//
// Loads FILE, derives STEPS steps REPEATS times (default 5) with the library's derive()
// (parameters stored as the last argument says; default single), every step written in full,
// and prints one line of JSON: {"modules": ..., "first_s": ..., "warm_s": ...}. first_s is
// the first derivation, which maps its buffers fresh from the kernel; warm_s is the fastest
// of the others, whose buffers land on memory the process has just given back. The gap
// between the two is the cost of first-touch page faults on the machine, which the whole
// process times of the table include and a long-running program (an editor, a server, a
// Python session) pays once.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>

#include "graftal/graftal.hpp"

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: derive_timing FILE STEPS [REPEATS]\n");
        return 2;
    }
    int steps = std::atoi(argv[2]);
    int repeats = argc > 3 ? std::max(2, std::atoi(argv[3])) : 5;
    try {
        graftal::LSystem ls = graftal::loadLSystem(argv[1]);
        graftal::DerivationOptions options;
        options.memoryLimit = std::size_t(16) << 30;
        if (argc > 4 && std::string(argv[4]) == "double")
            options.precision = graftal::Precision::Double;
        double first = 0, warm = 1e30;
        std::size_t modules = 0;
        for (int r = 0; r < repeats; ++r) {
            auto t0 = std::chrono::steady_clock::now();
            graftal::ModuleString s = graftal::derive(ls, steps, options);
            double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            modules = s.size();
            if (r == 0)
                first = t;
            else
                warm = std::min(warm, t);
        }
        std::printf("{\"modules\": %zu, \"first_s\": %.6f, \"warm_s\": %.6f}\n", modules, first,
                    warm);
    } catch (const graftal::Error& e) {
        std::cerr << e.what() << "\n";
        return 1;
    }
    return 0;
}
