// What the SVG and the Cairo painters of a derivation diagram share (derivation_diagram.hpp):
// the inks, the font and the text baselines, so that the two draw the same picture.
#pragma once

#include <cmath>
#include <filesystem>
#include <locale>
#include <sstream>
#include <string>

#include "graftal/output/derivation_diagram.hpp"

namespace graftal::diagram_style {

inline constexpr Rgb kInk{0.13f, 0.13f, 0.13f};      // text and outlines
inline constexpr Rgb kStepInk{0.45f, 0.45f, 0.45f};  // step numbers
inline constexpr const char* kFont = "DejaVu Sans";
inline constexpr double kCornerRadius = 0.18;  // of the cell height

// Baselines of the label and the parameters in a cell of height h at y.
inline double labelBaseline(const DiagramCell& c, double labelSize) {
    return c.parameters.empty() ? c.y + 0.5 * c.height + 0.36 * labelSize : c.y + 0.47 * c.height;
}
inline double parameterBaseline(const DiagramCell& c) {
    return c.y + 0.84 * c.height;
}

// A coordinate or size as SVG and messages write it: at most two decimals.
inline std::string number(double v) {
    std::ostringstream s;
    s.imbue(std::locale::classic());
    s << std::lround(v * 100) / 100.0;
    return s.str();
}

}  // namespace graftal::diagram_style

namespace graftal {

// The Cairo painters (derivation_diagram_cairo.cpp): the diagram as a PNG or PDF file.
void writeDerivationDiagramPng(const DerivationDiagram& d, const std::filesystem::path& path);
void writeDerivationDiagramPdf(const DerivationDiagram& d, const std::filesystem::path& path);

}  // namespace graftal
