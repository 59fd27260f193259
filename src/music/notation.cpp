// Bars of plain and dotted note values (see notation.hpp).
#include "notation.hpp"

#include <algorithm>
#include <cmath>

namespace graftal::notation {

namespace {

// The largest written value that fits in `units`.
int largestValue(int units) {
    static const int values[] = {64, 48, 32, 24, 16, 12, 8, 6, 4, 3, 2, 1};
    for (int v : values)
        if (v <= units) return v;
    return 1;
}

// Appends a sounding span (or a rest) [from, to) in units, split at bar lines and into
// written values; the pieces of one note are tied.
void appendSpan(std::vector<Bar>& out, long from, long to, bool rest, int pitch) {
    long at = from;
    while (at < to) {
        auto bar = static_cast<std::size_t>(at / kUnitsPerBar);
        if (out.size() <= bar) out.resize(bar + 1);
        long barEnd = (static_cast<long>(bar) + 1) * kUnitsPerBar;
        long end = std::min(to, barEnd);
        while (at < end) {
            int v = largestValue(static_cast<int>(end - at));
            out[bar].push_back(Piece{rest, pitch, v, !rest && at + v < to});
            at += v;
        }
    }
}

}  // namespace

std::vector<Bar> bars(const Score& score) {
    std::vector<Bar> out;
    long clock = 0;
    for (const Note& n : score.notes) {
        long start = std::max(clock, std::lround(n.start * kUnitsPerBeat));
        long end = std::max(start + 1, std::lround((n.start + n.duration) * kUnitsPerBeat));
        if (start > clock) appendSpan(out, clock, start, true, 0);
        appendSpan(out, start, end, false, n.pitch);
        clock = end;
    }
    // The last bar filled with rests, so that every bar is complete.
    long full = (clock + kUnitsPerBar - 1) / kUnitsPerBar * kUnitsPerBar;
    if (full > clock) appendSpan(out, clock, full, true, 0);
    return out;
}

int noteValue(int units, bool& dotted) {
    dotted = units == 48 || units == 24 || units == 12 || units == 6 || units == 3;
    int plain = dotted ? units * 2 / 3 : units;
    return kUnitsPerBar / plain;
}

}  // namespace graftal::notation
