// The named view settings: the one table of every setting a .l file or a cpfg view file
// states, with the checks every front end's values pass through and the printing of each.
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <variant>

#include "graftal/lang/parser_target.hpp"
#include "view_setting_table.hpp"
#include "view_setting_values.hpp"

namespace graftal {

namespace {

using Sources = SettingSources;
using Value = SettingValue;
using Syntax = CpfgSyntax;
using namespace view_setting_values;

// surface: NAME FILE [SCALE]
std::string applySurface(ViewSettings& view, const ViewSetting& setting) {
    std::vector<std::string> words;
    std::string cur;
    for (char c : text(setting)) {
        if (std::isspace(static_cast<unsigned char>(c))) {
            if (!cur.empty()) words.push_back(std::move(cur)), cur.clear();
        } else {
            cur += c;
        }
    }
    if (!cur.empty()) words.push_back(cur);
    // cpfg's view files add the patches' s and t subdivisions and a texture number after
    // the scale: `surface: b bud.s 300 2 2`. graftal subdivides patches by itself, so they
    // are read and checked, not used.
    if (words.size() < 2 || words.size() > 6)
        return "expected 'surface: NAME FILE [SCALE [S T [TEXTURE]]]', e.g. 'surface: l leaf.s "
               "0.5'";
    SurfaceDeclaration s{words[0], words[1], 1, setting.location};
    if (words.size() >= 3) {
        char* end = nullptr;
        s.scale = std::strtod(words[2].c_str(), &end);
        if (*end || !(s.scale > 0)) return "the surface scale must be a positive number";
    }
    for (std::size_t k = 3; k < words.size(); ++k) {
        char* end = nullptr;
        long n = std::strtol(words[k].c_str(), &end, 10);
        if (*end || n < -1)
            return "after the surface scale come whole numbers: the s and t subdivisions and "
                   "a texture, not '" +
                   words[k] + "'";
    }
    view.materials.surfaces.push_back(std::move(s));
    return "";
}

std::string applySpline(ViewSettings& view, const ViewSetting& s) {
    KolamSettings& k = view.kolam;
    std::string word = lowerCase(text(s));
    if (word == "path" || word == "segments") {
        k.splineMode = word == "path" ? SplineMode::Path : SplineMode::Segments;
        if (k.splineSubdivisions == 0) k.splineSubdivisions = 8;
    } else if (word == "off" || word == "none") {
        k.splineSubdivisions = 0;
    } else {
        return "spline is 'path' (every turtle position, f included), 'segments' (the "
               "drawn segments) or 'off', not '" +
               text(s) + "'";
    }
    return "";
}

std::string applyBackground(ViewSettings& view, const ViewSetting& s) {
    const std::string& t = text(s);
    std::string hex = t.substr(t.starts_with("#") ? 1 : 0);
    bool ok =
        hex.size() == 6 && hex.find_first_not_of("0123456789abcdefABCDEF") == std::string::npos;
    if (!ok) return "background is a colour #rrggbb";
    unsigned c = static_cast<unsigned>(std::stoul(hex, nullptr, 16));
    view.camera.background =
        Rgb{((c >> 16) & 255) / 255.0f, ((c >> 8) & 255) / 255.0f, (c & 255) / 255.0f};
    return "";
}

std::string applyColorIndex(ViewSettings& view, const ViewSetting& s) {
    double d = number(s);
    if (d < 0 || d > 65535 || !isWhole(d))
        return s.name + " is a colour-map index, a whole number from 0 to 65535";
    (s.name == "initial color" ? view.turtle.initialColor : view.turtle.colorIncrement) =
        static_cast<int>(d);
    return "";
}

std::string applyLight(ViewSettings& view, const ViewSetting& s) {
    double d = number(s);
    if (d < 0 || d > 10) return s.name + " must be from 0 to 10";
    (s.name == "light intensity" ? view.camera.lightIntensity : view.camera.skyIntensity) = d;
    return "";
}

// A `tropism:` or `torque:` line of a view file, in its own syntax.
void printMovements(std::ostream& os, std::string_view name,
                    const std::vector<TurtleSettings::Movement>& list) {
    for (const auto& m : list)
        line(os, name, "T: " + vec(m.direction) + " E: " + num(m.elasticity));
}

// A row of the table: the setting's name, value, sources, check and printing, with its
// aliases and view-file spellings added.
struct Row {
    ViewSettingDescriptor d;
    Row& alias(std::string_view name) {
        d.aliases.push_back(name);
        return *this;
    }
    Row& spelling(std::string_view name, CpfgSyntax syntax = CpfgSyntax::Same) {
        d.cpfg.push_back({name, syntax});
        return *this;
    }
    Row& note(std::string_view why) {
        d.note = why;
        return *this;
    }
};

Row row(std::string_view name, SettingValue value, SettingSources sources,
        std::string (*apply)(ViewSettings&, const ViewSetting&),
        void (*print)(std::ostream&, const ViewSettings&)) {
    return Row{{name, value, sources, {}, {}, {}, apply, print}};
}

// Every view setting, in the order they are printed and listed. Settings only a view file
// states print in the view file's syntax.
std::string applyAngleFactor(ViewSettings& v, const ViewSetting& s) {
    if (number(s) <= 0) return "angle factor must be positive (delta = 360 / factor)";
    v.turtle.angleDegrees = 360.0 / number(s);
    return "";
}

std::string applyAngleIncrement(ViewSettings& v, const ViewSetting& s) {
    v.turtle.angleDegrees = number(s);
    return "";
}

void printAngleIncrement(std::ostream& os, const ViewSettings& v) {
    line(os, "angle increment", num(v.turtle.angleDegrees));
}

std::string applyStepLength(ViewSettings& v, const ViewSetting& s) {
    if (number(s) <= 0) return "step length must be positive";
    v.turtle.stepLength = number(s);
    return "";
}

void printStepLength(std::ostream& os, const ViewSettings& v) {
    line(os, "step length", num(v.turtle.stepLength));
}

std::string applyInitialHeading(ViewSettings& v, const ViewSetting& s) {
    v.turtle.initialHeading = number(s);
    return "";
}

void printInitialHeading(std::ostream& os, const ViewSettings& v) {
    line(os, "initial heading", num(v.turtle.initialHeading));
}

std::string applyScaleFactor(ViewSettings& v, const ViewSetting& s) {
    if (number(s) <= 0) return "scale factor must be positive";
    v.camera.scaleFactor = number(s);
    return "";
}

void printScaleFactor(std::ostream& os, const ViewSettings& v) {
    line(os, "scale factor", num(v.camera.scaleFactor));
}

std::string applyPlusTurns(ViewSettings& v, const ViewSetting& s) {
    std::string word = lowerCase(text(s));
    if (word == "clockwise")
        v.turtle.clockwisePlus = true;
    else if (word == "counterclockwise" || word == "counter-clockwise")
        v.turtle.clockwisePlus = false;
    else
        return "plus turns 'clockwise' (as in pfg data files) or 'counterclockwise', "
               "not '" +
               text(s) + "'";
    return "";
}

void printPlusTurns(std::ostream& os, const ViewSettings& v) {
    if (v.turtle.clockwisePlus) line(os, "plus turns", "clockwise");
}

std::string applyLineWidth(ViewSettings& v, const ViewSetting& s) {
    if (number(s) <= 0) return "line width must be positive (the stem diameter in model units)";
    v.turtle.initialWidth = number(s);
    return "";
}

void printLineWidth(std::ostream& os, const ViewSettings& v) {
    if (v.turtle.initialWidth != TurtleSettings{}.initialWidth)
        line(os, "line width", num(v.turtle.initialWidth));
}

std::string applyWidthFactor(ViewSettings& v, const ViewSetting& s) {
    double d = number(s);
    if (d <= 0 || d >= 1) return "width factor must be between 0 and 1 (what ! multiplies by)";
    v.turtle.widthFactor = d;
    return "";
}

void printWidthFactor(std::ostream& os, const ViewSettings& v) {
    if (v.turtle.widthFactor != TurtleSettings{}.widthFactor)
        line(os, "width factor", num(v.turtle.widthFactor));
}

std::string applyLineWidthIncrement(ViewSettings& v, const ViewSetting& s) {
    if (number(s) < 0)
        return "line width increment must not be negative (what # adds and ! "
               "subtracts)";
    v.turtle.widthIncrement = number(s);
    return "";
}

void printLineWidthIncrement(std::ostream& os, const ViewSettings& v) {
    if (v.turtle.widthIncrement) line(os, "line width increment", num(*v.turtle.widthIncrement));
}

std::string applyCpfgLineWidthUnit(ViewSettings& v, const ViewSetting& s) {
    if (text(s) != "pixels" && text(s) != "model")
        return "the line width unit is 'pixels' or 'model'";
    v.materials.widthsInModelUnits = text(s) == "model";
    return "";
}

void printCpfgLineWidthUnit(std::ostream& os, const ViewSettings& v) {
    if (v.materials.widthsInModelUnits) line(os, "initial line width", num(v.turtle.initialWidth));
}

void printInitialColor(std::ostream& os, const ViewSettings& v) {
    if (v.turtle.initialColor != TurtleSettings{}.initialColor)
        line(os, "initial color", std::to_string(v.turtle.initialColor));
}

void printColorIncrement(std::ostream& os, const ViewSettings& v) {
    if (v.turtle.colorIncrement != TurtleSettings{}.colorIncrement)
        line(os, "color increment", std::to_string(v.turtle.colorIncrement));
}

std::string applyTropismDirection(ViewSettings& v, const ViewSetting& s) {
    Vec3 unit;
    if (std::string e = unitDirection(s, unit); !e.empty()) return e;
    v.turtle.tropism = unit;
    return "";
}

void printTropismDirection(std::ostream& os, const ViewSettings& v) {
    if (v.turtle.tropism && !v.turtle.cpfgTropism)
        line(os, "tropism direction", vec(*v.turtle.tropism));
}

std::string applyCpfgTropismDirection(ViewSettings& v, const ViewSetting& s) {
    Vec3 unit;
    if (std::string e = unitDirection(s, unit); !e.empty()) return e;
    v.turtle.tropism = unit;
    v.turtle.cpfgTropism = true;
    return "";
}

void printCpfgTropismDirection(std::ostream& os, const ViewSettings& v) {
    if (v.turtle.tropism && v.turtle.cpfgTropism)
        line(os, "tropism direction", vec(*v.turtle.tropism));
}

std::string applyTropismElasticity(ViewSettings& v, const ViewSetting& s) {
    v.turtle.elasticity = number(s);
    return "";
}

void printTropismElasticity(std::ostream& os, const ViewSettings& v) {
    if (v.turtle.elasticity != 0) line(os, "tropism elasticity", num(v.turtle.elasticity));
}

std::string applyElasticityIncrement(ViewSettings& v, const ViewSetting& s) {
    v.turtle.elasticityIncrement = number(s);
    return "";
}

void printElasticityIncrement(std::ostream& os, const ViewSettings& v) {
    if (v.turtle.elasticityIncrement != 0)
        line(os, "elasticity increment", num(v.turtle.elasticityIncrement));
}

void printTropism(std::ostream& os, const ViewSettings& v) {
    printMovements(os, "tropism", v.turtle.tropisms);
}

std::string applyTropismLineDirection(ViewSettings& v, const ViewSetting& s) {
    Vec3 unit;
    if (std::string e = unitDirection(s, unit); !e.empty()) return e;
    v.turtle.tropisms.push_back({unit, 0});
    return "";
}

std::string applyTropismLineElasticity(ViewSettings& v, const ViewSetting& s) {
    if (v.turtle.tropisms.empty()) return "an elasticity without a tropism direction";
    v.turtle.tropisms.back().elasticity = number(s);
    return "";
}

void printTorque(std::ostream& os, const ViewSettings& v) {
    printMovements(os, "torque", v.turtle.torques);
}

std::string applyTorqueLineDirection(ViewSettings& v, const ViewSetting& s) {
    Vec3 unit;
    if (std::string e = unitDirection(s, unit); !e.empty()) return e;
    v.turtle.torques.push_back({unit, 0});
    return "";
}

std::string applyTorqueLineElasticity(ViewSettings& v, const ViewSetting& s) {
    if (v.turtle.torques.empty()) return "an elasticity without a torque direction";
    v.turtle.torques.back().elasticity = number(s);
    return "";
}

std::string applyTorqueDirection(ViewSettings& v, const ViewSetting& s) {
    Vec3 unit;
    if (std::string e = unitDirection(s, unit); !e.empty()) return e;
    v.turtle.torque = unit;
    return "";
}

std::string applyTorqueElasticity(ViewSettings& v, const ViewSetting& s) {
    v.turtle.torqueElasticity = number(s);
    return "";
}

// A camera point the ray tracer can aim from or at: finite and within 1e15 of the origin
// (farther, single-precision rays lose the scene). Said where the file sets it, not later
// by the picture.
std::string cameraPointProblem(const Vec3& p, const char* what) {
    constexpr double kFarthest = 1e15;
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) &&
        std::abs(p.x) <= kFarthest && std::abs(p.y) <= kFarthest && std::abs(p.z) <= kFarthest)
        return "";
    return std::string("the ") + what +
           " must be a finite point within 1e15 of the origin (a picture cannot be aimed "
           "from or at one farther out)";
}

std::string applyViewpoint(ViewSettings& v, const ViewSetting& s) {
    if (std::string e = cameraPointProblem(vector(s), "viewpoint"); !e.empty()) return e;
    v.camera.viewpoint = vector(s);
    return "";
}

void printViewpoint(std::ostream& os, const ViewSettings& v) {
    if (v.camera.viewpoint) line(os, "viewpoint", vec(*v.camera.viewpoint));
}

std::string applyViewReferencePoint(ViewSettings& v, const ViewSetting& s) {
    if (std::string e = cameraPointProblem(vector(s), "view reference point"); !e.empty())
        return e;
    v.camera.referencePoint = vector(s);
    return "";
}

void printViewReferencePoint(std::ostream& os, const ViewSettings& v) {
    if (v.camera.referencePoint) line(os, "view reference point", vec(*v.camera.referencePoint));
}

std::string applyUpVector(ViewSettings& v, const ViewSetting& s) {
    if (isZero(vector(s))) return "the up vector must not be zero";
    if (!cameraPointProblem(vector(s), "up vector").empty())
        return "the up vector must be finite (each component within 1e15)";
    v.camera.upVector = vector(s);
    return "";
}

void printUpVector(std::ostream& os, const ViewSettings& v) {
    if (v.camera.upVector) line(os, "up vector", vec(*v.camera.upVector));
}

std::string applyProjection(ViewSettings& v, const ViewSetting& s) {
    std::string word = lowerCase(text(s));
    if (word == "parallel" || word == "orthographic")
        v.camera.parallelProjection = true;
    else if (word == "perspective")
        v.camera.parallelProjection = false;
    else
        return "projection is 'perspective' or 'parallel', not '" + text(s) + "'";
    return "";
}

void printProjection(std::ostream& os, const ViewSettings& v) {
    if (v.camera.parallelProjection) line(os, "projection", "parallel");
}

std::string applyFieldOfView(ViewSettings& v, const ViewSetting& s) {
    double d = number(s);
    if (!(d > 0 && d < 180)) return "field of view must be between 0 and 180 degrees";
    v.camera.fieldOfView = d;
    return "";
}

void printFieldOfView(std::ostream& os, const ViewSettings& v) {
    if (v.camera.fieldOfView) line(os, "field of view", num(*v.camera.fieldOfView));
}

std::string applyTwist(ViewSettings& v, const ViewSetting& s) {
    v.camera.twistDegrees = number(s);
    return "";
}

void printTwist(std::ostream& os, const ViewSettings& v) {
    if (v.camera.twistDegrees != 0) line(os, "twist", num(v.camera.twistDegrees * 10));
}

std::string applyLightDirection(ViewSettings& v, const ViewSetting& s) {
    if (isZero(vector(s))) return "the light direction must not be zero";
    v.camera.lightDirection = vector(s);
    return "";
}

void printLightDirection(std::ostream& os, const ViewSettings& v) {
    if (v.camera.lightDirection) line(os, "light direction", vec(*v.camera.lightDirection));
}

void printLight(std::ostream& os, const ViewSettings& v) {
    const CameraSettings& c = v.camera;
    if (!c.lightIntensity && !c.skyIntensity) return;
    std::string fields;
    if (c.lightIntensity) {
        std::string d = num(*c.lightIntensity);
        fields += "D: " + d + " " + d + " " + d;
    }
    if (c.skyIntensity) {
        std::string a = num(*c.skyIntensity);
        fields += std::string(fields.empty() ? "" : " ") + "A: " + a + " " + a + " " + a;
    }
    line(os, "light", fields);
}

void printBackground(std::ostream& os, const ViewSettings& v) {
    if (v.camera.background) line(os, "background", hexColor(*v.camera.background));
}

std::string applyLineStyle(ViewSettings& v, const ViewSetting& s) {
    std::string word = lowerCase(text(s));
    if (word == "cylinder" || word == "cylinders" || word == "polygon")
        v.materials.lineStyle = LineStyle::Cylinders;
    else if (word == "lines" || word == "line" || word == "pixel")
        v.materials.lineStyle = LineStyle::Lines;
    else
        return "line style is 'cylinder' or 'lines', not '" + text(s) + "'";
    return "";
}

void printLineStyle(std::ostream& os, const ViewSettings& v) {
    if (v.materials.lineStyle == LineStyle::Lines) line(os, "line style", "lines");
}

std::string applyCylinderSides(ViewSettings& v, const ViewSetting& s) {
    double d = number(s);
    if (d < 3 || d > 1024 || !isWhole(d))
        return "cylinder sides is a whole number from 3 to 1024 (the corners around a "
               "stem)";
    v.materials.tubeSides = static_cast<int>(d);
    return "";
}

void printCylinderSides(std::ostream& os, const ViewSettings& v) {
    if (v.materials.tubeSides) line(os, "cylinder sides", std::to_string(*v.materials.tubeSides));
}

std::string applyColorMap(ViewSettings& v, const ViewSetting& s) {
    if (text(s).empty()) return "expected a .map file name";
    v.materials.colorMap = text(s);
    return "";
}

void printColorMap(std::ostream& os, const ViewSettings& v) {
    if (!v.materials.colorMap.empty()) line(os, "color map", v.materials.colorMap);
}

std::string applyMaterialFile(ViewSettings& v, const ViewSetting& s) {
    if (text(s).empty()) return "expected a .mat file name";
    v.materials.materialFile = text(s);
    return "";
}

void printMaterialFile(std::ostream& os, const ViewSettings& v) {
    if (!v.materials.materialFile.empty()) line(os, "material file", v.materials.materialFile);
}

void printSurface(std::ostream& os, const ViewSettings& v) {
    for (const auto& s : v.materials.surfaces)
        line(os, "surface", s.name + " " + s.file + " " + num(s.scale));
}

std::string applyContourSides(ViewSettings& v, const ViewSetting& s) {
    double d = number(s);
    if (d < 3 || d > 1024 || !isWhole(d))
        return "contour sides is a whole number from 3 to 1024 (the points around a "
               "generalized cylinder)";
    v.materials.contourSides = static_cast<int>(d);
    return "";
}

void printContourSides(std::ostream& os, const ViewSettings& v) {
    if (v.materials.contourSides != MaterialSettings{}.contourSides)
        line(os, "contour sides", std::to_string(v.materials.contourSides));
}

void printContour(std::ostream& os, const ViewSettings& v) {
    for (const auto& c : v.materials.contours)
        if (!c.file.empty()) line(os, "contour", std::to_string(c.id) + " " + c.file);
}

void printSpline(std::ostream& os, const ViewSettings& v) {
    if (v.kolam.splineMode == SplineMode::Path) line(os, "spline", "path");
}

std::string applySplineSubdivisions(ViewSettings& v, const ViewSetting& s) {
    double d = number(s);
    if (d < 0 || d > 64 || !isWhole(d))
        return "spline subdivisions is a whole number from 0 (straight lines) to 64";
    v.kolam.splineSubdivisions = static_cast<int>(d);
    return "";
}

void printSplineSubdivisions(std::ostream& os, const ViewSettings& v) {
    if (v.kolam.splineSubdivisions != 0 || v.kolam.splineMode == SplineMode::Path)
        line(os, "spline subdivisions", std::to_string(v.kolam.splineSubdivisions));
}

std::string applyKolamDots(ViewSettings& v, const ViewSetting& s) {
    std::string word = lowerCase(text(s));
    if (word == "on" || word == "yes" || word == "1")
        v.kolam.dots = true;
    else if (word == "off" || word == "no" || word == "0")
        v.kolam.dots = false;
    else
        return "kolam dots is 'on' or 'off', not '" + text(s) + "'";
    return "";
}

void printKolamDots(std::ostream& os, const ViewSettings& v) {
    if (v.kolam.dots) line(os, "kolam dots", "on");
}

std::string applyMusicScale(ViewSettings& v, const ViewSetting& s) {
    ScaleSteps steps;
    if (std::string e = parseScale(text(s), steps); !e.empty()) return e;
    v.music.scale = std::move(steps);
    return "";
}

void printMusicScale(std::ostream& os, const ViewSettings& v) {
    if (!v.music.scale) return;
    std::string steps;
    for (int step : *v.music.scale) steps += (steps.empty() ? "" : " ") + std::to_string(step);
    line(os, "music scale", steps);
}

std::string applyMusicRoot(ViewSettings& v, const ViewSetting& s) {
    int root = 0;
    if (std::string e = parseNoteName(text(s), root); !e.empty()) return e;
    v.music.root = root;
    return "";
}

void printMusicRoot(std::ostream& os, const ViewSettings& v) {
    if (v.music.root) line(os, "music root", std::to_string(*v.music.root));
}

std::string applyMusicTempo(ViewSettings& v, const ViewSetting& s) {
    double d = number(s);
    if (d <= 0 || d > 1000) return "music tempo is beats per minute, above 0 and at most 1000";
    v.music.tempo = d;
    return "";
}

void printMusicTempo(std::ostream& os, const ViewSettings& v) {
    if (v.music.tempo) line(os, "music tempo", num(*v.music.tempo));
}

std::string applyMusicInstrument(ViewSettings& v, const ViewSetting& s) {
    double d = number(s);
    if (d < 1 || d > 128 || !isWhole(d))
        return "music instrument is a General MIDI program, a whole number from 1 to "
               "128";
    v.music.instrument = static_cast<int>(d);
    return "";
}

void printMusicInstrument(std::ostream& os, const ViewSettings& v) {
    if (v.music.instrument) line(os, "music instrument", std::to_string(*v.music.instrument));
}

std::string applyMusicAxis(ViewSettings& v, const ViewSetting& s) {
    std::string word = lowerCase(text(s));
    if (word == "y")
        v.music.pitchFromX = false;
    else if (word == "x")
        v.music.pitchFromX = true;
    else
        return "music axis is 'y' (pitch from y, the book's reading) or 'x', not '" + text(s) + "'";
    return "";
}

void printMusicAxis(std::ostream& os, const ViewSettings& v) {
    if (v.music.pitchFromX) line(os, "music axis", *v.music.pitchFromX ? "x" : "y");
}

std::string applyMusicUnit(ViewSettings& v, const ViewSetting& s) {
    double d = number(s);
    if (d <= 0 || d > 64) return "music unit is the beats of one step, above 0 and at most 64";
    v.music.unit = d;
    return "";
}

void printMusicUnit(std::ostream& os, const ViewSettings& v) {
    if (v.music.unit) line(os, "music unit", num(*v.music.unit));
}

std::vector<ViewSettingDescriptor> makeTable() {
    std::vector<ViewSettingDescriptor> t;
    auto add = [&t](Row r) { t.push_back(std::move(r.d)); };

    // The turtle.
    add(row("angle factor", Value::Number, Sources::Both, applyAngleFactor,
            nullptr));  // printed as the angle increment
    add(row("angle increment", Value::Number, Sources::Both, applyAngleIncrement,
            printAngleIncrement));
    add(row("step length", Value::Number, Sources::LFile, applyStepLength, printStepLength));
    add(row("initial heading", Value::Number, Sources::LFile, applyInitialHeading,
            printInitialHeading));
    add(row("scale factor", Value::Number, Sources::Both, applyScaleFactor, printScaleFactor)
            .spelling("scale factor", Syntax::Percent));
    // pfg data files turn right on +; this keeps that when one is printed as a .l file.
    add(row("plus turns", Value::Word, Sources::LFile, applyPlusTurns, printPlusTurns));
    add(row("line width", Value::Number, Sources::Both, applyLineWidth, printLineWidth)
            .spelling("initial line width", Syntax::WidthWithUnit));
    add(row("width factor", Value::Number, Sources::LFile, applyWidthFactor, printWidthFactor));
    add(row("line width increment", Value::Number, Sources::ViewFile, applyLineWidthIncrement,
            printLineWidthIncrement));
    // Sent with a view file's `initial line width:` and `line style:`.
    add(row("cpfg line width unit", Value::Word, Sources::Reader, applyCpfgLineWidthUnit,
            printCpfgLineWidthUnit));
    add(row("initial color", Value::Number, Sources::ViewFile, applyColorIndex, printInitialColor)
            .spelling("initial color")
            .spelling("initial colour"));
    add(row("color increment", Value::Number, Sources::ViewFile, applyColorIndex,
            printColorIncrement)
            .spelling("color increment")
            .spelling("colour increment"));

    // Tropisms and torques.
    add(row("tropism direction", Value::Vector, Sources::LFile, applyTropismDirection,
            printTropismDirection));
    // A view file's `tropism direction:` bends by cpfg's rule, not the book's.
    add(row("cpfg tropism direction", Value::Vector, Sources::ViewFile, applyCpfgTropismDirection,
            printCpfgTropismDirection)
            .spelling("tropism direction"));
    add(row("tropism elasticity", Value::Number, Sources::Both, applyTropismElasticity,
            printTropismElasticity)
            .alias("initial elasticity")
            .alias("elasticity")
            .spelling("initial elasticity"));
    add(row("elasticity increment", Value::Number, Sources::ViewFile, applyElasticityIncrement,
            printElasticityIncrement));
    // `tropism:` and `torque:` lines reach the settings as a direction and an elasticity.
    add(row("tropism", Value::None, Sources::ViewFile, nullptr, printTropism)
            .spelling("tropism", Syntax::Fields));
    add(row("tropism line direction", Value::Vector, Sources::Reader, applyTropismLineDirection,
            nullptr));
    add(row("tropism line elasticity", Value::Number, Sources::Reader, applyTropismLineElasticity,
            nullptr));
    add(row("torque", Value::None, Sources::ViewFile, nullptr, printTorque)
            .spelling("torque", Syntax::Fields));
    add(row("torque line direction", Value::Vector, Sources::Reader, applyTorqueLineDirection,
            nullptr));
    add(row("torque line elasticity", Value::Number, Sources::Reader, applyTorqueLineElasticity,
            nullptr));
    // The single torque direction and elasticity: set by name through the API only (no file
    // states them; a view file's `torque:` lines add up instead), so never printed.
    add(row("torque direction", Value::Vector, Sources::Reader, applyTorqueDirection, nullptr));
    add(row("torque elasticity", Value::Number, Sources::Reader, applyTorqueElasticity, nullptr));

    // The camera and the light.
    add(row("viewpoint", Value::Vector, Sources::Both, applyViewpoint, printViewpoint));
    add(row("view reference point", Value::Vector, Sources::Both, applyViewReferencePoint,
            printViewReferencePoint));
    add(row("up vector", Value::Vector, Sources::Both, applyUpVector, printUpVector));
    add(row("projection", Value::FileOrWord, Sources::Both, applyProjection, printProjection));
    add(row("field of view", Value::Number, Sources::LFile, applyFieldOfView, printFieldOfView));
    add(row("twist", Value::Number, Sources::ViewFile, applyTwist, printTwist)
            .spelling("twist", Syntax::TenthsOfDegree));
    add(row("light direction", Value::Vector, Sources::Both, applyLightDirection,
            printLightDirection));
    // A view file's `light:` lines give the direction, the sun's and the sky's strength.
    add(row("light", Value::None, Sources::ViewFile, nullptr, printLight)
            .spelling("light", Syntax::Light));
    add(row("light intensity", Value::Number, Sources::Reader, applyLight, nullptr));
    add(row("sky intensity", Value::Number, Sources::Reader, applyLight, nullptr));
    add(row("background", Value::FileOrWord, Sources::LFile, applyBackground, printBackground));

    // What the model is drawn with.
    add(row("line style", Value::FileOrWord, Sources::Both, applyLineStyle, printLineStyle)
            .spelling("line style", Syntax::StyleWithUnit));
    add(row("cylinder sides", Value::Number, Sources::ViewFile, applyCylinderSides,
            printCylinderSides)
            .spelling("cylinder sides")
            .spelling("polygonization level", Syntax::PolygonizationLevel));
    add(row("color map", Value::FileOrWord, Sources::LFile, applyColorMap, printColorMap)
            .alias("colour map"));
    add(row("material file", Value::FileOrWord, Sources::LFile, applyMaterialFile,
            printMaterialFile));
    add(row("surface", Value::FileOrWord, Sources::Both, applySurface, printSurface));
    add(row("contour sides", Value::Number, Sources::ViewFile, applyContourSides,
            printContourSides));
    // The contours of `contour:` lines (those of a model folder's contour set are found
    // there again, not printed).
    add(row("contour", Value::File, Sources::ViewFile, nullptr, printContour));
    // Files of the L-system (its functions and curves), read by the target; printed with it.
    add(row("function", Value::File, Sources::ViewFile, nullptr, nullptr));
    add(row("function set", Value::File, Sources::ViewFile, nullptr, nullptr));
    add(row("curve", Value::File, Sources::ViewFile, nullptr, nullptr));

    // Smooth curves and kolams: `spline:` before the subdivisions it may set.
    add(row("spline", Value::Word, Sources::LFile, applySpline, printSpline));
    add(row("spline subdivisions", Value::Number, Sources::LFile, applySplineSubdivisions,
            printSplineSubdivisions));
    add(row("kolam dots", Value::Word, Sources::LFile, applyKolamDots, printKolamDots));

    // Music.
    add(row("music scale", Value::Word, Sources::LFile, applyMusicScale, printMusicScale));
    add(row("music root", Value::Word, Sources::LFile, applyMusicRoot, printMusicRoot));
    add(row("music tempo", Value::Number, Sources::LFile, applyMusicTempo, printMusicTempo));
    add(row("music instrument", Value::Number, Sources::LFile, applyMusicInstrument,
            printMusicInstrument));
    add(row("music axis", Value::Word, Sources::LFile, applyMusicAxis, printMusicAxis));
    add(row("music unit", Value::Number, Sources::LFile, applyMusicUnit, printMusicUnit));

    // View-file lines graftal reads and warns about.
    auto ignored = [&add](std::string_view name, std::string_view why) {
        add(row(name, Value::None, Sources::ViewFile, nullptr, nullptr)
                .spelling(name, Syntax::Ignored)
                .note(why));
    };
    ignored("box", "the box is recomputed from the geometry");
    ignored("render mode", "graftal chooses how to draw by the output format");
    add(row("material", Value::None, Sources::ViewFile, nullptr, nullptr)
            .spelling("material", Syntax::NotCpfg)
            .note("cpfg's view files have no such line (cpfg reads materials from a .mat file "
                  "given on its command line); graftal reads a model folder's one .mat, or the "
                  ".l file's 'material file:'"));
    ignored("shade mode", "graftal chooses the shading by the output format");
    ignored("z buffer", "graftal chooses how to draw by the output format");
    ignored("contact point", "contact points are not read yet");
    ignored("end point", "end points are not read yet");
    ignored("heading", "headings are not read yet");
    ignored("up", "up vectors of surfaces are not read yet");
    ignored("size", "sizes of surfaces are not read yet");
    ignored("front distance", "clipping planes are not read");
    ignored("back distance", "clipping planes are not read");
    ignored("twist of cylinders", "generalized cylinders are drawn without twist");
    return t;
}

}  // namespace

const std::vector<ViewSettingDescriptor>& viewSettingTable() {
    static const std::vector<ViewSettingDescriptor> table = makeTable();
    return table;
}

}  // namespace graftal
