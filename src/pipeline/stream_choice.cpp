// Whether a derivation is held in memory or streamed depth-first, and the options a request
// makes for a derivation.
#include <cmath>

#include "graftal/growth.hpp"
#include "graftal/pipeline.hpp"
#include "graftal/streaming.hpp"
#include "graftal/turtle.hpp"

namespace graftal {

int requestedSteps(const Model& model, const DeriveRequest& request) {
    if (request.steps && *request.steps < 0)
        throw Error(
            SourceLocation{"graftal", 0, 0},
            "-n " + std::to_string(*request.steps) + ": the derivation length must be 0 or more");
    return request.steps.value_or(model.lsystem.derivationLength);
}

DerivationOptions derivationOptions(const Model& model, const DeriveRequest& request) {
    DerivationOptions opts;
    opts.memoryLimit = request.memoryLimit;
    opts.seed = request.seed;
    opts.threads = request.threads;
    opts.queryResolver = turtleQueryResolver(model.view);
    opts.progress = request.progress;
    opts.cancel = request.cancel;
    opts.print = request.print;
    opts.precision = request.precision;
    return opts;
}

bool shouldStream(const Model& model, int steps, const DeriveRequest& request, bool canStream,
                  bool countGeometry, bool pixelBound, std::vector<Diagnostic>& notes) {
    const LSystem& ls = model.lsystem;
    std::string obstacle = streamingObstacle(ls);
    if (request.stream == StreamPolicy::Always) {
        if (!obstacle.empty())
            throw Error(SourceLocation{ls.file, 0, 0},
                        "--stream: this L-system cannot be streamed: " + obstacle);
        if (!canStream)
            throw Error(SourceLocation{"graftal", 0, 0},
                        "--stream is not available for this output");
        return true;
    }
    GrowthPrediction g = predictGrowth(ls, steps);
    if (g.expectedModules.size() < 2) return false;
    // Streaming needs no memory, but time grows with the string: past this many modules a
    // run would take hours, so it is refused with a message rather than started.
    const double streamLimit = static_cast<double>(request.streamLimit);
    // The last step holds the previous string and the new one; parameters take more.
    const double paramBytes = request.precision == Precision::Single ? 4 : 8;
    double perModule = ls.isParametric() ? 1 + 4 + paramBytes * 2 : 1;
    double last = g.expectedModules.back(),
           previous = g.expectedModules[g.expectedModules.size() - 2];
    double bytes = (last + previous) * perModule;
    // A picture drawn from a held string also holds its segments.
    if (countGeometry && g.exact) {
        double segments = 0;
        for (Symbol s : {Symbol('F'), Symbol('G')})
            if (s < g.symbolsAtEnd.size()) segments += g.symbolsAtEnd[s].toDouble();
        bytes = last * perModule + segments * static_cast<double>(sizeof(Segment));
    }
    if (bytes <= static_cast<double>(request.memoryLimit)) return false;
    std::string size =
        g.exact ? g.modules.back().toString() : "about " + formatNumber(std::round(last));
    if (canStream && obstacle.empty() && last > streamLimit && !pixelBound)
        obstacle = "more than --stream-limit " + formatNumber(streamLimit) + " modules";
    if (canStream && obstacle.empty()) {
        Diagnostic d{Severity::Note, SourceLocation{ls.file, 0, 0},
                     "the string would have " + size +
                         " modules, more than --memory-limit holds; streaming it instead"};
        if (request.notify) request.notify(d);
        notes.push_back(std::move(d));
        return true;
    }
    throw Error(
        SourceLocation{ls.file, 0, 0},
        "derivation step " + std::to_string(steps) + " would make a string of " + size +
            " modules (about " + formatBytes(bytes) + "), more than the memory limit of " +
            formatBytes(static_cast<double>(request.memoryLimit)) +
            "; lower the derivation length (-n) or raise --memory-limit" +
            (obstacle.empty() || !canStream ? std::string()
                                            : " (it cannot be streamed: " + obstacle + ")"));
}

}  // namespace graftal
