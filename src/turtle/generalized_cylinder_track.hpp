// The turtle's side of cpfg's generalized cylinders: what @Gs, @Gc, @Ge, @Gt, @Gr, @# and
// @! set, cpfg's `{(n)` ... `}(n)` cylinders whose control points `.`, F and f set, the
// control point a cylinder continues from, and the branches ([ copies it, ] restores it, as
// cpfg's spline stack does). It hands each piece between two control points back as
// rings (generalized_cylinder.hpp); the turtle draws them.
//
// `{(n[, rings])` with n = 1..4 starts a cylinder (cpfg's InitializeSpline): n = 1 an open
// one and n = 2 a closed one whose centre line is the Hermite curve of @Gc; n = 3 open and
// n = 4 closed with a uniform cubic B-spline centre line through none of its control
// points. `rings` (4 without it) is the pieces' steps when `.` gives none. Inside it F and
// f set a control point after they move; `}(n)` (n not 0) ends it, a closed one going back
// through its first one (Hermite) or three (B-spline) control points.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <map>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "graftal/core/module_string.hpp"
#include "graftal/geometry/contour_points.hpp"
#include "graftal/geometry/generalized_cylinder.hpp"

namespace graftal::turtle {

inline constexpr int kDefaultCylinderSteps = 4;  // cpfg's rings per piece without a parameter
inline constexpr int kMaxCylinderSides = 1024;
inline constexpr int kMaxCylinderSteps = 10000;

class GeneralizedCylinderTrack {
  public:
    // What a piece between two control points needs to be drawn.
    struct Piece {
        CylinderControlPoint from, to;
        int steps = kDefaultCylinderSteps;
        // A B-spline centre line: the span of these four control positions.
        std::optional<std::array<Vec3, 4>> bspline;
    };

    GeneralizedCylinderTrack(const std::vector<Contour>& contours, int sides)
        : contours_(contours) {
        branch_.attributes.sides = std::clamp(sides, 3, kMaxCylinderSides);
    }

    // [ and ]: branches carry the cylinder on; after ] the trunk goes on from where it was.
    void push() {
        if (!used_) {
            ++depth_;
            return;
        }
        stack_.push_back(branch_);
    }
    void pop() {
        if (!used_) {
            if (depth_ > 0) --depth_;
            return;
        }
        if (stack_.empty()) return;
        branch_ = std::move(stack_.back());
        stack_.pop_back();
    }

    // @#(id): the contour of the next control points (id 0, or none, is the circle; an id
    // no `contour:` line gave is the circle too, as in cpfg).
    void selectContour(std::span<const double> args) {
        use();
        int index = -1;
        if (!args.empty())
            for (std::size_t i = 0; i < contours_.size(); ++i)
                if (args[0] != 0 && contours_[i].id == static_cast<int>(args[0])) {
                    index = static_cast<int>(i);
                    break;
                }
        branch_.attributes.contour = index;
    }

    // @!(n): the points around a cross-section (8 without a parameter, at least 3).
    void setSides(std::span<const double> args) {
        use();
        double n = args.empty() ? 8 : args[0];
        branch_.attributes.sides =
            n >= kMaxCylinderSides ? kMaxCylinderSides : (n >= 3 ? static_cast<int>(n) : 3);
    }

    // The module after @G: s, c, e set control points (a piece to draw is returned), t and
    // r set tangents; others are ignored, as cpfg ignores them.
    template <class Draw>
    void command(Symbol sub, std::span<const double> args, const CylinderControlPoint& here,
                 Draw&& draw) {
        use();
        CylinderControlPoint& a = branch_.attributes;
        switch (sub) {
            case 's':
                // cpfg's @Gs: a new open Hermite cylinder whose points only @G sets.
                begin(Mode::AtCommandsOnly, 1, 0);
                controlPoint(here, 0, draw);
                break;
            case 'c':
            case 'e': {
                int steps = 0;
                if (!args.empty())
                    steps = args[0] >= kMaxCylinderSteps
                                ? kMaxCylinderSteps
                                : (args[0] >= 1 ? static_cast<int>(args[0]) : 1);
                // Without a cylinder, @Gc and @Ge start an open Hermite one (in which, as in
                // cpfg, F and f then set control points too).
                if (branch_.mode == Mode::None) begin(Mode::MovesToo, 1, 0);
                controlPoint(here, steps, draw);
                if (sub == 'e') finish(draw);
                break;
            }
            case 't':
                if (!args.empty()) {
                    a.tangentArriving = args[0];
                    a.tangentLeaving = args.size() > 1 ? args[1] : args[0];
                }
                break;
            case 'r':
                if (args.size() == 1) {
                    a.scaleRadiusTangents = args[0] != 0;
                } else if (args.size() >= 2) {
                    a.radiusArriving = a.radiusLeaving = polar(args[0], args[1]);
                    if (args.size() >= 4) a.radiusLeaving = polar(args[2], args[3]);
                }
                break;
            default:
                break;
        }
    }

    // `{(n[, rings])` with n not 0: a cylinder of type n (1..4, see above); false for
    // another n, which cpfg ignores with a warning.
    bool beginSpline(std::span<const double> args) {
        const double n = args.empty() ? 0 : args[0];
        if (!(n >= 1 && n < 5)) return false;
        use();
        const int type = static_cast<int>(n);
        int rings = 0;
        if (args.size() > 1 && args[1] >= 1)
            rings = args[1] >= kMaxCylinderSteps ? kMaxCylinderSteps : static_cast<int>(args[1]);
        begin(Mode::MovesToo, type, rings);
        return true;
    }

    // `}(n)` with n not 0: ends the cylinder (closing a closed one); false when none is
    // drawn (cpfg warns).
    template <class Draw>
    bool finishSpline(Draw&& draw) {
        if (branch_.mode == Mode::None) return false;
        finish(draw);
        return true;
    }

    // `.` outside a polygon: a control point (with `.(n)`, its piece in n steps); false
    // when no cylinder is drawn.
    template <class Draw>
    bool dot(std::span<const double> args, const CylinderControlPoint& here, Draw&& draw) {
        if (branch_.mode == Mode::None) return false;
        int steps = 0;
        if (!args.empty() && args[0] >= 1)
            steps = args[0] >= kMaxCylinderSteps ? kMaxCylinderSteps : static_cast<int>(args[0]);
        controlPoint(here, steps, draw);
        return true;
    }

    // Whether F and f set control points: inside `{(n)` (not after @Gs).
    bool movesSetPoints() const { return branch_.mode == Mode::MovesToo; }

    // F or f moved the turtle to `here` inside `{(n)`: a control point.
    template <class Draw>
    void moved(const CylinderControlPoint& here, Draw&& draw) {
        controlPoint(here, 0, draw);
    }

    // The cross-section points of contour index `contour` (-1: the circle), cached.
    const std::vector<Vec3>& contourPointsOf(int contour, int sides) {
        auto key = std::make_pair(contour, sides);
        auto it = cache_.find(key);
        if (it == cache_.end())
            it = cache_
                     .emplace(key, contour < 0 ? circleContourPoints(sides)
                                               : contourPoints(contours_[contour], sides))
                     .first;
        return it->second;
    }
    bool closedContour(int contour) const { return contour < 0 || contours_[contour].closed; }

    // The attributes @G, @# and @! give the control points set from here on.
    const CylinderControlPoint& attributes() const { return branch_.attributes; }

  private:
    // cpfg's spline flag: no cylinder, one whose points only @G and `.` set (@Gs), or one
    // whose points F and f set too (`{(n)`).
    enum class Mode { None, AtCommandsOnly, MovesToo };

    struct Branch {
        CylinderControlPoint attributes;  // position and frame unused
        Mode mode = Mode::None;
        bool closed = false, bspline = false;
        int defaultSteps = kDefaultCylinderSteps;
        int points = 0;             // control points met (cpfg's num)
        CylinderControlPoint last;  // where the next piece starts
        // B-spline: the last three control points; the next one draws the span of the four.
        std::vector<CylinderControlPoint> window;
        // Closed: the first control points (one, or three for a B-spline), met again at the
        // end.
        std::vector<CylinderControlPoint> closing;
    };

    static std::array<double, 2> polar(double degrees, double length) {
        double r = radians(degrees);
        return {std::cos(r) * length, std::sin(r) * length};
    }

    void use() {
        if (used_) return;
        used_ = true;
        stack_.assign(depth_, branch_);
    }

    // cpfg's InitializeSpline: type 1..4 (open/closed, Hermite/B-spline), `rings` the
    // default steps (4 when 0).
    void begin(Mode mode, int type, int rings) {
        branch_.mode = mode;
        branch_.closed = (type - 1) % 2 == 1;
        branch_.bspline = (type - 1) / 2 == 1;
        branch_.defaultSteps = rings > 0 ? rings : kDefaultCylinderSteps;
        branch_.points = 0;
        branch_.window.clear();
        branch_.closing.clear();
    }

    // cpfg's FinishSpline: a closed cylinder goes back through its first control points.
    template <class Draw>
    void finish(Draw& draw) {
        if (branch_.closed) {
            const std::vector<CylinderControlPoint> first = branch_.closing;
            for (const CylinderControlPoint& p : first) controlPoint(p, 0, draw);
        }
        branch_.mode = Mode::None;
        branch_.points = 0;
        branch_.window.clear();
        branch_.closing.clear();
    }

    // A B-spline piece's end: the control point `p`'s attributes at `position`, heading
    // along `slope`, its up vector carried there from p's (cpfg keeps p's heading when the
    // slope vanishes).
    static CylinderControlPoint bsplineEnd(const CylinderControlPoint& p, const Vec3& position,
                                           const Vec3& slope) {
        CylinderControlPoint end = p;
        end.position = position;
        if (length(slope) > 1e-7) {
            const Vec3 h = normalized(slope);
            end.up = carryUp(p.up, p.heading, h);
            end.heading = h;
            end.left = cross(end.up, h);
        }
        return end;
    }

    template <class Draw>
    void controlPoint(CylinderControlPoint here, int steps, Draw& draw) {
        if (steps <= 0) steps = branch_.defaultSteps;
        if (branch_.bspline) {
            if (branch_.points < 3) {
                branch_.window.push_back(here);
                if (branch_.closed) branch_.closing.push_back(here);
                ++branch_.points;
                return;
            }
            const std::array<Vec3, 4> p{branch_.window[0].position, branch_.window[1].position,
                                        branch_.window[2].position, here.position};
            const CylinderControlPoint from =
                branch_.points == 3
                    ? bsplineEnd(branch_.window[1], bsplinePoint(p, 0), bsplineSlope(p, 0))
                    : branch_.last;
            const CylinderControlPoint to =
                bsplineEnd(branch_.window[2], bsplinePoint(p, 1), bsplineSlope(p, 1));
            draw(Piece{from, to, steps, p});
            branch_.last = to;
            branch_.window.erase(branch_.window.begin());
            branch_.window.push_back(here);
            ++branch_.points;
            return;
        }
        if (branch_.points == 0) {
            branch_.last = here;
            branch_.points = 1;
            if (branch_.closed) branch_.closing.push_back(here);
            return;
        }
        // cpfg keeps the cylinder untwisted: the new point's up vector is the last one's,
        // carried by the smallest rotation from the last heading to the new one.
        here.up = carryUp(branch_.last.up, branch_.last.heading, here.heading);
        here.left = cross(here.up, here.heading);
        draw(Piece{branch_.last, here, steps, std::nullopt});
        branch_.last = here;
        ++branch_.points;
    }

    const std::vector<Contour>& contours_;
    Branch branch_;
    std::vector<Branch> stack_;
    std::size_t depth_ = 0;  // [ met before the first @G, @# or @!
    bool used_ = false;
    std::map<std::pair<int, int>, std::vector<Vec3>> cache_;
};

}  // namespace graftal::turtle
