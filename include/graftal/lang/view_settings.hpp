// How a model is drawn: the view settings a .l file and a cpfg view file carry, grouped by
// what they concern (the turtle, the camera, what the model is drawn with, kolams, music).
// A separate value from the grammar (LSystem): the same grammar can be drawn with other
// settings, and front ends set them by name through ParserTarget::viewSetting; one table
// (src/lang/view_settings.cpp) names every setting, reads it and prints it.
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "graftal/core/contour_shape.hpp"
#include "graftal/core/diagnostics.hpp"
#include "graftal/core/music_scale.hpp"
#include "graftal/core/rgb.hpp"
#include "graftal/core/vec3.hpp"

namespace graftal {

enum class LineStyle { Lines, Cylinders };

// A predefined surface a file names: `surface: l leaf.s 0.5` places leaf.s at `~l`.
struct SurfaceDeclaration {
    std::string name;  // what follows ~ in module strings
    std::string file;  // a .s file, relative to the L-system file, or a built-in name
    double scale = 1;
    SourceLocation location;
};

// How the turtle starts and moves: its turn, step, heading, widths and colours, and the
// tropisms and torques that bend its path.
struct TurtleSettings {
    double angleDegrees = 90;    // δ, the turn of + and -
    double stepLength = 1;       // length of F and f
    double initialHeading = 0;   // degrees counter-clockwise from up (+y)
    bool clockwisePlus = false;  // pfg data files: + turns right on screen
    double initialWidth = 0.1;   // stem diameter before any ! or #, in model units
    double widthFactor = 0.7;    // ! multiplies the width by this, # divides by it
    // cpfg's "line width increment": when set, ! subtracts it and # adds it (no factor).
    std::optional<double> widthIncrement;
    int initialColor = 0;    // the colour index before any ; or ,
    int colorIncrement = 1;  // what ; adds and , subtracts
    // Tropism (LSFP ch. 3.1): after each segment H turns toward `tropism` by e·|H × T|.
    std::optional<Vec3> tropism;
    double elasticity = 0;
    // cpfg's `elasticity increment:`: what `_` adds to the turtle's elasticity (`_(e)` sets
    // it); a branch keeps the elasticity it had at `[`.
    double elasticityIncrement = 0;
    // `tropism direction:` read from a cpfg view file: cpfg's rule after each segment, H
    // pitches toward T (by the angle whose sine is e·T·U) and then turns toward it (sine
    // e·T·L), instead of the book's rotation about H × T.
    bool cpfgTropism = false;
    // cpfg's `tropism: T: x,y,z E: e` lines (T normalised): before every move (F, G, f, g)
    // H turns toward V = Σ e·T by min(1, |H × V|) radians.
    struct Movement {
        Vec3 direction;
        double elasticity = 0;
    };
    std::vector<Movement> tropisms;
    // Torque (cpfg's "torque:"): before every move the turtle rolls about H so that its up
    // vector turns toward the part of e·T across H, by min(1, |U × that|) radians.
    std::optional<Vec3> torque;
    double torqueElasticity = 0;
    // A view file's `torque: T: x,y,z E: e` lines: the turtle rolls by their sum Σ e·T
    // (with the torque above), as the `tropism:` lines add up.
    std::vector<Movement> torques;
};

// The camera and light for pictures of 3D scenes (cpfg's view-file names), and the frame
// of every picture: its size in the window and its background.
struct CameraSettings {
    std::optional<Vec3> viewpoint, referencePoint, upVector;
    std::optional<double> fieldOfView;  // degrees
    bool parallelProjection = false;
    double twistDegrees = 0;   // turns the camera about its viewing direction
    double scaleFactor = 100;  // pfg's picture size in percent of the window
    std::optional<Vec3> lightDirection;
    // A view file's first `light:` line: D: (diffuse) the sun's strength, A: (ambient) the
    // sky's; the ray tracer's full sun (0.9) is D: 1 1 1.
    std::optional<double> lightIntensity, skyIntensity;
    std::optional<Rgb> background;
};

// What the model is drawn with: colours, materials, surfaces and the shape of its stems.
struct MaterialSettings {
    std::string colorMap;  // a cpfg .map file, relative to the L-system file
    // A cpfg .mat file (relative to the L-system file): its diffuse colours are the 3D
    // palette, as cpfg draws with materials instead of the colour map when given one.
    std::string materialFile;
    std::vector<SurfaceDeclaration> surfaces;
    LineStyle lineStyle = LineStyle::Cylinders;  // how 3D outputs draw segments
    // Whether 2D line art draws widths in model units, scaled with the picture, rather than
    // relative to the initial width: cpfg's view file says so with `initial line width: W`
    // without `pixels` (or `line style: polygon` or `cylinder`), where cpfg draws the lines
    // as polygons or cylinders `W` wide in the world.
    bool widthsInModelUnits = false;
    // cpfg's `cylinder sides:`: the corners of a 3D stem's cross-section (the command
    // line's --tube-sides wins when given).
    std::optional<int> tubeSides;
    // Generalized cylinders (@Gs, @Gc, @Ge): the points around a cross-section (cpfg's
    // `contour sides:`) and the contours `contour: ID FILE` lines load, which @#(ID) picks.
    int contourSides = 8;
    std::vector<Contour> contours;
};

// Which turtle positions a B-spline runs through (when splineSubdivisions > 0).
enum class SplineMode {
    Segments,  // the drawn segments' ends (F): Fig 2.11b; f moves leave gaps
    Path,      // every position, f moves included, and the whole path is drawn (kolams)
};

// Smooth curves through the turtle's path (LSFP Fig 2.10) and kolams (LSFP 6.2).
struct KolamSettings {
    int splineSubdivisions = 0;                    // > 0: draw turtle paths as B-splines
    SplineMode splineMode = SplineMode::Segments;  // `spline: path` draws kolams
    bool dots = false;  // `kolam dots: on`: the grid of dots the kolam's loops surround
};

// How `graftal music` reads the curve as a score (LSFP ch. 6.3); an empty value takes the
// command's default (see docs/language.md).
struct MusicSettings {
    std::optional<ScaleSteps> scale;  // `music scale:` major, minor, ... or semitone offsets
    std::optional<int> root;          // `music root:` MIDI note of the first note (C4 = 60)
    std::optional<double> tempo;      // `music tempo:` beats per minute
    std::optional<int> instrument;    // `music instrument:` General MIDI program, 1..128
    std::optional<bool> pitchFromX;   // `music axis: x`: pitch from x, time from vertical moves
    std::optional<double> unit;       // `music unit:` beats per step length
};

struct ViewSettings {
    TurtleSettings turtle;
    CameraSettings camera;
    MaterialSettings materials;
    KolamSettings kolam;
    MusicSettings music;
};

// Prints the settings as .l lines (`angle increment: 30`), read back by the parser to the
// same settings. A setting only a cpfg view file can state is printed as a comment
// (`/* view file: contour sides: 12 */`); printViewFile() writes those as a view file.
std::ostream& operator<<(std::ostream& os, const ViewSettings& v);

// The settings only a cpfg view file states, as the lines of one (`contour sides: 12`): with
// the .l text operator<< prints, it reads back to the same settings.
void printViewFile(std::ostream& os, const ViewSettings& v);

// True when tropisms or a torque change the turtle's path (no shortcut may skip them).
inline bool turtleIsBent(const ViewSettings& v) {
    const TurtleSettings& t = v.turtle;
    // A tropism direction bends the path as soon as `_` gives the turtle an elasticity.
    if (t.tropism) return true;
    if (t.torque && t.torqueElasticity != 0) return true;
    for (const auto& m : t.tropisms)
        if (m.elasticity != 0) return true;
    for (const auto& m : t.torques)
        if (m.elasticity != 0) return true;
    return false;
}

// What ! (narrower) and # (wider) do to a width: subtract or add cpfg's line width increment
// when the view gives one, else multiply or divide by the width factor. Never below zero.
inline float changedWidth(const ViewSettings& v, float width, bool wider) {
    const TurtleSettings& t = v.turtle;
    if (t.widthIncrement) {
        double w = width + (wider ? *t.widthIncrement : -*t.widthIncrement);
        return static_cast<float>(w > 0 ? w : 0);
    }
    return wider ? width / static_cast<float>(t.widthFactor)
                 : width * static_cast<float>(t.widthFactor);
}

}  // namespace graftal
