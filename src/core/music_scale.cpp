// Scale names, scale lists and note names (see music_scale.hpp).
#include "graftal/core/music_scale.hpp"

#include <cctype>
#include <cstdlib>

namespace graftal {

namespace {

struct NamedScale {
    const char* name;
    ScaleSteps steps;
};

const std::vector<NamedScale>& namedScales() {
    static const std::vector<NamedScale> scales = {
        {"major", {0, 2, 4, 5, 7, 9, 11}},
        {"minor", {0, 2, 3, 5, 7, 8, 10}},
        {"pentatonic", {0, 2, 4, 7, 9}},
        {"blues", {0, 3, 5, 6, 7, 10}},
        {"chromatic", {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11}},
    };
    return scales;
}

std::string lower(std::string_view s) {
    std::string out(s);
    for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

std::string_view trimmed(std::string_view s) {
    std::size_t a = s.find_first_not_of(" \t\r\n");
    if (a == std::string_view::npos) return {};
    return s.substr(a, s.find_last_not_of(" \t\r\n") - a + 1);
}

}  // namespace

const std::vector<std::string>& scaleNames() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> n;
        for (const auto& s : namedScales()) n.emplace_back(s.name);
        return n;
    }();
    return names;
}

std::string parseScale(std::string_view text, ScaleSteps& out) {
    std::string_view t = trimmed(text);
    if (t.empty()) return "expected a scale name or a list of semitone offsets";
    if (std::isalpha(static_cast<unsigned char>(t[0]))) {
        std::string name = lower(t);
        for (const auto& s : namedScales())
            if (name == s.name) {
                out = s.steps;
                return "";
            }
        std::string list;
        for (const auto& n : scaleNames()) list += (list.empty() ? "" : ", ") + n;
        return "unknown scale '" + std::string(t) + "' (expected " + list +
               ", or a list of semitone offsets such as 0 2 4 7 9)";
    }
    ScaleSteps steps;
    std::string item;
    auto flush = [&]() -> std::string {
        if (item.empty()) return "";
        char* end = nullptr;
        long v = std::strtol(item.c_str(), &end, 10);
        if (*end) return "'" + item + "' is not a whole number of semitones";
        if (v < 0 || v > 11)
            return "scale offset " + item + " is outside one octave (expected 0 to 11)";
        if (steps.empty() && v != 0) return "a scale list starts at 0, the root (got " + item + ")";
        if (!steps.empty() && v <= steps.back())
            return "a scale list must be increasing, but " + item + " follows " +
                   std::to_string(steps.back());
        steps.push_back(static_cast<int>(v));
        item.clear();
        return "";
    };
    for (char c : t) {
        if (c == ',' || std::isspace(static_cast<unsigned char>(c))) {
            if (std::string e = flush(); !e.empty()) return e;
        } else {
            item += c;
        }
    }
    if (std::string e = flush(); !e.empty()) return e;
    if (steps.empty()) return "expected a scale name or a list of semitone offsets";
    out = std::move(steps);
    return "";
}

std::string parseNoteName(std::string_view text, int& out) {
    std::string_view t = trimmed(text);
    if (t.empty()) return "expected a note such as C4 or a MIDI note number";
    if (std::isdigit(static_cast<unsigned char>(t[0]))) {
        std::string s(t);
        char* end = nullptr;
        long v = std::strtol(s.c_str(), &end, 10);
        if (*end || v < 0 || v > 127)
            return "'" + s + "' is not a MIDI note number (expected 0 to 127) or a note name";
        out = static_cast<int>(v);
        return "";
    }
    static const int letterSemitone[] = {9, 11, 0, 2, 4, 5, 7};  // A B C D E F G
    char letter = static_cast<char>(std::toupper(static_cast<unsigned char>(t[0])));
    if (letter < 'A' || letter > 'G')
        return "'" + std::string(t) + "' is not a note name (expected e.g. C4, F#3, Bb2)";
    int semitone = letterSemitone[letter - 'A'];
    std::size_t i = 1;
    while (i < t.size() && (t[i] == '#' || t[i] == 'b' || t[i] == 's')) {
        semitone += t[i] == 'b' ? -1 : 1;
        ++i;
    }
    std::string octaveText(t.substr(i));
    char* end = nullptr;
    long octave = std::strtol(octaveText.c_str(), &end, 10);
    if (octaveText.empty() || *end)
        return "'" + std::string(t) + "' needs an octave number (e.g. C4, middle C)";
    long midi = (octave + 1) * 12 + semitone;
    if (midi < 0 || midi > 127)
        return "note " + std::string(t) + " is outside the MIDI range (C-1 to G9)";
    out = static_cast<int>(midi);
    return "";
}

std::string noteName(int midiNote) {
    static const char* names[] = {"C", "C#", "D", "D#", "E", "F", "F#", "G", "G#", "A", "A#", "B"};
    int octave = (midiNote >= 0 ? midiNote / 12 : (midiNote - 11) / 12) - 1;
    int pc = ((midiNote % 12) + 12) % 12;
    return std::string(names[pc]) + std::to_string(octave);
}

}  // namespace graftal
