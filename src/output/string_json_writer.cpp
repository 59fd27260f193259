// The derived string as JSON (string_json_writer.hpp): each symbol's line up to its
// parameters made once, a held string formatted in chunks on every core, a streamed one
// gathered into large pieces.
#include "graftal/output/string_json_writer.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "module_text.hpp"

namespace graftal {

namespace {

using module_text::kParameterRoom;
using module_text::NumberCache;
using module_text::TextBuffer;

constexpr std::size_t kModulesPerChunk = std::size_t(1) << 20;
constexpr std::size_t kStreamPiece = std::size_t(4) << 20;

// A string as JSON; bytes that are not UTF-8 (a file name, a symbol) become U+FFFD.
std::string jsonString(std::string_view text) {
    return nlohmann::json(text).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

// A module's line but its parameters: ",\n    {"symbol": "F", "params": [" (the first
// module's without the comma), and what closes it.
struct JsonLines {
    explicit JsonLines(const SymbolTable& table) : heads(kMaxSymbols) {
        for (std::size_t s = 0; s < table.size(); ++s)
            heads[s] =
                ",\n    {\"symbol\": " + jsonString(table.name(static_cast<Symbol>(s))) +
                ", \"params\": [";
    }
    std::vector<std::string> heads;
};

std::string headerText(const StringJsonHeader& header) {
    return "{\n  \"file\": " + jsonString(header.file) +
           ",\n  \"steps\": " + std::to_string(header.steps) + ",\n  \"modules\": [";
}

std::string_view closingText(bool empty) {
    return empty ? "]\n}\n" : "\n  ]\n}\n";
}

// Module `index` of the string (the first has no comma before it) with its n parameters.
template <class T>
void formatModule(TextBuffer& out, const JsonLines& lines, Symbol s, bool first, const T* values,
                  std::size_t n, NumberCache& cache) {
    const std::string& head = lines.heads[s];
    char* p = out.room(head.size() + 2 + n * (kParameterRoom + 4));
    const std::size_t skip = first ? 1 : 0;
    std::memcpy(p, head.data() + skip, head.size() - skip);
    p += head.size() - skip;
    for (std::size_t k = 0; k < n; ++k) {
        if (k) *p++ = ',', *p++ = ' ';
        if (std::isfinite(values[k])) {
            p = cache.put(p, values[k]);
        } else {
            std::memcpy(p, "null", 4);
            p += 4;
        }
    }
    *p++ = ']';
    *p++ = '}';
    out.commit(p);
}

template <class T>
void formatHeld(const ModuleString& s, const T* values, const JsonLines& lines, std::size_t b,
                std::size_t e, TextBuffer& out, NumberCache& cache) {
    const Symbol* symbols = s.symbols().data();
    if (!s.hasParameters()) {
        for (std::size_t i = b; i < e; ++i)
            formatModule<T>(out, lines, symbols[i], i == 0, nullptr, 0, cache);
        return;
    }
    const std::uint32_t* starts = s.paramStarts().data();
    for (std::size_t i = b; i < e; ++i)
        formatModule(out, lines, symbols[i], i == 0, values + starts[i], starts[i + 1] - starts[i],
                     cache);
}

}  // namespace

void writeStringJson(const ModuleString& string, const SymbolTable& symbols,
                     const StringJsonHeader& header, std::ostream& out, unsigned threads) {
    const JsonLines lines(symbols);
    out << headerText(header);
    module_text::writeChunksInOrder(
        string.size(), threads, kModulesPerChunk, out,
        [&](std::size_t b, std::size_t e, TextBuffer& buffer) {
            NumberCache cache;
            if (string.precision() == Precision::Single)
                formatHeld(string, string.floatParams().data(), lines, b, e, buffer, cache);
            else
                formatHeld(string, string.doubleParams().data(), lines, b, e, buffer, cache);
            return true;
        },
        [](std::size_t, std::size_t) {});
    out << closingText(string.empty());
}

struct StringJsonStream::State {
    State(const SymbolTable& symbols, Precision p, std::ostream& o)
        : lines(symbols), precision(p), out(o), buffer(kStreamPiece + (1 << 16)) {}
    void maybeFlush() {
        if (buffer.size() >= kStreamPiece) flush();
    }
    void flush() {
        buffer.writeTo(out);
        buffer.clear();
    }
    JsonLines lines;
    Precision precision;
    std::ostream& out;
    TextBuffer buffer;
    NumberCache cache;
    std::vector<float> singles;
    bool first = true;
};

StringJsonStream::StringJsonStream(const SymbolTable& symbols, const StringJsonHeader& header,
                                   Precision precision, std::ostream& out)
    : state_(std::make_unique<State>(symbols, precision, out)) {
    state_->buffer.append(headerText(header));
}

StringJsonStream::~StringJsonStream() = default;

void StringJsonStream::module(Symbol symbol, std::span<const double> params) {
    State& st = *state_;
    if (st.precision == Precision::Single && !params.empty()) {
        // Stored as a held string would store them: rounded to floats.
        st.singles.assign(params.begin(), params.end());
        formatModule(st.buffer, st.lines, symbol, st.first, st.singles.data(), params.size(),
                     st.cache);
    } else {
        formatModule(st.buffer, st.lines, symbol, st.first, params.data(), params.size(), st.cache);
    }
    st.first = false;
    st.maybeFlush();
}

void StringJsonStream::run(std::span<const Symbol> symbols) {
    State& st = *state_;
    for (Symbol s : symbols) {
        formatModule<double>(st.buffer, st.lines, s, st.first, nullptr, 0, st.cache);
        st.first = false;
        st.maybeFlush();
    }
}

void StringJsonStream::finish() {
    state_->buffer.append(closingText(state_->first));
    state_->flush();
}

}  // namespace graftal
