// 2D line art of a 3D scene: an orthographic projection onto a view plane.
#pragma once

#include <optional>
#include <string>

#include "graftal/geometry/scene.hpp"

namespace graftal {

enum class ViewDirection { Front, Back, Side, Top };

// "front" (looking along -z: x right, y up), "back", "side" (looking along -x: z right,
// y up), "top" (looking down -y: x right, -z up); nullopt for anything else.
std::optional<ViewDirection> viewDirectionFromName(const std::string& name);

// The scene with every point mapped to (right, up, 0) of the view; discs and spheres
// become filled polygons (their outlines as seen), which is how line art draws them.
Scene projectScene(const Scene& scene, ViewDirection view);

}  // namespace graftal
