// The turtle's side of cpfg's generalized cylinders: what @Gs, @Gc, @Ge, @Gt, @Gr, @# and
// @! set, the control point a cylinder continues from, and the branches ([ copies it, ]
// restores it, as cpfg's spline stack does). It hands each piece between two control
// points back as rings (generalized_cylinder.hpp); the turtle draws them.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <map>
#include <span>
#include <utility>
#include <vector>

#include "graftal/contour.hpp"
#include "graftal/generalized_cylinder.hpp"
#include "graftal/module_string.hpp"

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
                branch_.active = true;
                branch_.points = 0;
                controlPoint(here, 0, draw);
                break;
            case 'c':
            case 'e': {
                int steps = 0;
                if (!args.empty())
                    steps = args[0] >= kMaxCylinderSteps
                                ? kMaxCylinderSteps
                                : (args[0] >= 1 ? static_cast<int>(args[0]) : 1);
                if (!branch_.active) {
                    branch_.active = true;
                    branch_.points = 0;
                }
                controlPoint(here, steps, draw);
                if (sub == 'e') branch_.active = false;
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
    struct Branch {
        CylinderControlPoint attributes;  // position and frame unused
        bool active = false;
        int points = 0;
        CylinderControlPoint last;
    };

    static std::array<double, 2> polar(double degrees, double length) {
        double r = degrees * 3.14159265358979323846 / 180;
        return {std::cos(r) * length, std::sin(r) * length};
    }

    void use() {
        if (used_) return;
        used_ = true;
        stack_.assign(depth_, branch_);
    }

    template <class Draw>
    void controlPoint(CylinderControlPoint here, int steps, Draw& draw) {
        if (branch_.points == 0) {
            branch_.last = here;
            branch_.points = 1;
            return;
        }
        // cpfg keeps the cylinder untwisted: the new point's up vector is the last one's,
        // carried by the smallest rotation from the last heading to the new one.
        here.up = carryUp(branch_.last.up, branch_.last.heading, here.heading);
        here.left = cross(here.up, here.heading);
        draw(Piece{branch_.last, here, steps > 0 ? steps : kDefaultCylinderSteps});
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
