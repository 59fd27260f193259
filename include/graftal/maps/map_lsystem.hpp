// Map L-systems (the book's chapter 5): L-systems that rewrite the directed, labelled edges
// of a planar map instead of the modules of a string. This header is the language: what a
// map L-system file says, parsed; plane_map.hpp holds the map and its derivation.
#pragma once

#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "graftal/core/diagnostics.hpp"
#include "graftal/lang/lsystem.hpp"

namespace graftal {

// One edge of a successor's main axis or of the axiom: its label and whether `~` reverses
// it against the predecessor's direction (on the axiom: against the cycle's direction).
struct MapAxisEdge {
    char label = 0;
    bool reversed = false;
};

// A branch `[+a]`, `[-~a]`: one edge attached at vertex `vertex` of the main axis
// (0 is the predecessor's start, axis.size() its end), on the left (`+`) or the right (`-`)
// of the axis as seen along the predecessor's direction. Without `~` the branch points
// away from the axis, with `~` towards it.
struct MapBranch {
    std::size_t vertex = 0;
    bool left = true;
    bool towards = false;
    char label = 0;
};

struct MapProduction {
    char predecessor = 0;
    std::vector<MapAxisEdge> axis;    // at least one edge
    std::vector<MapBranch> branches;  // in the order written
    SourceLocation location;
};

struct MapLSystem {
    std::string file;
    int derivationLength = 0;
    std::vector<MapAxisEdge> axiom;  // a cycle, clockwise around the first cell
    // Production for each label (indexed by the label's byte), absent for unused labels.
    std::array<std::optional<MapProduction>, 256> productions;

    const MapProduction* production(char label) const {
        const auto& p = productions[static_cast<unsigned char>(label)];
        return p ? &*p : nullptr;
    }
};

struct MapParseResult {
    MapLSystem system;
    std::vector<Diagnostic> diagnostics;

    bool ok() const;
    std::vector<Diagnostic> errors() const;
    std::vector<Diagnostic> warnings() const;
    // The system; throws Error carrying every error when the parse failed.
    MapLSystem orThrow() &&;
};

// True when the text is a map L-system: its first statement (after comments, blank lines
// and #define lines) is `map L-system:`.
bool isMapLSystemText(std::string_view text);
// The same for a file; false when it cannot be read (loadModel then reports that).
bool isMapLSystemFile(const std::filesystem::path& path);

// Parses map L-system text. ParseOptions::fileName names it in locations and
// ParseOptions::defines (-D) win over #define. Never throws for bad input.
MapParseResult parseMapLSystem(std::string_view text, const ParseOptions& options);
// Reads and parses a file; a file that cannot be read is a diagnostic at line 0.
MapParseResult loadMapLSystem(const std::filesystem::path& path, ParseOptions options = {});

// The successor written back in the book's notation, e.g. "c[-~a]x[+~b]g".
std::string successorText(const MapProduction& p);

}  // namespace graftal
