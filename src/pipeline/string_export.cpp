// The derived string as text or JSON (string_export.hpp). Held when the homomorphism is
// asked for or the L-system cannot be streamed; otherwise streamed depth first, in bounded
// memory: in runs when nothing depends on a module's position (the D0L case, at memory
// speed), module by module when the prediction says the string would not fit.
#include "string_export.hpp"

#include <streambuf>

#include "graftal/output/string_json_writer.hpp"
#include "graftal/output/string_text_writer.hpp"
#include "graftal/rewrite/parallel_stream.hpp"
#include "graftal/rewrite/streamed_runs.hpp"
#include "graftal/rewrite/streaming.hpp"

namespace graftal {

namespace {

// An ostream's bytes appended to a string: a worker formats its block with the held
// string's writer, so streamed and held text are the same bytes.
class AppendingBuffer : public std::streambuf {
  public:
    explicit AppendingBuffer(std::string& text) : text_(text) {}

  protected:
    int_type overflow(int_type c) override {
        if (!traits_type::eq_int_type(c, traits_type::eof()))
            text_.push_back(traits_type::to_char_type(c));
        return c;
    }
    std::streamsize xsputn(const char* p, std::streamsize n) override {
        text_.append(p, static_cast<std::size_t>(n));
        return n;
    }

  private:
    std::string& text_;
};

// The text of the string streamed in parallel: each worker formats its blocks, this
// thread writes them in order.
void streamTextInParallel(const Model& model, int steps, const DerivationOptions& options,
                          std::ostream& out) {
    const SymbolTable& symbols = model.lsystem.symbols;
    streamDerivationParallel(
        model.lsystem, steps,
        [&](StreamBlock& block) {
            AppendingBuffer buffer(block.text);
            std::ostream text(&buffer);
            writeStringText(block.modules, symbols, text, 1);
            block.text.pop_back();  // the newline that ends a whole string
            block.modules.clear();
        },
        [&](const StreamBlock& block) {
            out.write(block.text.data(), static_cast<std::streamsize>(block.text.size()));
        },
        options);
    out.put('\n');
}

// Streams the string into `sink` (StringTextStream or StringJsonStream).
template <class Sink>
void streamInto(Sink& sink, const Model& model, int steps, bool inRuns,
                const DerivationOptions& options) {
    if (inRuns)
        streamDerivationRuns(
            model.lsystem, steps, [&](std::span<const Symbol> run) { sink.run(run); }, options);
    else
        streamDerivation(model.lsystem, steps, sink, options);
    sink.finish();
}

}  // namespace

ExportResult writeDerivedString(const ExportFormat& format, const Model& model,
                                const ExportRequest& request, const Destination& destination) {
    const bool json = format.name == "json";
    const std::string what = json ? "JSON" : "string";
    const int steps = requestedSteps(model, request);
    ExportResult result;
    result.steps = steps;
    // The string after the homomorphism needs the whole string.
    const bool canStream = !request.homomorphism;
    const bool streamed =
        shouldStream(model, steps, request, canStream, false, false, result.notes);
    const bool inRuns = canStream && streamsInRuns(model.lsystem);
    // Text is formatted by the workers of the parallel stream, which also holds no string:
    // taken whenever it is at least as fast as the held derivation.
    const bool parallel = canStream && !json && !inRuns &&
                          (streamed || (request.stream == StreamPolicy::Auto &&
                                        parallelStreamPays(model.lsystem, steps,
                                                           request.threads))) &&
                          streamsInParallel(model.lsystem) &&
                          parallelThreads(request.threads) > 1;
    const SymbolTable& symbols = model.lsystem.symbols;
    const StringJsonHeader header{
        request.inputName.empty() ? model.lsystem.file : request.inputName, steps};
    if (streamed || inRuns || parallel) {
        const DerivationOptions options = derivationOptions(model, request);
        destination.write(what, [&](std::ostream& out) {
            if (parallel) {
                streamTextInParallel(model, steps, options, out);
            } else if (json) {
                StringJsonStream sink(symbols, header, request.precision, out);
                streamInto(sink, model, steps, inRuns, options);
            } else {
                StringTextStream sink(symbols, request.precision, out);
                streamInto(sink, model, steps, inRuns, options);
            }
        });
        return result;
    }
    DeriveRequest derive = request;
    derive.steps = steps;
    Derived d = derived(model, derive);
    if (request.homomorphism)
        d.modules = applyHomomorphism(model.lsystem, d.modules, derivationOptions(model, request));
    request.cancel.check();
    destination.write(what, [&](std::ostream& out) {
        if (json)
            writeStringJson(d.modules, symbols, header, out, request.threads);
        else
            writeStringText(d.modules, symbols, out, request.threads);
    });
    result.notes.insert(result.notes.end(), d.notes.begin(), d.notes.end());
    return result;
}

}  // namespace graftal
