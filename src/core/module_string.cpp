#include "graftal/core/module_string.hpp"

#include "graftal/core/diagnostics.hpp"
#include "graftal/core/number_chars.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <new>
#include <sstream>

#include <sys/mman.h>

#include "graftal/core/parallel.hpp"

namespace graftal {

namespace {
constexpr std::size_t kLargeBlock = std::size_t(4) << 20;
constexpr std::size_t kHugePage = std::size_t(2) << 20;
std::size_t roundToHugePages(std::size_t b) {
    return (b + kHugePage - 1) / kHugePage * kHugePage;
}
}  // namespace

// WebAssembly has no pages to map: emscripten's mmap is malloc followed by a memset of the
// whole block, the very cost the buffers' uninitialised resize avoids. There a large block
// is allocated as a small one (fresh memory of a WebAssembly module is zero already).
#ifdef __EMSCRIPTEN__
constexpr bool kMapsLargeBlocks = false;
#else
constexpr bool kMapsLargeBlocks = true;
#endif

void* allocateLarge(std::size_t bytes) {
    if (bytes < kLargeBlock || !kMapsLargeBlocks) {
        void* p = ::operator new(bytes == 0 ? 1 : bytes);
        return p;
    }
    std::size_t size = roundToHugePages(bytes);
    void* p = ::mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
    ::madvise(p, size, MADV_HUGEPAGE);
#endif
    return p;
}

void deallocateLarge(void* p, std::size_t bytes) noexcept {
    if (!p) return;
    if (bytes < kLargeBlock || !kMapsLargeBlocks) {
        ::operator delete(p);
        return;
    }
    ::munmap(p, roundToHugePages(bytes));
}

SymbolTable::SymbolTable() {
    names_.resize(kFirstNamedSymbol);
    for (int c = 0; c < static_cast<int>(kFirstNamedSymbol); ++c) {
        names_[c] = std::string(1, static_cast<char>(c));
    }
    // Query and communication modules of open L-systems exist in every L-system.
    for (const char* q : {"?E", "?P", "?H", "?L", "?U"}) declare(q);
}

Symbol SymbolTable::declare(std::string_view name, Matching matching) {
    if (name.size() == 1 && static_cast<unsigned char>(name[0]) < kFirstNamedSymbol)
        return static_cast<Symbol>(name[0]);
    auto it = ids_.find(std::string(name));
    Symbol id;
    if (it != ids_.end()) {
        id = it->second;
        if (std::find(byLength_.begin(), byLength_.end(), id) != byLength_.end()) return id;
    } else {
        if (names_.size() >= kMaxSymbols)
            throw Error(SourceLocation{}, "too many module names: at most " +
                                              std::to_string(kMaxSymbols - kFirstDeclaredSymbol) +
                                              " multi-letter names per L-system");
        id = static_cast<Symbol>(names_.size());
        names_.emplace_back(name);
        ids_.emplace(std::string(name), id);
    }
    if (matching == Matching::AfterTildeOnly) return id;
    byLength_.push_back(id);
    std::stable_sort(byLength_.begin(), byLength_.end(),
                     [this](Symbol a, Symbol b) { return names_[a].size() > names_[b].size(); });
    return id;
}

int SymbolTable::find(std::string_view name) const {
    if (name.size() == 1 && static_cast<unsigned char>(name[0]) < kFirstNamedSymbol)
        return static_cast<unsigned char>(name[0]);
    auto it = ids_.find(std::string(name));
    return it == ids_.end() ? -1 : it->second;
}

void ModuleString::clear() {
    symbols_.clear();
    paramStart_.clear();
    params_.clear();
    floats_.clear();
}

void ModuleString::reserve(std::size_t modules, std::size_t params) {
    symbols_.reserve(modules);
    if (params) {
        paramStart_.reserve(modules + 1);
        if (precision_ == Precision::Single)
            floats_.reserve(params);
        else
            params_.reserve(params);
    }
}

void ModuleString::setPrecision(Precision p) {
    if (p == precision_) return;
    if (p == Precision::Single) {
        floats_.assign(params_.begin(), params_.end());
        ParamBuffer().swap(params_);
    } else {
        params_.assign(floats_.begin(), floats_.end());
        FloatBuffer().swap(floats_);
    }
    precision_ = p;
}

bool operator==(const ModuleString& a, const ModuleString& b) {
    if (a.symbols_ != b.symbols_ || a.paramStart_ != b.paramStart_) return false;
    if (a.precision_ == b.precision_)
        return a.precision_ == Precision::Single ? a.floats_ == b.floats_ : a.params_ == b.params_;
    const std::size_t n = a.paramCount();
    if (n != b.paramCount()) return false;
    for (std::size_t k = 0; k < n; ++k) {
        double x = a.precision_ == Precision::Single ? a.floats_[k] : a.params_[k];
        double y = b.precision_ == Precision::Single ? b.floats_[k] : b.params_[k];
        if (x != y) return false;
    }
    return true;
}

void ModuleString::push(Symbol s) {
    symbols_.push_back(s);
    if (!paramStart_.empty()) paramStart_.push_back(static_cast<std::uint32_t>(paramCount()));
}

void ModuleString::push(Symbol s, ParamView args) {
    if (args.empty()) {
        push(s);
        return;
    }
    if (paramStart_.empty()) paramStart_.assign(symbols_.size() + 1, 0);
    symbols_.push_back(s);
    for (std::size_t k = 0; k < args.size(); ++k) {
        if (precision_ == Precision::Single)
            floats_.push_back(static_cast<float>(args[k]));
        else
            params_.push_back(args[k]);
    }
    paramStart_.push_back(static_cast<std::uint32_t>(paramCount()));
}

void ModuleString::append(const ModuleString& other) {
    for (std::size_t i = 0; i < other.size(); ++i) push(other.symbol(i), other.params(i));
}

std::size_t ModuleString::memoryBytes() const {
    return symbols_.capacity() * sizeof(Symbol) + paramStart_.capacity() * sizeof(std::uint32_t) +
           params_.capacity() * sizeof(double) + floats_.capacity() * sizeof(float);
}

std::string formatBytes(double b) {
    const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    int u = 0;
    while (b >= 1024 && u < 6) {
        b /= 1024;
        ++u;
    }
    char buf[64];
    std::snprintf(buf, sizeof buf, u == 0 ? "%.0f %s" : "%.1f %s", b, units[u]);
    return buf;
}

namespace {

char* copyText(char* out, const char* text) {
    while (*text) *out++ = *text++;
    return out;
}

// The shortest text that reads back as v, whole numbers without a point: one rule for the
// double and the float printer.
template <typename Real>
char* formatRealTo(char* out, Real v) {
    if (v == 0) return copyText(out, "0");  // also folds -0
    if (std::isnan(v)) return copyText(out, "nan");
    if (std::isinf(v)) return copyText(out, v > 0 ? "inf" : "-inf");
    char* end = out + kNumberTextCapacity;
    if (std::fabs(v) < Real(1e15) && v == std::trunc(v))
        return std::to_chars(out, end, static_cast<long long>(v)).ptr;
    return numberToChars(out, end, v).ptr;
}

}  // namespace

char* formatNumberTo(char* out, double v) {
    return formatRealTo(out, v);
}

char* formatSingleTo(char* out, float v) {
    return formatRealTo(out, v);
}

std::string formatNumber(double v) {
    char buf[kNumberTextCapacity];
    return std::string(buf, formatNumberTo(buf, v));
}

std::string formatSingle(float v) {
    char buf[kNumberTextCapacity];
    return std::string(buf, formatSingleTo(buf, v));
}

std::string formatParameter(ParamView params, std::size_t k) {
    return params.single() ? formatSingle(static_cast<float>(params[k])) : formatNumber(params[k]);
}

void ModuleString::print(std::ostream& os, const SymbolTable& table) const {
    std::string chunk;
    chunk.reserve(1 << 16);
    for (std::size_t i = 0; i < symbols_.size(); ++i) {
        appendModuleText(chunk, table, symbols_[i], params(i));
        if (chunk.size() > (1 << 16) - 256) {
            os.write(chunk.data(), static_cast<std::streamsize>(chunk.size()));
            chunk.clear();
        }
    }
    os.write(chunk.data(), static_cast<std::streamsize>(chunk.size()));
}

std::string ModuleString::toString(const SymbolTable& table) const {
    std::ostringstream os;
    print(os, table);
    return std::move(os).str();
}

void tallySymbols(std::span<const Symbol> run, std::uint64_t* t, std::size_t symbolCount) {
    const Symbol* p = run.data();
    const std::size_t n = run.size();
    std::size_t i = 0;
    for (; i + 4 <= n; i += 4) {
        ++t[p[i]];
        ++t[symbolCount + p[i + 1]];
        ++t[2 * symbolCount + p[i + 2]];
        ++t[3 * symbolCount + p[i + 3]];
    }
    for (; i < n; ++i) ++t[p[i]];
}

std::vector<std::uint64_t> countSymbols(const ModuleString& s, std::size_t symbolCount,
                                        unsigned threads) {
    std::span<const Symbol> syms = s.symbols();
    std::size_t chunks = syms.size() < (1u << 20) ? 1 : (threads ? threads : defaultThreadCount());
    std::vector<std::vector<std::uint64_t>> tallies(chunks,
                                                    std::vector<std::uint64_t>(4 * symbolCount));
    forEachChunk(syms.size(), chunks, [&](std::size_t c, std::size_t b, std::size_t e) {
        tallySymbols(syms.subspan(b, e - b), tallies[c].data(), symbolCount);
    });
    std::vector<std::uint64_t> counts(symbolCount, 0);
    for (const auto& t : tallies)
        for (std::size_t k = 0; k < 4 * symbolCount; ++k) counts[k % symbolCount] += t[k];
    return counts;
}

void appendModuleText(std::string& out, const SymbolTable& table, Symbol symbol, ParamView params) {
    out += table.name(symbol);
    if (params.empty()) return;
    out += '(';
    for (std::size_t k = 0; k < params.size(); ++k) {
        if (k) out += ',';
        out += formatParameter(params, k);
    }
    out += ')';
}

}  // namespace graftal
