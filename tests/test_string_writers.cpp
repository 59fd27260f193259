// The derived string's writers (text and JSON, held and streamed), the streamed derivation
// in runs, and their rows in the export registry: exact bytes, as `graftal derive` prints.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "graftal/lang/model.hpp"
#include "graftal/output/string_json_writer.hpp"
#include "graftal/output/string_text_writer.hpp"
#include "graftal/pipeline/export.hpp"
#include "graftal/rewrite/derivation.hpp"
#include "graftal/rewrite/streamed_runs.hpp"
#include "graftal/rewrite/streaming.hpp"
#include "graftal/studio/studio_model.hpp"
#include "process.hpp"

using namespace graftal;
using graftal::testing::runGraftal;

namespace {

std::string textOf(const ModuleString& s, const SymbolTable& t, unsigned threads = 0) {
    std::ostringstream out;
    writeStringText(s, t, out, threads);
    return out.str();
}

std::string jsonOf(const ModuleString& s, const SymbolTable& t, unsigned threads = 0) {
    std::ostringstream out;
    writeStringJson(s, t, StringJsonHeader{"x.l", 3}, out, threads);
    return out.str();
}

// Parameters of every kind the printer must keep: integers, -0, fractions, tiny and huge
// values, values a float rounds, and what JSON has no number for.
ModuleString awkwardParameters(Precision precision) {
    const double inf = std::numeric_limits<double>::infinity();
    ModuleString s(precision);
    s.push('F', std::vector<double>{0, -0.0, 1, 2.5, -3});
    s.push('+');
    s.push('A', std::vector<double>{0.1, 1e-7, 1e20, 123456789, 1.0 / 3});
    s.push('[');
    s.push('B', std::vector<double>{std::nan(""), inf, -inf});
    s.push(']');
    s.push('C', std::vector<double>{1e15, 999999999999999, 6.02214076e23, -2.5e-300});
    return s;
}

Model modelOf(const std::string& text) {
    ParseResult parsed = parse(text, {});
    EXPECT_TRUE(parsed.ok()) << parsed.errors().front().message;
    return parsed.model;
}

}  // namespace

TEST(StringTextWriter, FloatsPrintInTheirShortestForm) {
    const SymbolTable t;
    EXPECT_EQ(textOf(awkwardParameters(Precision::Single), t),
              "F(0,0,1,2.5,-3)+A(0.1,1e-07,1e+20,123456792,0.33333334)[B(nan,inf,-inf)]"
              "C(1e+15,1e+15,6.0221406e+23,0)\n");
    EXPECT_EQ(textOf(awkwardParameters(Precision::Double), t),
              "F(0,0,1,2.5,-3)+A(0.1,1e-07,1e+20,123456789,0.3333333333333333)[B(nan,inf,-inf)]"
              "C(1e+15,999999999999999,6.02214076e+23,-2.5e-300)\n");
}

TEST(StringTextWriter, SameBytesAsTheModuleStringPrintsForAnyThreadCount) {
    // Longer than one chunk, with names of several letters: chunks meet mid-string.
    SymbolTable t;
    const Symbol leaf = t.declare("leaf");
    ModuleString s(Precision::Single);
    for (int i = 0; i < 2'500'000; ++i) {
        if (i % 7 == 0)
            s.push(leaf, std::vector<double>{i * 0.25, 1.0 / (i + 1)});
        else
            s.push(static_cast<Symbol>("F+-[]"[i % 5]));
    }
    const std::string expected = s.toString(t) + "\n";
    for (unsigned threads : {1u, 2u, 3u}) EXPECT_EQ(textOf(s, t, threads), expected) << threads;
}

TEST(StringTextWriter, AStringWithoutParametersIsItsOwnText) {
    SymbolTable t;
    ModuleString s;
    for (int i = 0; i < 3'000'000; ++i) s.push(static_cast<Symbol>("F+F-"[i % 4]));
    EXPECT_EQ(textOf(s, t, 2), s.toString(t) + "\n");
    // One declared name among them: no longer its own text.
    s.push(t.declare("apex"));
    const std::string text = textOf(s, t, 2);
    EXPECT_EQ(text.substr(text.size() - 6), "-apex\n");
    EXPECT_EQ(text, s.toString(t) + "\n");
    EXPECT_EQ(textOf(ModuleString(), t), "\n");
}

TEST(StringJsonWriter, OneObjectPerModuleNullForWhatJsonCannotHold) {
    SymbolTable t;
    const Symbol quote = t.declare("q\"\\");
    ModuleString s(Precision::Single);
    s.push('F', std::vector<double>{2.5, std::nan("")});
    s.push(quote);
    s.push('"');
    EXPECT_EQ(jsonOf(s, t),
              "{\n  \"file\": \"x.l\",\n  \"steps\": 3,\n  \"modules\": [\n"
              "    {\"symbol\": \"F\", \"params\": [2.5, null]},\n"
              "    {\"symbol\": \"q\\\"\\\\\", \"params\": []},\n"
              "    {\"symbol\": \"\\\"\", \"params\": []}\n  ]\n}\n");
    EXPECT_EQ(jsonOf(ModuleString(), t),
              "{\n  \"file\": \"x.l\",\n  \"steps\": 3,\n  \"modules\": []\n}\n");
}

TEST(StringJsonWriter, ChunksMeetWhereTheyShould) {
    SymbolTable t;
    ModuleString s(Precision::Double);
    for (int i = 0; i < 2'200'000; ++i) s.push('A', std::vector<double>{i * 0.5});
    const std::string one = jsonOf(s, t, 1);
    EXPECT_EQ(jsonOf(s, t, 2), one);
    EXPECT_EQ(jsonOf(s, t, 3), one);
    EXPECT_NE(one.find("\"params\": [1048575.5]},\n    {\"symbol\": \"A\", \"params\": [1048576]}"),
              std::string::npos);
    EXPECT_EQ(one.substr(one.size() - 45),
              "{\"symbol\": \"A\", \"params\": [1099999.5]}\n  ]\n}\n");
}

TEST(StringWriters, StreamedBytesEqualTheHeldOnes) {
    // Parametric and stochastic: module by module, doubles rounded to floats as held.
    const Model m = modelOf(
        "Lsystem: 1\nderivation length: 6\naxiom: A(1)\n"
        "A(x) --> F(x/3)[+A(x*0.7)]A(x+ran(1))\n"
        "F(x) --> F(x*1.1)\nendlsystem\n");
    for (Precision precision : {Precision::Single, Precision::Double}) {
        DerivationOptions options;
        options.precision = precision;
        const ModuleString held = derive(m.lsystem, 6, options);
        std::ostringstream text, json;
        StringTextStream textSink(m.lsystem.symbols, precision, text);
        streamDerivation(m.lsystem, 6, textSink, options);
        textSink.finish();
        EXPECT_EQ(text.str(), textOf(held, m.lsystem.symbols));
        StringJsonStream jsonSink(m.lsystem.symbols, StringJsonHeader{"x.l", 3}, precision, json);
        streamDerivation(m.lsystem, 6, jsonSink, options);
        jsonSink.finish();
        EXPECT_EQ(json.str(), jsonOf(held, m.lsystem.symbols));
    }
}

TEST(StreamedRuns, TheSameStringAsTheDerivationInOrder) {
    const char* systems[] = {
        // The Koch island: subtrees kept and copied.
        "Lsystem: 1\nderivation length: 7\naxiom: F+F+F+F\nF --> F+F-F-FF+F+F-F\nendlsystem\n",
        // Brackets, a symbol that only becomes another, names of several letters.
        "Lsystem: 1\nderivation length: 9\naxiom: X\nX --> F[+X]F[-Y]+X\nY --> Z\nZ --> apex\n"
        "F --> FF\nendlsystem\n",
        // Tables: the successor depends on the step.
        "Lsystem: 1\nderivation length: 8\naxiom: A\ntable: one\nA --> AB\ntable: two\n"
        "A --> BA\nB --> BC\ntable schedule: one 1, two 2, repeat\nendlsystem\n",
    };
    for (const char* text : systems) {
        const Model m = modelOf(text);
        ASSERT_TRUE(streamsInRuns(m.lsystem)) << text;
        const int steps = m.lsystem.derivationLength;
        const ModuleString held = derive(m.lsystem, steps, {});
        std::vector<Symbol> streamed;
        std::size_t runs = 0;
        streamDerivationRuns(m.lsystem, steps, [&](std::span<const Symbol> run) {
            streamed.insert(streamed.end(), run.begin(), run.end());
            ++runs;
        });
        const auto symbols = held.symbols();
        EXPECT_EQ(std::vector<Symbol>(symbols.begin(), symbols.end()), streamed) << text;
        EXPECT_LT(runs, held.size()) << text;
    }
    // Parameters and random choices depend on a module's place: not in runs.
    EXPECT_FALSE(
        streamsInRuns(modelOf("Lsystem: 1\naxiom: A(1)\nA(x) --> A(x+1)\nendlsystem\n").lsystem));
    EXPECT_FALSE(streamsInRuns(
        modelOf("Lsystem: 1\naxiom: A\nA --> AB : 0.5\nA --> B : 0.5\nendlsystem\n").lsystem));
}

TEST(ExportRegistry, TheDerivedStringIsARowOfItsOwnKind) {
    EXPECT_EQ(findExportFormat("text")->kind, ExportKind::String);
    EXPECT_EQ(findExportFormat(".json")->name, "json");
    // The lists of the other kinds, and the studio's downloads, are as they were.
    EXPECT_EQ(exportFormatList(ExportKind::Picture), ".svg, .png or .pdf");
    EXPECT_EQ(exportFormatList(ExportKind::Mesh), ".obj, .ply or .glb");
    for (const ExportFormat* f : studio::studioExportFormats()) EXPECT_NE(f->kind, ExportKind::String);

    const Model m =
        modelOf("Lsystem: 1\nderivation length: 2\naxiom: A(1)\nA(x) --> A(x/2)B\nendlsystem\n");
    std::string text, json;
    ExportRequest request;
    exportModel(m, Destination::memory(text, "a.txt"), request);
    EXPECT_EQ(text, "A(0.25)BB\n");
    request.format = "json";
    request.inputName = "a.l";
    exportModel(m, Destination::memory(json), request);
    EXPECT_EQ(json,
              "{\n  \"file\": \"a.l\",\n  \"steps\": 2,\n  \"modules\": [\n"
              "    {\"symbol\": \"A\", \"params\": [0.25]},\n"
              "    {\"symbol\": \"B\", \"params\": []},\n"
              "    {\"symbol\": \"B\", \"params\": []}\n  ]\n}\n");
}

// `graftal derive` on the book's examples prints what it printed before its writers moved
// into the export registry (text recorded from that version).
TEST(DeriveCommand, ExamplesPrintTheirStringsExactly) {
    const std::string dir = std::string(GRAFTAL_EXAMPLES_DIR) + "/";
    const std::pair<const char*, const char*> cases[] = {
        {"fig1.3-fibonacci.l", "abaababaabaab\n"},
        {"fig1.4-anabaena.l", "blarblararblarblararblararblarblararblarar\n"},
        {"fig3.12-acropetal-signal.l", "FJ[+FJ]FJ[-FJ]FJ[+FJ]FJ\n"},
        {"fig3.7-lily-of-the-valley.l",
         "I[IF(13)]I[IF(12)]I[IF(11)]I[IF(10)]I[IF(9)]I[IF(8)]I[IF(7)]I[IF(6)]I[IF(5)]I[IF(4)]"
         "I[IF(3)]I[IF(2)]I[IF(1)]I[IF(0)]A\n"},
        {"fig4.1-generic-plant.l",
         "internode[leaf]internode[leaf]internode[leaf]internode[leaf]internode[petal1]/(60)"
         "[petal2]/(60)[petal1]/(60)[petal2]/(60)[petal1]/(60)[petal2]\n"},
        {"fig3.14b-basipetal-flowering.l",
         "I[+J[L]J[L]J[L]J[L]F(4)]I[+J[L]J[L]J[L]J[L]F(3)]I[+J[L]J[L]J[L]F(5)]I[+J[L]J[L]J[L]F(4)]"
         "I[+J[L]J[L]F(6)]I[+J[L]J[L]F(5)]I[+J[L]F(7)]I[+J[L]F(6)]I[+F(8)]I[+F(7)]I[+F(6)]"
         "I[+F(5)]F(5)\n"},
        {"fig3.10-capsella-table.l",
         "I[L(19)]I[L(18)]I[L(17)]I[L(16)]I[L(15)]I[L(14)]I[L(13)]I[IF(12)]I[IF(11)]I[IF(10)]"
         "I[IF(9)]I[IF(8)]I[IF(7)]I[IF(6)]I[IF(5)]I[IF(4)]I[IF(3)]I[IF(2)]I[IF(1)]I[IF(0)]B\n"},
    };
    for (const auto& [file, expected] : cases) {
        const auto r = runGraftal("derive " + dir + file);
        EXPECT_EQ(r.status, 0) << file << ": " << r.err;
        EXPECT_EQ(r.out, expected) << file;
        // Streamed where it can be, the same bytes.
        const auto s = runGraftal("derive --stream " + dir + file);
        if (s.status == 0) {
            EXPECT_EQ(s.out, expected) << file;
        }
    }
}
