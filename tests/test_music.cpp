// Fractal music (LSFP ch. 6.3): the Hilbert curve read as notes, and every file format read
// back the way a user's program would read it.
#include <glib.h>  // before smf.h, which includes it inside extern "C"
#include <gtest/gtest.h>
#include <smf.h>

#include <cstdint>
#include <cstdio>
#include <regex>

#include "graftal/music/music.hpp"
#include "process.hpp"
#include "test_helpers.hpp"

using graftal::testing::parseModel;
using graftal::testing::readFile;
using graftal::testing::runGraftal;
using graftal::testing::TempDir;

namespace graftal {
namespace {

const char* kHilbert2 =
    "Lsystem: 1\nderivation length: 2\nangle factor: 4\naxiom: X\n"
    "X --> -YF+XFX+FY-\nY --> +XF-YFY-FX+\nendlsystem\n";

Score hilbertScore(MusicOptions options = {}) {
    return scoreFromModel(parseModel(kHilbert2, "hilbert.l"), -1, options);
}

// The Hilbert curve after two steps, '+' turning left and the turtle starting up, visits
//   (0,0) (0,1) (1,1) (1,0) (2,0) (3,0) (3,1) (2,1) (2,2) (3,2) (3,3) (2,3) (1,3) (1,2)
//   (0,2) (0,3).
// Its horizontal runs, in order: y=1 length 1; y=0 length 2 (two segments, one note);
// y=1 length 1; y=2 length 1; y=3 length 2; y=2 length 1. The first note is the root C4 at
// y=1, so the heights are the scale degrees 0, -1, 0, 1, 2, 1 of C major: C4 B3 C4 D4 E4
// D4, lasting 1 2 1 1 2 1 beats.
TEST(Music, HilbertTwoStepsGivesTheNotesWorkedOutByHand) {
    Score s = hilbertScore();
    std::vector<Note> expected = {{60, 0, 1, 80}, {59, 1, 2, 80}, {60, 3, 1, 80},
                                  {62, 4, 1, 80}, {64, 5, 2, 80}, {62, 7, 1, 80}};
    EXPECT_EQ(s.notes, expected);
    EXPECT_DOUBLE_EQ(s.beats(), 8);
    EXPECT_DOUBLE_EQ(s.seconds(), 4);  // 120 beats per minute
    EXPECT_EQ(s.title, "hilbert");
}

TEST(Music, ScaleRootUnitAndAxisChangeTheReading) {
    MusicOptions o;
    ASSERT_EQ(parseScale("pentatonic", o.scale), "");
    ASSERT_EQ(parseNoteName("A3", o.root), "");
    o.unit = 0.5;
    Score s = hilbertScore(o);
    // Degrees 0 -1 0 1 2 1 of A pentatonic (offsets 0 2 4 7 9): A3 F#3(-1: 9-12) A3 B3 C#4 B3.
    std::vector<int> pitches;
    for (const Note& n : s.notes) pitches.push_back(n.pitch);
    EXPECT_EQ(pitches, (std::vector<int>{57, 54, 57, 59, 61, 59}));
    EXPECT_DOUBLE_EQ(s.notes[1].duration, 1);  // two steps of half a beat
    EXPECT_DOUBLE_EQ(s.beats(), 4);

    // Read sideways, the vertical runs are the notes: x=0 (1 step), x=1 (1), x=3 (1), x=2 (1),
    // x=3 (1), x=1 (1), x=0 (1): degrees 0 1 3 2 3 1 0 of C major.
    MusicOptions sideways;
    sideways.pitchFromX = true;
    pitches.clear();
    for (const Note& n : hilbertScore(sideways).notes) pitches.push_back(n.pitch);
    EXPECT_EQ(pitches, (std::vector<int>{60, 62, 65, 64, 65, 62, 60}));
}

TEST(Music, ScalesAndNoteNamesParse) {
    ScaleSteps steps;
    EXPECT_EQ(parseScale("blues", steps), "");
    EXPECT_EQ(steps, (ScaleSteps{0, 3, 5, 6, 7, 10}));
    EXPECT_EQ(parseScale("0, 2, 4, 7, 9", steps), "");
    EXPECT_EQ(steps, (ScaleSteps{0, 2, 4, 7, 9}));
    EXPECT_NE(parseScale("0 4 2", steps).find("must be increasing, but 2 follows 4"),
              std::string::npos);
    EXPECT_NE(parseScale("0 4 4", steps).find("increasing"), std::string::npos);
    EXPECT_NE(parseScale("2 4", steps).find("starts at 0"), std::string::npos);
    EXPECT_NE(parseScale("0 12", steps).find("outside one octave"), std::string::npos);
    EXPECT_NE(parseScale("lydian", steps).find("unknown scale 'lydian'"), std::string::npos);
    int n = 0;
    EXPECT_EQ(parseNoteName("C4", n), "");
    EXPECT_EQ(n, 60);
    EXPECT_EQ(parseNoteName("f#3", n), "");
    EXPECT_EQ(n, 54);
    EXPECT_EQ(parseNoteName("Bb2", n), "");
    EXPECT_EQ(n, 46);
    EXPECT_EQ(parseNoteName("69", n), "");
    EXPECT_EQ(n, 69);
    EXPECT_NE(parseNoteName("H4", n), "");
    EXPECT_NE(parseNoteName("C", n).find("octave"), std::string::npos);
    EXPECT_NE(parseNoteName("G10", n).find("outside the MIDI range"), std::string::npos);
    EXPECT_EQ(noteName(61), "C#4");
}

std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.diagnostics().front().toString();
    }
    return "";
}

TEST(Music, CurvesThatCannotBePlayedAreClearErrors) {
    // Only vertical segments: no notes.
    Model up = parseModel("Lsystem: 1\naxiom: FFF\nendlsystem\n", "up.l");
    std::string e = errorOf([&] { scoreFromModel(up, -1, {}); });
    EXPECT_NE(e.find("up.l"), std::string::npos) << e;
    EXPECT_NE(e.find("no horizontal segments"), std::string::npos) << e;

    // From F9 (125), two degrees of C major up is 125 + 4 = 129: past G9 (127).
    MusicOptions high;
    high.root = 125;
    e = errorOf([&] { hilbertScore(high); });
    EXPECT_NE(e.find("note 5 at (3, 3)"), std::string::npos) << e;
    EXPECT_NE(e.find("MIDI pitch 129, outside MIDI's range 0 to 127"), std::string::npos) << e;
    MusicOptions bad;
    bad.scale = {0, 4, 2};
    e = errorOf([&] { hilbertScore(bad); });
    EXPECT_NE(e.find("increasing"), std::string::npos) << e;
}

TEST(Music, CommandRefusesAndLeavesNoFile) {
    TempDir t;
    // Up, then 45 degrees left, up, 45 degrees left: no horizontal segment.
    auto file = t.write("up.l", "Lsystem: 1\naxiom: F+F-F+F\nangle factor: 8\nendlsystem\n");
    auto out = t.path() / "up.mid";
    auto r = runGraftal("music " + file.string() + " -o " + out.string());
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("no horizontal segments"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));

    auto hilbert = t.write("h.l", kHilbert2);
    r = runGraftal("music " + hilbert.string() + " --scale 0,4,2 -o " + out.string());
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("--scale: a scale list must be increasing"), std::string::npos) << r.err;
    r = runGraftal("music " + hilbert.string() + " --root C9 --scale chromatic -o " +
                   (t.path() / "x.txt").string());
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("expected a music file"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(t.path() / "x.txt"));
}

TEST(Music, FileSettingsAreReadAndCheckedWhereTheyStand) {
    Model m = parseModel(
        std::string(kHilbert2).insert(std::string(kHilbert2).find("axiom"),
                                      "music scale: minor\nmusic root: D4\nmusic tempo: 90\n"
                                      "music instrument: 41\nmusic unit: 0.5\n"),
        "h.l");
    MusicOptions o = musicOptions(m.view);
    EXPECT_EQ(o.scale, (ScaleSteps{0, 2, 3, 5, 7, 8, 10}));
    EXPECT_EQ(o.root, 62);
    EXPECT_DOUBLE_EQ(o.tempo, 90);
    EXPECT_EQ(o.instrument, 41);
    EXPECT_DOUBLE_EQ(o.unit, 0.5);

    std::string e =
        graftal::testing::parseError("Lsystem: 1\nmusic scale: 0 7 5\naxiom: F\nendlsystem\n");
    EXPECT_NE(e.find("test.l:2:14"), std::string::npos) << e;
    EXPECT_NE(e.find("increasing"), std::string::npos) << e;
    e = graftal::testing::parseError("Lsystem: 1\nmusic root: Q4\naxiom: F\nendlsystem\n");
    EXPECT_NE(e.find("test.l:2:13"), std::string::npos) << e;
}

TEST(Music, MidiFileReadsBackWithLibsmf) {
    TempDir t;
    Score s = hilbertScore();
    s.instrument = 74;  // flute
    auto path = t.path() / "h.mid";
    writeScore(s, path);
    smf_t* smf = smf_load(path.c_str());
    ASSERT_NE(smf, nullptr);
    EXPECT_EQ(smf->ppqn, 480);
    std::vector<std::pair<int, int>> ons;   // pitch, tick
    std::vector<std::pair<int, int>> offs;  // pitch, tick
    long tempo = -1;
    int program = -1;
    while (smf_event_t* e = smf_get_next_event(smf)) {
        const unsigned char* b = e->midi_buffer;
        if (e->midi_buffer_length >= 6 && b[0] == 0xFF && b[1] == 0x51)
            tempo = (b[3] << 16) | (b[4] << 8) | b[5];
        else if ((b[0] & 0xF0) == 0xC0)
            program = b[1];
        else if ((b[0] & 0xF0) == 0x90 && b[2] > 0)
            ons.push_back({b[1], e->time_pulses});
        else if ((b[0] & 0xF0) == 0x80 || ((b[0] & 0xF0) == 0x90 && b[2] == 0))
            offs.push_back({b[1], e->time_pulses});
    }
    EXPECT_EQ(tempo, 500000);  // 120 beats per minute
    EXPECT_EQ(program, 73);
    EXPECT_EQ(ons, (std::vector<std::pair<int, int>>{
                       {60, 0}, {59, 480}, {60, 1440}, {62, 1920}, {64, 2400}, {62, 3360}}));
    EXPECT_EQ(offs, (std::vector<std::pair<int, int>>{
                        {60, 480}, {59, 1440}, {60, 1920}, {62, 2400}, {64, 3360}, {62, 3840}}));
    EXPECT_NEAR(smf_get_length_seconds(smf), 4.0, 1e-6);
    smf_delete(smf);
}

std::uint32_t le32(const std::string& s, std::size_t at) {
    return static_cast<std::uint8_t>(s[at]) | static_cast<std::uint8_t>(s[at + 1]) << 8 |
           static_cast<std::uint8_t>(s[at + 2]) << 16 |
           static_cast<std::uint32_t>(static_cast<std::uint8_t>(s[at + 3])) << 24;
}

TEST(Music, WavLastsAsLongAsTheScoreAndIsNotSilent) {
    if (findSoundFont().empty()) GTEST_SKIP() << "no General MIDI SoundFont installed";
    TempDir t;
    Score s = hilbertScore();
    auto path = t.path() / "h.wav";
    AudioOptions audio;
    audio.sampleRate = 16000;
    audio.releaseSeconds = 0.5;
    writeWav(s, path, audio);
    std::string w = readFile(path);
    ASSERT_GE(w.size(), 44u);
    EXPECT_EQ(w.substr(0, 4), "RIFF");
    EXPECT_EQ(w.substr(8, 8), "WAVEfmt ");
    EXPECT_EQ(le32(w, 24), 16000u);
    std::uint32_t bytes = le32(w, 40);
    EXPECT_EQ(bytes + 44, w.size());
    double seconds = bytes / 2.0 / 16000.0;
    EXPECT_NEAR(seconds, s.seconds() + 0.5, 1.0 / 16000);
    // Loud while the notes play: every half second of the 4 has a sample above a tenth of
    // full scale.
    for (int half = 0; half < 8; ++half) {
        int peak = 0;
        for (std::size_t i = 44 + half * 16000; i < 44 + (half + 1) * 16000u; i += 2) {
            int v = static_cast<std::int16_t>(static_cast<std::uint8_t>(w[i]) |
                                              static_cast<std::uint8_t>(w[i + 1]) << 8);
            peak = std::max(peak, std::abs(v));
        }
        EXPECT_GT(peak, 3276) << "half second " << half;
    }
}

TEST(Music, LilyPondSourceCompilesToAPdf) {
    Score s = hilbertScore();
    std::string ly = lilyPondSource(s);
    // Two bars of 4/4: C4 B3(half) C4 | D4 E4(half) D4.
    EXPECT_NE(ly.find("c'4 b2 c'4 |"), std::string::npos) << ly;
    EXPECT_NE(ly.find("d'4 e'2 d'4 |"), std::string::npos) << ly;
    EXPECT_NE(ly.find("\\tempo 4 = 120"), std::string::npos);
    if (findLilyPond().empty()) GTEST_SKIP() << "lilypond is not installed";
    TempDir t;
    auto pdf = t.path() / "h.pdf";
    writeScore(s, pdf);
    std::string bytes = readFile(pdf);
    ASSERT_EQ(bytes.substr(0, 5), "%PDF-");
    FILE* p = ::popen(("pdfinfo " + pdf.string() + " 2>/dev/null").c_str(), "r");
    ASSERT_NE(p, nullptr);
    std::string info;
    char buf[256];
    while (std::fgets(buf, sizeof buf, p)) info += buf;
    ::pclose(p);
    std::smatch m;
    ASSERT_TRUE(std::regex_search(info, m, std::regex("Pages:\\s+(\\d+)"))) << info;
    EXPECT_GE(std::stoi(m[1]), 1);

    auto png = t.path() / "h.png";
    writeScore(s, png);
    EXPECT_EQ(readFile(png).substr(1, 3), "PNG");
    // A note that crosses a bar line is split and tied.
    Score across;
    across.notes = {{60, 0, 3, 80}, {62, 3, 2, 80}};
    EXPECT_NE(lilyPondSource(across).find("c'2. d'4 ~ |\n    d'4 r2. |"), std::string::npos)
        << lilyPondSource(across);
}

TEST(Music, EngravingWithoutLilyPondSaysHowToGetIt) {
    TempDir t;
    ::setenv("GRAFTAL_LILYPOND", "", 1);
    std::string oldPath = std::getenv("PATH") ? std::getenv("PATH") : "";
    ::setenv("PATH", t.path().c_str(), 1);
    auto pdf = t.path() / "h.pdf";
    std::string e = errorOf([&] { writeScore(hilbertScore(), pdf); });
    ::setenv("PATH", oldPath.c_str(), 1);
    EXPECT_NE(e.find("lilypond program is not installed"), std::string::npos) << e;
    EXPECT_NE(e.find("apt-get install lilypond"), std::string::npos) << e;
    EXPECT_FALSE(std::filesystem::exists(pdf));
    writeScore(hilbertScore(), t.path() / "h.ly");  // needs nothing
    EXPECT_TRUE(std::filesystem::exists(t.path() / "h.ly"));
}

// A small XML reader: elements balance, and the notes' pitches and durations are collected.
struct XmlNotes {
    bool balanced = true;
    std::vector<std::string> pitches;  // "C4", "B3", ... (rests as "r")
    std::vector<int> durations;
    int ties = 0;
};

XmlNotes readMusicXml(const std::string& xml) {
    XmlNotes r;
    std::vector<std::string> open;
    std::string step, octave, duration, alter;
    bool rest = false;
    std::size_t i = 0;
    while ((i = xml.find('<', i)) != std::string::npos) {
        std::size_t end = xml.find('>', i);
        if (end == std::string::npos) return r.balanced = false, r;
        std::string tag = xml.substr(i + 1, end - i - 1);
        std::size_t textEnd = xml.find('<', end);
        std::string text = xml.substr(end + 1, textEnd - end - 1);
        i = end + 1;
        if (tag[0] == '?' || tag[0] == '!') continue;
        bool closing = tag[0] == '/', selfClosing = tag.back() == '/';
        std::string name = tag.substr(closing ? 1 : 0);
        name = name.substr(0, name.find_first_of(" /"));
        if (closing) {
            if (open.empty() || open.back() != name) return r.balanced = false, r;
            open.pop_back();
            if (name == "note") {
                r.pitches.push_back(rest ? "r" : step + (alter == "1" ? "#" : "") + octave);
                r.durations.push_back(std::stoi(duration));
                rest = false;
                alter.clear();
            }
        } else if (!selfClosing) {
            open.push_back(name);
            if (name == "step") step = text;
            if (name == "octave") octave = text;
            if (name == "duration") duration = text;
            if (name == "alter") alter = text;
        } else {
            if (name == "rest") rest = true;
            if (name == "tie" && tag.find("start") != std::string::npos) ++r.ties;
        }
    }
    r.balanced = r.balanced && open.empty();
    return r;
}

TEST(Music, MusicXmlReparses) {
    TempDir t;
    auto path = t.path() / "h.musicxml";
    writeScore(hilbertScore(), path);
    std::string xml = readFile(path);
    EXPECT_NE(xml.find("<score-partwise version=\"4.0\">"), std::string::npos);
    XmlNotes n = readMusicXml(xml);
    EXPECT_TRUE(n.balanced);
    EXPECT_EQ(n.pitches, (std::vector<std::string>{"C4", "B3", "C4", "D4", "E4", "D4"}));
    EXPECT_EQ(n.durations, (std::vector<int>{16, 32, 16, 16, 32, 16}));  // 16 a beat
    EXPECT_EQ(n.ties, 0);

    Score across;
    across.notes = {{61, 0, 3, 80}, {62, 3, 2, 80}};
    n = readMusicXml(musicXml(across));
    EXPECT_TRUE(n.balanced);
    EXPECT_EQ(n.pitches, (std::vector<std::string>{"C#4", "D4", "D4", "r"}));
    EXPECT_EQ(n.durations, (std::vector<int>{48, 16, 16, 48}));
    EXPECT_EQ(n.ties, 1);
}

TEST(Music, CommandWritesEveryFormatOfTheFig69Example) {
    TempDir t;
    const std::string example = std::string(GRAFTAL_EXAMPLES_DIR) + "/fig6.9-hilbert-music.l";
    for (const char* ext : {"mid", "ly", "musicxml"}) {
        auto out = t.path() / (std::string("h.") + ext);
        auto r = runGraftal("music " + example + " -o " + out.string());
        EXPECT_EQ(r.status, 0) << r.err;
        EXPECT_GT(std::filesystem::file_size(out), 100u) << ext;
    }
}

}  // namespace
}  // namespace graftal
