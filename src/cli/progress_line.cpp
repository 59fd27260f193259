#include "progress_line.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>

namespace graftal::cli {

namespace {

// A run shorter than this needs no progress; later, the line changes at most this often.
constexpr std::chrono::milliseconds kQuietStart{500};
constexpr std::chrono::milliseconds kRefresh{200};

std::string shortCount(double v) {
    char buf[32];
    if (v >= 1e9)
        std::snprintf(buf, sizeof buf, "%.1fG", v / 1e9);
    else if (v >= 1e6)
        std::snprintf(buf, sizeof buf, "%.1fM", v / 1e6);
    else if (v >= 1e3)
        std::snprintf(buf, sizeof buf, "%.1fk", v / 1e3);
    else
        std::snprintf(buf, sizeof buf, "%.0f", v);
    return buf;
}

std::string duration(double seconds) {
    char buf[32];
    if (seconds < 90)
        std::snprintf(buf, sizeof buf, "%.0f s", std::ceil(seconds));
    else if (seconds < 5400)
        std::snprintf(buf, sizeof buf, "%.0f min", seconds / 60);
    else
        std::snprintf(buf, sizeof buf, "%.1f h", seconds / 3600);
    return buf;
}

}  // namespace

void ProgressLine::expect(std::vector<double> modulesPerStep) {
    perStep_ = std::move(modulesPerStep);
    doneThrough_.assign(perStep_.size(), 0);
    for (std::size_t k = 1; k < perStep_.size(); ++k)
        doneThrough_[k] = doneThrough_[k - 1] + perStep_[k];
    start_ = std::chrono::steady_clock::now();
}

double ProgressLine::fractionDone(int step, double modules) const {
    const int last = static_cast<int>(perStep_.size()) - 1;
    if (last < 1 || step < 0 || step > last) return -1;
    if (step == last) return std::min(1.0, modules / std::max(1.0, perStep_[last]));
    return doneThrough_[step] / std::max(1.0, doneThrough_[last]);
}

void ProgressLine::report(int step, std::size_t modules) {
    const auto now = std::chrono::steady_clock::now();
    if (now - start_ < kQuietStart || (shown_ && now - lastShown_ < kRefresh)) return;
    const double f = fractionDone(step, static_cast<double>(modules));
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    std::string line = "\rgraftal: ";
    if (f < 0) {
        line += "step " + std::to_string(step) + ", " + shortCount(static_cast<double>(modules)) +
                " modules";
    } else {
        // A streamed picture walks the derivation twice (measure, then draw): a fraction
        // that falls back is the second pass starting.
        char pct[16];
        std::snprintf(pct, sizeof pct, "%3.0f%%", 100 * f);
        line += std::string(pct) + " (step " + std::to_string(step) + " of " +
                std::to_string(perStep_.size() - 1) + ")";
        const int last = static_cast<int>(perStep_.size()) - 1;
        const double work = step == last ? static_cast<double>(modules) : doneThrough_[step];
        if (elapsed > 0) line += ", " + shortCount(work / elapsed) + " modules/s";
        if (f > 0.01 && f < 1 && f >= lastFraction_)
            line += ", about " + duration(elapsed * (1 - f) / f) + " left";
    }
    lastFraction_ = f;
    std::cerr << line << "      " << std::flush;
    shown_ = true;
    lastShown_ = now;
}

void ProgressLine::end() {
    if (shown_) std::cerr << '\n' << std::flush;
    shown_ = false;
}

}  // namespace graftal::cli
