// The ray tracer's camera. Framing fits the camera to the scene's own projected outline:
// with the viewing direction fixed (from the front, slightly raised, or towards a given
// target), the four sides of the picture are planes through the eye, and each is pushed
// against the point of the scene that sticks out furthest across it. Two opposite sides
// then touch the scene (within the margin) and the other two hold it centred, so a tall
// tree fills the picture's height and a wide one its width, whatever their depth.
#include "raytrace_camera.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>

#include "graftal/core/diagnostics.hpp"
#include "graftal/output/framed_picture.hpp"

namespace graftal {

namespace {

// The scene's outline spans this fraction of the picture's width or height (the tighter),
// a margin of 3% on each side: close to the edges, never cut by them. The camera is raised
// this far above the horizontal: a plant is seen slightly from above, as one stands
// before it.
constexpr double kFrameFill = 0.94;
constexpr double kFrameElevationDegrees = 20;
constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Embree takes rays in single precision and asserts that their origins and directions lie
// within 1.8e18 (FLT_LARGE); far short of that a float cannot tell a plant's points apart.
constexpr double kFarthest = 1e15;

std::string formatPoint(const Vec3& p) {
    std::ostringstream os;
    os << p.x << ", " << p.y << ", " << p.z;
    return os.str();
}

bool within(const Vec3& p, double limit) {
    return isFinite(p) && std::abs(p.x) <= limit && std::abs(p.y) <= limit &&
           std::abs(p.z) <= limit;
}

Error cameraError(const std::string& message) {
    return Error(SourceLocation{"graftal", 0, 0}, message);
}

double tanHalfVertical(const Camera& c) {
    return std::tan(radians(c.fieldOfView / 2));
}

// A unit vector perpendicular to `up` pointing out of the picture towards the viewer: +z
// when up is the default +y. A z-up world has no +z front, so -y serves there.
Vec3 frontDirection(Vec3 up) {
    Vec3 front = Vec3{0, 0, 1} - up * up.z;
    if (length(front) < 1e-6) front = Vec3{0, -1, 0} - up * (-up.y);
    return unitOrZero(front);
}

// The camera's axes: right and up across the picture, forward into it.
struct Axes {
    Vec3 right, up, forward;
};

Axes axesLookingAlong(Vec3 forward, Vec3 worldUp) {
    Axes a;
    a.forward = unitOrZero(forward);
    Vec3 right = cross(a.forward, worldUp);
    if (length(right) < 1e-9) {
        // Looking straight along the up vector: any horizontal direction is as good.
        const Vec3 axis = std::abs(a.forward.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 0, 1};
        right = cross(a.forward, cross(axis, a.forward));
    }
    a.right = unitOrZero(right);
    a.up = cross(a.right, a.forward);
    return a;
}

Bounds boundsOf(const PointSource& points) {
    Bounds b;
    points([&](const Vec3& p, double r) {
        b.extend(p - Vec3{r, r, r});
        b.extend(p + Vec3{r, r, r});
    });
    return b;
}

double largestSide(const Bounds& b) {
    if (b.empty()) return 0;
    return std::max({b.max.x - b.min.x, b.max.y - b.min.y, b.max.z - b.min.z});
}

// A point seen in the camera's axes: x across, y up, z in depth.
struct Seen {
    double x, y, z;
};

Seen seen(const Axes& a, const Vec3& p) {
    return {dot(p, a.right), dot(p, a.up), dot(p, a.forward)};
}

// The eye's depth (in the camera's axes) and position across that fit the scene into a
// perspective picture whose edges are at |x| <= tx * depth and |y| <= ty * depth.
struct Fit {
    double x = 0, y = 0, z = 0;
};

// Free target: each side plane is moved to touch the scene; the eye goes where the left
// and right planes meet, or where the top and bottom ones do, whichever is further back.
Fit fitPerspective(const PointSource& points, const Axes& a, double tx, double ty) {
    const double sx = std::sqrt(1 + tx * tx), sy = std::sqrt(1 + ty * ty);
    double left = kInfinity, right = -kInfinity, bottom = kInfinity, top = -kInfinity;
    points([&](const Vec3& p, double r) {
        const Seen s = seen(a, p);
        right = std::max(right, s.x - tx * s.z + r * sx);
        left = std::min(left, s.x + tx * s.z - r * sx);
        top = std::max(top, s.y - ty * s.z + r * sy);
        bottom = std::min(bottom, s.y + ty * s.z - r * sy);
    });
    Fit f;
    f.x = (left + right) / 2;
    f.y = (bottom + top) / 2;
    f.z = std::min((left - right) / (2 * tx), (bottom - top) / (2 * ty));
    return f;
}

// With the eye's depth fixed, moves it across (along x when `alongX`, else y) until the
// scene's projection is centred on that axis. The projection's extreme points decide: the
// eye is put where those two project symmetrically, and the extremes are looked up again
// (a few rounds settle it; each round only improves the balance).
void centreAcross(const PointSource& points, const Axes& a, Fit& f, bool alongX) {
    for (int round = 0; round < 4; ++round) {
        double high = -kInfinity, low = kInfinity;
        double highAt = 0, highDepth = 1, lowAt = 0, lowDepth = 1;
        const double eye = alongX ? f.x : f.y;
        points([&](const Vec3& p, double r) {
            const Seen s = seen(a, p);
            const double depth = s.z - f.z;
            if (!(depth > 0)) return;
            const double across = alongX ? s.x : s.y;
            const double hi = (across + r - eye) / depth, lo = (across - r - eye) / depth;
            if (hi > high) high = hi, highAt = across + r, highDepth = depth;
            if (lo < low) low = lo, lowAt = across - r, lowDepth = depth;
        });
        if (!(high >= low) || std::abs(high + low) <= 1e-9 * (high - low)) return;
        const double moved =
            (highAt / highDepth + lowAt / lowDepth) / (1 / highDepth + 1 / lowDepth);
        (alongX ? f.x : f.y) = moved;
    }
}

}  // namespace

PointSource drawnPoints(std::span<const TracedScene> scenes) {
    return [scenes](const PointVisitor& visit) {
        for (const TracedScene& s : scenes) forEachDrawnPoint(s, visit);
    };
}

bool embreeCanTrace(const Vec3& origin, const Vec3& direction) {
    return within(origin, 1e18) && within(direction, 1e18);
}

// Values no picture can be made from, refused before any geometry reaches Embree.
void checkCamera(const Camera& c) {
    // A fitted parallel view takes only the direction from viewpoint to target: those may be
    // far out, as long as their difference is a finite vector.
    const bool directionOnly = c.orthographic && c.fitWindow && c.viewpoint && c.target;
    const double limit = directionOnly ? 1e150 : kFarthest;
    if (c.viewpoint && !within(*c.viewpoint, limit))
        throw cameraError("the viewpoint " + formatPoint(*c.viewpoint) +
                          " is not a finite point within " + (directionOnly ? "1e150" : "1e15") +
                          " of the origin (the ray tracer "
                          "cannot aim from there): give a nearer one (--viewpoint, or "
                          "`viewpoint:` in the view file)");
    if (c.target && !within(*c.target, limit))
        throw cameraError("the view's target " + formatPoint(*c.target) +
                          " is not a finite point within " + (directionOnly ? "1e150" : "1e15") +
                          " of the origin: give a nearer one "
                          "(--target, or `view reference point:` in the view file)");
    if (!within(c.up, kFarthest) || !(length(c.up) > 0))
        throw cameraError("the camera's up vector " + formatPoint(c.up) +
                          " must be finite and not zero (--up, or `up vector:` in the view "
                          "file)");
    if (!(c.fieldOfView > 0 && c.fieldOfView < 180))
        throw cameraError(
            "the field of view must be between 0 and 180 degrees (--fov, or "
            "`field of view:` in the view file)");
}

Camera frameCamera(const Camera& c, const PointSource& points, int width, int height) {
    checkCamera(c);
    Camera framed = c;
    const bool directionOnly = c.orthographic && c.fitWindow && c.viewpoint && c.target &&
                               length(*c.target - *c.viewpoint) > 0;
    if (c.viewpoint && c.target && !directionOnly) return framed;
    const Bounds box = boundsOf(points);
    const Vec3 centre = box.empty() ? Vec3{} : (box.min + box.max) * 0.5;
    if (c.viewpoint && !directionOnly) {
        framed.target = centre;
        return framed;
    }

    const Vec3 worldUp = unitOrZero(c.up);
    const double elevation = radians(kFrameElevationDegrees);
    const Vec3 towardsEye =
        frontDirection(worldUp) * std::cos(elevation) + worldUp * std::sin(elevation);
    const Axes a = directionOnly ? axesLookingAlong(*c.target - *c.viewpoint, worldUp)
                                 : axesLookingAlong(-towardsEye, worldUp);
    const double aspect = static_cast<double>(width) / height;
    const double ty = kFrameFill * tanHalfVertical(c), tx = ty * aspect;

    // Nothing drawn, or a single point: frame a ball of radius 1 there instead, so that
    // any picture can be made.
    const bool point = box.empty() || largestSide(box) == 0;
    const PointSource unitBall = [&](const PointVisitor& visit) { visit(centre, 1.0); };
    const PointSource& fitted = point ? unitBall : points;

    // Depths of the scene in the camera's axes (the orthographic eye stands before them).
    double nearest = kInfinity, farthest = -kInfinity;
    fitted([&](const Vec3& p, double r) {
        const double z = dot(p, a.forward);
        nearest = std::min(nearest, z - r);
        farthest = std::max(farthest, z + r);
    });
    // The eye never touches the scene: at least this far before its nearest point.
    const double clearance = 1e-3 * std::max(largestSide(box), 1e-9);

    Fit f;
    if (c.target && !directionOnly) {
        const Seen t = seen(a, *c.target);
        f = {t.x, t.y, t.z};
        if (c.orthographic) {
            double half = 0;  // the window's half-height that holds everything
            fitted([&](const Vec3& p, double r) {
                const Seen s = seen(a, p);
                half =
                    std::max({half, (std::abs(s.y - t.y) + r), (std::abs(s.x - t.x) + r) / aspect});
            });
            const double distance = std::max(half / ty, clearance);
            framed.viewpoint = *c.target - a.forward * distance;
            return framed;
        }
        // The eye moves back from the target until every ball is inside all four planes.
        const double sx = std::sqrt(1 + 1 / (tx * tx)), sy = std::sqrt(1 + 1 / (ty * ty));
        double z = t.z - clearance;
        fitted([&](const Vec3& p, double r) {
            const Seen s = seen(a, p);
            z = std::min({z, s.z - std::abs(s.x - t.x) / tx - r * sx,
                          s.z - std::abs(s.y - t.y) / ty - r * sy});
        });
        framed.viewpoint = *c.target - a.forward * (t.z - std::min(z, nearest - clearance));
        return framed;
    }

    if (c.orthographic) {
        double left = kInfinity, right = -kInfinity, bottom = kInfinity, top = -kInfinity;
        fitted([&](const Vec3& p, double r) {
            const Seen s = seen(a, p);
            left = std::min(left, s.x - r);
            right = std::max(right, s.x + r);
            bottom = std::min(bottom, s.y - r);
            top = std::max(top, s.y + r);
        });
        const double half = std::max((top - bottom) / 2, (right - left) / 2 / aspect);
        const double distance = std::max(half / ty, clearance);
        const Vec3 target = a.right * ((left + right) / 2) + a.up * ((bottom + top) / 2) +
                            a.forward * ((nearest + farthest) / 2);
        framed.target = target;
        framed.viewpoint = target - a.forward * distance;
        return framed;
    }

    f = fitPerspective(fitted, a, tx, ty);
    if (f.z > nearest - clearance) f.z = nearest - clearance;
    {
        // The tighter pair of sides set the depth and touches the scene; the other pair
        // has room, and the scene is centred between them.
        double left = kInfinity, right = -kInfinity, bottom = kInfinity, top = -kInfinity;
        fitted([&](const Vec3& p, double r) {
            const Seen s = seen(a, p);
            const double depth = s.z - f.z;
            if (!(depth > 0)) return;
            left = std::min(left, (s.x - r - f.x) / depth);
            right = std::max(right, (s.x + r - f.x) / depth);
            bottom = std::min(bottom, (s.y - r - f.y) / depth);
            top = std::max(top, (s.y + r - f.y) / depth);
        });
        const bool xLoose = (right - left) / tx < (top - bottom) / ty;
        centreAcross(fitted, a, f, xLoose);
    }
    const Vec3 eye = a.right * f.x + a.up * f.y + a.forward * f.z;
    framed.viewpoint = eye;
    framed.target = eye + a.forward * ((nearest + farthest) / 2 - f.z);
    return framed;
}

View makeView(const Camera& c, const PointSource& points, int width, int height) {
    checkCamera(c);
    const Vec3 worldUp = unitOrZero(c.up);
    const double aspect = static_cast<double>(width) / height;
    const double tanHalfV = tanHalfVertical(c);
    const Vec3 target = *c.target;
    const Vec3 eye = *c.viewpoint;

    const Vec3 toTarget = target - eye;
    const double distance = length(toTarget);
    if (!(distance > 0))
        throw Error(SourceLocation{}, "the camera's viewpoint and target are the same point");
    const Axes a = axesLookingAlong(toTarget, worldUp);
    View view;
    view.orthographic = c.orthographic;
    view.eye = eye;
    view.forward = a.forward;
    // The orthographic window is what the perspective camera shows in the target's plane,
    // so switching projections keeps the plant the same size there.
    const double scale = c.orthographic ? distance : 1.0;
    view.right = a.right * (tanHalfV * aspect * scale);
    view.up = a.up * (tanHalfV * scale);
    view.pixelHeight = 2 * tanHalfV * scale / height;
    if (c.orthographic) {
        double nearest = 0;
        points([&](const Vec3& p, double r) {
            nearest = std::min(nearest, dot(p - eye, a.forward) - r);
        });
        view.orthographicBackOff = -nearest * 1.001 + 1e-6 * distance;
    }
    // A scene too large (or a camera framed too far back for it) leaves the range too.
    const double reach = (c.orthographic ? std::abs(view.orthographicBackOff) : 0) +
                         length(view.right) + length(view.up) + length(view.forward);
    if (!within(view.eye, kFarthest) || !std::isfinite(reach) || reach > kFarthest)
        throw cameraError("the camera would stand at " + formatPoint(view.eye) +
                          ", not within 1e15 of the origin: the scene is too large for the ray "
                          "tracer (lower the steps or the lengths) or the viewpoint too far");
    return view;
}

Camera framedCamera(const Camera& camera, const Bounds& frame, int width, int height) {
    const PointSource corners = [&](const PointVisitor& visit) {
        if (frame.empty()) return;
        const Vec3 lo = frame.min, hi = frame.max;
        for (int k = 0; k < 8; ++k)
            visit(Vec3{k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z}, 0.0);
    };
    return frameCamera(camera, corners, width, height);
}

Camera framedCamera(const Camera& camera, std::span<const MeshScene* const> scenes, int width,
                    int height) {
    std::vector<TracedScene> traced;
    for (const MeshScene* s : scenes)
        if (s) traced.push_back(TracedScene::of(*s));
    return frameCamera(camera, drawnPoints(traced), width, height);
}

Camera framedCamera(const Camera& camera, const MeshScene& scene, int width, int height) {
    const MeshScene* one[] = {&scene};
    return framedCamera(camera, one, width, height);
}

}  // namespace graftal
