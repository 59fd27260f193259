// The derived string as text (string_text_writer.hpp): a held string formatted in chunks on
// every core, a streamed one gathered into large pieces; a run of symbols that are their
// own text (every symbol below 128) is written as it is.
#include "graftal/output/string_text_writer.hpp"

#include "module_text.hpp"

namespace graftal {

namespace {

using module_text::kParameterRoom;
using module_text::NumberCache;
using module_text::SymbolNames;
using module_text::TextBuffer;

// About 2 M modules a chunk: a few megabytes of text, large enough that writing a chunk
// costs one system call, small enough that the team's buffers stay in a few dozen MB.
constexpr std::size_t kModulesPerChunk = std::size_t(1) << 21;
// A streamed string is written whenever this much is gathered.
constexpr std::size_t kStreamPiece = std::size_t(4) << 20;

char* copyName(char* p, const std::string& name) {
    std::memcpy(p, name.data(), name.size());
    return p + name.size();
}

// "(a,b,c)" for the n parameters at `values`.
template <class T>
char* parameterText(char* p, const T* values, std::size_t n, NumberCache& cache) {
    *p++ = '(';
    for (std::size_t k = 0; k < n; ++k) {
        if (k) *p++ = ',';
        p = cache.put(p, values[k]);
    }
    *p++ = ')';
    return p;
}

// Modules [b, e) of a held string with parameters.
template <class T>
void formatParametric(const ModuleString& s, const T* values, const SymbolNames& names,
                      std::size_t b, std::size_t e, TextBuffer& out, NumberCache& cache) {
    const Symbol* symbols = s.symbols().data();
    const std::uint32_t* starts = s.paramStarts().data();
    for (std::size_t i = b; i < e; ++i) {
        const Symbol sym = symbols[i];
        const std::size_t first = starts[i], n = starts[i + 1] - first;
        char* p = out.room(names.roomFor(sym) + 2 + n * kParameterRoom);
        p = names.put(p, sym);
        if (n) p = parameterText(p, values + first, n, cache);
        out.commit(p);
    }
}

void formatNames(std::span<const Symbol> symbols, const SymbolNames& names, TextBuffer& out) {
    for (Symbol s : symbols) out.commit(names.put(out.room(names.roomFor(s)), s));
}

}  // namespace

void writeStringText(const ModuleString& string, const SymbolTable& symbols, std::ostream& out,
                     unsigned threads) {
    const SymbolNames names(symbols);
    const std::span<const Symbol> all = string.symbols();
    module_text::writeChunksInOrder(
        string.size(), threads, kModulesPerChunk, out,
        [&](std::size_t b, std::size_t e, TextBuffer& buffer) {
            if (!string.hasParameters()) {
                const std::span<const Symbol> run = all.subspan(b, e - b);
                if (SymbolNames::isOwnText(run)) return false;
                formatNames(run, names, buffer);
                return true;
            }
            NumberCache cache;
            if (string.precision() == Precision::Single)
                formatParametric(string, string.floatParams().data(), names, b, e, buffer, cache);
            else
                formatParametric(string, string.doubleParams().data(), names, b, e, buffer, cache);
            return true;
        },
        [&](std::size_t b, std::size_t e) {
            out.write(reinterpret_cast<const char*>(all.data() + b),
                      static_cast<std::streamsize>(e - b));
        });
    out.put('\n');
}

struct StringTextFormatter::State {
    explicit State(const SymbolTable& symbols) : names(symbols) {}
    SymbolNames names;
    NumberCache cache;
};

StringTextFormatter::StringTextFormatter(const SymbolTable& symbols)
    : state_(std::make_unique<State>(symbols)) {}

StringTextFormatter::~StringTextFormatter() = default;

void StringTextFormatter::append(const ModuleString& string, std::size_t b, std::size_t e,
                                 ByteBuffer& out) {
    State& st = *state_;
    const std::span<const Symbol> run = string.symbols().subspan(b, e - b);
    if (!string.hasParameters() && SymbolNames::isOwnText(run))
        out.append(reinterpret_cast<const char*>(run.data()), run.size());
    else if (!string.hasParameters())
        formatNames(run, st.names, out);
    else if (string.precision() == Precision::Single)
        formatParametric(string, string.floatParams().data(), st.names, b, e, out, st.cache);
    else
        formatParametric(string, string.doubleParams().data(), st.names, b, e, out, st.cache);
}

struct StringTextStream::State {
    State(const SymbolTable& symbols, Precision p, std::ostream& o)
        : names(symbols), precision(p), out(o), buffer(kStreamPiece + (1 << 16)) {}
    void maybeFlush() {
        if (buffer.size() >= kStreamPiece) flush();
    }
    void flush() {
        buffer.writeTo(out);
        buffer.clear();
    }
    SymbolNames names;
    Precision precision;
    std::ostream& out;
    TextBuffer buffer;
    NumberCache cache;
    std::vector<float> singles;
};

StringTextStream::StringTextStream(const SymbolTable& symbols, Precision precision,
                                   std::ostream& out)
    : state_(std::make_unique<State>(symbols, precision, out)) {}

StringTextStream::~StringTextStream() = default;

void StringTextStream::module(Symbol symbol, std::span<const double> params) {
    State& st = *state_;
    const std::string& name = st.names.names[symbol];
    char* p = st.buffer.room(name.size() + 2 + params.size() * kParameterRoom);
    p = copyName(p, name);
    if (!params.empty()) {
        if (st.precision == Precision::Single) {
            // Stored as a held string would store them: rounded to floats.
            st.singles.assign(params.begin(), params.end());
            p = parameterText(p, st.singles.data(), params.size(), st.cache);
        } else {
            p = parameterText(p, params.data(), params.size(), st.cache);
        }
    }
    st.buffer.commit(p);
    st.maybeFlush();
}

void StringTextStream::run(std::span<const Symbol> symbols) {
    State& st = *state_;
    if (!SymbolNames::isOwnText(symbols)) {
        formatNames(symbols, st.names, st.buffer);
    } else if (symbols.size() >= kStreamPiece / 4) {
        st.flush();
        st.out.write(reinterpret_cast<const char*>(symbols.data()),
                     static_cast<std::streamsize>(symbols.size()));
    } else {
        st.buffer.append(reinterpret_cast<const char*>(symbols.data()), symbols.size());
    }
    st.maybeFlush();
}

void StringTextStream::finish() {
    state_->buffer.append("\n", 1);
    state_->flush();
}

}  // namespace graftal
