// parse() and loadModel(): the model as far as the parser got, every diagnostic as a value,
// and the ParserTarget the parser writes through.
#include <gtest/gtest.h>

#include "graftal/graftal.hpp"
#include "test_helpers.hpp"

using namespace graftal;

namespace {

ParseResult parseText(const std::string& text) {
    ParseOptions o;
    o.fileName = "test.l";
    return graftal::parse(text, o);
}

}  // namespace

TEST(ParseResult, KeepsThePartialModelAndEveryDiagnostic) {
    ParseResult r = parseText(
        "Lsystem: 1\nangle increment: 30\naxiom: A\nstep length: -2\nA --> AB\n"
        "b < A --> A\nA --> C\nendlsystem\n");
    EXPECT_FALSE(r.ok());
    ASSERT_EQ(r.errors().size(), 1u);
    EXPECT_EQ(r.errors()[0].toString(), "test.l:4:14: error: step length must be positive");
    EXPECT_EQ(r.errors()[0].location.endLine, 4);
    EXPECT_EQ(r.errors()[0].location.endColumn, 16) << "the end of '-2'";
    EXPECT_EQ(r.warnings().size(), 1u);
    EXPECT_EQ(r.model.lsystem.productions.size(), 3u);
    EXPECT_DOUBLE_EQ(r.model.view.turtle.angleDegrees, 30);
    EXPECT_THROW(r.orThrow(), Error);
}

TEST(ParseResult, AnErrorAtATokenEndsWithTheToken) {
    ParseResult r = parseText("Lsystem: 1\nderivation lenght: 4\naxiom: F\n");
    ASSERT_FALSE(r.ok());
    const SourceLocation& at = r.errors()[0].location;
    EXPECT_EQ(at.line, 2);
    EXPECT_EQ(at.column, 1);
    EXPECT_EQ(at.endLine, 2);
    EXPECT_EQ(at.endColumn, 11) << "just past 'derivation'";
}

TEST(ParseResult, AnUnreadableFileIsADiagnosticNotAnException) {
    ParseResult r = loadModel("/no/such/dir/plant.l");
    ASSERT_EQ(r.diagnostics.size(), 1u);
    EXPECT_EQ(r.diagnostics[0].toString(),
              "/no/such/dir/plant.l: error: cannot open the file (does it exist?)");
    EXPECT_THROW(loadLSystem("/no/such/dir/plant.l"), Error);
}

TEST(ParseResult, ThrowingWrappersKeepTheGrammar) {
    LSystem ls = parseLSystem("Lsystem: 1\naxiom: F\nF --> FF\nendlsystem\n");
    EXPECT_EQ(ls.productions.size(), 1u);
}

TEST(ParserTarget, ViewSettingsAreSetByNameWithTheirChecks) {
    DiagnosticList diags;
    ModelBuilder builder(diags);
    builder.viewSetting({"step length", 2.5, SourceLocation{"plant.v", 3, 14, 3, 17}});
    builder.viewSetting({"viewpoint", Vec3{0, 0, 10}, SourceLocation{"plant.v", 4, 12}});
    builder.viewSetting({"line style", std::string("lines"), SourceLocation{"plant.v", 5, 13}});
    builder.viewSetting({"width factor", 1.5, SourceLocation{"plant.v", 6, 15, 6, 18}});
    builder.viewSetting({"projection", 3.0, SourceLocation{"plant.v", 7, 13}});
    EXPECT_DOUBLE_EQ(builder.model().view.turtle.stepLength, 2.5);
    ASSERT_TRUE(builder.model().view.camera.viewpoint);
    EXPECT_DOUBLE_EQ(builder.model().view.camera.viewpoint->z, 10);
    EXPECT_EQ(builder.model().view.materials.lineStyle, LineStyle::Lines);
    ASSERT_EQ(diags.items().size(), 2u);
    EXPECT_EQ(diags.items()[0].toString(),
              "plant.v:6:15: error: width factor must be between 0 and 1 (what ! multiplies by)");
    EXPECT_EQ(diags.items()[0].location.endColumn, 18);
    EXPECT_EQ(diags.items()[1].toString(),
              "plant.v:7:13: error: 'projection:' expects a word or a file name, not a number");
}

// A target that records what the parser says, as a front end's test would.
class RecordingTarget : public ModelBuilder {
  public:
    using ModelBuilder::ModelBuilder;
    std::vector<std::string> calls;
    void production(ProductionGroup group, Production p) override {
        calls.push_back("production " + std::to_string(static_cast<int>(group)) + " line " +
                        std::to_string(p.location.line));
        ModelBuilder::production(group, std::move(p));
    }
    void viewSetting(const ViewSetting& s) override {
        calls.push_back("view " + s.name + " at " + s.location.toString());
        ModelBuilder::viewSetting(s);
    }
    void table(const std::string& name, const SourceLocation& where) override {
        calls.push_back("table " + name + " at " + where.toString());
        ModelBuilder::table(name, where);
    }
};

TEST(ParserTarget, TheParserWritesEveryFactThroughTheTarget) {
    ParseOptions o;
    o.fileName = "t.l";
    DiagnosticList diags;
    RecordingTarget target(diags);
    parseInto(
        "Lsystem: 1\nangle factor: 8\naxiom: A\ntable: one\nA --> B\ntable schedule: one\n"
        "homomorphism\nB --> F\nendlsystem\n",
        o, target, diags);
    EXPECT_TRUE(diags.items().empty());
    EXPECT_EQ(target.calls,
              (std::vector<std::string>{"view angle factor at t.l:2:15", "table one at t.l:4:8",
                                        "production 0 line 5", "production 2 line 8"}));
    const Model& m = target.model();
    EXPECT_DOUBLE_EQ(m.view.turtle.angleDegrees, 45);
    EXPECT_EQ(m.lsystem.tableNames, std::vector<std::string>{"one"});
    EXPECT_EQ(m.lsystem.productions[0].table, 0);
    EXPECT_EQ(m.lsystem.schedule.size(), 1u);
}
