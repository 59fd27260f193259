// The module string: the state of an L-system between derivation steps.
//
// Stored as parallel flat arrays (structure of arrays) so that a string of a hundred
// million modules is a few contiguous buffers: no object and no allocation per module.
#pragma once

#include <cstdint>
#include <memory>
#include <ostream>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

namespace graftal {

// Allocation of large flat buffers. Big blocks are mapped directly and marked for
// transparent huge pages: a step writes hundreds of megabytes into fresh memory, and
// with 4 KiB pages the page faults would cost more than the rewriting itself.
void* allocateLarge(std::size_t bytes);
void deallocateLarge(void* p, std::size_t bytes) noexcept;

// A std::allocator whose resize() leaves new elements uninitialised: the derivation engine
// sizes a buffer and then writes every element, so zero-filling first would double the
// memory traffic of a step.
template <class T>
struct UninitializedAllocator {
    using value_type = T;
    UninitializedAllocator() = default;
    template <class U>
    UninitializedAllocator(const UninitializedAllocator<U>&) noexcept {}

    T* allocate(std::size_t n) { return static_cast<T*>(allocateLarge(n * sizeof(T))); }
    void deallocate(T* p, std::size_t n) noexcept { deallocateLarge(p, n * sizeof(T)); }

    template <class U>
    void construct(U* p) noexcept {
        ::new (static_cast<void*>(p)) U;
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
    template <class U>
    friend bool operator==(const UninitializedAllocator&, const UninitializedAllocator<U>&) {
        return true;
    }
};

// A module name is a small integer, one byte per module in a string (as a cpfg module is a
// character): strings of 10^9 modules then take 1 GB, and every derivation step moves
// half the bytes it would with wider ids. Single printable ASCII characters are their own
// code (so 'F' is 70 everywhere); declared multi-letter names get ids from 128 up, which
// leaves room for 123 of them beside the predeclared query modules.
using Symbol = std::uint8_t;

inline constexpr Symbol kFirstNamedSymbol = 128;
// Ids of the predeclared query modules ?E ?P ?H ?L ?U (in this order).
inline constexpr Symbol kQueryE = 128, kQueryP = 129, kQueryH = 130, kQueryL = 131, kQueryU = 132;
inline constexpr Symbol kFirstDeclaredSymbol = 133;  // the first name a file declares
inline constexpr std::size_t kMaxSymbols = 256;

class SymbolTable {
  public:
    SymbolTable();

    // Declares a multi-letter name (or returns the existing id).
    Symbol declare(std::string_view name);
    // The id of a declared name or single character; -1 when unknown.
    int find(std::string_view name) const;
    const std::string& name(Symbol s) const { return names_[s]; }
    std::size_t size() const { return names_.size(); }
    // Declared multi-letter names, longest first: the order the tokenizer tries them in.
    const std::vector<Symbol>& namesLongestFirst() const { return byLength_; }

  private:
    std::vector<std::string> names_;
    std::unordered_map<std::string, Symbol> ids_;
    std::vector<Symbol> byLength_;
};

class ModuleString {
  public:
    using SymbolBuffer = std::vector<Symbol, UninitializedAllocator<Symbol>>;
    using OffsetBuffer = std::vector<std::uint32_t, UninitializedAllocator<std::uint32_t>>;
    using ParamBuffer = std::vector<double, UninitializedAllocator<double>>;

    std::size_t size() const { return symbols_.size(); }
    bool empty() const { return symbols_.empty(); }
    bool hasParameters() const { return !paramStart_.empty(); }

    Symbol symbol(std::size_t i) const { return symbols_[i]; }
    std::span<const Symbol> symbols() const { return symbols_; }

    std::span<const double> params(std::size_t i) const {
        if (paramStart_.empty()) return {};
        return {params_.data() + paramStart_[i], paramStart_[i + 1] - paramStart_[i]};
    }
    std::size_t paramCount() const { return params_.size(); }

    void clear();
    void reserve(std::size_t modules, std::size_t params = 0);
    void push(Symbol s);
    void push(Symbol s, std::span<const double> args);
    void append(const ModuleString& other);

    // Raw access for the derivation engine, which sizes the buffers once and fills them.
    SymbolBuffer& rawSymbols() { return symbols_; }
    OffsetBuffer& rawParamStart() { return paramStart_; }
    ParamBuffer& rawParams() { return params_; }
    const OffsetBuffer& paramStarts() const { return paramStart_; }

    // Bytes held by the buffers (capacity, not size): what the memory limit counts.
    std::size_t memoryBytes() const;

    // Modules concatenated, parameters as A(1,2.5) in shortest round-trip form.
    std::string toString(const SymbolTable& table) const;
    void print(std::ostream& os, const SymbolTable& table) const;

    friend bool operator==(const ModuleString&, const ModuleString&) = default;

  private:
    SymbolBuffer symbols_;
    OffsetBuffer paramStart_;  // size()+1 offsets into params_, or empty
    ParamBuffer params_;
};

// How many modules of each symbol `s` has, indexed by symbol id (`symbolCount` entries),
// counted in parallel with `threads` threads (0: all cores).
std::vector<std::uint64_t> countSymbols(const ModuleString& s, std::size_t symbolCount,
                                        unsigned threads = 0);

// Shortest decimal text that reads back as the same double; integers without a point.
std::string formatNumber(double v);

// Appends one module as a string prints it: its name, then "(a,b,...)" when it has
// parameters.
void appendModuleText(std::string& out, const SymbolTable& table, Symbol symbol,
                      std::span<const double> params);
// "190.7 MiB": binary units, as --memory-limit reads them (2G is 2 GiB).
std::string formatBytes(double bytes);

}  // namespace graftal
