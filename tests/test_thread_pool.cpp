#include "graftal/core/thread_pool.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <numeric>
#include <stdexcept>
#include <thread>
#include <vector>

using namespace graftal;

namespace {

// Sums 1..n in fixed chunks, each chunk's sum kept, then the chunks added in order.
double chunkedSum(ThreadPool& pool, std::size_t n, std::size_t chunks) {
    std::vector<double> part(chunks, 0.0);
    pool.run([&](unsigned t) {
        pool.forEachChunk(t, n, chunks, [&](std::size_t c, std::size_t b, std::size_t e) {
            double s = 0;
            for (std::size_t i = b; i < e; ++i) s += 1.0 / static_cast<double>(i + 1);
            part[c] = s;
        });
    });
    return std::accumulate(part.begin(), part.end(), 0.0);
}

}  // namespace

TEST(ThreadPool, EveryThreadRunsTheTaskOnceTheCallerBeingThreadZero) {
    for (unsigned size : {1u, 2u, 7u}) {
        ThreadPool pool(size);
        ASSERT_EQ(pool.size(), size);
        std::vector<int> calls(size, 0);
        std::vector<std::thread::id> ids(size);
        pool.run([&](unsigned t) {
            ++calls[t];
            ids[t] = std::this_thread::get_id();
        });
        EXPECT_EQ(calls, std::vector<int>(size, 1));
        EXPECT_EQ(ids[0], std::this_thread::get_id());
        for (unsigned t = 1; t < size; ++t) EXPECT_NE(ids[t], ids[0]);
    }
    EXPECT_EQ(ThreadPool(0).size(), 1u);
}

TEST(ThreadPool, ChunksDoNotDependOnTheTeamSizeAndCoverEveryItemOnce) {
    // More threads than chunks, fewer, and none of either: the ranges are the chunks of
    // [0, n) whatever the team, and the sum is the same to the last bit.
    for (std::size_t chunks : {1u, 3u, 64u}) {
        std::vector<double> sums;
        for (unsigned size : {1u, 2u, 7u}) {
            ThreadPool pool(size);
            std::vector<std::atomic<int>> seen(1000);
            std::vector<std::pair<std::size_t, std::size_t>> ranges(chunks);
            pool.run([&](unsigned t) {
                pool.forEachChunk(t, seen.size(), chunks,
                                  [&](std::size_t c, std::size_t b, std::size_t e) {
                                      ranges[c] = {b, e};
                                      for (std::size_t i = b; i < e; ++i) ++seen[i];
                                  });
            });
            for (const auto& s : seen) ASSERT_EQ(s.load(), 1);
            for (std::size_t c = 0; c < chunks; ++c) {
                EXPECT_EQ(ranges[c].first, 1000 * c / chunks);
                EXPECT_EQ(ranges[c].second, 1000 * (c + 1) / chunks);
            }
            sums.push_back(chunkedSum(pool, 100000, chunks));
        }
        EXPECT_EQ(sums[1], sums[0]);
        EXPECT_EQ(sums[2], sums[0]);
    }
}

TEST(ThreadPool, ZeroWorkCallsNothing) {
    ThreadPool pool(3);
    std::atomic<int> calls{0};
    pool.run([&](unsigned t) {
        pool.forEachChunk(t, 0, 8, [&](std::size_t, std::size_t, std::size_t) { ++calls; });
        pool.forEachChunk(t, 10, 0, [&](std::size_t, std::size_t, std::size_t) { ++calls; });
    });
    EXPECT_EQ(calls.load(), 0);
    auto [first, last] = pool.share(2, 0);
    EXPECT_EQ(first, last);
}

TEST(ThreadPool, BarrierSeparatesPassesOverSharedData) {
    // Each pass rotates the vector by one place, reading a value another thread's share may
    // hold: without the barrier a thread would read values of the wrong pass.
    for (unsigned size : {1u, 2u, 7u}) {
        ThreadPool pool(size);
        const std::size_t n = 4096;
        std::vector<long> a(n), b(n, 0);
        std::iota(a.begin(), a.end(), 0L);
        pool.run([&](unsigned t) {
            auto [first, last] = pool.share(t, n);
            for (int pass = 0; pass < 50; ++pass) {
                const std::vector<long>& from = pass % 2 ? b : a;
                std::vector<long>& to = pass % 2 ? a : b;
                for (std::size_t i = first; i < last; ++i) to[i] = from[(i + 1) % n];
                pool.barrier();
            }
        });
        for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(a[i], static_cast<long>((i + 50) % n));
    }
}

TEST(ThreadPool, AThrowingThreadReleasesTheOthersAndItsErrorIsRethrown) {
    for (unsigned size : {1u, 2u, 7u}) {
        ThreadPool pool(size);
        const unsigned thrower = size - 1;
        std::atomic<int> afterBarrier{0};
        try {
            pool.run([&](unsigned t) {
                if (t == thrower) throw std::runtime_error("thread " + std::to_string(t));
                // The others wait for the thrower, which never comes: they must be let go.
                pool.barrier();
                ++afterBarrier;
            });
            FAIL() << "no exception";
        } catch (const std::runtime_error& e) {
            EXPECT_EQ(std::string(e.what()), "thread " + std::to_string(thrower));
        }
        EXPECT_EQ(afterBarrier.load(), 0);
        // Of several throwers the lowest-numbered one's error is rethrown.
        try {
            pool.run([&](unsigned t) { throw std::runtime_error("thread " + std::to_string(t)); });
            FAIL() << "no exception";
        } catch (const std::runtime_error& e) {
            EXPECT_STREQ(e.what(), "thread 0");
        }
        // The pool is usable afterwards.
        EXPECT_EQ(chunkedSum(pool, 1000, 8), chunkedSum(pool, 1000, 8));
        std::atomic<int> calls{0};
        pool.run([&](unsigned) {
            pool.barrier();
            ++calls;
        });
        EXPECT_EQ(calls.load(), static_cast<int>(size));
    }
}

TEST(ThreadPool, ManyShortRunsAndBarriers) {
    ThreadPool pool(2);
    std::atomic<long> total{0};
    for (int run = 0; run < 2000; ++run)
        pool.run([&](unsigned t) {
            pool.barrier();
            total += t + 1;
        });
    EXPECT_EQ(total.load(), 2000 * 3);
}
