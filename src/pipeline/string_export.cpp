// The derived string as text or JSON (string_export.hpp). Held when the homomorphism is
// asked for or the L-system cannot be streamed; otherwise streamed depth first, in bounded
// memory: in runs when nothing depends on a module's position (the D0L case, at memory
// speed), module by module when the prediction says the string would not fit.
#include "string_export.hpp"

#include <atomic>
#include <map>
#include <memory>
#include <mutex>
#include <thread>

#include "graftal/output/string_json_writer.hpp"
#include "graftal/output/string_text_writer.hpp"
#include "graftal/rewrite/parallel_stream.hpp"
#include "graftal/rewrite/streamed_runs.hpp"
#include "graftal/rewrite/streaming.hpp"

namespace graftal {

namespace {

// The text of the string streamed in parallel: each worker formats its blocks (with the
// held string's formatting), this thread writes them in order.
void streamTextInParallel(const Model& model, int steps, const DerivationOptions& options,
                          std::ostream& out) {
    // One formatter a worker, each keeping the texts of the numbers it has met. The writer
    // is called for every run of modules, often a few modules long: each thread finds its
    // formatter under the lock once per call of this function, then in its own memory.
    static std::atomic<std::uint64_t> calls{0};
    const std::uint64_t call = ++calls;
    std::mutex mutex;
    std::map<std::thread::id, std::unique_ptr<StringTextFormatter>> formatters;
    auto formatter = [&]() -> StringTextFormatter& {
        thread_local std::uint64_t seenCall = 0;
        thread_local StringTextFormatter* mine = nullptr;
        if (seenCall != call) {
            std::lock_guard lock(mutex);
            auto& f = formatters[std::this_thread::get_id()];
            if (!f) f = std::make_unique<StringTextFormatter>(model.lsystem.symbols);
            mine = f.get();
            seenCall = call;
        }
        return *mine;
    };
    streamDerivationParallel(
        model.lsystem, steps,
        [&](const ModuleString& string, std::size_t b, std::size_t e, StreamBlock& block) {
            formatter().append(string, b, e, block.text);
        },
        [&](const StreamBlock& block) {
            block.text.writeTo(out);
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
    Derived d = suggestingStream(model, request, canStream, [&] { return derived(model, derive); });
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
