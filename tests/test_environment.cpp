// Open L-systems: the Environment interface, the built-in environments, the external
// process protocol and the errors of `environment:` lines.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "process.hpp"
#include "test_helpers.hpp"

using namespace graftal;
using graftal::testing::derived;
using graftal::testing::loadExample;
using graftal::testing::parse;
using graftal::testing::parseModel;
namespace fs = std::filesystem;

namespace {

const fs::path kExamples = GRAFTAL_EXAMPLES_DIR;

// The first diagnostic building a file's environment produces, or "" when it builds.
std::string environmentError(const std::string& text) {
    try {
        Model ls = parseModel(text);
        makeEnvironment(ls.lsystem);
    } catch (const Error& e) {
        return e.diagnostics().front().toString();
    }
    return "";
}

// The message of the Error a derivation throws, or "" when it succeeds.
std::string derivationError(const Model& ls, int steps, DerivationOptions o = {}) {
    try {
        deriveWithQueries(ls, steps, o);
    } catch (const Error& e) {
        return e.diagnostics().front().toString();
    }
    return "";
}

bool haveCommand(const std::string& name) {
    return std::system(("command -v " + name + " > /dev/null 2>&1").c_str()) == 0;
}

std::string withEnvironment(const std::string& environmentLines, const std::string& rest) {
    return "Lsystem: 1\n" + environmentLines + rest + "endlsystem\n";
}

struct Seen {
    int step;
    std::size_t module;
    TurtleFrame frame;
    std::vector<double> params;
};

// Records what it is asked and answers 100 * step + the request's rank.
class RecordingEnvironment : public Environment {
  public:
    std::string name() const override { return "recording"; }
    void respond(int step, std::span<CommunicationRequest> requests) override {
        for (std::size_t k = 0; k < requests.size(); ++k) {
            auto& r = requests[k];
            seen.push_back({step, r.module, r.frame, {r.params.begin(), r.params.end()}});
            for (auto& p : r.params) p = 100.0 * step + static_cast<double>(k);
        }
    }
    std::vector<Seen> seen;
};

void expectNear(const Vec3& v, double x, double y, double z) {
    EXPECT_NEAR(v.x, x, 1e-12);
    EXPECT_NEAR(v.y, y, 1e-12);
    EXPECT_NEAR(v.z, z, 1e-12);
}

}  // namespace

// --- The interface -------------------------------------------------------------------

TEST(Environment, ReceivesFramesInStringOrderAndItsAnswersAreDerived) {
    Model ls = parseModel(
        "Lsystem: 1\nangle increment: 90\n"
        "axiom: F ?E(5) + F(2) ?E(6,7) ?E\nendlsystem\n");
    RecordingEnvironment env;
    DerivationOptions o;
    o.environment = &env;
    EXPECT_EQ(deriveWithQueries(ls, 0, o).toString(ls.lsystem.symbols), "F?E(0)+F(2)?E(1,1)?E");
    ASSERT_EQ(env.seen.size(), 3u);
    EXPECT_EQ(env.seen[0].step, 0);
    EXPECT_EQ(env.seen[0].module, 1u) << "the module's position in the string";
    expectNear(env.seen[0].frame.position, 0, 1, 0);
    expectNear(env.seen[0].frame.heading, 0, 1, 0);
    EXPECT_EQ(env.seen[0].params, std::vector<double>{5}) << "what the string held";
    EXPECT_EQ(env.seen[1].module, 4u);
    expectNear(env.seen[1].frame.position, -2, 1, 0);
    expectNear(env.seen[1].frame.heading, -1, 0, 0);
    expectNear(env.seen[1].frame.left, 0, -1, 0);
    expectNear(env.seen[1].frame.up, 0, 0, 1);
    EXPECT_EQ(env.seen[1].params, (std::vector<double>{6, 7}));
    EXPECT_TRUE(env.seen[2].params.empty()) << "a ?E without parameters is still asked";
}

TEST(Environment, IsAskedAfterEveryStepAndProductionsReadTheAnswers) {
    Model ls = parseModel(
        "Lsystem: 1\naxiom: A?E(0)\n"
        "A > ?E(t) : t < 200 --> FA\nA > ?E(t) : t >= 200 --> B\nendlsystem\n");
    RecordingEnvironment env;
    DerivationOptions o;
    o.environment = &env;
    EXPECT_EQ(deriveWithQueries(ls, 4, o).toString(ls.lsystem.symbols), "FFB?E(400)");
    ASSERT_EQ(env.seen.size(), 5u) << "once for the axiom and once per step";
    for (int s = 0; s <= 4; ++s) EXPECT_EQ(env.seen[s].step, s);
    EXPECT_EQ(env.seen[3].params, std::vector<double>{200}) << "its own answer of step 2";
    EXPECT_NEAR(env.seen[3].frame.position.y, 2, 1e-12);
}

TEST(Environment, OptionsEnvironmentReplacesTheFilesOne) {
    Model ls = parseModel(withEnvironment("environment: clock\n", "axiom: ?E(9)\n"));
    EXPECT_EQ(derived(ls.lsystem, 3), "?E(3)");
    RecordingEnvironment env;
    DerivationOptions o;
    o.environment = &env;
    EXPECT_EQ(deriveWithQueries(ls, 3, o).toString(ls.lsystem.symbols), "?E(300)");
}

TEST(Environment, NoEnvironmentLinesMeansNoEnvironment) {
    Model ls = parseModel("Lsystem: 1\naxiom: A?E(4)\nendlsystem\n");
    EXPECT_EQ(makeEnvironment(ls.lsystem), nullptr);
    EXPECT_EQ(derived(ls.lsystem, 2), "A?E(4)") << "unanswered ?E modules keep their values";
}

TEST(Environment, NamesOfTheBuiltInEnvironments) {
    auto nameOf = [](const std::string& lines) {
        Model ls = parseModel(withEnvironment(lines, "axiom: A\n"));
        return makeEnvironment(ls.lsystem)->name();
    };
    EXPECT_EQ(nameOf("environment: clock\n"), "clock");
    EXPECT_EQ(nameOf("environment: obstacles\nenvironment: sphere 0 0 0 radius 1\n"), "obstacles");
    EXPECT_EQ(nameOf("environment: occupancy\n"), "occupancy");
    EXPECT_EQ(nameOf("environment: light radius 2\n"), "light");
    EXPECT_EQ(nameOf("environment: process cat\n"), "process");
}

// --- The lecture's example -----------------------------------------------------------

TEST(LectureOpenLSystem, DerivesThePrintedStringsExactly) {
    Model ls = loadExample(kExamples / "lecture-open-lsystem-distance-limit.l");
    EXPECT_EQ(derived(ls.lsystem, 0), "F(0,0)A?E(0)");
    EXPECT_EQ(derived(ls.lsystem, 1), "F(0,0)F(0,1)A?E(1)");
    EXPECT_EQ(derived(ls.lsystem, 2), "F(0,0)F(0,1)F(0,2)A?E(2)");
    EXPECT_EQ(derived(ls.lsystem, 3), "F(0,0)F(0,1)F(0,2)?E(3)");
    EXPECT_EQ(derived(ls.lsystem, 4), "F(0,0)F(0,1)F(0,2)?E(4)") << "the plant stops; time goes on";
    // The picture is the derivation: the string draws nothing (the homomorphism erases F),
    // and the diagram's rows are the four printed strings, ?E's answer under ?E.
    Scene scene = interpret(ls, applyHomomorphism(ls.lsystem, deriveWithQueries(ls)));
    EXPECT_TRUE(scene.segments.empty());
    std::vector<ModuleString> steps;
    for (int k = 0; k <= 3; ++k) steps.push_back(deriveWithQueries(ls, k));
    RenderOptions o;
    DerivationDiagram d = layoutDerivationDiagram(steps, ls.lsystem.symbols, o);
    ASSERT_EQ(d.rows.size(), 4u);
    EXPECT_EQ(d.rows[3].cells.size(), 4u);
    EXPECT_EQ(d.rows[3].cells.back().label, "?E");
    EXPECT_EQ(d.rows[3].cells.back().parameters, "3");
    EXPECT_EQ(d.rows[1].cells[1].parameters, "0,1");
}

TEST(LectureOpenLSystem, APositionReadingDiffersOnlyInTheLastValue) {
    // The same rules with the tip's position (?P) as the answer; F(x,y) is drawn as the unit
    // step it is in this model. Identical up to step 2; then 2 where the lecture prints 3.
    Model ls = parseModel(
        "#define x 0\nLsystem: 1\naxiom: F(0,0)A?P(0,0)\n"
        "A > ?P(px,y) : y < 2 --> F(x, y+1)A\nA > ?P(px,y) : y >= 2 --> *\n"
        "homomorphism\nF(u,v) : v > 0 --> F(1)\nF(u,v) --> *\nendlsystem\n");
    EXPECT_EQ(derived(ls.lsystem, 1), "F(0,0)F(0,1)A?P(0,1)");
    EXPECT_EQ(derived(ls.lsystem, 2), "F(0,0)F(0,1)F(0,2)A?P(0,2)");
    EXPECT_EQ(derived(ls.lsystem, 3), "F(0,0)F(0,1)F(0,2)?P(0,2)");
}

// --- clock ---------------------------------------------------------------------------

TEST(ClockEnvironment, WritesTheStepNumberIntoTheFirstParameter) {
    Model ls = parseModel(withEnvironment("environment: clock\n", "axiom: ?E(7,8) ?E\n"));
    EXPECT_EQ(derived(ls.lsystem, 0), "?E(0,8)?E");
    EXPECT_EQ(derived(ls.lsystem, 5), "?E(5,8)?E");
}

// --- obstacles -----------------------------------------------------------------------

TEST(ObstacleEnvironment, AnApexStopsWhereTheSphereBegins) {
    std::string rules = "axiom: A?E(0,0,0,0,0)\nA > ?E(c,d,x,y,z) : c == 0 --> FA\nendlsystem\n";
    Model touching = parseModel(
        "Lsystem: 1\nenvironment: obstacles\nenvironment: sphere 0 5 0 radius 1\n" + rules);
    EXPECT_EQ(derived(touching.lsystem, 2), "FFA?E(0,2,0,-1,0)") << "2 units below the surface";
    EXPECT_EQ(derived(touching.lsystem, 8), "FFFFA?E(1,0,0,-1,0)") << "on the surface: collision";
    Model withMargin = parseModel(
        "Lsystem: 1\nenvironment: obstacles margin 1\nenvironment: sphere 0 5 0 radius 1\n" +
        rules);
    EXPECT_EQ(derived(withMargin.lsystem, 8), "FFFA?E(1,1,0,-1,0)") << "stops one unit earlier";
}

TEST(ObstacleEnvironment, DistancesAndWayOutForEveryShape) {
    // Probes (f moves, nothing drawn) below, inside and above a box, behind a plane (the
    // solid x < -3) and at the centre of a sphere; each ?E gets the nearest obstacle.
    Model ls = parseModel(
        "Lsystem: 1\n"
        "environment: obstacles\n"
        "environment: box -1 2 -1 1 3 1\n"
        "environment: plane -3 0 0 normal 10 0 0\n"
        "environment:   sphere 0 -20 0 radius 0.5 sphere 50 0 0 radius 1\n"
        "axiom: [?E(0,0,0,0,0)] f(2.5) ?E(0,0,0,0,0) f(2) ?E(0,0,0,0,0) "
        "[+(90) f(8) ?E(0,0,0,0,0)] [-(90) f(1) ?E(0,0)] f(-24.5) ?E(0,0,0,0,0,9)\n"
        "endlsystem\n");
    EXPECT_EQ(derived(ls.lsystem, 0),
              "[?E(0,2,0,-1,0)]f(2.5)?E(1,-0.5,0,1,0)f(2)?E(0,1.5,0,1,0)"
              "[+(90)f(8)?E(1,-5,1,0,0)][-(90)f(1)?E(0,1.5)]f(-24.5)?E(1,-0.5,0,1,0,9)");
}

TEST(ObstacleEnvironment, ShapesMayUseDefinesAndExpressions) {
    Model ls = parseModel(
        "#define R 2\nLsystem: 1\nenvironment: obstacles\n"
        "environment: sphere 0 2*R 0 radius R\naxiom: ?E(0,0)\nendlsystem\n");
    EXPECT_EQ(derived(ls.lsystem, 0), "?E(0,2)");
}

TEST(ObstacleEnvironment, TheAvoidanceExampleNeverGrowsIntoAnObstacle) {
    Model ls = loadExample(kExamples / "open-obstacle-avoidance.l");
    auto constant = [&](const char* name) {
        return evaluateConstant(name, {}, ls.lsystem.defines);
    };
    Vec3 c{constant("SX"), constant("SY"), 0};
    double r = constant("SR");
    double x0 = constant("WX0"), y0 = constant("WY0"), x1 = constant("WX1"), y1 = constant("WY1");
    auto inside = [&](const Vec3& p) {
        bool inSphere = std::hypot(p.x - c.x, p.y - c.y) < r - 1e-9;
        bool inBox = p.x > x0 + 1e-9 && p.x < x1 - 1e-9 && p.y > y0 + 1e-9 && p.y < y1 - 1e-9;
        return inSphere || inBox;
    };
    auto count = [](const ModuleString& s, const Model& l, const std::string& sym) {
        std::string text = s.toString(l.lsystem.symbols);
        std::size_t n = 0;
        for (std::size_t p = 0; (p = text.find(sym, p)) != std::string::npos; ++p) ++n;
        return n;
    };

    ModuleString s = deriveWithQueries(ls);
    Scene scene = interpret(ls, applyHomomorphism(ls.lsystem, s));
    for (const Segment& seg : scene.segments) {
        EXPECT_FALSE(inside(seg.a) || inside(seg.b))
            << "segment (" << seg.a.x << "," << seg.a.y << ")-(" << seg.b.x << "," << seg.b.y
            << ") enters an obstacle";
    }
    EXPECT_GE(count(s, ls, "X"), 10u) << "apices that met an obstacle flowered";
    EXPECT_GE(count(s, ls, "A("), 10u) << "others grew on around the obstacles";

    ls.lsystem.environment.clear();  // without its environment the same shrub grows through them
    Scene blind = interpret(ls, applyHomomorphism(ls.lsystem, deriveWithQueries(ls)));
    std::size_t entering = 0;
    for (const Segment& seg : blind.segments) entering += inside(seg.b);
    EXPECT_GT(entering, 50u);
}

// --- occupancy and light -------------------------------------------------------------

TEST(OccupancyEnvironment, CountsTheOthersInTheSameCell) {
    Model ls = parseModel(withEnvironment(
        "environment: occupancy cell 1\n",
        "axiom: ?E(9,9) f(0.5) ?E(9,9) f(0.4) ?E(9) f(2) ?E(9,9) [-(90) f(0.5) ?E(9,9)]\n"));
    // 1/3 as the string stores it: a 32-bit float (0.3333333333333333 with doubles).
    EXPECT_EQ(derived(ls.lsystem, 0),
              "?E(2,0.33333334)f(0.5)?E(2,0.33333334)f(0.4)?E(2)f(2)?E(1,0.5)"
              "[-(90)f(0.5)?E(1,0.5)]");
}

TEST(OccupancyEnvironment, CountsTheOthersWithinTheRadius) {
    Model ls = parseModel(withEnvironment(
        "environment: occupancy radius 0.5\n",
        "axiom: ?E(9) f(0.5) ?E(9) f(0.4) ?E(9) f(2) ?E(9) [+(90) f(0.3) ?E(9)]\n"));
    EXPECT_EQ(derived(ls.lsystem, 0), "?E(1)f(0.5)?E(2)f(0.4)?E(1)f(2)?E(1)[+(90)f(0.3)?E(1)]")
        << "exactly one radius apart counts";
}

TEST(OccupancyEnvironment, LightIsTheSameFieldAnsweredAsLightFirst) {
    Model ls = parseModel(withEnvironment(
        "environment: light\n", "axiom: ?E(9,9) f(0.2) ?E(9,9) f(0.2) ?E(9,9) f(5) ?E(9,9)\n"));
    EXPECT_EQ(derived(ls.lsystem, 0),
              "?E(0.33333334,2)f(0.2)?E(0.33333334,2)f(0.2)?E(0.33333334,2)f(5)?E(1,0)")
        << "default: cells of side 1";
}

TEST(OccupancyEnvironment, RoundingNoiseDoesNotMoveAPointAcrossACellBoundary) {
    // Ten steps of 0.1 end at 0.9999999999999999: meant to be 1, in the same cell as f(1).
    Model ls = parseModel(
        withEnvironment("environment: occupancy cell 1\n",
                        "axiom: [f(0.1)f(0.1)f(0.1)f(0.1)f(0.1)f(0.1)f(0.1)f(0.1)f(0.1)f(0.1) "
                        "?E(9)] f(1.5) ?E(9)\n"));
    EXPECT_EQ(derived(ls.lsystem, 0),
              "[f(0.1)f(0.1)f(0.1)f(0.1)f(0.1)f(0.1)f(0.1)f(0.1)f(0.1)f(0.1)?E(1)]f(1.5)?E(1)");
}

TEST(OccupancyEnvironment, CrowdedApicesStopAndThePlantDiffersFromTheOpenOne) {
    Model ls = loadExample(kExamples / "open-crowding-stops-branches.l");
    ModuleString s = deriveWithQueries(ls);
    std::string text = s.toString(ls.lsystem.symbols);
    EXPECT_EQ(text.find("A("), std::string::npos) << "every apex has stopped by itself";
    std::size_t leaves = std::count(text.begin(), text.end(), 'V');
    EXPECT_GT(leaves, 50u);
    Scene crowded = interpret(ls, applyHomomorphism(ls.lsystem, s));

    Model open = ls;
    open.lsystem.environment.clear();
    Scene free = interpret(open, applyHomomorphism(open.lsystem, deriveWithQueries(open)));
    EXPECT_EQ(free.segments.size(), (std::size_t(1) << (ls.lsystem.derivationLength + 1)) - 1)
        << "without the environment: a full binary tree";
    EXPECT_LT(crowded.segments.size() * 20, free.segments.size());
}

TEST(OccupancyEnvironment, AnswersDoNotDependOnTheThreadCount) {
    Model ls = loadExample(kExamples / "open-crowding-stops-branches.l");
    DerivationOptions one, many;
    one.threads = 1;
    many.threads = 7;
    for (int n : {6, 9, 12})
        EXPECT_EQ(deriveWithQueries(ls, n, one).toString(ls.lsystem.symbols),
                  deriveWithQueries(ls, n, many).toString(ls.lsystem.symbols));
}

// --- process -------------------------------------------------------------------------

TEST(ProcessEnvironment, SpeaksTheDocumentedLineProtocol) {
    // A POSIX sh environment that logs what it reads and answers "7 8" per request.
    graftal::testing::TempDir dir;
    dir.write("env.sh",
              "while read w s n; do echo \"$w $s $n\" >> log.txt; i=0\n"
              "  while [ $i -lt $n ]; do read line; echo \"$line\" >> log.txt; echo 7 8\n"
              "    i=$((i+1)); done\ndone\n");
    fs::path file = dir.write("model.l",
                              "Lsystem: 1\nangle increment: 90\nenvironment: process sh env.sh\n"
                              "axiom: F?E(1,2)+F(0.5)A?E(0.25,-3)\nA --> FA\nendlsystem\n");
    {
        Model ls = loadExample(file);  // the program runs in the file's directory
        EXPECT_EQ(derived(ls.lsystem, 1), "F?E(7,8)+F(0.5)FA?E(7,8)");
    }
    EXPECT_EQ(graftal::testing::readFile(dir.path() / "log.txt"),
              "step 0 2\n"
              "1 0 1 0 0 1 0 -1 0 0 0 0 1 1 2\n"
              "5 -0.5 1 0 -1 0 0 0 -1 0 0 0 1 0.25 -3\n"
              "step 1 2\n"
              "1 0 1 0 0 1 0 -1 0 0 0 0 1 7 8\n"
              "6 -1.5 1 0 -1 0 0 0 -1 0 0 0 1 7 8\n");
}

TEST(ProcessEnvironment, TheReferenceHeightFieldProgram) {
    if (!haveCommand("python3")) GTEST_SKIP() << "python3 is not installed";
    std::string script = (kExamples / "environments" / "height_field.py").string();
    Model ls = parseModel(withEnvironment("environment: process python3 '" + script + "' 4\n",
                                          "axiom: A?E(9,0)\nA > ?E(c,h) : c >= 1 --> FA\n"));
    EXPECT_EQ(derived(ls.lsystem, 0), "A?E(4,4)");
    EXPECT_EQ(derived(ls.lsystem, 1), "FA?E(3,4)");
    EXPECT_EQ(derived(ls.lsystem, 8), "FFFFA?E(0,4)");

    // The example next to it: every stem flowers just under the ceiling.
    Model ceiling = loadExample(kExamples / "environments" / "open-height-field-ceiling.l");
    std::string s = derived(ceiling.lsystem, ceiling.lsystem.derivationLength);
    EXPECT_EQ(std::count(s.begin(), s.end(), 'X'), 21);
}

TEST(ProcessEnvironment, FromCppWithMakeExternalProcessEnvironment) {
    auto env = makeExternalProcessEnvironment(
        "while read w s n; do i=0; while [ $i -lt $n ]; do read line; set -- $line;"
        " echo \"$s$1\"; i=$((i+1)); done; done");
    EXPECT_EQ(env->name(), "process");
    Model ls = parseModel("Lsystem: 1\naxiom: ?E(0) f ?E(0)\nA --> A\nendlsystem\n");
    DerivationOptions o;
    o.environment = env.get();
    EXPECT_EQ(deriveWithQueries(ls, 2, o).toString(ls.lsystem.symbols), "?E(20)f?E(22)")
        << "the step number followed by the module index";
}

TEST(ProcessEnvironment, ProgramThatExitsEarly) {
    Model ls = parseModel(
        withEnvironment("environment: process echo oops >&2; exit 3\n", "axiom: A?E(0)\n"));
    EXPECT_EQ(derivationError(ls, 1),
              "test.l:2:14: error: the environment program 'echo oops >&2; exit 3' exited with "
              "status 3 in step 0 after 0 of 1 answer lines; its error output ends with: oops");
}

TEST(ProcessEnvironment, ProgramThatDiesAfterSomeSteps) {
    Model ls =
        parseModel(withEnvironment("environment: process read h; read r; echo 5; read h; exit 0\n",
                                   "axiom: A?E(0)\nA --> FA\n"));
    std::string e = derivationError(ls, 3);
    EXPECT_NE(e.find("exited with status 0 in step 1 after 0 of 1 answer lines"), std::string::npos)
        << e;
}

TEST(ProcessEnvironment, MalformedAnswers) {
    auto errorFor = [](const std::string& program) {
        Model ls = parseModel(
            withEnvironment("environment: process " + program + "\n", "axiom: A?E(0,0) ?E(1)\n"));
        return derivationError(ls, 0);
    };
    EXPECT_EQ(errorFor("echo garbage; cat > /dev/null"),
              "test.l:2:14: error: the environment program 'echo garbage; cat > /dev/null' "
              "wrote 'garbage' as answer line 1 of step 0 (for the ?E at module 1, with 2 "
              "parameters): 'garbage' is not a finite number");
    EXPECT_NE(errorFor("echo 1; cat > /dev/null")
                  .find("wrote '1' as answer line 1 of step 0 (for the ?E at module 1, with 2 "
                        "parameters): expected 2 numbers, one per parameter, found 1"),
              std::string::npos);
    EXPECT_NE(errorFor("echo 1 nan; cat > /dev/null").find("'nan' is not a finite number"),
              std::string::npos);
    EXPECT_NE(errorFor("printf '1 2\\n3\\n4\\n'; cat > /dev/null")
                  .find("wrote more than 2 answer lines in step 0: '4' is one too many"),
              std::string::npos);
    EXPECT_NE(errorFor("echo 1 2; exec 0<&- 1>&-; sleep 3")
                  .find("closed its output in step 0 after 1 of 2 answer lines"),
              std::string::npos);
}

TEST(ProcessEnvironment, CommandNotFound) {
    Model ls = parseModel(
        withEnvironment("environment: process no_such_program_graftal\n", "axiom: ?E(0)\n"));
    std::string e = derivationError(ls, 0);
    EXPECT_NE(e.find("exited with status 127"), std::string::npos) << e;
    EXPECT_NE(e.find("not found"), std::string::npos) << e;
}

TEST(ProcessEnvironment, ASilentProgramTimesOutInsteadOfHanging) {
    // Many requests: the program never reads them, so the pipe fills; still no hang.
    std::string axiom = "axiom:";
    for (int i = 0; i < 20000; ++i) axiom += " ?E(1,2,3)";
    Model ls = parseModel(
        withEnvironment("environment: process sleep 20\nenvironment: timeout 0.5\n", axiom + "\n"));
    auto start = std::chrono::steady_clock::now();
    std::string e = derivationError(ls, 0);
    double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_LT(seconds, 5);
    EXPECT_NE(e.find("test.l:2:14: error: the environment program 'sleep 20' did not answer "
                     "within 0.5 s in step 0 after 0 of 20000 answer lines"),
              std::string::npos)
        << e;
}

TEST(ProcessEnvironment, AFailedProgramIsNotAskedAgain) {
    auto env = makeExternalProcessEnvironment("exit 1");
    std::vector<double> values{0};
    CommunicationRequest r{0, {}, values};
    std::span<CommunicationRequest> requests(&r, 1);
    EXPECT_THROW(env->respond(0, requests), Error);
    try {
        env->respond(1, requests);
        FAIL() << "expected an Error";
    } catch (const Error& e) {
        EXPECT_NE(e.diagnostics().front().message.find("exited with status 1 in step 0"),
                  std::string::npos);
    }
}

TEST(ProcessEnvironment, ClosingDoesNotWaitForAProgramThatIgnoresEndOfInput) {
    auto start = std::chrono::steady_clock::now();
    {
        auto env = makeExternalProcessEnvironment("read h; read r; echo 1; exec sleep 30");
        std::vector<double> values{0};
        CommunicationRequest r{0, {}, values};
        env->respond(0, std::span<CommunicationRequest>(&r, 1));
        EXPECT_EQ(values[0], 1);
    }
    double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_LT(seconds, 5);
}

// --- errors in `environment:` lines ----------------------------------------------------

TEST(EnvironmentErrors, PointAtTheWordThatIsWrong) {
    auto e = [](const std::string& lines) {
        return environmentError(withEnvironment(lines, "axiom: A\n"));
    };
    EXPECT_EQ(e("environment: forest\n"),
              "test.l:2:14: error: unknown environment 'forest'; expected one of obstacles, "
              "occupancy, light, clock, process");
    EXPECT_EQ(e("environment: sphere 0 0 0 radius 1\n"),
              "test.l:2:14: error: unknown environment 'sphere'; expected one of obstacles, "
              "occupancy, light, clock, process (obstacles follow a first line 'environment: "
              "obstacles')");
    EXPECT_EQ(e("environment: obstacles\n"),
              "test.l:2:14: error: the obstacles environment has no obstacles: add lines such "
              "as 'environment: sphere 0 5 0 radius 1.5'");
    EXPECT_EQ(e("environment: obstacles\nenvironment: sphere 0 5 0 1.5\n"),
              "test.l:3:27: error: expected 'radius' after the sphere's centre, found '1.5'");
    EXPECT_EQ(e("environment: obstacles\nenvironment: sphere 0 5 0 radius -1\n"),
              "test.l:3:34: error: a sphere's radius must be > 0");
    EXPECT_EQ(e("environment: obstacles\nenvironment: sphere 0 y 0 radius 1\n"),
              "test.l:3:23: error: expected the sphere's centre y (a number), found 'y'");
    EXPECT_EQ(e("environment: obstacles\nenvironment: box 0 0 0 1 1\n"),
              "test.l:3:27: error: expected the box's opposite corner z (a number) before the "
              "end of the line");
    EXPECT_EQ(e("environment: obstacles\nenvironment: plane 0 0 0 normal 0 0 0\n"),
              "test.l:3:33: error: a plane's normal must not be 0 0 0");
    EXPECT_EQ(e("environment: obstacles\nenvironment: cylinder 0 0 0\n"),
              "test.l:3:14: error: expected an obstacle ('sphere X Y Z radius R', 'box X0 Y0 "
              "Z0 X1 Y1 Z1' or 'plane X Y Z normal NX NY NZ') or 'margin M', found 'cylinder'");
    EXPECT_EQ(e("environment: obstacles margin -2\nenvironment: box 0 0 0 1 1 1\n"),
              "test.l:2:31: error: the margin must be >= 0");
    EXPECT_EQ(e("environment: occupancy cell 0\n"),
              "test.l:2:29: error: the cell size must be > 0");
    EXPECT_EQ(e("environment: occupancy cell 1\nenvironment: radius 2\n"),
              "test.l:3:14: error: the neighbourhood is already given by 'cell' at test.l:2:24; "
              "give either 'cell' or 'radius'");
    EXPECT_EQ(e("environment: light cells 2\n"),
              "test.l:2:20: error: expected 'cell SIZE' or 'radius R' for the light "
              "environment, found 'cells'");
    EXPECT_EQ(e("environment: occupancy radius\n"),
              "test.l:2:30: error: expected a size (a number) after 'radius' before the end "
              "of the line");
    EXPECT_EQ(e("environment: clock 4\n"),
              "test.l:2:20: error: the clock environment takes no arguments; found '4'");
    EXPECT_EQ(e("environment: process   \n"),
              "test.l:2:21: error: expected a command after 'process', e.g. 'environment: "
              "process python3 height_field.py'");
    EXPECT_EQ(e("environment: process cat\nenvironment: timeout 0\n"),
              "test.l:3:22: error: the timeout must be > 0 and at most 1000000 seconds");
    EXPECT_EQ(e("environment: process cat\nenvironment: verbose\n"),
              "test.l:3:14: error: expected 'timeout SECONDS' (the command is the rest of the "
              "'process' line), found 'verbose'");
}

TEST(EnvironmentErrors, TheCommandLineReportsThemWithFileLineAndColumn) {
    graftal::testing::TempDir dir;
    fs::path file = dir.write("bad.l",
                              "Lsystem: 1\nenvironment: obstacles\nenvironment: sphere 0 5 0 "
                              "radius\naxiom: A?E(0)\nendlsystem\n");
    auto r = graftal::testing::runGraftal("derive " + file.string());
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("bad.l:3:33: error: expected the sphere's radius (a number) before "
                         "the end of the line"),
              std::string::npos)
        << r.err;
}
