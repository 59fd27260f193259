#include "context_rewriter.hpp"

#include <algorithm>
#include <cstring>

#include "graftal/core/parallel.hpp"
#include "graftal/core/random_stream.hpp"

namespace graftal {

namespace {

// Kinds of symbols besides the context classes 0..126 (class 0: any symbol no context
// names, and "no context at all"; neither matches a context).
constexpr std::uint8_t kIgnoredKind = 0xFD, kOpenKind = 0xFE, kCloseKind = 0xFF;
// Scan values from kUnknown on stand for the unknown state before a chunk (see Level).
constexpr std::uint32_t kUnknown = std::uint32_t(1) << 20;
constexpr std::uint64_t kIncoming = std::uint64_t(1) << 40;
// A waiting module's row while its left context is unknown: kDeferRow | that context; and
// kDeferRow alone for an incoming level's waiting module.
constexpr std::uint32_t kDeferRow = std::uint32_t(1) << 31;
// In a packed cell: the result in the low byte (with kGroup: a stochastic group), and the
// number of modules it writes above it.
constexpr std::uint32_t kGroup = 0x80;
constexpr std::uint32_t kMaxClasses = 127, kMaxResults = 127, kMaxGroups = 128;
constexpr std::size_t kMaxCells = std::size_t(1) << 22;
// Deferred choices a chunk notes, at least; past that the step is scanned in one chunk.
constexpr std::size_t kMinDeferred = 4096;
// Distance between the chunks' "nobody" slots: a cache line.
constexpr std::size_t kNobodyStride = 64;
// Successors up to this long are also kept padded to it, for fixed-size copies.
constexpr std::size_t kPadded = 8;

}  // namespace

ContextRewriter::ContextRewriter(const LSystem& ls, const std::vector<Production>& productions,
                                 const Candidates& candidates, std::uint64_t seed)
    : seed_(seed) {
    std::vector<double> weights(productions.size(), 0.0);
    for (std::size_t k = 0; k < productions.size(); ++k) {
        const Production& p = productions[k];
        if (p.predecessor.size() != 1 || p.left.size() > 1 || p.right.size() > 1 || p.condition ||
            p.isParametric())
            return;
        for (const auto* part : {&p.left, &p.right})
            for (const auto& m : *part)
                if (m.symbol == '[' || m.symbol == ']') return;
        if (p.probability) {
            // A weight without parameters or ran() is the same number at every module.
            if (p.probability->usesRandom()) return;
            double slot = 0;
            try {
                weights[k] = p.probability->evaluate({&slot, 1});
            } catch (const Error&) {
                return;  // the generic path reports it at the module that needs it
            }
        }
    }
    std::size_t symbols = ls.symbols.size();
    std::vector<int> classOf(symbols, -1);
    for (const auto& p : productions)
        for (const auto* part : {&p.left, &p.right})
            for (const auto& m : *part)
                if (!ls.ignored[m.symbol] && classOf[m.symbol] < 0)
                    classOf[m.symbol] = static_cast<int>(classCount_++);
    if (classCount_ > kMaxClasses) return;
    const std::size_t classes = classCount_;

    // Cells hold results while the tables are built, and are packed at the end. The first
    // row is "nothing" (writes no module: what the "nobody" slot settles to); the next
    // block copies every module.
    resultOfProduction_.assign(productions.size(), 0);
    resultStart_.assign(1, 0);
    resultLength_.assign(1, 1);
    std::vector<std::uint32_t> cells(classes + classes * classes, 0);
    const auto copyBlock = static_cast<std::uint32_t>(classes);
    info_.assign(candidates.size(), std::vector<SymbolInfo>(symbols));
    for (std::size_t t = 0; t < candidates.size(); ++t) {
        for (std::size_t s = 0; s < symbols; ++s) {
            std::uint64_t kind = 0, row = 0, base = copyBlock, waits = 0;
            if (s == '[') {
                kind = kOpenKind;
            } else if (s == ']') {
                kind = kCloseKind;
            } else if (ls.ignored[s]) {
                kind = kIgnoredKind;
            } else if (classOf[s] > 0) {
                kind = static_cast<std::uint64_t>(classOf[s]);
                row = kind * classes;
            }
            if (s < candidates[t].size() && !candidates[t][s].empty()) {
                if (cells.size() + classes * classes > kMaxCells) return;
                base = cells.size();
                for (std::size_t lc = 0; lc < classes; ++lc) {
                    for (std::size_t rc = 0; rc < classes; ++rc) {
                        cells.push_back(cellFor(productions, candidates[t][s], classOf, weights,
                                                static_cast<int>(lc), static_cast<int>(rc)));
                        waits |= cells.back() != cells[base + lc * classes];
                    }
                }
                // Only a module that settles the one before it can wait for its own right
                // context: the scan keeps one waiting module per axis.
                if (waits && kind >= kIgnoredKind) return;
            }
            info_[t][s] = base | row << 32 | kind << 48 | waits << 56;
        }
    }
    if (resultLength_.size() > kMaxResults + 1 || groups_.size() > kMaxGroups) return;
    cells_.resize(cells.size());
    for (std::size_t c = 0; c < cells.size(); ++c)
        cells_[c] = cells[c] & kGroup ? cells[c] : cells[c] | resultLength_[cells[c]] << 8;
    std::fill(cells_.begin(), cells_.begin() + copyBlock, 0u);
    if (*std::max_element(resultLength_.begin(), resultLength_.end()) <= kPadded) {
        padded_.assign(resultLength_.size() * kPadded, 0);
        for (std::size_t r = 1; r < resultLength_.size(); ++r)
            std::copy(resultSymbols_.begin() + resultStart_[r - 1],
                      resultSymbols_.begin() + resultStart_[r], padded_.begin() + r * kPadded);
    }
    // The in-place codes: every symbol is its own copy, and each result takes a byte no
    // symbol uses; a result is one production's, so its code also names the module it
    // rewrote.
    symbolCount_ = static_cast<std::uint32_t>(symbols);
    if (symbolCount_ + resultLength_.size() - 1 <= 256) {
        codesFit_ = true;
        decode_.resize(256);
        codeLength_.assign(256, 1);
        codeStart_.assign(257, 0);
        std::vector<Symbol> predecessorOf(resultLength_.size(), 0);
        for (std::size_t k = 0; k < productions.size(); ++k)
            if (resultOfProduction_[k] != 0)
                predecessorOf[resultOfProduction_[k]] = productions[k].predecessor[0].symbol;
        for (std::uint32_t code = 0; code < 256; ++code) {
            const std::uint32_t r = code >= symbolCount_ ? code - symbolCount_ + 1 : 0;
            if (r == 0 || r >= resultLength_.size()) {
                decode_[code] = static_cast<Symbol>(code);
                codeSymbols_.push_back(static_cast<Symbol>(code));
            } else {
                decode_[code] = predecessorOf[r];
                codeLength_[code] = resultLength_[r];
                codeSymbols_.insert(codeSymbols_.end(),
                                    resultSymbols_.begin() + resultStart_[r - 1],
                                    resultSymbols_.begin() + resultStart_[r]);
            }
            codeStart_[code + 1] = static_cast<std::uint32_t>(codeSymbols_.size());
        }
        nonShrinking_ = *std::min_element(resultLength_.begin(), resultLength_.end()) >= 1;
        if (!padded_.empty()) {
            codePadded_.assign(256 * kPadded, 0);
            for (std::uint32_t code = 0; code < 256; ++code)
                std::copy(codeSymbols_.begin() + codeStart_[code],
                          codeSymbols_.begin() + codeStart_[code + 1],
                          codePadded_.begin() + code * kPadded);
        }
    }
    usable_ = true;
}

std::uint8_t ContextRewriter::resultOf(const std::vector<Production>& productions,
                                       std::uint32_t k) {
    if (resultOfProduction_[k] == 0) {
        resultOfProduction_[k] = static_cast<std::uint32_t>(resultLength_.size());
        for (const auto& m : productions[k].successor) resultSymbols_.push_back(m.symbol);
        resultStart_.push_back(static_cast<std::uint32_t>(resultSymbols_.size()));
        resultLength_.push_back(static_cast<std::uint32_t>(productions[k].successor.size()));
    }
    // Past kMaxResults the rewriter is not used, so the truncation does no harm.
    return static_cast<std::uint8_t>(std::min(resultOfProduction_[k], kMaxResults));
}

// What RewritingEngine::choose picks for a module whose left and right contexts have
// the classes lc and rc: the first applicable production in file order, or when that one
// has a probability, the group of applicable productions with probabilities.
std::uint8_t ContextRewriter::cellFor(const std::vector<Production>& productions,
                                      const std::vector<std::uint32_t>& cands,
                                      const std::vector<int>& classOf,
                                      const std::vector<double>& weights, int lc, int rc) {
    auto fits = [&](const std::vector<ModulePattern>& context, int cls) {
        return context.empty() ||
               (classOf[context[0].symbol] > 0 && classOf[context[0].symbol] == cls);
    };
    auto applies = [&](const Production& p) { return fits(p.left, lc) && fits(p.right, rc); };
    for (std::size_t k = 0; k < cands.size(); ++k) {
        const Production& p = productions[cands[k]];
        if (!applies(p)) continue;
        if (!p.probability) return resultOf(productions, cands[k]);
        Group g;
        for (std::size_t r = k; r < cands.size(); ++r) {
            const Production& q = productions[cands[r]];
            if (!q.probability || !applies(q)) continue;
            double w = weights[cands[r]];
            if (w > 0) {
                g.entries.push_back({w, resultOf(productions, cands[r])});
                g.sum += w;
            }
        }
        // cpfg: when every applicable weight is 0, the first applicable production applies.
        if (g.sum <= 0) return resultOf(productions, cands[k]);
        std::size_t id = 0;
        while (id < groups_.size() &&
               (groups_[id].sum != g.sum || groups_[id].entries != g.entries))
            ++id;
        if (id == groups_.size()) groups_.push_back(std::move(g));
        return static_cast<std::uint8_t>(kGroup | std::min<std::size_t>(id, kMaxGroups - 1));
    }
    return 0;
}

// The draw RewritingEngine::choose makes for a stochastic group, with the same arithmetic;
// returns the packed cell of the result.
std::uint32_t ContextRewriter::pick(std::uint32_t cell, std::uint64_t step,
                                    std::uint64_t position) const {
    if (!(cell & kGroup)) return cell;
    const Group& g = groups_[cell & (kGroup - 1)];
    double u = uniformAt(seed_, step, position, 1u << 20) * g.sum;
    std::uint8_t result = g.entries.back().second;
    for (const auto& [w, r] : g.entries) {
        if (u < w) {
            result = r;
            break;
        }
        u -= w;
    }
    return result | resultLength_[result] << 8;
}

// The scan keeps, per axis, the left context of the next module and the module waiting
// for its right context (cpfg's contexts, as matchLeft and matchRight find them): a module
// a context sees settles the waiting one and becomes the left context; a '[' enters a new
// axis whose left context is still the parent's; a ']' ends its axis (nothing to the right)
// and returns to the parent as it was before the branch, so the branch is skipped whole
// both ways. An unmatched ']' leaves no context, and modules still waiting at the end of
// the string have none to their right.
//
// Every module is decided as if nothing were to its right, and a waiting module again
// when it is settled (it is counted then). Modules live in slots 1..n of choice_; past
// them each chunk has a slot of its own for "nobody", whose row 0 writes nothing (one
// shared slot would bounce between the cores' caches). The state is kept in scalars and
// the rare cases out of line, so that the loop keeps everything in registers.
//
// Counting (Tally), a module is counted where its choice is final instead: a waiting one
// when it is settled, one whose left context is not known yet in decide().
template <bool Unknown, bool Tally>
void ContextRewriter::scan(const Symbol* in, std::size_t b, std::size_t e, Scan& st,
                           const SymbolInfo* info, std::uint64_t step) {
    const std::uint32_t* cells = cells_.data();
    std::uint8_t* slot = slots_;
    const std::uint32_t shift = shift_, keep = keep_;
    const Symbol* decode = decode_.empty() ? nullptr : decode_.data();
    std::uint64_t* tally = Tally ? st.tally.data() : nullptr;
    const std::uint64_t last = n_;
    // Counts the final choice `cell` of the module in slot k.
    auto note = [&](std::uint64_t k, std::uint32_t cell) {
        const std::uint32_t r = cell & 0xFFu;
        ++tally[r ? r : kCopiedTally + in[k - 1]];
    };
    const std::uint64_t nobody = st.nobody;
    std::uint32_t left = st.axis.left, row = st.axis.row;
    std::uint64_t waiting = st.axis.waiting;
    std::vector<Level>& stack = st.stack;
    std::size_t count = 0;
    st.cap = std::max<std::size_t>(kMinDeferred, (e - b) / 16);
    // Settles the waiting module with the right context `right`.
    auto settle = [&](std::uint32_t right) {
        if (Unknown && row >= kDeferRow) [[unlikely]] {
            settleLater(st, waiting, row, right);
            return;
        }
        std::uint32_t cell = cells[row + right];
        if (cell & kGroup) [[unlikely]]
            cell = pick(cell, step, waiting - 1);
        if constexpr (Tally) {
            if (waiting <= last) note(waiting, cell);
        } else {
            // A copy written in place is the module's own symbol, which the provisional code
            // still names.
            const std::uint32_t r = cell & 0xFFu;
            slot[waiting] =
                static_cast<std::uint8_t>(r ? r + shift : (keep ? decode[slot[waiting]] : 0u));
        }
        count += cell >> 8;
    };
    for (std::size_t i = b; i < e; ++i) {
        const SymbolInfo si = info[in[i]];
        const std::uint32_t kind = infoKind(si);
        const bool waits = infoWaits(si);
        std::uint32_t own = infoBase(si) + left, cell = 0;
        bool deferred = false;
        if (Unknown && left >= kUnknown) [[unlikely]] {
            if (!waits) deferChoice(st, i + 1, left, 0);
            own = left | kDeferRow;
            deferred = true;
        } else {
            cell = cells[own];
            if (cell & kGroup) [[unlikely]]
                cell = pick(cell, step, i);
        }
        if constexpr (!Tally) {
            const std::uint32_t r = cell & 0xFFu;
            slot[i + 1] = static_cast<std::uint8_t>(r ? r + shift : in[i] & keep);
        }
        if (kind < kIgnoredKind) {
            settle(kind);
            if (waits) {
                row = own;
                waiting = i + 1;
            } else {
                row = 0;
                waiting = nobody;
                count += cell >> 8;
                if (Tally && !deferred) note(i + 1, cell);
            }
            left = infoRow(si);
            continue;
        }
        count += cell >> 8;
        if (Tally && !deferred) note(i + 1, cell);
        if (kind == kIgnoredKind) continue;
        if (kind == kOpenKind) {
            stack.push_back(Level{left, waiting, row});
            row = 0;
            waiting = nobody;
            continue;
        }
        settle(0);  // the end of a branch: nothing to the right
        if (!stack.empty()) {
            left = stack.back().left;
            row = stack.back().row;
            waiting = stack.back().waiting;
            stack.pop_back();
        } else if (Unknown) {
            ++st.basePops;
            left = kUnknown + st.basePops;
            row = kDeferRow;
            waiting = kIncoming + st.basePops;
        } else {
            left = row = 0;
            waiting = nobody;
        }
    }
    st.axis = {left, waiting, row};
    st.count += count;
}

// A choice whose left context is not known yet.
void ContextRewriter::deferChoice(Scan& st, std::uint64_t slot, std::uint32_t left,
                                  std::uint32_t right) {
    if (st.deferred.size() < st.cap)
        st.deferred.push_back({slot, left, right});
    else
        st.overflow = true;
}

// A waiting module settled with the right context `right` while its own left context, or
// (an incoming level's module) the module itself, is not known yet.
void ContextRewriter::settleLater(Scan& st, std::uint64_t waiting, std::uint32_t row,
                                  std::uint32_t right) {
    if (waiting >= kIncoming)
        st.settled.push_back({static_cast<std::uint32_t>(waiting - kIncoming), right});
    else
        deferChoice(st, waiting, row & ~kDeferRow, right);
}

// A left context of a chunk's scan, given the known state before the chunk.
std::uint32_t ContextRewriter::resolve(std::uint32_t left) const {
    if (left < kUnknown) return left;
    const Level* level = knownLevel(left - kUnknown);
    return level ? level->left : 0;
}

// Incoming level k of the known state (0: the axis itself), or nullptr past the bottom.
const ContextRewriter::Level* ContextRewriter::knownLevel(std::size_t k) const {
    if (k == 0) return &known_;
    return k <= knownStack_.size() ? &knownStack_[knownStack_.size() - k] : nullptr;
}

ContextRewriter::Level ContextRewriter::resolve(const Level& level) const {
    Level out = level;
    out.left = resolve(level.left);
    if (level.waiting >= kIncoming) {
        const Level* from = knownLevel(level.waiting - kIncoming);
        out.row = from ? from->row : 0;
        out.waiting = from ? from->waiting : nobody_;
    } else if (level.row & kDeferRow) {
        out.row = infoBase(info_[table_][in_[level.waiting - 1]]) + resolve(level.row & ~kDeferRow);
    }
    return out;
}

// Decides the module in `slot` outside the scan loop, and counts it for its chunk.
void ContextRewriter::decide(std::uint64_t step, std::uint64_t slot, std::uint32_t row,
                             std::uint32_t right) {
    if (slot > n_) return;  // nobody
    std::uint64_t position = slot - 1;
    std::uint32_t cell = pick(cells_[row + right], step, position);
    std::size_t c = static_cast<std::size_t>(
        std::upper_bound(bounds_.begin(), bounds_.end(), position) - bounds_.begin() - 1);
    scans_[c].count += cell >> 8;
    const std::uint32_t r = cell & 0xFFu;
    if (tally_)
        ++scans_[c].tally[r ? r : kCopiedTally + in_[position]];
    else
        slots_[slot] =
            static_cast<std::uint8_t>(r ? r + shift_ : (keep_ ? decode_[slots_[slot]] : 0u));
}

// Scans the chunks in parallel, then settles in chunk order what each left open. False
// when a chunk had too many deferred choices to note.
bool ContextRewriter::scanChunks(std::size_t n, std::size_t chunks, std::uint64_t step) {
    return tally_ ? scanChunksAs<true>(n, chunks, step) : scanChunksAs<false>(n, chunks, step);
}

template <bool Tally>
bool ContextRewriter::scanChunksAs(std::size_t n, std::size_t chunks, std::uint64_t step) {
    const Symbol* in = in_;
    const SymbolInfo* info = info_[table_].data();
    chunks_ = chunks;
    scans_.resize(chunks);
    bounds_.resize(chunks + 1);
    for (std::size_t c = 0; c <= chunks; ++c) bounds_[c] = chunkBegin(n, chunks, c);
    forEachChunk(n, chunks, [&](std::size_t c, std::size_t b, std::size_t e) {
        Scan& st = scans_[c];
        st.stack.clear();
        st.basePops = 0;
        st.deferred.clear();
        st.settled.clear();
        st.overflow = false;
        st.count = 0;
        st.nobody = n + 1 + kNobodyStride * c;
        if (Tally) st.tally.assign(kCopiedTally + kMaxSymbols, 0);
        if (c == 0) {
            st.axis = {0, st.nobody, 0};
            scan<false, Tally>(in, b, e, st, info, step);
        } else {
            st.axis = {kUnknown, kIncoming, kDeferRow};
            scan<true, Tally>(in, b, e, st, info, step);
        }
    });
    for (const auto& st : scans_)
        if (st.overflow) return false;
    known_ = scans_[0].axis;
    knownStack_ = scans_[0].stack;
    std::vector<Level> pushed;
    for (std::size_t c = 1; c < chunks; ++c) {
        const Scan& st = scans_[c];
        // (A deferred module was noted as its own symbol: in place, the string still has it.)
        for (const Deferred& d : st.deferred)
            decide(step, d.slot, infoBase(info[in[d.slot - 1]]) + resolve(d.left), d.right);
        for (const auto& [k, right] : st.settled)
            if (const Level* level = knownLevel(k)) decide(step, level->waiting, level->row, right);
        Level axis = resolve(st.axis);
        pushed.clear();
        for (const Level& level : st.stack) pushed.push_back(resolve(level));
        knownStack_.resize(knownStack_.size() -
                           std::min<std::size_t>(st.basePops, knownStack_.size()));
        knownStack_.insert(knownStack_.end(), pushed.begin(), pushed.end());
        known_ = axis;
    }
    // Whatever still waits reached the end of the string or of an unclosed branch.
    while (true) {
        decide(step, known_.waiting, known_.row, 0);
        if (knownStack_.empty()) break;
        known_ = knownStack_.back();
        knownStack_.pop_back();
    }
    return true;
}

std::size_t ContextRewriter::prepare(const ModuleString& cur, int table, std::size_t chunks) {
    const std::size_t n = cur.size();
    in_ = cur.symbols().data();
    table_ = static_cast<std::size_t>(table);
    n_ = n;
    nobody_ = n + 1;
    return chunkCountFor(n, chunks);
}

std::size_t ContextRewriter::choose(const ModuleString& cur, int stepNumber, int table,
                                    std::size_t chunks) {
    const std::size_t n = cur.size();
    chunks = prepare(cur, table, chunks);
    // Room for the longer strings of later steps, as for the strings themselves.
    if (choice_.capacity() < n + 1 + kNobodyStride * chunks) {
        choice_.clear();
        choice_.reserve(4 * (n + 1 + kNobodyStride * chunks));
    }
    choice_.resize(n + 1 + kNobodyStride * chunks);
    tally_ = false;
    inPlace_ = false;
    slots_ = choice_.data();
    shift_ = 0;
    keep_ = 0;
    const auto step = static_cast<std::uint64_t>(stepNumber);
    if (!scanChunks(n, chunks, step)) scanChunks(n, 1, step);
    std::size_t total = 0;
    for (const auto& s : scans_) total += s.count;
    return total;
}

std::size_t ContextRewriter::chooseInPlace(ModuleString& cur, int stepNumber, int table,
                                           std::size_t chunks) {
    const std::size_t n = cur.size();
    chunks = prepare(cur, table, chunks);
    auto& symbols = cur.rawSymbols();
    // The chunks' "nobody" slots past the string, for the time of the scan (uninitialised
    // bytes, within the room the string's buffer usually has).
    symbols.resize(n + 1 + kNobodyStride * chunks);
    in_ = symbols.data();
    tally_ = false;
    inPlace_ = true;
    // Slot k is module k - 1 (the scan's slots count from 1).
    slots_ = symbols.data() - 1;
    shift_ = symbolCount_ - 1;
    keep_ = 0xFFu;
    const auto step = static_cast<std::uint64_t>(stepNumber);
    if (!scanChunks(n, chunks, step)) {
        // Every module holds a code now: the string again, then one chunk.
        symbols.resize(n);
        restore(cur);
        symbols.resize(n + 1 + kNobodyStride);
        in_ = symbols.data();
        slots_ = symbols.data() - 1;
        scanChunks(n, 1, step);
    }
    symbols.resize(n);
    std::size_t total = 0;
    for (const auto& s : scans_) total += s.count;
    return total;
}

bool ContextRewriter::fitsInPlace(ModuleString& cur, std::size_t chunks) const {
    const std::size_t room = cur.size() + 1 + kNobodyStride * std::max<std::size_t>(chunks, 1);
    return codesFit_ && room <= cur.rawSymbols().capacity();
}

void ContextRewriter::restore(ModuleString& cur) const {
    Symbol* s = cur.rawSymbols().data();
    const Symbol* decode = decode_.data();
    forEachChunk(cur.size(), chunkCountFor(cur.size(), chunks_),
                 [&](std::size_t, std::size_t b, std::size_t e) {
                     for (std::size_t i = b; i < e; ++i) s[i] = decode[s[i]];
                 });
}

std::size_t ContextRewriter::chooseAndCount(const ModuleString& cur, int stepNumber, int table,
                                            std::size_t chunks,
                                            std::vector<std::uint64_t>& counts) {
    const std::size_t n = cur.size();
    chunks = prepare(cur, table, chunks);
    tally_ = true;
    struct Reset {
        bool& tally;
        ~Reset() { tally = false; }
    } reset{tally_};
    const auto step = static_cast<std::uint64_t>(stepNumber);
    if (!scanChunks(n, chunks, step)) scanChunks(n, 1, step);
    std::size_t total = 0;
    for (const Scan& st : scans_) {
        total += st.count;
        for (std::size_t s = 0; s < counts.size(); ++s) counts[s] += st.tally[kCopiedTally + s];
        for (std::size_t r = 1; r < resultLength_.size(); ++r) {
            if (st.tally[r] == 0) continue;
            for (std::uint32_t k = resultStart_[r - 1]; k < resultStart_[r]; ++k)
                counts[resultSymbols_[k]] += st.tally[r];
        }
    }
    return total;
}

// The successors the codes of modules b..e-1 name (pick[i]: module i's code), written
// from `o` on up to `end`; true when any is a production's. Every code, a copy included, is
// a row of the code tables, so the loop does not look at the string's own symbols. Copies
// of kPadded symbols stop where they could pass `end` and, over the codes themselves
// (OverItself), where they could reach the next module's code; successors are copied
// exactly from there on.
template <bool OverItself>
bool ContextRewriter::writeChunk(const std::uint8_t* pick, std::size_t b, std::size_t e, Symbol* o,
                                 const Symbol* end) const {
    const std::uint32_t* length = codeLength_.data();
    const std::uint32_t* start = codeStart_.data();
    const Symbol* successors = codeSymbols_.data();
    const Symbol* padded = codePadded_.empty() ? nullptr : codePadded_.data();
    const std::uint32_t first = symbolCount_;
    std::uint32_t any = 0;
    std::size_t i = b;
    if (padded) {
        for (; i < e && o + kPadded <= end && (!OverItself || o + kPadded <= pick + i + 1); ++i) {
            const std::uint32_t code = pick[i];
            std::memcpy(o, padded + code * kPadded, kPadded * sizeof(Symbol));
            o += length[code];
            any |= code >= first;
        }
    }
    for (; i < e; ++i) {
        const std::uint32_t code = pick[i];
        any |= code >= first;
        for (std::uint32_t k = start[code]; k < start[code + 1]; ++k) *o++ = successors[k];
    }
    return any != 0;
}

void ContextRewriter::writeCodes(const std::uint8_t* codes, std::size_t n,
                                 const std::vector<std::size_t>& offsets,
                                 std::vector<std::uint32_t>& applied, Symbol* out) const {
    forEachChunk(n, chunks_, [&](std::size_t c, std::size_t b, std::size_t e) {
        Symbol* o = out + offsets[c];
        applied[c] = writeChunk<false>(codes, b, e, o, o + scans_[c].count);
    });
}

bool ContextRewriter::growsInPlace(ModuleString& cur, std::size_t total) const {
    // With room left for the next step's scan slots (fitsInPlace), else that step would
    // take the path with a byte a module beside the string.
    return inPlace_ && nonShrinking_ && total >= cur.size() &&
           total + 1 + kNobodyStride * std::max<std::size_t>(chunks_, 1) <=
               cur.rawSymbols().capacity();
}

// Chunk c's codes are first moved to the end of the chunk's output, the chunks from the
// last to the first (each moves right, onto room the chunks after it have left). Then each
// chunk writes its successors from the start of its output on: the output of the modules
// up to i ends where the codes of the modules after i begin at the latest, since each of
// those writes one module or more. A copy of kPadded symbols is made only while it ends
// before the next module's code; past that point (the end of the chunk, where the codes
// catch up with the output) successors are copied exactly.
bool ContextRewriter::writeOverItself(ModuleString& cur, std::size_t total) {
    const std::size_t n = cur.size(), chunks = chunks_;
    std::vector<std::size_t> offsets(chunks + 1, 0), bases(chunks, 0);
    for (std::size_t c = 0; c < chunks; ++c) offsets[c + 1] = offsets[c] + scans_[c].count;
    auto& symbols = cur.rawSymbols();
    symbols.resize(total);  // within its capacity: nothing moves, nothing is initialised
    Symbol* data = symbols.data();
    for (std::size_t c = chunks; c-- > 0;) {
        const std::size_t b = bounds_[c], e = bounds_[c + 1];
        bases[c] = offsets[c + 1] - (e - b);
        std::memmove(data + bases[c], data + b, e - b);
    }
    std::vector<std::uint32_t> applied(chunks, 0);
    forEachChunk(n, chunks, [&](std::size_t c, std::size_t b, std::size_t e) {
        // pick[i]: module i's code, now at the end of the chunk's output.
        applied[c] =
            writeChunk<true>(data + bases[c] - b, b, e, data + offsets[c], data + offsets[c + 1]);
    });
    inPlace_ = false;  // the string holds no codes any more
    return std::any_of(applied.begin(), applied.end(), [](std::uint32_t a) { return a != 0; });
}

bool ContextRewriter::write(const ModuleString& cur, Symbol* out) {
    std::size_t n = cur.size(), chunks = chunks_;
    std::vector<std::size_t> offsets(chunks, 0);
    std::vector<std::uint32_t> applied(chunks, 0);
    for (std::size_t c = 1; c < chunks; ++c) offsets[c] = offsets[c - 1] + scans_[c - 1].count;
    if (inPlace_) {
        writeCodes(cur.symbols().data(), n, offsets, applied, out);
        return std::any_of(applied.begin(), applied.end(), [](std::uint32_t a) { return a != 0; });
    }
    const Symbol* in = cur.symbols().data();
    const std::uint8_t* choice = choice_.data() + 1;
    const std::uint32_t* start = resultStart_.data();
    const std::uint32_t* length = resultLength_.data();
    const Symbol* successors = resultSymbols_.data();
    const Symbol* padded = padded_.empty() ? nullptr : padded_.data();
    forEachChunk(n, chunks, [&](std::size_t c, std::size_t b, std::size_t e) {
        // Locals, not captures: the stores below could alias anything the closure holds.
        const Symbol* from = in;
        const std::uint8_t* pick = choice;
        const std::uint32_t* count = length;
        const Symbol* fixed = padded;
        Symbol* o = out + offsets[c];
        Symbol* end = o + scans_[c].count;
        std::uint32_t any = 0;
        std::size_t i = b;
        if (fixed) {
            // Every module stores kPadded symbols (of its successor, or of the string from
            // itself on for a copy) and advances by the successor's length; the loop stops
            // where that could read past the string or write past the chunk.
            std::size_t stop = std::min(e, n >= kPadded ? n - kPadded + 1 : 0);
            for (; i < stop && o + kPadded <= end; ++i) {
                std::uint32_t r = pick[i];
                std::memcpy(o, r ? fixed + r * kPadded : from + i, kPadded * sizeof(Symbol));
                o += count[r];
                any |= r;
            }
        }
        for (; i < e; ++i) {
            std::uint8_t r = pick[i];
            any |= r;
            if (r == 0) {
                *o++ = from[i];
                continue;
            }
            const Symbol* s = successors + start[r - 1];
            const Symbol* last = successors + start[r];
            while (s != last) *o++ = *s++;
        }
        applied[c] = any;
    });
    return std::any_of(applied.begin(), applied.end(), [](std::uint32_t a) { return a != 0; });
}

}  // namespace graftal
