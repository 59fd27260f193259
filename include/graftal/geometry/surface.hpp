// Predefined bicubic surfaces: cpfg's .s files (sets of Bézier patches) and their library.
#pragma once

#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "graftal/core/diagnostics.hpp"
#include "graftal/geometry/scene.hpp"

namespace graftal {

// 16 control points, row-major (s across, t down).
struct BezierPatch {
    std::array<Vec3, 16> points;
    std::string name;
};

// A surface as cpfg describes it: patches plus the frame used to place it at the turtle.
struct Surface {
    std::string name;
    std::vector<BezierPatch> patches;
    Vec3 contactPoint;  // goes to the turtle position
    Vec3 endPoint;
    Vec3 heading{0, 1, 0};  // goes to the turtle's H
    Vec3 up{0, 0, 1};       // goes to the turtle's U
    double size = 1;        // the surface's own scale
    Bounds bounds;          // of the control points
};

// Parses the text of a .s file. Errors carry file:line:column.
Surface parseSurface(std::string_view text, const std::string& fileName);
Surface loadSurface(const std::filesystem::path& path);

// Point and normal of a patch at (s, t) in [0,1]^2.
Vec3 evaluatePatch(const BezierPatch& p, double s, double t, Vec3* normal = nullptr);

// The folder of the built-in surfaces: share/graftal/surfaces beside the installed
// library (found from where the library is loaded). Throws Error when it is missing.
std::filesystem::path builtinSurfacesDirectory();

class SurfaceLibrary {
  public:
    // The surfaces shipped with graftal (a leaf and a petal), always available.
    static SurfaceLibrary builtin();

    void add(Surface s);
    // Adds every *.s file of a directory; the file stem is the surface's name.
    void addDirectory(const std::filesystem::path& dir);
    const Surface* find(const std::string& name) const;
    std::vector<std::string> names() const;

  private:
    std::map<std::string, Surface> surfaces_;
};

// Takes out of `scene` the placements of surfaces `library` does not hold and returns their
// names, each once, in the order first placed: cpfg draws nothing for a `~X` whose X no
// `surface:` line declares (and leaves the turtle where it is).
std::vector<std::string> removeUnknownSurfaces(Scene& scene, const SurfaceLibrary& library);

}  // namespace graftal
