// Map L-systems (the book's chapter 5) in Python: graftal.load() and graftal.parse() return a
// MapModel for a file that starts `map L-system:`, as the command does. It is derived by the
// pipeline's derivedMap() (a graftal.Map: the cells as `graftal derive` prints them, counts
// and vertex positions) and drawn by the export registry's exportMap(), as `graftal render`.
#include <algorithm>
#include <cctype>
#include <fstream>
#include <iterator>
#include <sstream>

#include "bindings.hpp"
#include "graftal/maps/map_drawing.hpp"
#include "graftal/maps/map_lsystem.hpp"
#include "graftal/maps/plane_map.hpp"
#include "graftal/pipeline/stages.hpp"

namespace graftal::python {

namespace {

// A parsed map L-system and where it came from (to read it again in another process).
struct MapHandle {
    std::shared_ptr<const MapLSystem> system;
    std::vector<Diagnostic> warnings;
    std::shared_ptr<const ModelSource> source;
};

// A derived map.
struct MapResult {
    DerivedMap derived;
    bool relaxed = false;
};

// The names a map L-system's text defines (`#define NAME ...` lines): a map has no table of
// constants to ask, and an override of a name it does not define would change nothing.
std::vector<std::string> definedNames(const ModelSource& source) {
    std::string text = source.text;
    if (!source.path.empty()) {
        std::ifstream in(source.path, std::ios::binary);
        text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    std::vector<std::string> names;
    std::istringstream lines(text);
    std::string line;
    auto blank = [](char c) { return c == ' ' || c == '\t'; };
    auto word = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
    while (std::getline(lines, line)) {
        std::size_t i = 0;
        while (i < line.size() && blank(line[i])) ++i;
        if (i >= line.size() || line[i] != '#') continue;
        ++i;
        while (i < line.size() && blank(line[i])) ++i;
        if (line.compare(i, 6, "define") != 0) continue;
        i += 6;
        std::size_t start = i;
        while (i < line.size() && blank(line[i])) ++i;
        if (i == start) continue;
        start = i;
        while (i < line.size() && word(line[i])) ++i;
        if (i > start) names.push_back(line.substr(start, i - start));
    }
    return names;
}

void checkMapDefines(const ModelSource& source) {
    if (source.defines.empty()) return;
    const std::vector<std::string> names = definedNames(source);
    for (const auto& [name, value] : source.defines) {
        if (std::find(names.begin(), names.end(), name) != names.end()) continue;
        std::string known;
        for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
        throw py::value_error(
            "defines: the map L-system has no #define " + name +
            (known.empty() ? std::string(" (it defines none)") : " (it defines " + known + ")"));
    }
}

MapHandle readMap(ModelSource source) {
    checkMapDefines(source);
    ParseOptions options;
    options.defines = source.defines;
    MapParseResult parsed;
    {
        py::gil_scoped_release release;
        if (!source.path.empty()) {
            parsed = loadMapLSystem(source.path, options);
        } else {
            options.fileName = source.file;
            parsed = parseMapLSystem(source.text, options);
        }
    }
    if (!parsed.ok()) raiseParseError(parsed.errors());
    MapHandle h;
    h.warnings = parsed.warnings();
    h.system = std::make_shared<const MapLSystem>(std::move(parsed).orThrow());
    h.source = std::make_shared<const ModelSource>(std::move(source));
    return h;
}

// The command's --map-geometry and --map-outline as keywords.
MapDerivationOptions derivationOptions(const std::string& geometry, const std::string& outline,
                                       unsigned threads) {
    MapDerivationOptions o;
    o.threads = threads;
    if (geometry == "siero")
        o.geometry = MapGeometry::Siero;
    else if (geometry == "relaxed" || geometry == "spline")
        o.geometry = MapGeometry::Relaxed;
    else
        throw py::value_error("geometry '" + geometry +
                              "': expected 'siero', 'relaxed' or 'spline'");
    if (outline == "growing")
        o.outline = MapOutline::Growing;
    else if (outline == "polygon")
        o.outline = MapOutline::Polygon;
    else
        throw py::value_error("outline '" + outline + "': expected 'growing' or 'polygon'");
    return o;
}

std::optional<int> stepCount(const py::object& steps) {
    if (steps.is_none()) return std::nullopt;
    if (!py::isinstance<py::int_>(steps) || py::isinstance<py::bool_>(steps))
        throw py::type_error("steps: expected an int");
    return steps.cast<int>();  // derivedMap() checks the count
}

MapResult derive(const MapHandle& h, py::object steps, unsigned threads,
                 const std::string& geometry, const std::string& outline) {
    MapRequest request;
    request.derivation = derivationOptions(geometry, outline, threads);
    const std::optional<int> n = stepCount(steps);
    CancellationToken cancel;
    MapResult r;
    r.relaxed = request.derivation.geometry != MapGeometry::Siero;
    r.derived = interruptible(cancel, [&] { return derivedMap(*h.system, n, request, cancel); });
    return r;
}

std::string mapText(const MapResult& r) {
    std::ostringstream os;
    writeMapText(r.derived.map, os);
    return os.str();
}

// What `graftal stats` reports of a map, as a dict.
py::dict mapStatistics(const MapResult& r) {
    const PlaneMap& m = r.derived.map;
    py::dict d;
    d["steps"] = m.step;
    d["vertices"] = m.vertexCount();
    d["edges"] = m.edgeCount();
    d["cells"] = m.cellCount();
    std::map<std::size_t, std::size_t> sides;
    for (std::uint32_t region = 1; region < m.regionCount(); ++region)
        ++sides[m.boundary(region).size()];
    py::dict histogram;
    for (const auto& [k, n] : sides) histogram[py::int_(k)] = n;
    d["cell_sides"] = histogram;
    py::dict branches;
    branches["connected"] = r.derived.last.connected;
    branches["discarded"] = r.derived.last.discarded;
    branches["crossing"] = r.derived.last.crossing;
    branches["outside"] = r.derived.last.outside;
    d["branches"] = branches;
    if (r.relaxed) d["relaxation_iterations"] = r.derived.relaxIterations;
    Bounds b;
    for (const Vec3& p : m.position) b.extend(p);
    if (b.empty()) b.extend(Vec3{});
    d["bounds"] = py::make_tuple(py::make_tuple(b.min.x, b.min.y, b.min.z),
                                 py::make_tuple(b.max.x, b.max.y, b.max.z));
    return d;
}

py::object exportMapPicture(const MapHandle& h, py::object path, py::object format,
                            py::object steps, unsigned threads, const std::string& geometry,
                            const std::string& outline, const std::string& fill, bool uniformWidth,
                            py::kwargs options) {
    ExportRequest request;
    CancellationToken cancel;
    request.cancel = cancel;
    request.threads = threads;
    request.steps = stepCount(steps);
    request.map.derivation = derivationOptions(geometry, outline, threads);
    request.map.drawing.splines = geometry == "spline";
    request.map.drawing.widthByAge = !uniformWidth;
    const auto mapFill = mapFillFromName(fill);
    if (!mapFill)
        throw py::value_error("fill '" + fill + "': expected 'none', 'age', 'sides' or 'labels'");
    request.map.drawing.fill = *mapFill;
    applyExportOptions(request, options);
    if (request.spline && *request.spline > 0)
        request.map.drawing.splineSubdivisions = *request.spline;
    std::string bytes;
    const bool toMemory = path.is_none();
    const Destination destination = exportDestination(request, path, format, bytes, "map", "svg");
    interruptible(cancel, [&] { exportMap(*h.system, destination, request); });
    if (!toMemory) return py::none();
    return py::bytes(bytes);
}

py::tuple mapState(const MapHandle& h) {
    const ModelSource& s = *h.source;
    return py::make_tuple(s.path, s.text, s.file, s.defines);
}

MapHandle mapFromState(const py::tuple& t) {
    if (t.size() != 4) throw py::value_error("not a pickled graftal.MapModel");
    ModelSource s;
    s.path = t[0].cast<std::string>();
    s.text = t[1].cast<std::string>();
    s.file = t[2].cast<std::string>();
    s.defines = t[3].cast<std::map<std::string, std::string>>();
    return readMap(std::move(s));
}

}  // namespace

bool isMapSource(const ModelSource& source) {
    if (!source.path.empty()) return isMapLSystemFile(source.path);
    return isMapLSystemText(source.text);
}

py::object loadMapModel(ModelSource source) {
    if (source.view)
        throw py::value_error("a map L-system takes no view file (" + *source.view + ")");
    if (source.functions || source.random)
        throw py::value_error(
            "a map L-system has no func() and draws no random numbers: "
            "functions= and random= do not apply");
    return py::cast(readMap(std::move(source)));
}

void bindMaps(py::module_& m) {
    py::class_<MapResult>(m, "Map",
                          "A derived map L-system: its cells (str() is the text `graftal "
                          "derive` prints), counts and vertex positions.")
        .def_property_readonly(
            "steps", [](const MapResult& r) { return r.derived.map.step; }, "steps derived")
        .def_property_readonly(
            "vertices", [](const MapResult& r) { return r.derived.map.vertexCount(); },
            "the number of vertices")
        .def_property_readonly(
            "edges", [](const MapResult& r) { return r.derived.map.edgeCount(); },
            "the number of walls")
        .def_property_readonly(
            "cells", [](const MapResult& r) { return r.derived.map.cellCount(); },
            "the number of cells")
        .def_property_readonly(
            "positions",
            [](const MapResult& r) {
                const auto& p = r.derived.map.position;
                py::array_t<double> a({py::ssize_t(p.size()), py::ssize_t(3)});
                for (std::size_t i = 0; i < p.size(); ++i) {
                    double* row = a.mutable_data(py::ssize_t(i), 0);
                    row[0] = p[i].x, row[1] = p[i].y, row[2] = p[i].z;
                }
                return a;
            },
            "the vertices' positions, a (vertices, 3) float64 array")
        .def("statistics", &mapStatistics,
             "What `graftal stats` reports of the map, as a dict: steps, vertices, edges, "
             "cells, cell_sides (cells per number of walls), branches, bounds, and "
             "relaxation_iterations for a relaxed geometry.")
        .def("__str__", &mapText)
        .def("__repr__", [](const MapResult& r) {
            return "<graftal.Map " + std::to_string(r.derived.map.cellCount()) + " cells after " +
                   std::to_string(r.derived.map.step) + " steps>";
        });

    py::class_<MapHandle>(m, "MapModel",
                          "A map L-system (the book's chapter 5), made by graftal.load() or "
                          "graftal.parse() from text that starts `map L-system:`: it rewrites "
                          "the labelled walls of a map of cells.")
        .def_property_readonly(
            "file", [](const MapHandle& h) { return h.system->file; }, "the file it was read from")
        .def_property_readonly(
            "derivation_length", [](const MapHandle& h) { return h.system->derivationLength; },
            "the file's derivation length, the steps derive() makes by default")
        .def_property_readonly(
            "warnings", [](const MapHandle& h) { return diagnosticList(h.warnings); },
            "the parse's warnings (graftal.Diagnostic)")
        .def_property_readonly(
            "overrides", [](const MapHandle& h) { return h.source->defines; },
            "the #define overrides it was read with")
        .def("derive", &derive, py::arg("steps") = py::none(), py::kw_only(),
             py::arg("threads") = 0u, py::arg("geometry") = "siero", py::arg("outline") = "growing",
             "Derives the map `steps` steps (default: its derivation length) and returns a "
             "graftal.Map. geometry: 'siero' (vertices stay where born), 'relaxed' (at their "
             "neighbours' centre) or 'spline' (relaxed; drawn as B-splines); outline "
             "(relaxed): 'growing' or 'polygon' -- the command's --map-geometry and "
             "--map-outline. The GIL is released; Ctrl-C stops it with KeyboardInterrupt.")
        .def(
            "statistics",
            [](const MapHandle& h, py::object steps, unsigned threads, const std::string& geometry,
               const std::string& outline) {
                return mapStatistics(derive(h, std::move(steps), threads, geometry, outline));
            },
            py::arg("steps") = py::none(), py::kw_only(), py::arg("threads") = 0u,
            py::arg("geometry") = "siero", py::arg("outline") = "growing",
            "derive(...).statistics(): what `graftal stats` reports of the map.")
        .def("export", &exportMapPicture, py::arg("path") = py::none(), py::kw_only(),
             py::arg("format") = py::none(), py::arg("steps") = py::none(), py::arg("threads") = 0u,
             py::arg("geometry") = "siero", py::arg("outline") = "growing",
             py::arg("fill") = "none", py::arg("uniform_width") = false,
             "Draws the derived map as `graftal render` does, in a picture format (svg, png, "
             "pdf): to `path`, or returned as bytes with format=. fill colours the cells "
             "('none', 'age', 'sides', 'labels'); uniform_width draws every wall equally "
             "wide; the picture options of Model.export (size, line_width, margin, "
             "background, line_color, spline) apply.")
        .def(
            "with_defines",
            [](const MapHandle& h, py::object defines) {
                ModelSource source = *h.source;
                for (auto& [name, value] : defineMap(defines)) source.defines[name] = value;
                return readMap(std::move(source));
            },
            py::arg("defines"),
            "The same map L-system read again with these #define constants overridden too "
            "({'L': 3}); the overrides it was read with stay unless named again. A name the "
            "text does not #define is a ValueError.")
        .def(py::pickle(&mapState, &mapFromState))
        .def("__repr__", [](const MapHandle& h) {
            return "<graftal.MapModel '" + h.system->file +
                   "' derivation_length=" + std::to_string(h.system->derivationLength) + ">";
        });
}

}  // namespace graftal::python
