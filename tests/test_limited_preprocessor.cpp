// The web build's preprocessor (lang/limited_preprocessor.hpp) against mcpp: the same lines,
// the same places in the user's file, the same defines, on every example and on the
// directives the language documents.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "lang/limited_preprocessor.hpp"
#include "lang/preprocessor.hpp"

using namespace graftal;

namespace {

struct Outcome {
    bool ok = false;
    SourceText text;
    std::string messages;
};

Outcome run(bool limited, const std::string& source, const PreprocessOptions& options) {
    Outcome o;
    DiagnosticList diags;
    o.ok = limited ? preprocessLimited(source, options, o.text, diags)
                   : preprocessSource(source, options, o.text, diags);
    for (const auto& d : diags.items()) o.messages += d.toString() + "\n";
    return o;
}

// The lines with text, without blanks, each with the place its first word came from. mcpp
// may put a blank between an operator and an expansion (`s/ 1.618` for `s/P`), which the
// parser reads as it reads `s/1.618`.
std::string described(const SourceText& t) {
    std::string out;
    for (const SourceLine& line : t.lines) {
        std::string words;
        for (char c : line.text)
            if (c != ' ' && c != '\t' && c != '\r') words += c;
        if (words.empty()) continue;
        const std::size_t first = line.text.find_first_not_of(" \t\r");
        const SourceLocation at = t.at(line.number, static_cast<int>(first) + 1);
        out += std::to_string(at.line) + ":" + std::to_string(at.column) + " " + words + "\n";
    }
    for (const auto& [name, value] : t.defines) out += "#define " + name + " " + value + "\n";
    return out;
}

void expectSame(const std::string& source, PreprocessOptions options = {}) {
    if (options.fileName.empty()) options.fileName = "model.l";
    const Outcome mcpp = run(false, source, options);
    const Outcome limited = run(true, source, options);
    ASSERT_TRUE(mcpp.ok) << mcpp.messages;
    EXPECT_TRUE(limited.ok) << limited.messages;
    EXPECT_EQ(described(limited.text), described(mcpp.text)) << source;
}

}  // namespace

TEST(LimitedPreprocessor, GivesMcppsLinesOnEveryExample) {
    int compared = 0;
    for (const auto& entry : std::filesystem::directory_iterator(GRAFTAL_EXAMPLES_DIR)) {
        if (entry.path().extension() != ".l") continue;
        std::ifstream in(entry.path(), std::ios::binary);
        std::stringstream text;
        text << in.rdbuf();
        PreprocessOptions options;
        options.fileName = entry.path().filename().string();
        if (!needsPreprocessing(text.str(), options)) continue;
        SCOPED_TRACE(entry.path().filename().string());
        expectSame(text.str(), options);
        ++compared;
    }
    EXPECT_GE(compared, 20) << "the examples with #define";
}

TEST(LimitedPreprocessor, GivesMcppsLinesForEveryDirective) {
    expectSame("#define in(x,y) ((x) > 1 && (y) < 3)\n#define TWICE(a) (2*(a))\nLsystem: 1\n"
               "axiom: A(1,2)\nA(x,y) : !in(x,y) --> A(TWICE(x),y) B(TWICE(x+y))\nendlsystem\n");
    const std::string chosen =
        "#if STEPS > 2 && defined(KIND0)\n#define KIND 3\n#elif STEPS > 1 || !defined KIND0\n"
        "#define KIND 2\n#else\n#define KIND 1\n#endif\nLsystem: 1\naxiom: K(KIND)\nendlsystem\n";
    for (const char* steps : {"3", "2", "0"}) {
        PreprocessOptions options;
        options.defines["STEPS"] = steps;
        expectSame(chosen, options);
        options.defines["KIND0"] = "1";
        expectSame(chosen, options);
    }
    expectSame("#define BRANCH\n#ifdef BRANCH\n#define S F[+F]\n#endif\n#undef BRANCH\n"
               "#ifndef BRANCH\n#define T G\n#endif\nLsystem: 1\naxiom: S T S\nendlsystem\n");
    expectSame("#define E 2\n#define A 1.5 /* a comment */\nLsystem: 1\naxiom: F(2E) F(E) "
               "F(A*E)//F(3)\nendlsystem\n");
    PreprocessOptions overridden;
    overridden.defines["N"] = "7";
    expectSame("#define N 3\n#define M N+1\nLsystem: 1\nderivation length: N\naxiom: F(M)\n",
               overridden);
}

TEST(LimitedPreprocessor, ReportsWhatItCannotDoAtItsLine) {
    PreprocessOptions options;
    options.fileName = "web.l";
    Outcome o = run(true, "Lsystem: 1\n#include \"leaf.l\"\n", options);
    EXPECT_FALSE(o.ok);
    EXPECT_NE(o.messages.find("web.l:2:10: error: #include is not available in the web build"),
              std::string::npos)
        << o.messages;
    o = run(true, "#if 1\n#define A 2\n", options);
    EXPECT_FALSE(o.ok);
    EXPECT_NE(o.messages.find("web.l:1:1: error: this #if has no #endif"), std::string::npos)
        << o.messages;
    o = run(true, "#error stop here\n", options);
    EXPECT_NE(o.messages.find("web.l:1:1: error: #error stop here"), std::string::npos)
        << o.messages;
    // Macros that double at every level: stopped at the size limit, not run out of memory.
    std::string doubling = "#define A0 F\n";
    for (int i = 1; i <= 40; ++i)
        doubling += "#define A" + std::to_string(i) + " A" + std::to_string(i - 1) + " A" +
                    std::to_string(i - 1) + "\n";
    o = run(true, doubling + "axiom: A40\n", options);
    EXPECT_FALSE(o.ok);
    EXPECT_NE(o.messages.find("web.l:42:8: error: the preprocessed text grows past"),
              std::string::npos)
        << o.messages;
}
