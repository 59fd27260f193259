// graftal derive: the derived string on standard output, as cpfg-style text or as JSON for
// scripts (one object per module, see docs/cli.md), held or streamed.
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "graftal/rewrite/streaming.hpp"

namespace graftal::cli {

namespace {

// Writes what it is given in large chunks: the string may have billions of modules.
class ChunkedOutput {
  public:
    ChunkedOutput() { buffer_.reserve(1 << 16); }
    ~ChunkedOutput() { flush(); }
    std::string& buffer() { return buffer_; }
    void maybeFlush() {
        if (buffer_.size() > (1 << 16) - 512) flush();
    }
    void flush() {
        std::cout.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
        buffer_.clear();
    }

  private:
    std::string buffer_;
};

// A streamed derivation hands over doubles; with single precision they came from floats
// and print as the held string's floats would.
class PrecisionSink : public ModuleSink {
  public:
    explicit PrecisionSink(Precision precision) : precision_(precision) {}
    void module(Symbol s, std::span<const double> params) override {
        if (precision_ == Precision::Single) {
            singles_.assign(params.begin(), params.end());
            held(s, ParamView(singles_.data(), singles_.size()));
        } else {
            held(s, ParamView(params));
        }
    }
    virtual void held(Symbol s, ParamView params) = 0;

  private:
    Precision precision_;
    std::vector<float> singles_;
};

// The modules as the L-system file writes them: F(1,2.5)+A
class TextSink : public PrecisionSink {
  public:
    TextSink(const SymbolTable& t, Precision precision) : PrecisionSink(precision), table_(t) {}
    void held(Symbol s, ParamView params) override {
        appendModuleText(out_.buffer(), table_, s, params);
        out_.maybeFlush();
    }
    void finish() {
        out_.buffer() += '\n';
        out_.flush();
    }

  private:
    const SymbolTable& table_;
    ChunkedOutput out_;
};

// {"file": ..., "steps": n, "modules": [{"symbol": "F", "params": [1, 2.5]}, ...]}, one
// module to a line so that line tools work on it too.
class JsonSink : public PrecisionSink {
  public:
    JsonSink(const SymbolTable& t, const std::string& file, int steps, Precision precision)
        : PrecisionSink(precision), table_(t) {
        names_.resize(t.size());
        out_.buffer() += "{\n  \"file\": " + nlohmann::json(file).dump() +
                         ",\n  \"steps\": " + std::to_string(steps) + ",\n  \"modules\": [";
    }
    void held(Symbol s, ParamView params) override {
        std::string& b = out_.buffer();
        if (names_[s].empty()) names_[s] = nlohmann::json(table_.name(s)).dump();
        b += first_ ? "\n    {\"symbol\": " : ",\n    {\"symbol\": ";
        first_ = false;
        b += names_[s];
        b += ", \"params\": [";
        for (std::size_t k = 0; k < params.size(); ++k) {
            if (k) b += ", ";
            // JSON has no NaN or infinity: a module's parameter that became one is null.
            b += std::isfinite(params[k]) ? formatParameter(params, k) : "null";
        }
        b += "]}";
        out_.maybeFlush();
    }
    void finish() {
        out_.buffer() += first_ ? "]\n}\n" : "\n  ]\n}\n";
        out_.flush();
    }

  private:
    const SymbolTable& table_;
    std::vector<std::string> names_;  // each symbol's name as a JSON string
    bool first_ = true;
    ChunkedOutput out_;
};

// Held or streamed, the modules go to `sink` in order, then it finishes.
template <class Sink>
int writeDerivation(Loaded l, const InputOptions& in, bool homomorphism, Sink& sink) {
    if (chooseStreaming(l, in, !homomorphism)) {
        streamDerivation(l.model.lsystem, l.steps, sink, derivationOptions(in, l.model));
        endProgressLine();
    } else {
        Derived d = deriveLoaded(std::move(l), in);
        if (homomorphism)
            d.modules =
                applyHomomorphism(d.model.lsystem, d.modules, derivationOptions(in, d.model));
        for (std::size_t i = 0; i < d.modules.size(); ++i)
            sink.held(d.modules.symbol(i), d.modules.params(i));
    }
    sink.finish();
    return std::cout ? 0 : 1;
}

}  // namespace

int runDerive(const InputOptions& in, bool homomorphism, DeriveFormat format) {
    Loaded l = loadInput(in);
    // The sinks refer to the symbol table: keep it alive after the model moves on.
    const SymbolTable symbols = l.model.lsystem.symbols;
    if (format == DeriveFormat::Json) {
        JsonSink sink(symbols, fileName(in), l.steps, in.precision);
        return writeDerivation(std::move(l), in, homomorphism, sink);
    }
    TextSink sink(symbols, in.precision);
    return writeDerivation(std::move(l), in, homomorphism, sink);
}

}  // namespace graftal::cli
