// The C preprocessor every .l file goes through (mcpp in a child process, kept): macros,
// conditionals, #include relative to the model, -D, and locations in the user's files.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <string>

#include "lang/preprocessor.hpp"
#include "process.hpp"
#include "test_helpers.hpp"

using namespace graftal;
using graftal::testing::derived;
using graftal::testing::parse;
using graftal::testing::parseError;
using graftal::testing::TempDir;

namespace {

// All error messages of a parse, one per line.
std::string allErrors(const std::string& text, const std::string& name = "test.l") {
    try {
        graftal::testing::parse(text, name);
    } catch (const Error& e) {
        std::string all;
        for (const auto& d : e.diagnostics()) all += d.toString() + "\n";
        return all;
    }
    return "";
}

std::string loadError(const std::filesystem::path& file) {
    try {
        loadLSystem(file);
    } catch (const Error& e) {
        return e.diagnostics().front().toString();
    }
    return "";
}

// `#define A0 x`, `#define A1 A0+A0`, ... `#define A<levels> ...`: 2^levels tokens.
std::string doublingMacros(int levels) {
    std::string s = "#define A0 F\n";
    for (int i = 1; i <= levels; ++i)
        s += "#define A" + std::to_string(i) + " A" + std::to_string(i - 1) + " A" +
             std::to_string(i - 1) + "\n";
    return s;
}

// A model whose 40 productions each use A8 (256 modules), and options capping its
// preprocessed text at 8 KiB, which it passes after line 11.
std::string manyUsesOfA8() {
    std::string text = doublingMacros(8) + "Lsystem: 1\naxiom: X\n";
    for (int i = 0; i < 40; ++i) text += "X --> A8\n";
    return text + "\nendlsystem\n";
}

PreprocessOptions cappedAt8KiB() {
    PreprocessOptions o;
    o.fileName = "big.l";
    o.maxOutputBytes = 8 << 10;
    return o;
}

}  // namespace

TEST(Preprocessor, FunctionLikeMacrosExpandInSuccessorsAndConditions) {
    LSystem ls = parse(
        "#define in(x,y) ((x) > 1 && (y) < 3)\n"
        "#define TWICE(a) (2*(a))\n"
        "Lsystem: 1\n"
        "axiom: A(1,2)\n"
        "A(x,y) : !in(x,y) --> A(TWICE(x),y) B(TWICE(x+y))\n"
        "endlsystem\n");
    EXPECT_EQ(derived(ls, 1), "A(2,2)B(6)");
    EXPECT_EQ(derived(ls, 2), "A(2,2)B(6)") << "in(2,2) is true: the production no longer applies";
}

TEST(Preprocessor, IfElifElseChoosesOneBranch) {
    const std::string model =
        "#if STEPS > 2\n"
        "#define KIND 3\n"
        "#elif STEPS > 1\n"
        "#define KIND 2\n"
        "#else\n"
        "#define KIND 1\n"
        "#endif\n"
        "Lsystem: 1\n"
        "axiom: K(KIND)\n"
        "\n"
        "endlsystem\n";
    for (auto [steps, kind] : {std::pair{"3", "K(3)"}, {"2", "K(2)"}, {"0", "K(1)"}}) {
        ParseOptions o;
        o.defines["STEPS"] = steps;
        LSystem ls = parseLSystem(model, o);
        EXPECT_EQ(derived(ls, 0), kind) << "STEPS=" << steps;
    }
}

TEST(Preprocessor, IfdefAndUndef) {
    LSystem ls = parse(
        "#define BRANCH\n"
        "#ifdef BRANCH\n"
        "#define S F[+F]\n"
        "#endif\n"
        "#undef BRANCH\n"
        "#ifndef BRANCH\n"
        "#define T G\n"
        "#endif\n"
        "#ifdef BRANCH\n"
        "#error BRANCH is still defined\n"
        "#endif\n"
        "Lsystem: 1\n"
        "axiom: S T\n"
        "\n"
        "endlsystem\n");
    EXPECT_EQ(derived(ls, 0), "F[+F]G");
}

TEST(Preprocessor, SimpleNumericDefinesStayInTheDefinesMap) {
    LSystem ls = parse(
        "#define N 3\n"
        "#define ANGLE 22.5\n"
        "#define HALF(v) ((v)/2)\n"
        "#define GONE 1\n"
        "#undef GONE\n"
        "Lsystem: 1\nderivation length: N\naxiom: F\n\nendlsystem\n");
    EXPECT_EQ(ls.derivationLength, 3);
    EXPECT_EQ(ls.defines.at("N"), "3");
    EXPECT_EQ(ls.defines.at("ANGLE"), "22.5");
    EXPECT_EQ(ls.defines.count("HALF"), 0u) << "a function-like macro is no slider";
    EXPECT_EQ(ls.defines.count("GONE"), 0u);
}

TEST(Preprocessor, RollsAndQuotesAreModulesNotComments) {
    // `//` and `'` mean nothing special to cpfg's modules; the preprocessor must not eat
    // them as a comment or a character constant.
    LSystem ls = parse(
        "#define N 2\n"
        "Lsystem: 1\n"
        "axiom: A\n"
        "A --> F//&&L(N)'/G''\n"
        "endlsystem\n");
    EXPECT_EQ(derived(ls, 1), "F//&&L(2)'/G''");
}

TEST(Preprocessor, IncludeIsRelativeToTheModel) {
    TempDir t;
    std::filesystem::create_directories(t.path() / "model" / "lib");
    t.write("model/lib/sizes.h", "#define LEN 4\n#include \"more.h\"\n");
    t.write("model/lib/more.h", "#define TWICE(a) (2*(a))\n");
    auto file = t.write("model/plant.l",
                        "#include \"lib/sizes.h\"\n"
                        "Lsystem: 1\naxiom: F(TWICE(LEN))\n\nendlsystem\n");
    LSystem ls = loadLSystem(file);
    EXPECT_EQ(derived(ls, 0), "F(8)");
}

TEST(Preprocessor, ErrorsInsideAnIncludedFileNameThatFileAndLine) {
    TempDir t;
    t.write("rules.h", "\n\nA --> B(qq)\n");
    auto file = t.write("m.l", "Lsystem: 1\naxiom: A\n#include \"rules.h\"\nendlsystem\n");
    std::string e = loadError(file);
    EXPECT_EQ(e.rfind((t.path() / "rules.h").string() + ":3:", 0), 0u) << e;
    EXPECT_NE(e.find("unknown name 'qq'"), std::string::npos) << e;
}

TEST(Preprocessor, LocationsAfterAMultiLineMacroCall) {
    // The call spans lines 5 and 6; cpfg reads it as one statement. The error on line 7
    // names line 7 and its column, not a line of the preprocessed text.
    std::string e = parseError(
        "#define TWICE(a) (2*(a))\n"
        "Lsystem: 1\n"
        "axiom: A(1)\n"
        "\n"
        "A(x) --> B(TWICE(\n"
        "\tx)) C(x)\n"
        "\tD(TWICE(x), qq)\n"
        "endlsystem\n");
    EXPECT_EQ(e.rfind("test.l:7:", 0), 0u) << e;
    EXPECT_NE(e.find("unknown name 'qq'"), std::string::npos) << e;
}

TEST(Preprocessor, ErrorDirectiveMissingIncludeAndUnterminatedIf) {
    EXPECT_EQ(parseError("Lsystem: 1\n#error pick a species with -D SPECIES=...\n"),
              "test.l:2:1: error: #error pick a species with -D SPECIES=...");
    EXPECT_NE(allErrors("Lsystem: 1\n#include \"nowhere.h\"\n")
                  .find("test.l:2:1: error: preprocessor: Can't open include file \"nowhere.h\""),
              std::string::npos)
        << allErrors("Lsystem: 1\n#include \"nowhere.h\"\n");
    std::string e = allErrors("#if 1\nLsystem: 1\naxiom: F\n\nendlsystem\n");
    EXPECT_NE(e.find("test.l:"), std::string::npos) << e;
    EXPECT_NE(e.find("#if"), std::string::npos) << e;
}

TEST(Preprocessor, AnIncludeCycleIsAnErrorAtTheInclude) {
    TempDir t;
    t.write("a.h", "#include \"b.h\"\n");
    t.write("b.h", "\n#include \"a.h\"\n");
    auto file = t.write("m.l", "#include \"a.h\"\nLsystem: 1\naxiom: F\n\nendlsystem\n");
    std::string e = loadError(file);
    EXPECT_NE(e.find("#include cycle"), std::string::npos) << e;
    EXPECT_TRUE(e.find("a.h:1:") != std::string::npos || e.find("b.h:2:") != std::string::npos)
        << e;
}

TEST(Preprocessor, AMacroThatDoublesTwentyFiveTimesIsRefusedAtItsUse) {
    // 2^25 modules: the expansion stops at the preprocessor's limit, with an error at
    // the line that uses the macro; no memory runs out.
    std::string text = doublingMacros(25) + "Lsystem: 1\naxiom: X\nX --> A25\n\nendlsystem\n";
    std::string e = parseError(text);
    EXPECT_EQ(e.rfind("test.l:29:", 0), 0u) << e;
    EXPECT_NE(e.find("macro expands to more text"), std::string::npos) << e;
}

TEST(Preprocessor, ThePreprocessedSizeIsCapped) {
    // Each use of A8 is 256 modules; many uses pass a small cap, reported at the line that
    // crosses it.
    SourceText src;
    DiagnosticList diags;
    EXPECT_FALSE(preprocessSource(manyUsesOfA8(), cappedAt8KiB(), src, diags));
    ASSERT_TRUE(diags.hasErrors());
    const Diagnostic& d = diags.items().back();
    EXPECT_EQ(d.location.file, "big.l");
    EXPECT_GT(d.location.line, 11);  // a line using A8, after the axiom
    EXPECT_LT(d.location.line, 11 + 40);
    EXPECT_NE(d.message.find("grows past 8 KiB"), std::string::npos) << d.message;
}

TEST(Preprocessor, BlocksAndTabContinuationsAfterThePreprocessor) {
    // The preprocessor runs first; then a block over several lines and a TAB continuation
    // are joined as in a file without directives, and an error names the user's line.
    LSystem ls = parse(
        "#define STEP 10\n"
        "Lsystem: 1\n"
        "axiom: Q(2)\n"
        "Q(m) : {\n"
        "    k = m*STEP;\n"
        "} k > 5 --> T(k)\n"
        "\tU\n"
        "endlsystem\n");
    EXPECT_EQ(derived(ls, 1), "T(20)U");
    std::string e = parseError(
        "#define STEP 10\n"
        "Lsystem: 1\n"
        "axiom: Q(2)\n"
        "Q(m) : {\n"
        "    k = m*STEP;\n"
        "} k > 5 --> T(k)\n"
        "\tU(qq)\n"
        "endlsystem\n");
    EXPECT_EQ(e.rfind("test.l:7:4:", 0), 0u) << e;
}

TEST(Preprocessor, CommandLineDefineSelectsABranch) {
    // The oracle's s02_preproc shape: #ifdef on a name given with -D, function-like macros.
    const std::string model =
        "#define TWICE(a) (2*(a))\n"
        "Lsystem: 1\n"
        "axiom: A(1)\n"
        "#ifdef WITH_BRANCH\n"
        "A(x) --> A(TWICE(x))[B]\n"
        "#else\n"
        "A(x) --> A(x+1)\n"
        "#endif\n"
        "endlsystem\n";
    ParseOptions o;
    o.fileName = "d.l";
    EXPECT_EQ(derived(parseLSystem(model, o), 1), "A(2)");
    o.defines["WITH_BRANCH"] = "1";
    EXPECT_EQ(derived(parseLSystem(model, o), 2), "A(4)[B][B]");
}

TEST(Preprocessor, RunsAfterAStoppedRunAndInAForkedProcessReadTheirOwnDefines) {
    // mcpp runs in a process kept from one model to the next: a -D or #define of one run
    // never reaches the next, a run stopped at the size cap leaves the next one whole, and
    // a forked copy of this process (a worker) preprocesses with its own.
    const std::string model =
        "Lsystem: 1\n"
        "axiom: A(N)\n"
        "endlsystem\n";
    ParseOptions o;
    o.fileName = "n.l";
    for (int n = 1; n <= 30; ++n) {
        o.defines["N"] = std::to_string(n);
        EXPECT_EQ(derived(parseLSystem("#define N 0\n" + model, o), 0),
                  "A(" + std::to_string(n) + ")");
    }
    SourceText src;
    DiagnosticList diags;
    EXPECT_FALSE(preprocessSource(manyUsesOfA8(), cappedAt8KiB(), src, diags));
    EXPECT_EQ(derived(parse("#define N 7\n" + model), 0), "A(7)");
    const pid_t child = ::fork();
    if (child == 0) {
        // Only the preprocessor here: a fork has none of the parent's worker threads.
        PreprocessOptions mine;
        mine.fileName = "n.l";
        mine.defines["N"] = "9";
        SourceText out;
        DiagnosticList messages;
        bool right = preprocessSource("#define N 0\n" + model, mine, out, messages);
        bool nine = false;
        for (const auto& line : out.lines) nine = nine || line.text == "axiom: A(9)";
        right = right && nine;
        ::_exit(right ? 0 : 1);
    }
    int status = -1;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    EXPECT_EQ(derived(parse("#define N 8\n" + model), 0), "A(8)");
}
