// The fast path for context-sensitive steps whose contexts are single modules. One
// forward pass finds every module's left context and, for the modules whose productions
// look to the right, the right context (a module waits on its axis until the next module
// there, or the end of the branch, settles it); the production comes from a table indexed
// by (predecessor, left context, right context). It chooses exactly what
// RewritingEngine::choose would, stochastic groups included.
#pragma once

#include <cstdint>
#include <vector>

#include "graftal/core/module_string.hpp"
#include "graftal/lang/lsystem.hpp"

namespace graftal {

class ContextRewriter {
  public:
    // Per table, per symbol: the productions whose predecessor is that symbol, in file order.
    using Candidates = std::vector<std::vector<std::vector<std::uint32_t>>>;

    ContextRewriter(const LSystem& ls, const std::vector<Production>& productions,
                    const Candidates& candidates, std::uint64_t seed);

    // False when the productions need the generic path: parameters, conditions,
    // multi-module predecessors or contexts, brackets in a context, random weights, a right
    // context on a module that contexts skip, or more context symbols and successors than
    // the tables hold.
    bool usable() const { return usable_; }

    // Chooses a successor for every module of `cur`, split into `chunks` parallel chunks,
    // and returns the length of the next string. The choice does not depend on `chunks`.
    std::size_t choose(const ModuleString& cur, int stepNumber, int table, std::size_t chunks);
    // The same, with each choice written over the module it is for, as a code that still
    // names the module (its symbol for a copy, past the symbols a production's own code):
    // no byte per module beside the string. Until write() or restore(), `cur` holds codes.
    // Only when codesFit().
    std::size_t chooseInPlace(ModuleString& cur, int stepNumber, int table, std::size_t chunks);
    // Whether chooseInPlace() applies: the codes fit in a byte, and the string's buffer has
    // room for the scan's slots past its end (a byte a chunk) without moving.
    bool fitsInPlace(ModuleString& cur, std::size_t chunks) const;
    // Turns the codes chooseInPlace() wrote back into the string (a step that fails).
    void restore(ModuleString& cur) const;
    // Whether the string chooseInPlace() coded can become the next one, `total` modules, in
    // its own buffer (writeOverItself): no successor is empty, so no module's output ends
    // past its own place once each chunk's codes sit at the end of that chunk's output, and
    // the buffer holds `total` symbols without moving (with the next scan's slots).
    bool growsInPlace(ModuleString& cur, std::size_t total) const;
    // Writes the successors chooseInPlace() chose over the string itself, which becomes the
    // next string; as write(), false when every module was copied unchanged. The previous
    // string and the next never both take memory: on a string that grows a quarter a step
    // (Hogeweg-Hesper at n = 70), a peak of 85 MiB instead of 147 MiB.
    bool writeOverItself(ModuleString& cur, std::size_t total);
    // Writes the successors picked by the last choose() or chooseInPlace() to `out`, which
    // holds as many symbols as it returned. Returns false when every module was copied
    // unchanged.
    bool write(const ModuleString& cur, Symbol* out);
    // choose() in a pass that notes no choice, counting what write() would write: the modules of
    // the next string by symbol into `counts` (one per symbol), and its length returned. The string
    // of the last step of `stats` is counted without a byte per module of the string before it.
    std::size_t chooseAndCount(const ModuleString& cur, int stepNumber, int table,
                               std::size_t chunks, std::vector<std::uint64_t>& counts);
    // Bytes of the per-module scratch buffer in use (for the memory limit).
    std::size_t scratchBytes() const { return choice_.size(); }

  private:
    // Per table and symbol, packed into one word (the scan loads it at once and keeps it
    // in one register): its first cell (bits 0-31), as a left context the row it selects
    // (class * classes, bits 32-47), its kind (a context class < 128, or one of the kinds in
    // the .cpp, bits 48-55), and whether its production depends on the right context (56).
    using SymbolInfo = std::uint64_t;
    static std::uint32_t infoBase(SymbolInfo i) { return static_cast<std::uint32_t>(i); }
    static std::uint32_t infoRow(SymbolInfo i) { return static_cast<std::uint16_t>(i >> 32); }
    static std::uint32_t infoKind(SymbolInfo i) { return static_cast<std::uint8_t>(i >> 48); }
    static bool infoWaits(SymbolInfo i) { return (i >> 56) != 0; }
    // The state of the scan on one axis: the left context of the next module (as a row
    // offset), and the module waiting for its right context (its slot: position + 1, or a
    // slot past n for nobody) with its row of cells. Before a chunk's incoming state is known, left
    // contexts from kUnknown on and waiting modules from kIncoming on stand for it: + 0 is
    // the incoming axis, + k its k-th level below.
    // (The fields are apart, so that the compiler does not pack left and row into one
    // vector register, which puts them on a slow path in the scan loop.)
    struct Level {
        std::uint32_t left = 0;
        std::uint64_t waiting = 0;
        std::uint32_t row = 0;
    };
    struct Deferred {
        std::uint64_t slot;
        std::uint32_t left, right;  // left is unknown
    };
    // One per chunk, each on its own cache lines: threads update their stacks constantly.
    struct alignas(64) Scan {
        Level axis;
        std::vector<Level> stack;
        std::uint32_t basePops = 0;      // levels taken from the incoming stack
        std::vector<Deferred> deferred;  // choices that need the incoming state
        std::vector<std::pair<std::uint32_t, std::uint32_t>> settled;  // (incoming level, right)
        std::size_t cap = 0;       // deferred choices it may note
        bool overflow = false;     // more than that: the step is scanned again, in one chunk
        std::size_t count = 0;     // modules the chunk's choices write
        std::uint64_t nobody = 0;  // the chunk's own "nobody" slot
        // Counting (chooseAndCount): the modules decided, by result (1..255), and the copied
        // ones by symbol (kCopiedTally + symbol).
        std::vector<std::uint64_t> tally;
    };
    static constexpr std::size_t kCopiedTally = 256;
    struct Group {
        double sum = 0;
        std::vector<std::pair<double, std::uint8_t>> entries;  // weight > 0, result
    };

    std::uint8_t resultOf(const std::vector<Production>& productions, std::uint32_t k);
    std::uint8_t cellFor(const std::vector<Production>& productions,
                         const std::vector<std::uint32_t>& cands, const std::vector<int>& classOf,
                         const std::vector<double>& weights, int lc, int rc);
    template <bool Unknown, bool Tally>
    void scan(const Symbol* in, std::size_t b, std::size_t e, Scan& st, const SymbolInfo* info,
              std::uint64_t step);
    static void deferChoice(Scan& st, std::uint64_t slot, std::uint32_t left, std::uint32_t right);
    static void settleLater(Scan& st, std::uint64_t waiting, std::uint32_t row,
                            std::uint32_t right);
    bool scanChunks(std::size_t n, std::size_t chunks, std::uint64_t step);
    bool nonShrinking_ = false;  // every successor has a module at least
    template <bool OverItself>
    bool writeChunk(const std::uint8_t* pick, std::size_t b, std::size_t e, Symbol* o,
                    const Symbol* end) const;
    void writeCodes(const std::uint8_t* codes, std::size_t n,
                    const std::vector<std::size_t>& offsets, std::vector<std::uint32_t>& applied,
                    Symbol* out) const;
    template <bool Tally>
    bool scanChunksAs(std::size_t n, std::size_t chunks, std::uint64_t step);
    std::size_t prepare(const ModuleString& cur, int table, std::size_t chunks);
    void decide(std::uint64_t step, std::uint64_t slot, std::uint32_t row, std::uint32_t right);
    const Level* knownLevel(std::size_t k) const;
    std::uint32_t resolve(std::uint32_t left) const;
    Level resolve(const Level& level) const;
    std::uint32_t pick(std::uint32_t cell, std::uint64_t step, std::uint64_t position) const;

    bool usable_ = false;
    std::uint64_t seed_;
    std::uint32_t classCount_ = 1;
    std::vector<std::vector<SymbolInfo>> info_;  // per table, per symbol
    // Per (left, right) class: a packed cell (see the .cpp).
    std::vector<std::uint32_t> cells_;
    std::vector<std::uint32_t> resultOfProduction_;
    // Result r >= 1 writes resultSymbols_[resultStart_[r - 1] .. resultStart_[r]).
    std::vector<std::uint32_t> resultStart_;
    std::vector<Symbol> resultSymbols_;
    std::vector<std::uint32_t> resultLength_;  // per result; 1 for the copy
    std::vector<Symbol> padded_;               // result r at r * kPadded, when all fit
    std::vector<Group> groups_;

    // Per module the chosen result, in slots 1..n, then the chunks' "nobody" slots.
    std::vector<std::uint8_t, UninitializedAllocator<std::uint8_t>> choice_;
    // Where the scan writes: choice_, or the string itself (slot k is module k - 1), and how
    // a result r is written there: r + shift_ (r > 0), or the module's own symbol masked
    // with keep_ (0 in choice_, 0xFF in the string).
    std::uint8_t* slots_ = nullptr;
    std::uint32_t shift_ = 0, keep_ = 0;
    bool inPlace_ = false;
    // In-place codes: below symbolCount_ a copy of that symbol, from there on result
    // code - symbolCount_ + 1. decode_ gives a code's module back; codeLength_, codeStart_
    // and codeSymbols_ what it writes, codePadded_ the same padded to kPadded when all fit.
    bool codesFit_ = false;
    std::uint32_t symbolCount_ = 0;
    std::vector<Symbol> decode_;
    std::vector<std::uint32_t> codeLength_, codeStart_;
    std::vector<Symbol> codeSymbols_, codePadded_;
    std::uint64_t n_ = 0, nobody_ = 1;  // the length of the last string; a nobody slot
    const Symbol* in_ = nullptr;        // the string of the last choose()
    std::size_t table_ = 0;
    std::vector<Scan> scans_;
    std::vector<std::size_t> bounds_;  // chunk boundaries of the last choose()
    Level known_;                      // the fix-up's state between chunks
    std::vector<Level> knownStack_;
    std::size_t chunks_ = 1;
    bool tally_ = false;  // chooseAndCount() is running: decisions are counted, not noted
};

}  // namespace graftal
