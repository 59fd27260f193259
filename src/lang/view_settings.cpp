// The named view settings: the checks every front end's values pass through.
#include <cmath>
#include <cstdlib>

#include "graftal/parser_target.hpp"

namespace graftal {

namespace {

bool isZero(const Vec3& v) {
    return v.x == 0 && v.y == 0 && v.z == 0;
}

std::string lowerCase(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

// surface: NAME FILE [SCALE]
std::string applySurface(ViewSettings& view, const std::string& text, const SourceLocation& where) {
    std::vector<std::string> words;
    std::string cur;
    for (char c : text) {
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
    SurfaceDeclaration s{words[0], words[1], 1, where};
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
    view.surfaces.push_back(std::move(s));
    return "";
}

// spline: path|segments|off, kolam dots: on|off, music scale/root/axis.
std::string applyWordSetting(ViewSettings& view, const std::string& kw, const std::string& text) {
    std::string word = lowerCase(text);
    if (kw == "spline") {
        if (word == "path") {
            view.splineMode = SplineMode::Path;
            if (view.splineSubdivisions == 0) view.splineSubdivisions = 8;
        } else if (word == "segments") {
            view.splineMode = SplineMode::Segments;
            if (view.splineSubdivisions == 0) view.splineSubdivisions = 8;
        } else if (word == "off" || word == "none") {
            view.splineSubdivisions = 0;
        } else {
            return "spline is 'path' (every turtle position, f included), 'segments' (the "
                   "drawn segments) or 'off', not '" +
                   text + "'";
        }
    } else if (kw == "kolam dots") {
        if (word == "on" || word == "yes" || word == "1")
            view.kolamDots = true;
        else if (word == "off" || word == "no" || word == "0")
            view.kolamDots = false;
        else
            return "kolam dots is 'on' or 'off', not '" + text + "'";
    } else if (kw == "music scale") {
        ScaleSteps steps;
        if (std::string e = parseScale(text, steps); !e.empty()) return e;
        view.music.scale = std::move(steps);
    } else if (kw == "music root") {
        int root = 0;
        if (std::string e = parseNoteName(text, root); !e.empty()) return e;
        view.music.root = root;
    } else {
        if (word == "y")
            view.music.pitchFromX = false;
        else if (word == "x")
            view.music.pitchFromX = true;
        else
            return "music axis is 'y' (pitch from y, the book's reading) or 'x', not '" + text +
                   "'";
    }
    return "";
}

}  // namespace

const std::vector<std::string>& viewSettingNames() {
    static const std::vector<std::string> names = {
        "angle factor",
        "angle increment",
        "scale factor",
        "initial heading",
        "step length",
        "viewpoint",
        "view reference point",
        "up vector",
        "light direction",
        "tropism direction",
        "tropism elasticity",
        "initial elasticity",
        "elasticity",
        "elasticity increment",
        "cylinder sides",
        "light intensity",
        "sky intensity",
        "projection",
        "field of view",
        "line style",
        "spline subdivisions",
        "line width",
        "width factor",
        "background",
        "color map",
        "colour map",
        "material file",
        "surface",
        "line width increment",
        "initial color",
        "color increment",
        "twist",
        "torque direction",
        "torque elasticity",
        "spline",
        "kolam dots",
        "music scale",
        "music root",
        "music tempo",
        "music instrument",
        "music axis",
        "music unit",
        "contour sides",
    };
    return names;
}

std::string applyViewSetting(ViewSettings& view, const ViewSetting& setting) {
    const std::string& kw = setting.name;
    const double* number = std::get_if<double>(&setting.value);
    const Vec3* vector = std::get_if<Vec3>(&setting.value);
    const std::string* text = std::get_if<std::string>(&setting.value);
    if (kw == "viewpoint" || kw == "view reference point" || kw == "up vector" ||
        kw == "light direction" || kw == "tropism direction" || kw == "torque direction" ||
        kw == "cpfg tropism direction" || kw == "tropism line direction" ||
        kw == "torque line direction") {
        if (!vector) return "'" + kw + ":' expects three numbers x, y, z";
        const Vec3& v = *vector;
        if (kw == "viewpoint") {
            view.viewpoint = v;
        } else if (kw == "view reference point") {
            view.viewReferencePoint = v;
        } else if (kw == "up vector") {
            if (isZero(v)) return "the up vector must not be zero";
            view.upVector = v;
        } else if (kw == "light direction") {
            if (isZero(v)) return "the light direction must not be zero";
            view.lightDirection = v;
        } else {
            double n = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
            if (n == 0) return "the " + kw + " must not be zero";
            Vec3 unit{v.x / n, v.y / n, v.z / n};
            if (kw == "tropism line direction")
                view.tropisms.push_back({unit, 0});
            else if (kw == "torque line direction")
                view.torques.push_back({unit, 0});
            else
                (kw == "torque direction" ? view.torque : view.tropism) = unit;
            if (kw == "cpfg tropism direction") view.cpfgTropism = true;
        }
        return "";
    }
    if (kw == "spline" || kw == "kolam dots" || kw == "music scale" || kw == "music root" ||
        kw == "music axis") {
        if (!text) return "'" + kw + ":' expects a word, not a number";
        return applyWordSetting(view, kw, *text);
    }
    if (kw == "cpfg line width unit") {  // sent by the view-file reader only
        if (!text || (*text != "pixels" && *text != "model"))
            return "the line width unit is 'pixels' or 'model'";
        view.widthsInModelUnits = *text == "model";
        return "";
    }
    if (kw == "projection" || kw == "line style" || kw == "background" || kw == "color map" ||
        kw == "colour map" || kw == "surface" || kw == "material file") {
        if (!text) return "'" + kw + ":' expects a word or a file name, not a number";
        std::string word = lowerCase(*text);
        if (kw == "projection") {
            if (word == "parallel" || word == "orthographic")
                view.parallelProjection = true;
            else if (word == "perspective")
                view.parallelProjection = false;
            else
                return "projection is 'perspective' or 'parallel', not '" + *text + "'";
        } else if (kw == "line style") {
            if (word == "cylinder" || word == "cylinders" || word == "polygon")
                view.lineStyle = LineStyle::Cylinders;
            else if (word == "lines" || word == "line" || word == "pixel")
                view.lineStyle = LineStyle::Lines;
            else
                return "line style is 'cylinder' or 'lines', not '" + *text + "'";
        } else if (kw == "background") {
            std::string hex = text->substr(text->starts_with("#") ? 1 : 0);
            bool ok = hex.size() == 6 &&
                      hex.find_first_not_of("0123456789abcdefABCDEF") == std::string::npos;
            if (!ok) return "background is a colour #rrggbb";
            unsigned c = static_cast<unsigned>(std::stoul(hex, nullptr, 16));
            view.background =
                Rgb{((c >> 16) & 255) / 255.0f, ((c >> 8) & 255) / 255.0f, (c & 255) / 255.0f};
        } else if (kw == "surface") {
            return applySurface(view, *text, setting.location);
        } else if (kw == "material file") {
            if (text->empty()) return "expected a .mat file name";
            view.materialFile = *text;
        } else {
            if (text->empty()) return "expected a .map file name";
            view.colorMap = *text;
        }
        return "";
    }
    // the view file's `tropism:` and `torque:` lines
    bool known = kw == "tropism line elasticity" || kw == "torque line elasticity";
    for (const auto& n : viewSettingNames()) known = known || n == kw;
    if (!known) return "unknown view setting '" + kw + "'";
    if (!number) return "'" + kw + ":' expects a number";
    double d = *number;
    if (kw == "angle factor") {
        if (d <= 0) return "angle factor must be positive (delta = 360 / factor)";
        view.angleDegrees = 360.0 / d;
    } else if (kw == "angle increment") {
        view.angleDegrees = d;
    } else if (kw == "scale factor") {
        if (d <= 0) return "scale factor must be positive";
        view.scaleFactor = d;
    } else if (kw == "initial heading") {
        view.initialHeading = d;
    } else if (kw == "step length") {
        if (d <= 0) return "step length must be positive";
        view.stepLength = d;
    } else if (kw == "tropism elasticity" || kw == "initial elasticity" || kw == "elasticity") {
        view.elasticity = d;
    } else if (kw == "field of view") {
        if (d <= 0 || d >= 180) return "field of view must be between 0 and 180 degrees";
        view.fieldOfView = d;
    } else if (kw == "spline subdivisions") {
        if (d < 0 || d > 64 || d != std::floor(d))
            return "spline subdivisions is a whole number from 0 (straight lines) to 64";
        view.splineSubdivisions = static_cast<int>(d);
    } else if (kw == "line width") {
        if (d <= 0) return "line width must be positive (the stem diameter in model units)";
        view.initialWidth = d;
    } else if (kw == "width factor") {
        if (d <= 0 || d >= 1) return "width factor must be between 0 and 1 (what ! multiplies by)";
        view.widthFactor = d;
    } else if (kw == "line width increment") {
        if (d < 0) return "line width increment must not be negative (what # adds and ! subtracts)";
        view.widthIncrement = d;
    } else if (kw == "initial color" || kw == "color increment") {
        if (d < 0 || d > 65535 || d != std::floor(d))
            return kw + " is a colour-map index, a whole number from 0 to 65535";
        (kw == "initial color" ? view.initialColor : view.colorIncrement) = static_cast<int>(d);
    } else if (kw == "twist") {
        view.twistDegrees = d;
    } else if (kw == "tropism line elasticity") {
        if (view.tropisms.empty()) return "an elasticity without a tropism direction";
        view.tropisms.back().elasticity = d;
    } else if (kw == "torque line elasticity") {
        if (view.torques.empty()) return "an elasticity without a torque direction";
        view.torques.back().elasticity = d;
    } else if (kw == "torque elasticity") {
        view.torqueElasticity = d;
    } else if (kw == "elasticity increment") {
        view.elasticityIncrement = d;
    } else if (kw == "light intensity" || kw == "sky intensity") {
        if (d < 0 || d > 10) return kw + " must be from 0 to 10";
        (kw == "light intensity" ? view.lightIntensity : view.skyIntensity) = d;
    } else if (kw == "cylinder sides") {
        if (d < 3 || d > 1024 || d != std::floor(d))
            return "cylinder sides is a whole number from 3 to 1024 (the corners around a stem)";
        view.tubeSides = static_cast<int>(d);
    } else if (kw == "music tempo") {
        if (d <= 0 || d > 1000) return "music tempo is beats per minute, above 0 and at most 1000";
        view.music.tempo = d;
    } else if (kw == "music instrument") {
        if (d < 1 || d > 128 || d != std::floor(d))
            return "music instrument is a General MIDI program, a whole number from 1 to 128";
        view.music.instrument = static_cast<int>(d);
    } else if (kw == "contour sides") {
        if (d < 3 || d > 1024 || d != std::floor(d))
            return "contour sides is a whole number from 3 to 1024 (the points around a "
                   "generalized cylinder)";
        view.contourSides = static_cast<int>(d);
    } else if (kw == "music unit") {
        if (d <= 0 || d > 64) return "music unit is the beats of one step, above 0 and at most 64";
        view.music.unit = d;
    }
    return "";
}

}  // namespace graftal
