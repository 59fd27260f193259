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

    // Whether the tokenizer matches a declared name anywhere, or only as a surface name
    // right after ~ (an undeclared `~leaf`).
    enum class Matching : std::uint8_t { Anywhere, AfterTildeOnly };
    // Declares a multi-letter name (or returns the existing id; Anywhere wins).
    Symbol declare(std::string_view name, Matching matching = Matching::Anywhere);
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

// How a string keeps its parameters. Single (the default of a derivation) stores each one
// as a 32-bit float, as cpfg does: half the memory of Double, so twice the modules fit.
// Expressions are still evaluated in double; only the value stored is rounded. Double
// keeps every parameter as computed (`--precision double`). docs/performance.md says
// where the two differ.
enum class Precision : std::uint8_t { Single, Double };

// The parameters of one module, read as doubles whatever the string stores.
class ParamView {
  public:
    ParamView() = default;
    ParamView(const double* d, std::size_t n) : d_(d), n_(static_cast<std::uint32_t>(n)) {}
    ParamView(const float* f, std::size_t n) : f_(f), n_(static_cast<std::uint32_t>(n)) {}
    ParamView(std::span<const double> d) : ParamView(d.data(), d.size()) {}

    std::size_t size() const { return n_; }
    bool empty() const { return n_ == 0; }
    double operator[](std::size_t k) const { return f_ ? static_cast<double>(f_[k]) : d_[k]; }
    // Stored as 32-bit floats (then printed in the shortest form that reads back as the
    // same float).
    bool single() const { return f_ != nullptr; }

    class iterator {
      public:
        using value_type = double;
        using difference_type = std::ptrdiff_t;
        iterator() = default;
        iterator(const ParamView* v, std::size_t k) : v_(v), k_(k) {}
        double operator*() const { return (*v_)[k_]; }
        iterator& operator++() {
            ++k_;
            return *this;
        }
        iterator operator++(int) {
            iterator t = *this;
            ++k_;
            return t;
        }
        bool operator==(const iterator& o) const { return k_ == o.k_; }

      private:
        const ParamView* v_ = nullptr;
        std::size_t k_ = 0;
    };
    iterator begin() const { return {this, 0}; }
    iterator end() const { return {this, n_}; }

    // The values as doubles: the storage itself when it holds doubles, else a copy in
    // `scratch`.
    std::span<const double> doubles(std::vector<double>& scratch) const {
        if (!f_) return {d_, n_};
        scratch.assign(f_, f_ + n_);
        return scratch;
    }

  private:
    const double* d_ = nullptr;
    const float* f_ = nullptr;
    std::uint32_t n_ = 0;
};

class ModuleString {
  public:
    using SymbolBuffer = std::vector<Symbol, UninitializedAllocator<Symbol>>;
    using OffsetBuffer = std::vector<std::uint32_t, UninitializedAllocator<std::uint32_t>>;
    using ParamBuffer = std::vector<double, UninitializedAllocator<double>>;
    using FloatBuffer = std::vector<float, UninitializedAllocator<float>>;

    ModuleString() = default;
    explicit ModuleString(Precision p) : precision_(p) {}

    std::size_t size() const { return symbols_.size(); }
    bool empty() const { return symbols_.empty(); }
    bool hasParameters() const { return !paramStart_.empty(); }

    Symbol symbol(std::size_t i) const { return symbols_[i]; }
    std::span<const Symbol> symbols() const { return symbols_; }

    ParamView params(std::size_t i) const {
        if (paramStart_.empty()) return {};
        std::size_t b = paramStart_[i], n = paramStart_[i + 1] - b;
        if (precision_ == Precision::Single) return {floats_.data() + b, n};
        return {params_.data() + b, n};
    }
    std::size_t paramCount() const {
        return precision_ == Precision::Single ? floats_.size() : params_.size();
    }

    // How parameters are stored. A string made by default stores doubles; a derivation
    // stores what DerivationOptions::precision says. Changing it converts what is held.
    Precision precision() const { return precision_; }
    void setPrecision(Precision p);
    // Bytes one stored parameter takes.
    std::size_t paramBytes() const { return precision_ == Precision::Single ? 4 : 8; }
    // Sets parameter `index` of the flat parameter array (rounded when stored as floats).
    void setParam(std::size_t index, double v) {
        if (precision_ == Precision::Single)
            floats_[index] = static_cast<float>(v);
        else
            params_[index] = v;
    }

    void clear();
    void reserve(std::size_t modules, std::size_t params = 0);
    void push(Symbol s);
    void push(Symbol s, ParamView args);
    void push(Symbol s, std::span<const double> args) { push(s, ParamView(args)); }
    void push(Symbol s, const std::vector<double>& args) { push(s, ParamView(args)); }
    void append(const ModuleString& other);

    // Raw access for the derivation engine, which sizes the buffers once and fills them.
    // rawParams() holds the parameters of a Double string, rawFloats() those of a Single one.
    SymbolBuffer& rawSymbols() { return symbols_; }
    OffsetBuffer& rawParamStart() { return paramStart_; }
    ParamBuffer& rawParams() { return params_; }
    FloatBuffer& rawFloats() { return floats_; }
    const OffsetBuffer& paramStarts() const { return paramStart_; }
    const ParamBuffer& doubleParams() const { return params_; }
    const FloatBuffer& floatParams() const { return floats_; }

    // Bytes held by the buffers (capacity, not size): what the memory limit counts.
    std::size_t memoryBytes() const;

    // Modules concatenated, parameters as A(1,2.5) in shortest round-trip form.
    std::string toString(const SymbolTable& table) const;
    void print(std::ostream& os, const SymbolTable& table) const;

    friend bool operator==(const ModuleString& a, const ModuleString& b);

  private:
    SymbolBuffer symbols_;
    OffsetBuffer paramStart_;  // size()+1 offsets into the parameters, or empty
    ParamBuffer params_;       // Precision::Double
    FloatBuffer floats_;       // Precision::Single
    Precision precision_ = Precision::Double;
};

// How many modules of each symbol `s` has, indexed by symbol id (`symbolCount` entries),
// counted in parallel with `threads` threads (0: all cores).
std::vector<std::uint64_t> countSymbols(const ModuleString& s, std::size_t symbolCount,
                                        unsigned threads = 0);

// Adds the symbols of `run` to `tallies`: four tables of `symbolCount` counters one after
// the other (a symbol's count is the sum of its four), so that a run of few distinct
// symbols does not make each increment wait for the previous one's store.
void tallySymbols(std::span<const Symbol> run, std::uint64_t* tallies, std::size_t symbolCount);

// Shortest decimal text that reads back as the same double; integers without a point.
std::string formatNumber(double v);
// The same for a 32-bit float: the shortest text that reads back as the same float.
std::string formatSingle(float v);
// Parameter k of a module as a string prints it (formatSingle for stored floats).
std::string formatParameter(ParamView params, std::size_t k);
// The same texts written at `out`, which has room for kNumberTextCapacity characters;
// return the end. The writers of strings of billions of parameters use these (no string
// per number).
inline constexpr std::size_t kNumberTextCapacity = 32;
char* formatNumberTo(char* out, double v);
char* formatSingleTo(char* out, float v);

// Appends one module as a string prints it: its name, then "(a,b,...)" when it has
// parameters.
void appendModuleText(std::string& out, const SymbolTable& table, Symbol symbol, ParamView params);
// "190.7 MiB": binary units, as --memory-limit reads them (2G is 2 GiB).
std::string formatBytes(double bytes);

}  // namespace graftal
