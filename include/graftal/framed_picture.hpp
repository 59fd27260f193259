// Pictures in memory framed on a region the caller gives, not on the scene's own bounds:
// a sequence of frames (an animation) keeps one camera while the plant grows inside it.
#pragma once

#include "graftal/animation_file.hpp"
#include "graftal/output.hpp"
#include "graftal/render3d.hpp"
#include "graftal/scene.hpp"

namespace graftal {

// 2D line art of the scene's (x, y), as writePng draws it, with `frame` (not the scene's
// bounds) fitted into the picture. Set RenderOptions::lineWidth for widths that do not
// change from frame to frame. Throws Error for a size Cairo cannot hold.
RgbaImage drawLineArt(const Scene& scene, const RenderOptions& options, const Bounds& frame);

// The camera with its unset viewpoint and target chosen as the ray tracer would choose
// them for a mesh whose bounds are `frame`.
Camera framedCamera(const Camera& camera, const Bounds& frame, int width, int height);

}  // namespace graftal
