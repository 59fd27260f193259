// The bandwidth floor of the benchmark (bench/run.sh): how fast this machine can write a
// buffer as large as a derivation's output.
//
//   memcpy_probe [BYTES] [REPEATS]
//
// BYTES defaults to the quadratic Koch island at n = 8: 124,630,747 modules at 1 byte per
// module. The probe copies a warm (already faulted-in) source buffer of that size into a
// warm destination REPEATS times (default 7) with one thread, takes the fastest copy, and
// prints one line of JSON:
//
//   {"bytes": ..., "copy_s": ..., "copy_GBps": ..., "first_touch_s": ..., "fill_GBps": ...}
//
// copy_s is the time to write the output once (reading a source as large): the floor any
// derivation that produces that string must pay. copy_GBps is bytes written per second
// (the read traffic is not counted). first_touch_s is the same copy into freshly mapped
// memory, page faults included, which is what a program that allocates its output pays
// unless it reuses memory. fill_GBps is a memset of the warm buffer (write only).
//
// Built by bench/run.sh with g++ -O2; it depends on nothing but the C++ standard library.

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace {

double seconds() {
    using clock = std::chrono::steady_clock;
    return std::chrono::duration<double>(clock::now().time_since_epoch()).count();
}

// Keeps the compiler from dropping a copy whose result is never read.
volatile unsigned char sink;

}  // namespace

int main(int argc, char** argv) {
    std::size_t bytes = 124630747ull;
    int repeats = 7;
    if (argc > 1) bytes = std::strtoull(argv[1], nullptr, 10);
    if (argc > 2) repeats = std::max(1, std::atoi(argv[2]));
    if (bytes == 0) {
        std::fprintf(stderr, "memcpy_probe: BYTES must be positive\n");
        return 2;
    }

    auto* src = static_cast<unsigned char*>(std::malloc(bytes));
    auto* dst = static_cast<unsigned char*>(std::malloc(bytes));
    if (!src || !dst) {
        std::fprintf(stderr, "memcpy_probe: cannot allocate 2 x %zu bytes\n", bytes);
        return 1;
    }
    // Fault the source in with a pattern that is not all zeros.
    for (std::size_t i = 0; i < bytes; ++i) src[i] = static_cast<unsigned char>(i * 131u + 7u);

    // First touch: the destination's pages are faulted in by the copy itself.
    double t0 = seconds();
    std::memcpy(dst, src, bytes);
    double firstTouch = seconds() - t0;
    sink = dst[bytes / 2];

    double best = 1e30;
    for (int r = 0; r < repeats; ++r) {
        src[static_cast<std::size_t>(r) % bytes] ^= 1;  // a different copy every time
        t0 = seconds();
        std::memcpy(dst, src, bytes);
        best = std::min(best, seconds() - t0);
        sink = dst[(bytes / 3 + static_cast<std::size_t>(r)) % bytes];
    }

    double bestFill = 1e30;
    for (int r = 0; r < repeats; ++r) {
        t0 = seconds();
        std::memset(dst, r + 1, bytes);
        bestFill = std::min(bestFill, seconds() - t0);
        sink = dst[bytes / 5];
    }

    std::printf(
        "{\"bytes\": %zu, \"copy_s\": %.6f, \"copy_GBps\": %.3f, \"first_touch_s\": %.6f, "
        "\"fill_GBps\": %.3f}\n",
        bytes, best, static_cast<double>(bytes) / best / 1e9, firstTouch,
        static_cast<double>(bytes) / bestFill / 1e9);
    std::free(src);
    std::free(dst);
    return 0;
}
