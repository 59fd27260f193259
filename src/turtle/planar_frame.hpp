// The turtle's frame in the z = 0 plane and the two operations that change it, shared by
// the walks that must give the generic turtle's doubles bit for bit (planar_measure.hpp
// says why the planar operations are exact).
#pragma once

#include <cmath>

namespace graftal::turtle {

// What [ saves and ] restores: TurtleState without what a flat measure never reads.
struct Frame {
    double x = 0, y = 0;     // position (z is +0)
    double hx = 0, hy = 1;   // heading H (z is a zero)
    double lx = -1, ly = 0;  // left L (z is a zero); U stays along z
    double weight = 0;       // inkLength()'s width factor for this width
    float width = 1;         // the turtle's width
    bool inBounds = false;   // the position is already in the bounds
};

// a' = a cos + b sin, b' = b cos - a sin on the x and y of H and L, as rotatePair() does.
inline void rotateFrame(Frame& f, double c, double s) {
    double hx = f.hx * c + f.lx * s, hy = f.hy * c + f.ly * s;
    double lx = f.lx * c + f.hx * (-s), ly = f.ly * c + f.hy * (-s);
    f.hx = hx;
    f.hy = hy;
    f.lx = lx;
    f.ly = ly;
}

// TurtleMachine::orthonormalise() without the z terms, which add exact zeros.
inline void orthonormalise(Frame& f) {
    double n = std::sqrt(f.hx * f.hx + f.hy * f.hy);
    if (n > 0) {
        double k = 1 / n;
        f.hx = f.hx * k;
        f.hy = f.hy * k;
    }
    double d = f.lx * f.hx + f.ly * f.hy;
    double lx = f.lx - f.hx * d, ly = f.ly - f.hy * d;
    double m = std::sqrt(lx * lx + ly * ly);
    if (m > 0) {
        double k = 1 / m;
        lx = lx * k;
        ly = ly * k;
    }
    f.lx = lx;
    f.ly = ly;
}

}  // namespace graftal::turtle
