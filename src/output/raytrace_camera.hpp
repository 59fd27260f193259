// The ray tracer's camera: where it stands when the caller leaves that open (framing the
// scene so that it fills the picture), and the ray through each point of the picture.
#pragma once

#include <functional>

#include "graftal/output/render3d.hpp"
#include "traced_scene.hpp"

namespace graftal {

// Calls its argument with (centre, radius) for every ball whose hull is to be kept in view.
using PointVisitor = std::function<void(const Vec3&, double)>;
using PointSource = std::function<void(const PointVisitor&)>;

// The points of the scenes as drawn (forEachDrawnPoint), as one source.
PointSource drawnPoints(std::span<const TracedScene> scenes);

// Throws Error for camera values no picture can be made from: a viewpoint or target that is
// not finite or lies farther than 1e15 from the origin (Embree's rays are floats), an up
// vector that is not finite or zero, a field of view outside (0, 180) degrees.
void checkCamera(const Camera& camera);

// True when Embree takes a ray from `origin` along `direction`: both finite and, as floats,
// within its assertion's range (1.8e18). A ray from a point found without Embree (the
// ground plane hit at a grazing angle, 1e180 away) may not be.
bool embreeCanTrace(const Vec3& origin, const Vec3& direction);

// The camera with its unset viewpoint and target chosen to frame the points: the projected
// extent of the hull of the balls fills kFrameFill of the picture's width or height (the
// tighter one) and is centred in the other. A given target stays the picture's centre.
Camera frameCamera(const Camera& camera, const PointSource& points, int width, int height);

// Where rays come from. For a perspective camera every ray starts at `eye` and goes through
// forward + u * right + v * up, u and v in [-1, 1] across the picture; an orthographic
// camera moves the start instead and keeps the direction `forward` (starting far enough
// behind the eye that nothing drawn is behind it, as a parallel projection shows all).
struct View {
    Vec3 eye, forward, right, up;
    bool orthographic = false;
    double orthographicBackOff = 0;
    double pixelHeight = 0;  // of one pixel, at distance 1 (perspective) or anywhere (ortho)

    // The ray through picture point (u, v): u from -1 (left) to 1, v from -1 (bottom) to 1.
    void ray(double u, double v, Vec3& origin, Vec3& direction) const {
        const Vec3 offset = right * u + up * v;
        if (orthographic) {
            origin = eye + offset - forward * orthographicBackOff;
            direction = forward;
        } else {
            origin = eye;
            direction = forward + offset;
        }
    }

    // The size of a pixel in model units at point p.
    double pixelSizeAt(const Vec3& p) const {
        if (orthographic) return pixelHeight;
        return pixelHeight * std::max(0.0, dot(p - eye, forward));
    }
};

// The view of a framed camera (viewpoint and target set) on the points. Throws Error when
// the viewpoint and the target are the same point.
View makeView(const Camera& framed, const PointSource& points, int width, int height);

}  // namespace graftal
