// Pictures in memory framed on a region the caller gives, not on the scene's own bounds:
// a sequence of frames (an animation) keeps one camera while the plant grows inside it.
#pragma once

#include <span>

#include "graftal/geometry/scene.hpp"
#include "graftal/output/animation_file.hpp"
#include "graftal/output/output.hpp"
#include "graftal/output/render3d.hpp"

namespace graftal {

// 2D line art of the scene's (x, y), as writePng draws it, with `frame` (not the scene's
// bounds) fitted into the picture. Set RenderOptions::lineWidth for widths that do not
// change from frame to frame. Throws Error for a size Cairo cannot hold.
RgbaImage drawLineArt(const Scene& scene, const RenderOptions& options, const Bounds& frame);

// The camera with its unset viewpoint and target chosen as the ray tracer chooses them:
// seen from the front and slightly above, the scenes' projected outline (every vertex and
// curve as drawn) spans 94% of the picture's width or height, whichever is tighter, and
// is centred in the other; a given target stays in the picture's centre. Several scenes
// (the frames of an animation) are framed together.
Camera framedCamera(const Camera& camera, const MeshScene& scene, int width, int height);
Camera framedCamera(const Camera& camera, std::span<const MeshScene* const> scenes, int width,
                    int height);
// The same for a box (framing its eight corners), when only bounds are known.
Camera framedCamera(const Camera& camera, const Bounds& frame, int width, int height);

}  // namespace graftal
