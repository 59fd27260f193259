// Keyword arguments into the pipeline's requests: derive()'s settings into a DeriveRequest,
// export()'s options into an ExportRequest. Each keyword is the request field's name in
// snake_case (memoryLimit is memory_limit), so that the library's messages about a field
// name the keyword to change.
#include <algorithm>
#include <climits>
#include <cmath>
#include <map>

#include "bindings.hpp"
#include "graftal/geometry/projection.hpp"

namespace graftal::python {

namespace {

// "2G", "512M", "100K", 1000000 -> bytes.
std::size_t byteSize(py::handle value) {
    if (py::isinstance<py::int_>(value)) {
        const long long n = value.cast<long long>();
        if (n <= 0) throw py::value_error("memory_limit must be a positive number of bytes");
        return static_cast<std::size_t>(n);
    }
    if (!py::isinstance<py::str>(value))
        throw py::type_error("memory_limit: expected bytes as an int or a size such as '2G'");
    const std::string text = value.cast<std::string>();
    std::size_t used = 0;
    double number = 0;
    try {
        number = std::stod(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    std::string unit = text.substr(used);
    for (char& c : unit) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    if (!unit.empty() && unit.back() == 'B') unit.pop_back();
    if (!unit.empty() && unit.back() == 'I') unit.pop_back();
    static const std::map<std::string, double> units = {{"", 1},
                                                        {"K", 1024.0},
                                                        {"M", 1024.0 * 1024},
                                                        {"G", 1024.0 * 1024 * 1024},
                                                        {"T", 1024.0 * 1024 * 1024 * 1024}};
    const auto u = units.find(unit);
    if (used == 0 || u == units.end() || !(number > 0) || !std::isfinite(number))
        throw py::value_error("memory_limit '" + text +
                              "': expected a size such as 2G, 512M or 1000000");
    return static_cast<std::size_t>(number * u->second);
}

Rgb colour(const std::string& keyword, py::handle value) {
    if (py::isinstance<py::str>(value)) {
        std::string hex = value.cast<std::string>();
        if (!hex.empty() && hex[0] == '#') hex.erase(0, 1);
        std::size_t used = 0;
        unsigned long v = 0;
        try {
            v = std::stoul(hex, &used, 16);
        } catch (const std::exception&) {
            used = 0;
        }
        if (hex.size() != 6 || used != 6)
            throw py::value_error(keyword + ": expected '#rrggbb' or (r, g, b) from 0 to 1");
        return {((v >> 16) & 255) / 255.0f, ((v >> 8) & 255) / 255.0f, (v & 255) / 255.0f};
    }
    const auto c = value.cast<std::vector<double>>();
    if (c.size() != 3)
        throw py::value_error(keyword + ": expected '#rrggbb' or (r, g, b) from 0 to 1");
    return {static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2])};
}

Vec3 vector3(const std::string& keyword, py::handle value) {
    const auto v = value.cast<std::vector<double>>();
    if (v.size() != 3) throw py::value_error(keyword + ": expected three numbers (x, y, z)");
    return {v[0], v[1], v[2]};
}

}  // namespace

std::optional<RandomStreams> randomStreams(const py::object& random) {
    if (random.is_none()) return std::nullopt;
    const std::string name = py::isinstance<py::str>(random) ? random.cast<std::string>() : "";
    if (name == "cpfg") return RandomStreams::Cpfg;
    if (name == "graftal") return RandomStreams::Graftal;
    throw py::value_error("random=" + py::repr(random).cast<std::string>() +
                          ": expected 'graftal' (graftal's streams) or 'cpfg' (cpfg's "
                          "generators in cpfg's order), as --random");
}

DeriveSettings deriveSettings(py::object steps, py::object seed, unsigned threads,
                              py::object memoryLimit, const std::string& precision,
                              py::object environment, py::object random) {
    DeriveSettings s;
    s.random = randomStreams(random);
    if (!steps.is_none()) {
        if (!py::isinstance<py::int_>(steps) || py::isinstance<py::bool_>(steps))
            throw py::type_error("steps: expected an int");
        // The library checks the count (a negative one is an Error about `steps`).
        const long long n = steps.cast<long long>();
        s.steps = static_cast<int>(std::clamp<long long>(n, INT_MIN, INT_MAX));
    }
    if (!seed.is_none()) {
        if (!py::isinstance<py::int_>(seed)) throw py::type_error("seed: expected an int");
        const long long v = seed.cast<long long>();
        if (v < 0) throw py::value_error("seed must be >= 0");
        s.seed = static_cast<std::uint64_t>(v);
    }
    s.threads = threads;
    if (!memoryLimit.is_none()) s.memoryLimit = byteSize(memoryLimit);
    if (precision == "double")
        s.precision = Precision::Double;
    else if (precision != "single")
        throw py::value_error("precision '" + precision + "': expected 'single' or 'double'");
    if (!environment.is_none() && !py::hasattr(environment, "respond") &&
        !PyCallable_Check(environment.ptr()))
        throw py::type_error(
            "environment: expected an object with respond(step, queries), or a callable");
    s.environment = std::move(environment);
    return s;
}

DeriveRequest deriveRequest(const DeriveSettings& settings, const CancellationToken& cancel) {
    DeriveRequest r;
    r.steps = settings.steps;
    r.seed = settings.seed;
    r.threads = settings.threads;
    r.memoryLimit = settings.memoryLimit;
    r.precision = settings.precision;
    r.random = settings.random;
    r.cancel = cancel;
    if (!settings.environment.is_none()) r.environment = pythonEnvironment(settings.environment);
    return r;
}

py::dict deriveKeywords(const DeriveSettings& settings, int steps) {
    py::dict d;
    d["steps"] = steps;
    d["seed"] = settings.seed ? py::cast(*settings.seed) : py::none();
    d["threads"] = settings.threads;
    d["memory_limit"] = settings.memoryLimit;
    d["environment"] = settings.environment;
    if (settings.random) d["random"] = *settings.random == RandomStreams::Cpfg ? "cpfg" : "graftal";
    return d;
}

// One of export()'s options into `request` (its name known, its value not None).
void applyExportOption(ExportRequest& request, const std::string& k, py::handle value);

// export()'s options (export's keyword arguments besides the derivation's) into `request`.
Destination exportDestination(ExportRequest& request, const py::object& path,
                              const py::object& format, std::string& bytes,
                              const std::string& stem, const char* example) {
    if (!format.is_none()) {
        if (!py::isinstance<py::str>(format))
            throw py::type_error("format: expected a name such as 'png'");
        request.format = format.cast<std::string>();
    }
    if (!path.is_none())
        return Destination::file(
            py::str(py::module_::import("os").attr("fspath")(path)).cast<std::string>());
    if (request.format.empty())
        throw py::value_error(std::string("export(): name a format (format='") + example +
                              "') or a path");
    const ExportFormat* f = findExportFormat(request.format);
    return Destination::memory(bytes, stem + (f ? std::string(f->extension) : std::string()));
}

void applyExportOptions(ExportRequest& request, const py::dict& options) {
    static const std::vector<std::string> known = {"size",
                                                   "width",
                                                   "height",
                                                   "line_width",
                                                   "margin",
                                                   "background",
                                                   "line_color",
                                                   "fill_color",
                                                   "view",
                                                   "viewpoint",
                                                   "target",
                                                   "up",
                                                   "light",
                                                   "field_of_view",
                                                   "samples_per_pixel",
                                                   "ground",
                                                   "quality",
                                                   "tube_sides",
                                                   "surface_divisions",
                                                   "spline",
                                                   "spline_path",
                                                   "kolam_dots",
                                                   "derivation_diagram",
                                                   "glb_instancing",
                                                   "glb_compression",
                                                   "first",
                                                   "last",
                                                   "frames_per_step",
                                                   "fps",
                                                   "hold_seconds",
                                                   "turntable_degrees",
                                                   "stream",
                                                   "stream_limit",
                                                   "source_file"};
    for (const auto& [key, value] : options) {
        const std::string k = key.cast<std::string>();
        if (std::find(known.begin(), known.end(), k) == known.end()) {
            std::string list;
            for (const std::string& n : known) list += (list.empty() ? "" : ", ") + n;
            throw py::type_error("export() got an unexpected keyword argument '" + k +
                                 "' (known: " + list + ")");
        }
        if (value.is_none()) continue;
        try {
            applyExportOption(request, k, value);
        } catch (const py::cast_error&) {
            throw py::type_error("export(): " + k + "=" + py::repr(value).cast<std::string>() +
                                 " has the wrong type");
        }
    }
}

void applyExportOption(ExportRequest& request, const std::string& k, py::handle value) {
    {
        RenderOptions& picture = request.picture;
        if (k == "size") {
            if (py::isinstance<py::int_>(value)) {
                picture.width = picture.height = value.cast<int>();
            } else {
                const auto wh = value.cast<std::vector<int>>();
                if (wh.size() != 2) throw py::value_error("size: expected (width, height)");
                picture.width = wh[0];
                picture.height = wh[1];
            }
            if (picture.width < 1 || picture.height < 1 || picture.width > 32767 ||
                picture.height > 32767)
                throw py::value_error("size: each side from 1 to 32767 pixels");
        } else if (k == "width") {
            picture.width = value.cast<int>();
        } else if (k == "height") {
            picture.height = value.cast<int>();
        } else if (k == "line_width") {
            picture.lineWidth = value.cast<double>();
        } else if (k == "margin") {
            picture.margin = value.cast<double>();
        } else if (k == "background") {
            request.background = colour(k, value);
        } else if (k == "line_color") {
            picture.lineColor = colour(k, value);
        } else if (k == "fill_color") {
            picture.fillColor = colour(k, value);
        } else if (k == "view") {
            const auto view = viewDirectionFromName(value.cast<std::string>());
            if (!view) throw py::value_error("view: expected 'front', 'back', 'side' or 'top'");
            request.view = *view;
        } else if (k == "viewpoint") {
            request.viewpoint = vector3(k, value);
        } else if (k == "target") {
            request.target = vector3(k, value);
        } else if (k == "up") {
            request.up = vector3(k, value);
        } else if (k == "light") {
            request.light = vector3(k, value);
        } else if (k == "field_of_view") {
            request.fieldOfView = value.cast<double>();
        } else if (k == "samples_per_pixel") {
            request.samplesPerPixel = value.cast<int>();
        } else if (k == "ground") {
            request.ground = value.cast<bool>();
        } else if (k == "quality") {
            const auto q = meshResolutionFor(py::str(value).cast<std::string>());
            if (!q) throw py::value_error("quality: expected 'low', 'medium', 'high' or 3 to 64");
            request.tubeSides = q->tubeSides;
            request.surfaceDivisions = q->surfaceDivisions;
        } else if (k == "tube_sides") {
            request.tubeSides = value.cast<int>();
        } else if (k == "surface_divisions") {
            request.surfaceDivisions = value.cast<int>();
        } else if (k == "spline") {
            request.spline = value.cast<int>();
        } else if (k == "spline_path") {
            request.splinePath = value.cast<bool>();
        } else if (k == "kolam_dots") {
            request.kolamDots = value.cast<bool>();
        } else if (k == "derivation_diagram") {
            request.derivationDiagram = value.cast<bool>();
        } else if (k == "glb_instancing") {
            request.glb.instancing = value.cast<bool>();
        } else if (k == "glb_compression") {
            request.glb.compression = value.cast<bool>();
        } else if (k == "first") {
            request.from = value.cast<int>();
        } else if (k == "last") {
            request.to = value.cast<int>();
        } else if (k == "frames_per_step") {
            request.framesPerStep = value.cast<int>();
        } else if (k == "fps") {
            request.fps = value.cast<double>();
        } else if (k == "hold_seconds") {
            request.holdSeconds = value.cast<double>();
        } else if (k == "turntable_degrees") {
            request.turntableDegrees = value.cast<double>();
        } else if (k == "stream") {
            request.stream = value.cast<bool>() ? StreamPolicy::Always : StreamPolicy::Auto;
        } else if (k == "stream_limit") {
            request.streamLimit = value.cast<std::uint64_t>();
        } else if (k == "source_file") {
            request.sourceFile = value.cast<std::string>();
        }
    }
}

}  // namespace graftal::python
