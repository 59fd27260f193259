// The parallel streamed derivation (parallel_stream.hpp). The string of some step k is held
// (a few thousand modules a thread) and cut into chunks; a worker takes the chunks in order
// and expands each depth-first through steps k+1..n as streamDerivation() does, writing the
// final modules into blocks. A chunk's blocks wait in its own queue (a few at most), and a
// worker takes a chunk only while it lies within a window ahead of the chunk the caller
// reads, so memory stays bounded whatever the string's length, and the caller sees the
// blocks in string order however the workers are scheduled.
#include "graftal/rewrite/parallel_stream.hpp"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>

#include "graftal/core/parallel.hpp"
#include "graftal/rewrite/growth.hpp"
#include "graftal/rewrite/streaming.hpp"
#include "rewriting_engine.hpp"

namespace graftal {

namespace {

// Modules a block holds: large enough that handing one over costs nothing beside its
// contents, small enough that the window of blocks stays in a few dozen MB.
constexpr std::size_t kBlockModules = std::size_t(1) << 15;
// The held string cut into chunks has at least this many modules a thread.
constexpr std::size_t kPrefixModulesPerThread = 8192;
// Chunks a thread: enough that a chunk whose subtrees grow little and one whose subtrees
// grow much even out.
constexpr std::size_t kChunksPerThread = 32;
// Blocks the chunk the caller reads may hold before its worker waits; blocks all the other
// chunks may hold together, a thread, before their workers wait. A worker on a later chunk
// keeps going while the caller still reads an earlier one, whose subtrees may be many
// times larger: a cap per chunk would leave it idle after a few blocks.
constexpr std::size_t kQueuedBlocks = 4;
constexpr std::size_t kAheadBlocksPerThread = 24;

unsigned threadCount(const DerivationOptions& options) {
    return parallelThreads(options.threads);
}

// Below this many modules a held derivation is over in a few milliseconds.
constexpr double kParallelStreamModules = 1 << 20;

// ModuleString::push() where the walk spends its time: the same layout (offsets only once
// some module has parameters), inlined.
template <class T>
inline void appendModule(ModuleString& out, Symbol s, const T* args, std::size_t n) {
    auto& symbols = out.rawSymbols();
    auto& starts = out.rawParamStart();
    if (n == 0) {
        symbols.push_back(s);
        if (!starts.empty()) starts.push_back(static_cast<std::uint32_t>(out.paramCount()));
        return;
    }
    if (starts.empty()) starts.assign(symbols.size() + 1, 0);
    symbols.push_back(s);
    if (out.precision() == Precision::Single) {
        auto& values = out.rawFloats();
        for (std::size_t k = 0; k < n; ++k) values.push_back(static_cast<float>(args[k]));
        starts.push_back(static_cast<std::uint32_t>(values.size()));
    } else {
        auto& values = out.rawParams();
        for (std::size_t k = 0; k < n; ++k) values.push_back(static_cast<double>(args[k]));
        starts.push_back(static_cast<std::uint32_t>(values.size()));
    }
}

// Module i of `from` appended to `to`, its stored parameters copied as they are.
inline void copyModule(const ModuleString& from, std::size_t i, ModuleString& to) {
    const auto& starts = from.paramStarts();
    const Symbol s = from.symbol(i);
    if (starts.empty()) return appendModule<float>(to, s, nullptr, 0);
    const std::size_t b = starts[i], n = starts[i + 1] - b;
    if (from.precision() == Precision::Single)
        appendModule(to, s, from.floatParams().data() + b, n);
    else
        appendModule(to, s, from.doubleParams().data() + b, n);
}

// The step that rewrites a module of string `level`, and its table.
struct StepOf {
    int number;
    int table;
};

// Expands the modules [b, e) of the string of step `first` depth-first to step `steps`,
// handing the final modules to emit(string, begin, end) in order, in runs of a string. A worker's own engine and
// level strings are kept from chunk to chunk.
class ChunkWalker {
  public:
    ChunkWalker(const LSystem& ls, int steps, const DerivationOptions& options)
        : ls_(ls),
          steps_(steps),
          options_(options),
          engine_(ls, ls.productions, options.seed.value_or(ls.seed), 1),
          fixed_(ls.symbols.size()) {
        for (std::size_t s = 0; s < fixed_.size(); ++s)
            fixed_[s] = !engine_.rewrites(static_cast<Symbol>(s));
        // The productions applied without a choice, per (table, symbol, arity).
        tables_ = std::max<std::size_t>(1, ls.tableNames.size());
        symbols_ = ls.symbols.size();
        direct_.assign(tables_ * symbols_ * kArities, nullptr);
        std::size_t slots = 1;
        directs_.resize(ls.productions.size());
        for (std::size_t k = 0; k < ls.productions.size(); ++k) {
            const Production& p = ls.productions[k];
            slots = std::max(slots, static_cast<std::size_t>(std::max(0, p.slotCount)));
            directs_[k].production = &p;
            directs_[k].modules = p.successor.size();
            for (const auto& m : p.successor) directs_[k].params += m.args.size();
        }
        slots_.assign(slots, 0);
        for (std::size_t t = 0; t < tables_; ++t)
            for (std::size_t s = 0; s < symbols_; ++s)
                for (std::size_t a = 0; a < kArities; ++a)
                    for (std::size_t k = 0; k < ls.productions.size(); ++k) {
                        const Production& p = ls.productions[k];
                        if (p.table >= 0 && static_cast<std::size_t>(p.table) != t) continue;
                        if (p.predecessor.size() != 1 || p.predecessor[0].symbol != s) continue;
                        if (p.predecessor[0].formals.size() != a) continue;
                        bool plain = !p.condition && !p.probability && !p.hasBlocks() &&
                                     !p.hasContext();
                        for (const auto& m : p.successor)
                            for (const auto& arg : m.args) plain &= !arg.needsContext();
                        if (plain) direct_[(t * symbols_ + s) * kArities + a] = &directs_[k];
                        break;
                    }
    }

    RewritingEngine& engine() { return engine_; }

    // Appends the successor of module i of `s` to `out` as expandOne() would, evaluating
    // the arguments directly when the production is known from the symbol and arity alone
    // and its arguments need no context (most parametric L-systems): no choice to make,
    // no call per module into the engine.
    void expand(const ModuleString& s, std::size_t i, StepOf step, ModuleString& out) {
        const ParamView params = s.params(i);
        if (const Direct* d = direct(step.table, s.symbol(i), params.size())) {
            const std::size_t mark = out.size();
            try {
                for (std::size_t k = 0; k < params.size(); ++k) slots_[k] = params[k];
                if (out.precision() == Precision::Single)
                    writeSuccessor(*d, out, out.rawFloats());
                else
                    writeSuccessor(*d, out, out.rawParams());
                return;
            } catch (const Error&) {
                // The engine says where it failed.
                truncate(out, mark);
            }
        }
        engine_.expandOne(s, i, 0, step.number, step.table, out);
    }
    bool fixed(Symbol s) const { return fixed_[s]; }
    StepOf stepOf(int level) const { return {level + 1, ls_.tableForStep(level + 1)}; }

    // `expandLast(string, i, step)`, when it returns true, has taken care of module i, which
    // the last step rewrites (the counting walk counts its successor without writing it).
    template <class Emit, class ExpandLast>
    void walk(const ModuleString& held, std::size_t b, std::size_t e, int first, Emit&& emit,
              ExpandLast&& expandLast) {
        const std::size_t depth = static_cast<std::size_t>(steps_ - first);
        if (levels_.size() < depth + 1) levels_.resize(depth + 1, ModuleString(options_.precision));
        cursor_.assign(depth + 1, 0);
        end_.assign(depth + 1, 0);
        cursor_[0] = b;
        end_[0] = e;
        std::size_t d = 0;
        while (true) {
            if (cursor_[d] == end_[d]) {
                if (d == 0) break;
                --d;
                continue;
            }
            const std::size_t i = cursor_[d];
            const ModuleString& here = d == 0 ? held : levels_[d];
            if (d == depth) {
                // A string of the last step: all of it at once.
                emit(here, i, end_[d]);
                cursor_[d] = end_[d];
                continue;
            }
            const Symbol s = here.symbol(i);
            if (fixed_[s]) {
                // Modules no step rewrites, as many as follow each other.
                std::size_t j = i + 1;
                while (j < end_[d] && fixed_[here.symbol(j)]) ++j;
                emit(here, i, j);
                cursor_[d] = j;
                continue;
            }
            ++cursor_[d];
            if ((++expansions_ & 0xFFFu) == 0) options_.cancel.check();
            const StepOf step = stepOf(first + static_cast<int>(d));
            if (d + 1 == depth && expandLast(here, i, step)) continue;
            ModuleString& next = levels_[d + 1];
            next.clear();
            expand(here, i, step, next);
            cursor_[d + 1] = 0;
            end_[d + 1] = next.size();
            ++d;
        }
    }

  private:
    static constexpr std::size_t kArities = 8;

    // A production applied without a choice, and the size of its successor.
    struct Direct {
        const Production* production = nullptr;
        std::size_t modules = 0, params = 0;
    };

    const Direct* direct(int table, Symbol s, std::size_t arity) const {
        if (arity >= kArities) return nullptr;
        const std::size_t t =
            std::min<std::size_t>(static_cast<std::size_t>(std::max(0, table)), tables_ - 1);
        return direct_[(t * symbols_ + s) * kArities + arity];
    }

    // The successor of `d` on the parameters in slots_, appended to `out` (whose stored
    // parameters are `values`) with one resize of each buffer.
    template <class Values>
    void writeSuccessor(const Direct& d, ModuleString& out, Values& values) {
        auto& symbols = out.rawSymbols();
        auto& starts = out.rawParamStart();
        const std::size_t m0 = symbols.size(), v0 = values.size();
        if (starts.empty()) starts.assign(m0 + 1, 0);
        symbols.resize(m0 + d.modules);
        starts.resize(m0 + 1 + d.modules);
        values.resize(v0 + d.params);
        Symbol* sym = symbols.data() + m0;
        std::uint32_t* start = starts.data() + m0 + 1;
        auto* value = values.data() + v0;
        std::size_t at = v0;
        const std::span<const double> vars(slots_.data(), slots_.size());
        for (const auto& m : d.production->successor) {
            *sym++ = m.symbol;
            for (const auto& arg : m.args)
                *value++ = static_cast<typename Values::value_type>(arg.evaluate(vars));
            at += m.args.size();
            *start++ = static_cast<std::uint32_t>(at);
        }
    }
    static void truncate(ModuleString& out, std::size_t modules) {
        ModuleString kept(out.precision());
        for (std::size_t i = 0; i < modules; ++i) kept.push(out.symbol(i), out.params(i));
        out = std::move(kept);
    }

    std::size_t tables_ = 1, symbols_ = 0;
    std::vector<Direct> directs_;  // per production
    std::vector<const Direct*> direct_;
    std::vector<double> slots_;
    const LSystem& ls_;
    int steps_;
    const DerivationOptions& options_;
    RewritingEngine engine_;
    std::vector<bool> fixed_;
    std::vector<ModuleString> levels_;
    std::vector<std::size_t> cursor_, end_;
    std::uint32_t expansions_ = 0;
};

// The string of the first step that has enough modules to share among `threads` threads
// (or of step `steps`), derived module by module as the stream derives it.
int derivePrefix(const LSystem& ls, int steps, unsigned threads, const DerivationOptions& options,
                 ChunkWalker& walker, ModuleString& out) {
    out = ls.axiom;
    out.setPrecision(options.precision);
    const std::size_t target = kPrefixModulesPerThread * threads;
    int level = 0;
    ModuleString next(options.precision);
    while (level < steps && out.size() < target) {
        options.cancel.check();
        next.clear();
        const StepOf step = walker.stepOf(level);
        for (std::size_t i = 0; i < out.size(); ++i) walker.expand(out, i, step, next);
        std::swap(out, next);
        ++level;
    }
    return level;
}

// The chunks' queues of blocks, read in order by the caller.
class OrderedBlocks {
  public:
    OrderedBlocks(std::size_t chunks, std::size_t window, std::size_t ahead)
        : chunks_(chunks), window_(window), ahead_(ahead), queues_(chunks), done_(chunks, false),
          errors_(chunks) {}

    // The next chunk to derive, once it lies within the window; chunks_ when there is none.
    std::size_t take() {
        std::unique_lock lock(mutex_);
        workers_.wait(lock, [&] { return aborted_ || next_ >= chunks_ || next_ < read_ + window_; });
        if (aborted_ || next_ >= chunks_) return chunks_;
        return next_++;
    }
    // Hands over a full block of chunk c; `block` comes back empty (a recycled one).
    void put(std::size_t c, StreamBlock& block) {
        std::unique_lock lock(mutex_);
        // The chunk being read never waits for the others: the caller waits for it.
        workers_.wait(lock, [&] {
            return aborted_ || (c == read_ ? queues_[c].size() < kQueuedBlocks
                                           : queued_ - queues_[read_].size() < ahead_);
        });
        if (aborted_) throw Aborted{};
        queues_[c].push_back(std::move(block));
        ++queued_;
        block = fresh();
        if (c == read_) reader_.notify_one();
    }
    void finish(std::size_t c, std::exception_ptr error) {
        std::lock_guard lock(mutex_);
        done_[c] = true;
        errors_[c] = std::move(error);
        if (c == read_) reader_.notify_one();
    }
    // The next block in order into `block` (whose old contents are recycled); false at the
    // end. Rethrows what a chunk's worker threw, when the caller reaches that chunk.
    bool next(StreamBlock& block) {
        std::unique_lock lock(mutex_);
        while (true) {
            if (read_ == chunks_) return false;
            auto& q = queues_[read_];
            if (!q.empty()) {
                recycle(std::move(block));
                block = std::move(q.front());
                q.pop_front();
                --queued_;
                workers_.notify_all();
                return true;
            }
            if (done_[read_]) {
                if (errors_[read_]) std::rethrow_exception(errors_[read_]);
                ++read_;
                workers_.notify_all();
                continue;
            }
            reader_.wait(lock);
        }
    }
    void abort() {
        std::lock_guard lock(mutex_);
        aborted_ = true;
        workers_.notify_all();
    }

    struct Aborted {};

  private:
    StreamBlock fresh() {
        if (free_.empty()) return {};
        StreamBlock b = std::move(free_.back());
        free_.pop_back();
        return b;
    }
    void recycle(StreamBlock&& b) {
        b.size = 0;
        b.modules.clear();
        b.text.clear();
        if (free_.size() < 4 * window_) free_.push_back(std::move(b));
    }

    std::size_t chunks_, window_, ahead_;
    std::size_t queued_ = 0;  // blocks in all the queues
    std::mutex mutex_;
    std::condition_variable workers_, reader_;
    std::vector<std::deque<StreamBlock>> queues_;
    std::vector<bool> done_;
    std::vector<std::exception_ptr> errors_;
    std::vector<StreamBlock> free_;
    std::size_t next_ = 0, read_ = 0;
    bool aborted_ = false;
};

void refuseUnlessParallel(const LSystem& ls) {
    if (!streamsInParallel(ls))
        throw Error(SourceLocation{ls.file, 0, 0},
                    "this L-system cannot be streamed in parallel: it draws random numbers, or "
                    "cannot be streamed at all");
}

// The successor symbols of every (table, symbol, arity) whose production is known without
// looking at the parameters: the first production of the table for that symbol and arity
// has no condition, no probability and no block. The counting walk counts those without
// evaluating a single argument.
class KnownSuccessors {
  public:
    static constexpr std::size_t kArities = 8;

    explicit KnownSuccessors(const LSystem& ls) : symbols_(ls.symbols.size()) {
        tables_ = std::max<std::size_t>(1, ls.tableNames.size());
        entries_.assign(tables_ * symbols_ * kArities, Entry{});
        for (std::size_t t = 0; t < tables_; ++t)
            for (std::size_t s = 0; s < symbols_; ++s)
                for (std::size_t a = 0; a < kArities; ++a) {
                    Entry& entry = entries_[(t * symbols_ + s) * kArities + a];
                    entry.state = Entry::Identity;
                    for (const Production& p : ls.productions) {
                        if (p.table >= 0 && static_cast<std::size_t>(p.table) != t) continue;
                        if (p.predecessor.size() != 1 || p.predecessor[0].symbol != s) continue;
                        if (p.predecessor[0].formals.size() != a) continue;
                        bool prints = false;
                        for (const auto& m : p.successor)
                            for (const auto& arg : m.args) prints |= arg.prints();
                        if (p.condition || p.probability || p.hasBlocks() || p.hasContext() ||
                            prints) {
                            entry.state = Entry::Unknown;
                        } else {
                            entry.state = Entry::Known;
                            for (const auto& m : p.successor) entry.symbols.push_back(m.symbol);
                        }
                        break;
                    }
                }
    }

    // The successor's symbols, or null when the parameters must decide.
    const std::vector<Symbol>* find(int table, Symbol s, std::size_t arity,
                                    bool& identity) const {
        identity = false;
        if (arity >= kArities) return nullptr;
        const std::size_t t = std::min<std::size_t>(static_cast<std::size_t>(std::max(0, table)),
                                                    tables_ - 1);
        const Entry& entry = entries_[(t * symbols_ + s) * kArities + arity];
        if (entry.state == Entry::Identity) identity = true;
        return entry.state == Entry::Known ? &entry.symbols : nullptr;
    }

  private:
    struct Entry {
        enum State : std::uint8_t { Unknown, Identity, Known } state = Unknown;
        std::vector<Symbol> symbols;
    };
    std::size_t tables_, symbols_;
    std::vector<Entry> entries_;
};

}  // namespace

bool streamsInParallel(const LSystem& ls) {
    return streamingObstacle(ls).empty() && !ls.drawsRandomNumbers();
}

unsigned parallelThreads(unsigned threads) {
    return threads == 0 ? defaultThreadCount() : threads;
}

bool parallelStreamPays(const LSystem& ls, int steps, unsigned threads) {
    if (parallelThreads(threads) < 2 || !ls.isParametric() || !streamsInParallel(ls))
        return false;
    const GrowthPrediction g = predictGrowth(ls, steps);
    return !g.expectedModules.empty() && g.expectedModules.back() >= kParallelStreamModules;
}

void streamDerivationParallel(const LSystem& ls, int steps,
                              const StreamBlockWriter& write,
                              const std::function<void(const StreamBlock&)>& consume,
                              const DerivationOptions& options) {
    refuseUnlessParallel(ls);
    if (steps < 0) steps = ls.derivationLength;
    const unsigned threads = threadCount(options);
    ChunkWalker first(ls, steps, options);
    ModuleString held(options.precision);
    const int level = derivePrefix(ls, steps, threads, options, first, held);
    std::uint64_t emitted = 0, reported = 0;
    auto handOver = [&](const StreamBlock& block) {
        options.cancel.check();
        consume(block);
        emitted += block.size;
        if (emitted - reported >= (std::uint64_t(1) << 20) && options.progress) {
            reported = emitted;
            options.progress(steps, static_cast<std::size_t>(emitted));
        }
    };
    // Modules [b, e) of `s` into the block: as the caller writes them, or copied.
    auto add = [&](const ModuleString& s, std::size_t b, std::size_t e, StreamBlock& block) {
        if (write)
            write(s, b, e, block);
        else
            for (std::size_t i = b; i < e; ++i) copyModule(s, i, block.modules);
        block.size += e - b;
    };
    if (threads == 1) {
        // One thread: the walk hands each block over itself, no queue between.
        StreamBlock block;
        block.modules.setPrecision(options.precision);
        auto hand = [&] {
            handOver(block);
            block.size = 0;
            block.modules.clear();
            block.text.clear();
        };
        first.walk(
            held, 0, held.size(), level,
            [&](const ModuleString& s, std::size_t b, std::size_t e) {
                add(s, b, e, block);
                if (block.size >= kBlockModules) hand();
            },
            [](const ModuleString&, std::size_t, StepOf) { return false; });
        if (block.size) hand();
        return;
    }
    const std::size_t chunks = chunkCountFor(held.size(), std::size_t(threads) * kChunksPerThread);
    OrderedBlocks blocks(chunks, 4 * std::size_t(threads) + 2,
                         kAheadBlocksPerThread * std::size_t(threads));

    auto work = [&](ChunkWalker& walker) {
        StreamBlock block;
        block.modules.setPrecision(options.precision);
        for (std::size_t c; (c = blocks.take()) < chunks;) {
            std::exception_ptr error;
            try {
                auto hand = [&] {
                    blocks.put(c, block);
                    block.modules.setPrecision(options.precision);
                };
                walker.walk(
                    held, chunkBegin(held.size(), chunks, c), chunkBegin(held.size(), chunks, c + 1),
                    level,
                    [&](const ModuleString& s, std::size_t b, std::size_t e) {
                        add(s, b, e, block);
                        if (block.size >= kBlockModules) hand();
                    },
                    [](const ModuleString&, std::size_t, StepOf) { return false; });
                if (block.size) hand();
            } catch (const OrderedBlocks::Aborted&) {
                return;
            } catch (...) {
                error = std::current_exception();
            }
            blocks.finish(c, error);
            if (error) return;
        }
    };
    std::vector<std::thread> workers;
    workers.reserve(threads);
    // The first worker uses the walker that derived the held string; each other its own.
    std::vector<std::unique_ptr<ChunkWalker>> walkers;
    for (unsigned t = 1; t < threads; ++t)
        walkers.push_back(std::make_unique<ChunkWalker>(ls, steps, options));
    struct Join {
        OrderedBlocks& blocks;
        std::vector<std::thread>& workers;
        ~Join() {
            blocks.abort();
            for (auto& w : workers) w.join();
        }
    } join{blocks, workers};
    workers.emplace_back([&] { work(first); });
    for (auto& w : walkers) workers.emplace_back([&, walker = w.get()] { work(*walker); });

    StreamBlock block;
    while (blocks.next(block)) handOver(block);
}

std::vector<std::uint64_t> countStreamedParallel(const LSystem& ls, int steps,
                                                 const DerivationOptions& options) {
    refuseUnlessParallel(ls);
    if (steps < 0) steps = ls.derivationLength;
    const unsigned threads = threadCount(options);
    const std::size_t symbols = ls.symbols.size();
    ChunkWalker first(ls, steps, options);
    ModuleString held(options.precision);
    const int level = derivePrefix(ls, steps, threads, options, first, held);
    const std::size_t chunks = chunkCountFor(held.size(), std::size_t(threads) * kChunksPerThread);
    const KnownSuccessors known(ls);
    std::atomic<std::size_t> nextChunk{0};
    std::atomic<bool> failed{false};
    std::atomic<std::uint64_t> emittedAll{0};
    std::vector<std::vector<std::uint64_t>> counts(threads,
                                                   std::vector<std::uint64_t>(symbols, 0));
    std::vector<std::exception_ptr> errors(threads);

    auto work = [&](unsigned t, ChunkWalker& walker) {
        std::vector<std::uint64_t>& mine = counts[t];
        ModuleString scratch(options.precision);
        try {
            for (std::size_t c; !failed && (c = nextChunk++) < chunks;) {
                std::uint64_t before = 0;
                for (std::uint64_t n : mine) before += n;
                walker.walk(
                    held, chunkBegin(held.size(), chunks, c), chunkBegin(held.size(), chunks, c + 1),
                    level,
                    [&](const ModuleString& s, std::size_t b, std::size_t e) {
                        const Symbol* run = s.symbols().data();
                        for (std::size_t i = b; i < e; ++i) ++mine[run[i]];
                    },
                    [&](const ModuleString& s, std::size_t i, StepOf step) {
                        bool identity = false;
                        const Symbol sym = s.symbol(i);
                        if (const std::vector<Symbol>* succ =
                                known.find(step.table, sym, s.params(i).size(), identity)) {
                            for (Symbol x : *succ) ++mine[x];
                            return true;
                        }
                        if (identity) {
                            ++mine[sym];
                            return true;
                        }
                        scratch.clear();
                        walker.expand(s, i, step, scratch);
                        for (Symbol x : scratch.symbols()) ++mine[x];
                        return true;
                    });
                std::uint64_t after = 0;
                for (std::uint64_t n : mine) after += n;
                const std::uint64_t total = emittedAll += after - before;
                if (t == 0 && options.progress)
                    options.progress(steps, static_cast<std::size_t>(total));
            }
        } catch (...) {
            errors[t] = std::current_exception();
            failed = true;
        }
    };
    std::vector<std::unique_ptr<ChunkWalker>> walkers;
    for (unsigned t = 1; t < threads; ++t)
        walkers.push_back(std::make_unique<ChunkWalker>(ls, steps, options));
    std::vector<std::thread> workers;
    for (unsigned t = 1; t < threads; ++t)
        workers.emplace_back([&, t] { work(t, *walkers[t - 1]); });
    work(0, first);
    for (auto& w : workers) w.join();
    for (auto& e : errors)
        if (e) std::rethrow_exception(e);
    std::vector<std::uint64_t> total(symbols, 0);
    for (const auto& c : counts)
        for (std::size_t s = 0; s < symbols; ++s) total[s] += c[s];
    return total;
}

}  // namespace graftal
