// Scales and note names for the musical reading of curves (LSFP ch. 6.3): the words a file's
// `music scale:` and `music root:` settings and the `graftal music` options accept. They live
// in the core so that the parser checks a file's settings where it reads them.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace graftal {

// The semitone offsets of one octave of a scale, from its root: strictly increasing, the
// first 0, every one below 12. The octave repeats every 12 semitones.
using ScaleSteps = std::vector<int>;

// The scale names: major, minor (natural), pentatonic (major), blues, chromatic.
const std::vector<std::string>& scaleNames();

// A scale from a name or a list of semitone offsets ("0 2 4 7 9" or "0,2,4,7,9"). Returns ""
// and sets `out`, or the message of what is wrong (an unknown name, a list that does not
// start at 0 or is not increasing, an offset of 12 or more).
std::string parseScale(std::string_view text, ScaleSteps& out);

// A MIDI note number from a note name with its octave (C4 is 60, middle C; A4 is 69; sharps
// C#4, flats Bb3) or a plain number 0..127. Returns "" and sets `out`, or the message.
std::string parseNoteName(std::string_view text, int& out);

// The name of a MIDI note number: 60 -> "C4", 61 -> "C#4".
std::string noteName(int midiNote);

}  // namespace graftal
