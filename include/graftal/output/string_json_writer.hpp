// The derived string as JSON for scripts: {"file": ..., "steps": n, "modules": [{"symbol":
// "F", "params": [1, 2.5]}, ...]}, one module to a line so that line tools work on it too
// (docs/cli.md). A parameter that became NaN or infinite is null (JSON has neither).
#pragma once

#include <memory>
#include <ostream>
#include <span>
#include <string>

#include "graftal/core/module_string.hpp"
#include "graftal/rewrite/streaming.hpp"

namespace graftal {

// The header of the JSON: the input's name and the step count it reports.
struct StringJsonHeader {
    std::string file;
    int steps = 0;
};

// Writes a held string, formatted in chunks on `threads` threads (0: one per core) and
// written in order.
void writeStringJson(const ModuleString& string, const SymbolTable& symbols,
                     const StringJsonHeader& header, std::ostream& out, unsigned threads = 0);

// The same JSON for a string handed over as it is derived (a streamed derivation).
class StringJsonStream : public ModuleSink {
  public:
    StringJsonStream(const SymbolTable& symbols, const StringJsonHeader& header,
                     Precision precision, std::ostream& out);
    ~StringJsonStream() override;
    void module(Symbol symbol, std::span<const double> params) override;
    void run(std::span<const Symbol> symbols);
    // The closing brackets, and everything still gathered, to the stream.
    void finish();

  private:
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace graftal
