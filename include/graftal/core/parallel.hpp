// Splitting a step's work into contiguous chunks, one per thread. Chunk boundaries depend
// only on the string length and the thread count, and every result is combined in chunk
// order, so the output never depends on scheduling.
#pragma once

#include <algorithm>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace graftal {

inline unsigned defaultThreadCount() {
    unsigned n = std::thread::hardware_concurrency();
    return n == 0 ? 1 : n;
}

// The number of chunks forEachChunk really makes of n items when asked for `chunks`.
inline std::size_t chunkCountFor(std::size_t n, std::size_t chunks) {
    return std::max<std::size_t>(1, std::min(chunks, n == 0 ? 1 : n));
}

// Where chunk c of `chunks` (as chunkCountFor gives them) begins; chunk `chunks` begins at n.
inline std::size_t chunkBegin(std::size_t n, std::size_t chunks, std::size_t c) {
    return n * c / chunks;
}

// Calls fn(chunk, begin, end) for `chunks` ranges covering [0, n). Exceptions are
// rethrown from the lowest-numbered chunk that threw.
template <class Fn>
void forEachChunk(std::size_t n, std::size_t chunks, Fn&& fn) {
    chunks = chunkCountFor(n, chunks);
    auto begin = [&](std::size_t c) { return chunkBegin(n, chunks, c); };
    if (chunks == 1) {
        fn(std::size_t(0), std::size_t(0), n);
        return;
    }
    std::vector<std::exception_ptr> errors(chunks);
    std::vector<std::thread> threads;
    threads.reserve(chunks - 1);
    for (std::size_t c = 1; c < chunks; ++c) {
        threads.emplace_back([&, c] {
            try {
                fn(c, begin(c), begin(c + 1));
            } catch (...) {
                errors[c] = std::current_exception();
            }
        });
    }
    try {
        fn(std::size_t(0), begin(0), begin(1));
    } catch (...) {
        errors[0] = std::current_exception();
    }
    for (auto& t : threads) t.join();
    for (auto& e : errors)
        if (e) std::rethrow_exception(e);
}

}  // namespace graftal
