// cpfg's movements read from a view file, with the coordinates cpfg gives (its oracle:
// v10_torque, v10_tropism_old, v10_tropism_new), and cpfg's view volume (the box of its
// output: t09_f_move, t09_start_moved).
#include <gtest/gtest.h>

#include <string>

#include "graftal/graftal.hpp"
#include "graftal/turtle/streamed_interpretation.hpp"
#include "process.hpp"

using namespace graftal;
using namespace graftal::testing;

namespace {

Model withView(const TempDir& dir, const std::string& successor, const std::string& view) {
    ParseOptions o;
    o.viewFile = dir.write("m.v", view).string();
    return loadModel(dir.write("m.l", "Lsystem: 1\nderivation length: 1\nAxiom: A\nA --> " +
                                          successor + "\nendlsystem\n"),
                     o)
        .orThrow();
}

void expectNear(const Vec3& got, const Vec3& want, const char* what) {
    EXPECT_NEAR(got.x, want.x, 1e-5) << what;
    EXPECT_NEAR(got.y, want.y, 1e-5) << what;
    EXPECT_NEAR(got.z, want.z, 1e-5) << what;
}

}  // namespace

TEST(CpfgMovements, TorqueRollsTheTurtleBeforeEveryMove) {
    TempDir dir;
    Model m = withView(dir, "F+F+F+F", "torque: T: 1,0,0 E: 0.5\n");
    Scene s = interpret(m, derive(m, -1));
    ASSERT_EQ(s.segments.size(), 4u);
    // The heading never meets T's direction, so the first segment is straight and the
    // rolls then tip the later turns out of the plane.
    expectNear(s.segments[0].b, {0, 1, 0}, "first");
    expectNear(s.segments[1].b, {-0.620545, 1.70711, 0.339005}, "second");
    expectNear(s.segments[2].b, {-1.37367, 1.73098, 0.996448}, "third");
    expectNear(s.segments[3].b, {-1.84678, 1.04948, 1.55477}, "fourth");
}

TEST(CpfgMovements, OldTropismBendsAfterEachSegment) {
    TempDir dir;
    Model m =
        withView(dir, "F F [+F F] F F", "tropism direction: 1,-1,1\ninitial elasticity: 0.2\n");
    Scene s = interpret(m, derive(m, -1));
    ASSERT_EQ(s.segments.size(), 6u);
    expectNear(s.segments[0].b, {0, 1, 0}, "the first segment is straight");
    // Pitch toward T first, then turn toward it: x and z differ.
    expectNear(s.segments[1].b, {0.11547, 1.98667, 0.114698}, "second");
    expectNear(s.segments[3].b, {-0.866826, 3.63728, 0.651515}, "branch end");
    expectNear(s.segments[5].b, {0.717679, 3.78766, 0.711914}, "main axis end");
}

TEST(CpfgMovements, NewTropismBendsBeforeEachMoveAndLinesAdd) {
    TempDir dir;
    Model m = withView(dir, "F F [+F F] F F", "tropism: T: 1,-1,1, E: 0.2\n");
    Scene s = interpret(m, derive(m, -1));
    ASSERT_EQ(s.segments.size(), 6u);
    expectNear(s.segments[0].b, {0.114958, 0.986696, 0.114958}, "the first segment is bent");
    expectNear(s.segments[1].b, {0.3529, 1.92838, 0.3529}, "second");
    expectNear(s.segments[5].b, {1.1882, 3.52992, 1.1882}, "main axis end");
    EXPECT_NEAR(s.segments[3].b.x, -0.51107, 1e-4) << "the branch's end: cpfg's box";
    // Two lines of half the elasticity each bend as one.
    Model two =
        withView(dir, "F F F F", "tropism: T: 1,-1,1, E: 0.1\ntropism: T: 1,-1,1, E: 0.1\n");
    Scene t = interpret(two, derive(two, -1));
    ASSERT_EQ(t.segments.size(), 4u);
    expectNear(t.segments[1].b, {0.3529, 1.92838, 0.3529}, "two lines");
}

TEST(CpfgViewVolume, HoldsTheStartOfEveryMoveAndTheEnd) {
    TempDir dir;
    // f moves are not drawn, but where they start and end is in cpfg's box.
    Model m = withView(dir, "F[+f(2)]F-f", "angle increment: 90\n");
    Bounds b = cpfgViewVolume(m, derive(m, -1));
    expectNear(b.min, {-2, 0, 0}, "min");
    expectNear(b.max, {1, 2, 0}, "max");
    // The origin is inside though nothing is drawn there.
    Model moved = withView(dir, "f(3)F+(90)F", "angle increment: 30\n");
    b = cpfgViewVolume(moved, derive(moved, -1));
    expectNear(b.min, {-1, 0, 0}, "min");
    expectNear(b.max, {0, 4, 0}, "max");
    // @o adds its square at z = 0, @O its cube.
    Model discs = withView(dir, "&F@o(2)@O(1)", "angle increment: 90\n");
    b = cpfgViewVolume(discs, derive(discs, -1));
    expectNear(b.min, {-1, -1, -1.5}, "min");
    expectNear(b.max, {1, 1, 0}, "max");
}
