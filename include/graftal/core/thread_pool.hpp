// A team of threads started once and kept for many short parallel passes: an iterative
// solver makes thousands of passes of a fraction of a millisecond each, and starting threads
// for every pass (forEachChunk in parallel.hpp) costs more than the pass. The team works
// inside one run() call, meeting at barrier() between passes; between runs the workers
// sleep.
//
// Determinism is the caller's: split the work into chunks fixed by the problem, not by the
// team size (forEachChunk below hands out such chunks), and combine chunk results in chunk
// order.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <thread>
#include <vector>

namespace graftal {

class ThreadPool {
  public:
    // threads - 1 workers are started here (the caller of run() is thread 0); 0 counts as 1.
    explicit ThreadPool(unsigned threads);
    ~ThreadPool();
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    unsigned size() const { return size_; }

    // Calls task(t) once on each thread t of the team, the caller being thread 0, and returns
    // when every call has returned. If a call throws, the other threads are released from
    // barrier() (they leave their task by an exception the pool catches), and once all
    // have left, the exception of the lowest-numbered thread that threw is rethrown. Not
    // reentrant: a task must not call run() on its own pool.
    void run(const std::function<void(unsigned)>& task);

    // Inside run(): returns when every thread of the team has called it (as often). What a
    // thread wrote before it is visible to all threads after it.
    void barrier();

    // fn(chunk, begin, end) for the `chunks` ranges of [0, n) that chunkBegin (parallel.hpp)
    // makes, each thread taking a contiguous run of chunks; inside run() (every thread of
    // the team calls it with the same arguments; no barrier at the end). Which thread runs a
    // chunk depends on the team size; the ranges do not.
    template <class Fn>
    void forEachChunk(unsigned thread, std::size_t n, std::size_t chunks, Fn&& fn) const {
        if (n == 0 || chunks == 0) return;
        const std::size_t first = chunks * thread / size_, last = chunks * (thread + 1) / size_;
        for (std::size_t c = first; c < last; ++c) fn(c, n * c / chunks, n * (c + 1) / chunks);
    }

    // The contiguous run [first, last) of `items` items that thread `thread` takes when the
    // items are shared as forEachChunk shares chunks.
    std::pair<std::size_t, std::size_t> share(unsigned thread, std::size_t items) const {
        return {items * thread / size_, items * (thread + 1) / size_};
    }

  private:
    struct Abandoned {};  // thrown out of barrier() when another thread's task threw

    void work(unsigned thread);
    void runTask(unsigned thread);
    void abandon();

    unsigned size_;
    std::vector<std::thread> workers_;
    const std::function<void(unsigned)>* task_ = nullptr;
    std::vector<std::exception_ptr> errors_;
    std::atomic<std::uint32_t> job_{0};       // bumped to start a run (or to stop)
    std::atomic<std::uint32_t> finished_{0};  // workers done with the current run
    std::atomic<std::uint32_t> arrived_{0};   // threads at the current barrier
    std::atomic<std::uint32_t> generation_{0};
    std::atomic<bool> abandoned_{false};
    bool stopping_ = false;
};

}  // namespace graftal
