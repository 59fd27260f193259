// The map L-system commands: parse, derive the map, then print it, count it or draw it.
#include "map_commands.hpp"

#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>

#include "graftal/maps/map_drawing.hpp"
#include "graftal/maps/map_lsystem.hpp"
#include "graftal/maps/plane_map.hpp"
#include "graftal/output/output.hpp"
#include "graftal/pipeline/stages.hpp"
#include "standard_streams.hpp"

namespace graftal::cli {

namespace {

Error usageError(const std::string& message) {
    return Error(SourceLocation{"graftal", 0, 0}, message);
}

struct LoadedMap {
    MapLSystem system;
    int steps = 0;
};

LoadedMap loadMap(const InputOptions& in) {
    if (!in.viewFile.empty())
        throw usageError("a map L-system takes no view file ('" + in.viewFile + "')");
    ParseOptions po;
    po.defines = in.defines;
    MapParseResult parsed;
    if (in.file == "-") {
        po.fileName = kStdinName;
        parsed = parseMapLSystem(standardInputText(), po);
    } else {
        parsed = loadMapLSystem(in.file, po);
    }
    if (!parsed.ok()) throw Error(parsed.errors());
    if (!in.quiet)
        for (const auto& w : parsed.warnings()) std::cerr << w.toString() << '\n';
    LoadedMap l{std::move(parsed).orThrow(), 0};
    l.steps = in.steps.value_or(l.system.derivationLength);  // derivedMap() checks it
    return l;
}

MapDerivationOptions derivationOptions(const InputOptions& in, const MapOptions& map) {
    MapDerivationOptions o;
    o.threads = in.threads;
    if (map.geometry == "siero")
        o.geometry = MapGeometry::Siero;
    else if (map.geometry == "relaxed" || map.geometry == "spline")
        o.geometry = MapGeometry::Relaxed;
    else
        throw usageError("--map-geometry '" + map.geometry +
                         "': expected siero, relaxed or spline");
    if (map.outline == "growing")
        o.outline = MapOutline::Growing;
    else if (map.outline == "polygon")
        o.outline = MapOutline::Polygon;
    else
        throw usageError("--map-outline '" + map.outline + "': expected growing or polygon");
    return o;
}

DerivedMap derive(const InputOptions& in, const MapOptions& options) {
    MapRequest request;
    request.derivation = derivationOptions(in, options);  // option errors first
    LoadedMap l = loadMap(in);
    return derivedMap(l.system, l.steps, request);
}

}  // namespace

void addMapOptions(CLI::App& cmd, MapOptions& map, bool drawing) {
    cmd.add_option("--map-geometry", map.geometry,
                   "map L-systems: siero (vertices stay where born), relaxed (at their "
                   "neighbours' centre), spline (relaxed, cells as B-splines)");
    cmd.add_option("--map-outline", map.outline,
                   "map L-systems, relaxed: growing (the outline moves until the cells along "
                   "it are alike; default) or polygon (the axiom's polygon stays)");
    if (!drawing) return;
    cmd.add_option("--map-fill", map.fill, "map L-systems: fill cells by none, age, sides, labels");
    cmd.add_flag("--map-uniform-width", map.uniformWidth,
                 "map L-systems: every wall equally wide (default: width grows with age)");
}

bool isMapInput(const InputOptions& in) {
    if (in.file == "-") return isMapLSystemText(standardInputText());
    return isMapLSystemFile(in.file);
}

int runMapDerive(const InputOptions& in, const MapOptions& map) {
    DerivedMap d = derive(in, map);
    writeMapText(d.map, std::cout);
    std::cout.flush();
    return std::cout ? 0 : 1;
}

int runMapStats(const InputOptions& in, const MapOptions& map) {
    DerivedMap d = derive(in, map);
    const PlaneMap& m = d.map;
    nlohmann::ordered_json j;
    j["file"] = fileName(in);
    j["steps"] = m.step;
    j["vertices"] = m.vertexCount();
    j["edges"] = m.edgeCount();
    j["cells"] = m.cellCount();
    std::map<std::size_t, std::size_t> sides;
    for (std::uint32_t r = 1; r < m.regionCount(); ++r) ++sides[m.boundary(r).size()];
    nlohmann::ordered_json hist = nlohmann::ordered_json::object();
    for (const auto& [k, n] : sides) hist[std::to_string(k)] = n;
    j["cell sides"] = hist;
    j["branches"] = {{"connected", d.last.connected},
                     {"discarded", d.last.discarded},
                     {"crossing", d.last.crossing},
                     {"outside", d.last.outside}};
    if (map.geometry != "siero") j["relaxation iterations"] = d.relaxIterations;
    Bounds b;
    for (const Vec3& p : m.position) b.extend(p);
    if (b.empty()) b.extend(Vec3{});
    j["bbox"] = {{"min", {b.min.x, b.min.y, b.min.z}}, {"max", {b.max.x, b.max.y, b.max.z}}};
    std::cout << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << '\n';
    return 0;
}

int runMapRender(const InputOptions& in, const RenderCommandOptions& out, const MapOptions& map) {
    ExportRequest request = renderRequest(in, out);
    request.map.derivation = derivationOptions(in, map);
    request.map.drawing.splines = map.geometry == "spline";
    request.map.drawing.widthByAge = !map.uniformWidth;
    if (auto fill = mapFillFromName(map.fill))
        request.map.drawing.fill = *fill;
    else
        throw usageError("--map-fill '" + map.fill + "': expected none, age, sides or labels");
    if (out.spline && *out.spline > 0) request.map.drawing.splineSubdivisions = *out.spline;
    LoadedMap l = loadMap(in);
    request.steps = l.steps;
    exportMap(l.system, renderDestination(out), request);
    return 0;
}

}  // namespace graftal::cli
