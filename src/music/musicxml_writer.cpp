// MusicXML 4.0 (score-partwise): one part, bars of 4/4, for notation programs.
#include <cmath>
#include <sstream>

#include "graftal/core/atomic_file.hpp"
#include "graftal/core/xml_text.hpp"
#include "graftal/music/music.hpp"
#include "notation.hpp"

namespace graftal {

namespace {

const char* typeName(int value) {
    switch (value) {
        case 1:
            return "whole";
        case 2:
            return "half";
        case 4:
            return "quarter";
        case 8:
            return "eighth";
        case 16:
            return "16th";
        case 32:
            return "32nd";
        default:
            return "64th";
    }
}

void writePitch(std::ostream& os, int midi) {
    static const char steps[] = {'C', 'C', 'D', 'D', 'E', 'F', 'F', 'G', 'G', 'A', 'A', 'B'};
    static const int alters[] = {0, 1, 0, 1, 0, 0, 1, 0, 1, 0, 1, 0};
    int pc = midi % 12;
    os << "        <pitch><step>" << steps[pc] << "</step>";
    if (alters[pc]) os << "<alter>1</alter>";
    os << "<octave>" << midi / 12 - 1 << "</octave></pitch>\n";
}

}  // namespace

std::string musicXml(const Score& score) {
    double mean = 0;
    for (const Note& n : score.notes) mean += n.pitch;
    if (!score.notes.empty()) mean /= static_cast<double>(score.notes.size());
    const bool bass = mean < 57;

    std::ostringstream os;
    os << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
          "<!DOCTYPE score-partwise PUBLIC \"-//Recordare//DTD MusicXML 4.0 Partwise//EN\" "
          "\"http://www.musicxml.org/dtds/partwise.dtd\">\n"
          "<score-partwise version=\"4.0\">\n";
    if (!score.title.empty())
        os << "  <work><work-title>" << xmlEscaped(score.title) << "</work-title></work>\n";
    os << "  <identification><encoding><software>graftal</software></encoding>"
          "</identification>\n";
    os << "  <part-list>\n    <score-part id=\"P1\">\n      <part-name>Curve</part-name>\n"
          "      <score-instrument id=\"P1-I1\"><instrument-name>General MIDI "
       << score.instrument
       << "</instrument-name></score-instrument>\n"
          "      <midi-instrument id=\"P1-I1\"><midi-channel>1</midi-channel><midi-program>"
       << score.instrument << "</midi-program></midi-instrument>\n    </score-part>\n"
       << "  </part-list>\n  <part id=\"P1\">\n";
    bool tiedIn = false;
    const std::vector<notation::Bar> bars = notation::bars(score);
    for (std::size_t b = 0; b < bars.size(); ++b) {
        os << "    <measure number=\"" << b + 1 << "\">\n";
        if (b == 0) {
            os << "      <attributes><divisions>" << notation::kUnitsPerBeat
               << "</divisions><key><fifths>0</fifths></key><time><beats>4</beats>"
                  "<beat-type>4</beat-type></time><clef><sign>"
               << (bass ? "F" : "G") << "</sign><line>" << (bass ? 4 : 2)
               << "</line></clef></attributes>\n";
            os << "      <direction placement=\"above\"><direction-type><metronome>"
                  "<beat-unit>quarter</beat-unit><per-minute>"
               << std::lround(score.tempo)
               << "</per-minute></metronome></direction-type><sound tempo=\"" << score.tempo
               << "\"/></direction>\n";
        }
        for (const notation::Piece& p : bars[b]) {
            bool dotted = false;
            int value = notation::noteValue(p.units, dotted);
            os << "      <note>\n";
            if (p.rest)
                os << "        <rest/>\n";
            else
                writePitch(os, p.pitch);
            os << "        <duration>" << p.units << "</duration>\n";
            if (tiedIn) os << "        <tie type=\"stop\"/>\n";
            if (p.tieToNext) os << "        <tie type=\"start\"/>\n";
            os << "        <voice>1</voice>\n        <type>" << typeName(value) << "</type>\n";
            if (dotted) os << "        <dot/>\n";
            if (tiedIn || p.tieToNext) {
                os << "        <notations>";
                if (tiedIn) os << "<tied type=\"stop\"/>";
                if (p.tieToNext) os << "<tied type=\"start\"/>";
                os << "</notations>\n";
            }
            os << "      </note>\n";
            tiedIn = p.tieToNext;
        }
        if (b + 1 == bars.size())
            os << "      <barline location=\"right\"><bar-style>light-heavy</bar-style>"
                  "</barline>\n";
        os << "    </measure>\n";
    }
    os << "  </part>\n</score-partwise>\n";
    return os.str();
}

void writeMusicXml(const Score& score, const Destination& destination) {
    std::string text = musicXml(score);
    destination.write("MusicXML score", [&](std::ostream& out) { out << text; });
}

}  // namespace graftal
