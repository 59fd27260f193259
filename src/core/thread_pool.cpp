#include "graftal/core/thread_pool.hpp"

namespace graftal {

namespace {

// A waiting thread first polls for a while (a pass of the solver on the other core ends
// within tens of microseconds; sleeping and being woken costs about as much), then sleeps
// in the kernel so a loaded machine gets the core back.
constexpr int kSpins = 2000;

inline void cpuRelax() {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#else
    std::this_thread::yield();
#endif
}

void waitWhileEqual(const std::atomic<std::uint32_t>& value, std::uint32_t old) {
    for (int i = 0; i < kSpins; ++i) {
        if (value.load(std::memory_order_acquire) != old) return;
        cpuRelax();
    }
    while (value.load(std::memory_order_acquire) == old) value.wait(old, std::memory_order_acquire);
}

}  // namespace

ThreadPool::ThreadPool(unsigned threads) : size_(threads == 0 ? 1 : threads), errors_(size_) {
    workers_.reserve(size_ - 1);
    for (unsigned t = 1; t < size_; ++t) workers_.emplace_back([this, t] { work(t); });
}

ThreadPool::~ThreadPool() {
    stopping_ = true;
    job_.fetch_add(1, std::memory_order_release);
    job_.notify_all();
    for (auto& w : workers_) w.join();
}

void ThreadPool::work(unsigned thread) {
    std::uint32_t seen = 0;
    for (;;) {
        waitWhileEqual(job_, seen);
        seen = job_.load(std::memory_order_acquire);
        if (stopping_) return;
        runTask(thread);
        if (finished_.fetch_add(1, std::memory_order_acq_rel) + 1 == size_ - 1)
            finished_.notify_one();
    }
}

void ThreadPool::runTask(unsigned thread) {
    try {
        (*task_)(thread);
    } catch (const Abandoned&) {
        // Released from a barrier because another thread threw; that one's error counts.
    } catch (...) {
        errors_[thread] = std::current_exception();
        abandon();
    }
}

void ThreadPool::abandon() {
    abandoned_.store(true, std::memory_order_seq_cst);
    generation_.fetch_add(1, std::memory_order_acq_rel);
    generation_.notify_all();
}

void ThreadPool::run(const std::function<void(unsigned)>& task) {
    task_ = &task;
    for (auto& e : errors_) e = nullptr;
    finished_.store(0, std::memory_order_relaxed);
    arrived_.store(0, std::memory_order_relaxed);
    abandoned_.store(false, std::memory_order_relaxed);
    if (size_ > 1) {
        job_.fetch_add(1, std::memory_order_release);
        job_.notify_all();
    }
    runTask(0);
    if (size_ > 1) {
        for (;;) {
            const std::uint32_t done = finished_.load(std::memory_order_acquire);
            if (done == size_ - 1) break;
            waitWhileEqual(finished_, done);
        }
    }
    task_ = nullptr;
    for (auto& e : errors_)
        if (e) std::rethrow_exception(e);
}

void ThreadPool::barrier() {
    const std::uint32_t generation = generation_.load(std::memory_order_acquire);
    if (abandoned_.load(std::memory_order_seq_cst)) throw Abandoned{};
    if (size_ == 1) return;
    if (arrived_.fetch_add(1, std::memory_order_acq_rel) + 1 == size_) {
        arrived_.store(0, std::memory_order_relaxed);
        generation_.fetch_add(1, std::memory_order_acq_rel);
        generation_.notify_all();
    } else {
        waitWhileEqual(generation_, generation);
    }
    if (abandoned_.load(std::memory_order_seq_cst)) throw Abandoned{};
}

}  // namespace graftal
