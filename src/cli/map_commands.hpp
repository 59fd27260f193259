// derive, stats and render for map L-systems (files whose first statement is
// `map L-system:`): the string L-system commands hand such files over to these.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "commands.hpp"

namespace graftal::cli {

struct MapOptions {
    std::string geometry = "siero";   // --map-geometry siero|relaxed|spline
    std::string outline = "growing";  // --map-outline growing|polygon
    std::string fill = "none";        // --map-fill none|age|sides|labels
    bool uniformWidth = false;        // --map-uniform-width: every wall as wide
};

// The map options of a subcommand (all of them for render, the geometry for the others).
void addMapOptions(CLI::App& cmd, MapOptions& map, bool drawing);

// True when the input file is a map L-system.
bool isMapInput(const InputOptions& in);

int runMapDerive(const InputOptions& in, const MapOptions& map);
int runMapStats(const InputOptions& in, const MapOptions& map);
int runMapRender(const InputOptions& in, const RenderCommandOptions& out, const MapOptions& map);

}  // namespace graftal::cli
