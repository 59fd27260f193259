// A score as written notation: bars of 4/4 filled with notes and rests whose lengths are
// plain or dotted note values, split at bar lines and tied. What the LilyPond and MusicXML
// writers share.
#pragma once

#include <vector>

#include "graftal/music/music.hpp"

namespace graftal::notation {

// Lengths are counted in 64th notes: a beat (a quarter note) is 16, a 4/4 bar 64. Note
// starts and lengths are rounded to this grid (a note never shorter than one 64th).
inline constexpr int kUnitsPerBeat = 16;
inline constexpr int kUnitsPerBar = 64;

struct Piece {
    bool rest = false;
    int pitch = 60;
    int units = 16;          // 64, 48, 32, 24, 16, 12, 8, 6, 4, 3, 2 or 1
    bool tieToNext = false;  // continues into the next piece (the same note)
};

using Bar = std::vector<Piece>;

std::vector<Bar> bars(const Score& score);

// The plain value of a piece (1 whole, 2 half, 4 quarter, ... 64) and whether it is dotted.
int noteValue(int units, bool& dotted);

}  // namespace graftal::notation
