#include <gtest/gtest.h>

#include "test_helpers.hpp"

using namespace graftal;
using graftal::testing::derived;
using graftal::testing::parse;

TEST(QueryModules, PositionAndOrientationAreWrittenIntoParameters) {
    LSystem ls = parse(
        "Lsystem: 1\nangle increment: 90\naxiom: F?P(0,0)+F?H(0,0)[F?P(9,9,9)]\nendlsystem\n");
    EXPECT_EQ(derived(ls, 0), "F?P(0,1)+F?H(-1,0)[F?P(-2,1,0)]");
}

TEST(QueryModules, AnswerAfterEveryStepSoProductionsCanReadThem) {
    // An apex that stops once it is higher than 3 units.
    LSystem ls = parse(
        "Lsystem: 1\naxiom: A?P(0,0)\n"
        "A > ?P(x,y) : y < 3 --> FA\nA > ?P(x,y) : y >= 3 --> *\nendlsystem\n");
    EXPECT_EQ(derived(ls, 2), "FFA?P(0,2)");
    EXPECT_EQ(derived(ls, 5), "FFF?P(0,3)");
}

TEST(QueryModules, SeeTheStringAfterTheHomomorphism) {
    LSystem ls = parse("Lsystem: 1\naxiom: II?P(0,0)\nhomomorphism\nI --> F(2)\nendlsystem\n");
    EXPECT_EQ(derived(ls, 0), "II?P(0,4)");
}

namespace {

class RecordingEnvironment : public Environment {
  public:
    std::string name() const override { return "recording"; }
    void respond(int step, std::span<CommunicationRequest> requests) override {
        for (auto& r : requests) {
            seen.push_back({step, r.frame.position.y});
            for (auto& p : r.params) p = 100 * step + r.frame.position.y;
        }
    }
    std::vector<std::pair<int, double>> seen;
};

}  // namespace

TEST(QueryModules, CommunicationModulesTalkToTheEnvironment) {
    LSystem ls = parse("Lsystem: 1\naxiom: A?E(0)\nA --> FA\nendlsystem\n");
    RecordingEnvironment env;
    DerivationOptions o;
    o.environment = &env;
    ModuleString s = deriveWithQueries(ls, 2, o);
    EXPECT_EQ(s.toString(ls.symbols), "FFA?E(202)");
    ASSERT_EQ(env.seen.size(), 3u) << "once for the axiom and once per step";
    EXPECT_EQ(env.seen[0], (std::pair<int, double>{0, 0}));
    EXPECT_EQ(env.seen[2], (std::pair<int, double>{2, 2}));
}
