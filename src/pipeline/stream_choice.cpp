// Whether a derivation is held in memory or streamed depth-first, and the options a request
// makes for a derivation.
#include <unistd.h>

#include <algorithm>
#include <cmath>

#include "graftal/pipeline/pipeline.hpp"
#include "graftal/rewrite/growth.hpp"
#include "graftal/rewrite/streaming.hpp"
#include "graftal/turtle/turtle.hpp"

namespace graftal {

int checkedSteps(int steps, std::optional<int> maxSteps, const std::string& file) {
    if (steps < 0) {
        Diagnostic d{
            Severity::Error, SourceLocation{"graftal", 0, 0},
            "a derivation length of " + std::to_string(steps) + " steps: it must be 0 or more"};
        d.fields = {"steps"};
        throw Error(std::move(d));
    }
    if (maxSteps && steps > *maxSteps) {
        Diagnostic d{Severity::Error, SourceLocation{file, 0, 0},
                     "derivation length " + std::to_string(steps) + " is over the limit of " +
                         std::to_string(*maxSteps) + " steps"};
        d.fields = {"steps"};
        throw Error(std::move(d));
    }
    return steps;
}

int requestedSteps(const Model& model, const DeriveRequest& request) {
    return checkedSteps(request.steps.value_or(model.lsystem.derivationLength), request.maxSteps,
                        model.lsystem.file);
}

DerivationOptions derivationOptions(const Model& model, const DeriveRequest& request) {
    DerivationOptions opts;
    opts.memoryLimit = request.memoryLimit;
    opts.seed = request.seed;
    opts.random = request.random;
    opts.threads = request.threads;
    opts.queryResolver = turtleQueryResolver(model.view);
    opts.progress = request.progress;
    opts.cancel = request.cancel;
    opts.print = request.print;
    opts.precision = request.precision;
    opts.environment = request.environment.get();
    return opts;
}

namespace {

// Past this many bytes no computer holds a string: say so rather than suggest more memory.
constexpr double kBeyondAnyMemory = 1e15;
// A streamed run expands about 10^8 modules a second: past this many the run would take
// more than a day, so a higher stream limit is no advice.
constexpr double kLongestStreamWorthSuggesting = 1e13;

// "4083900331739" while exact and readable, "about 10^19" past it.
std::string modulesInWords(const GrowthPrediction& g) {
    const double last = g.expectedModules.back();
    if (!std::isfinite(last)) return "more than 10^308";
    if (last >= 1e15) return "about 10^" + std::to_string(std::lround(std::log10(last)));
    if (g.exact) return g.modules.back().toString();
    return "about " + formatNumber(std::round(last));
}

std::string bytesInWords(double bytes) {
    return bytes >= kBeyondAnyMemory ? "far more than any memory" : "about " + formatBytes(bytes);
}

double physicalMemory() {
    const long pages = ::sysconf(_SC_PHYS_PAGES), size = ::sysconf(_SC_PAGE_SIZE);
    return pages > 0 && size > 0 ? static_cast<double>(pages) * static_cast<double>(size) : 0;
}

}  // namespace

bool shouldStream(const Model& model, int steps, const DeriveRequest& request, bool canStream,
                  bool countGeometry, bool pixelBound, std::vector<Diagnostic>& notes) {
    const LSystem& ls = model.lsystem;
    std::string obstacle = streamingObstacle(ls);
    if (request.stream == StreamPolicy::Always) {
        if (!obstacle.empty())
            throw Error(
                SourceLocation{ls.file, 0, 0},
                "streaming was asked for, but this L-system cannot be streamed: " + obstacle);
        if (!canStream)
            throw Error(SourceLocation{"graftal", 0, 0},
                        "streaming was asked for, but this output needs the whole string or "
                        "scene (streamed: derive, stats and 2D PNG pictures)");
        return true;
    }
    GrowthPrediction g = predictGrowth(ls, steps);
    if (g.expectedModules.size() < 2) return false;
    // The last step holds the previous string and the new one; parameters take more.
    const double paramBytes = request.precision == Precision::Single ? 4 : 8;
    double perModule = ls.isParametric() ? 1 + 4 + paramBytes * 2 : 1;
    double last = g.expectedModules.back(),
           previous = g.expectedModules[g.expectedModules.size() - 2];
    double stringBytes = (last + previous) * perModule;
    double bytes = stringBytes;
    // A picture drawn from a held string also holds its segments, usually far more than the
    // string itself.
    double segments = 0, geometryBytes = 0;
    if (countGeometry && g.exact) {
        for (Symbol s : {Symbol('F'), Symbol('G')})
            if (s < g.symbolsAtEnd.size()) segments += g.symbolsAtEnd[s].toDouble();
        geometryBytes = segments * static_cast<double>(sizeof(Segment));
        stringBytes = last * perModule;
        bytes = stringBytes + geometryBytes;
    }
    const double limit = static_cast<double>(request.memoryLimit);
    if (bytes <= limit) return false;
    const std::string size = modulesInWords(g);
    const bool geometryIsTheReason = geometryBytes > 0 && stringBytes <= limit;

    // The stream limit bounds the modules a streamed run expands: the whole string when it
    // is printed, counted or drawn stroke by stroke, a few per pixel for a picture drawn
    // from subtree summaries (docs/streaming.md). Every output is judged by that one count.
    const double streamLimit = static_cast<double>(request.streamLimit);
    const double expanded = pixelBound ? 0 : last;
    std::string overStreamLimit;
    if (canStream && obstacle.empty() && expanded > streamLimit)
        overStreamLimit =
            "a streamed run would expand its modules one by one, more than the stream limit "
            "of " +
            formatNumber(streamLimit) + " modules" +
            (countGeometry ? "; only pictures of deterministic L-systems without parameters, "
                             "colours or widths are drawn from subtree summaries, in a time "
                             "that follows the image"
                           : "");
    if (canStream && obstacle.empty() && overStreamLimit.empty()) {
        std::string why =
            geometryIsTheReason
                ? "the picture's geometry would need " + bytesInWords(bytes) + " (" +
                      formatNumber(segments) + " segments of a " + size + "-module string)"
                : "the string would have " + size + " modules (" + bytesInWords(stringBytes) + ")";
        Diagnostic d{Severity::Note, SourceLocation{ls.file, 0, 0},
                     why + ", more than the memory limit of " + formatBytes(limit) +
                         "; streaming it instead"};
        if (request.notify) request.notify(d);
        notes.push_back(std::move(d));
        return true;
    }
    Diagnostic d{Severity::Error, SourceLocation{ls.file, 0, 0},
                 "derivation step " + std::to_string(steps) + " would make a string of " + size +
                     " modules"};
    if (bytes >= kBeyondAnyMemory)
        d.message += ", far more than any memory";
    else
        d.message +=
            (geometryIsTheReason ? " whose picture's geometry would need about " : " (about ") +
            formatBytes(bytes) + (geometryIsTheReason ? "" : ")") +
            ", more than the memory limit of " + formatBytes(limit);
    if (!obstacle.empty() && canStream) d.message += " (it cannot be streamed: " + obstacle + ")";
    // Past a day of streaming the stream limit is no longer the point: only -n helps.
    if (!overStreamLimit.empty() && expanded < kLongestStreamWorthSuggesting)
        d.message += " (" + overStreamLimit + ")";
    if (obstacle.empty() && !canStream && last <= streamLimit)
        d.message += " (this output needs the whole scene; a 2D PNG could be streamed)";
    d.remedies.push_back(Remedy::LowerSteps);
    const double memory = physicalMemory();
    if (bytes < kBeyondAnyMemory && (memory == 0 || bytes < memory))
        d.remedies.push_back(Remedy::RaiseMemoryLimit);
    if (!overStreamLimit.empty() && expanded < kLongestStreamWorthSuggesting)
        d.remedies.push_back(Remedy::RaiseStreamLimit);
    throw Error(std::move(d));
}

std::optional<Error> withStreamRemedy(const Error& error, const Model& model,
                                      const DeriveRequest& request, bool canStream) {
    if (request.stream != StreamPolicy::Auto || !canStream ||
        dynamic_cast<const Cancelled*>(&error) || error.diagnostics().size() != 1 ||
        !streamingObstacle(model.lsystem).empty())
        return std::nullopt;
    std::vector<Diagnostic> ds = error.diagnostics();
    std::vector<Remedy>& remedies = ds.front().remedies;
    const auto has = [&](Remedy r) {
        return std::find(remedies.begin(), remedies.end(), r) != remedies.end();
    };
    if (!has(Remedy::RaiseMemoryLimit) || has(Remedy::Stream)) return std::nullopt;
    remedies.push_back(Remedy::Stream);
    return Error(std::move(ds));
}

}  // namespace graftal
