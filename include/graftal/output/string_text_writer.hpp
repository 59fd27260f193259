// The derived string as text, as an L-system file writes its modules: F(1,2.5)+A, then a
// newline (what `graftal derive` prints). Parameters are in their shortest form that reads
// back as the same value (formatSingle, formatNumber).
#pragma once

#include <memory>
#include <ostream>
#include <span>
#include <string>

#include "graftal/core/byte_buffer.hpp"
#include "graftal/core/module_string.hpp"
#include "graftal/rewrite/streaming.hpp"

namespace graftal {

// Writes a held string: chunks of it are formatted on `threads` threads (0: one per core)
// into large buffers that are written in order, so the bytes never depend on the thread
// count.
void writeStringText(const ModuleString& string, const SymbolTable& symbols, std::ostream& out,
                     unsigned threads = 0);

// The text of held strings, or of the pieces of one, appended without the final newline;
// the numbers' texts it has found are kept from piece to piece. Each worker of a parallel
// stream formats its blocks with its own.
class StringTextFormatter {
  public:
    explicit StringTextFormatter(const SymbolTable& symbols);
    ~StringTextFormatter();
    // Modules [begin, end) of `string`.
    void append(const ModuleString& string, std::size_t begin, std::size_t end,
                ByteBuffer& out);

  private:
    struct State;
    std::unique_ptr<State> state_;
};

// The same text for a string handed over as it is derived (a streamed derivation): modules
// one by one, or runs of modules without parameters, gathered into large pieces.
class StringTextStream : public ModuleSink {
  public:
    // With Precision::Single the parameters handed over are printed as the floats a held
    // string would store.
    StringTextStream(const SymbolTable& symbols, Precision precision, std::ostream& out);
    ~StringTextStream() override;
    void module(Symbol symbol, std::span<const double> params) override;
    void run(std::span<const Symbol> symbols);
    // The final newline, and everything still gathered, to the stream.
    void finish();

  private:
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace graftal
