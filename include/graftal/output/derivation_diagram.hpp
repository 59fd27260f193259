// A derivation drawn as the book draws Anabaena's filament and the Fibonacci derivation
// (LSFP Fig 1.3, 1.4): one row per derivation step, the axiom at the top, each module a
// labelled cell coloured by its symbol. It is the picture for L-systems whose strings have
// no turtle meaning, and for any file when asked (graftal render --derivation).
#pragma once

#include <cstddef>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "graftal/core/module_string.hpp"
#include "graftal/output/animation_file.hpp"
#include "graftal/output/output.hpp"

namespace graftal {

// One cell of the diagram, in pixels (PNG), points (PDF) or SVG user units, y down.
struct DiagramCell {
    double x = 0, y = 0, width = 0, height = 0;
    std::string label;       // the symbol's name, or "…" for the cell that cuts a row
    std::string parameters;  // "1,2.5" under the label; empty when none or too long
    Rgb fill;
    bool ellipsis = false;   // stands for `hidden` modules left out of the row
    std::size_t hidden = 0;  // modules (or, for a gap row's cell, steps) not drawn
};

struct DiagramRow {
    int step = 0;                   // the derivation step the row shows (0: the axiom)
    bool gap = false;               // a row standing for `cells[0].hidden` steps left out
    double labelX = 0, labelY = 0;  // where the step number is written (its right end)
    std::vector<DiagramCell> cells;
};

struct DerivationDiagram {
    double width = 0, height = 0;  // the picture's size
    double labelSize = 0;          // font size of the symbol names
    double parameterSize = 0;      // font size of the parameters and step numbers
    Rgb background;
    std::vector<DiagramRow> rows;
};

// The colour of the k-th distinct symbol of a derivation (in order of first appearance):
// a fixed palette of light colours that dark labels stay readable on. It repeats after
// derivationPaletteSize() colours. Brackets get a neutral grey instead.
Rgb derivationCellColor(std::size_t k);
std::size_t derivationPaletteSize();

// Lays out `steps` (steps[0] the axiom, steps[n] the string after n steps) in a
// o.width x o.height frame with o.margin free around it. Cells share one size, chosen so
// that the longest row and all rows fit; rows too long even at the smallest readable cell
// end in an ellipsis cell saying how many modules are hidden, and when there are too many
// steps the middle ones are replaced by one gap row. Throws Error for an empty `steps` or
// a frame size that is not positive.
DerivationDiagram layoutDerivationDiagram(const std::vector<ModuleString>& steps,
                                          const SymbolTable& symbols, const RenderOptions& o);

void writeDerivationDiagramSvg(const DerivationDiagram& diagram, std::ostream& out);
// The diagram as an image in memory (an animation's frame). Throws Error for a size out of
// range.
RgbaImage drawDerivationDiagram(const DerivationDiagram& diagram);
// Writes the diagram by the extension of `path` (.svg, .png or .pdf), atomically (nothing is
// left at `path` on failure). Throws Error.
void writeDerivationDiagram(const DerivationDiagram& diagram, const std::filesystem::path& path);
void writeDerivationDiagram(const std::vector<ModuleString>& steps, const SymbolTable& symbols,
                            const RenderOptions& o, const std::filesystem::path& path);
// The same in `format` to a file, a stream or memory.
void writeDerivationDiagram(const DerivationDiagram& diagram, ImageFormat format,
                            const Destination& destination);
void writeDerivationDiagram(const std::vector<ModuleString>& steps, const SymbolTable& symbols,
                            const RenderOptions& o, ImageFormat format,
                            const Destination& destination);

}  // namespace graftal
