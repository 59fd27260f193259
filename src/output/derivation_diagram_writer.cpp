// Painting a laid-out derivation diagram as SVG text, and writing it by format (PNG and PDF
// by derivation_diagram_cairo.cpp). Both painters draw the same things in the same order:
// background, step numbers, then each cell as a rounded box with its symbol's name and,
// smaller below it, its parameters.
#include <algorithm>
#include <cmath>
#include <ostream>

#include "diagram_style.hpp"
#include "graftal/core/diagnostics.hpp"
#include "graftal/core/xml_text.hpp"
#include "graftal/output/derivation_diagram.hpp"

namespace graftal {

using namespace diagram_style;

void writeDerivationDiagramSvg(const DerivationDiagram& d, std::ostream& out) {
    const std::string w = number(d.width), h = number(d.height);
    out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
        << "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" << w
        << "\" height=\"" << h << "\" viewBox=\"0 0 " << w << " " << h << "\">\n"
        << "<rect x=\"0\" y=\"0\" width=\"" << w << "\" height=\"" << h << "\" fill=\""
        << hexColor(d.background) << "\"/>\n"
        << "<g font-family=\"" << kFont << ", Arial, Helvetica, sans-serif\">\n";
    const double outline = std::max(1.0, d.labelSize / 14);
    for (const DiagramRow& row : d.rows) {
        if (!row.gap)
            out << "<text x=\"" << number(row.labelX) << "\" y=\""
                << number(row.labelY + 0.4 * d.parameterSize) << "\" font-size=\""
                << number(d.parameterSize * 1.2) << "\" text-anchor=\"end\" fill=\""
                << hexColor(kStepInk) << "\">" << row.step << "</text>\n";
        for (const DiagramCell& c : row.cells) {
            const double cx = c.x + c.width / 2;
            out << "<rect x=\"" << number(c.x) << "\" y=\"" << number(c.y) << "\" width=\""
                << number(c.width) << "\" height=\"" << number(c.height) << "\" rx=\""
                << number(std::min(kCornerRadius * c.height, c.width / 2)) << "\" fill=\""
                << hexColor(c.fill) << "\" stroke=\"" << hexColor(kInk) << "\" stroke-width=\""
                << number(outline) << "\"" << (c.ellipsis ? " stroke-dasharray=\"4 3\"" : "")
                << "/>\n"
                << "<text x=\"" << number(cx) << "\" y=\"" << number(labelBaseline(c, d.labelSize))
                << "\" font-size=\"" << number(d.labelSize)
                << "\" font-weight=\"bold\" text-anchor=\"middle\" fill=\"" << hexColor(kInk)
                << "\">" << xmlEscaped(c.label) << "</text>\n";
            if (!c.parameters.empty())
                out << "<text x=\"" << number(cx) << "\" y=\"" << number(parameterBaseline(c))
                    << "\" font-size=\"" << number(d.parameterSize)
                    << "\" text-anchor=\"middle\" fill=\"" << hexColor(kInk) << "\">"
                    << xmlEscaped(c.parameters) << "</text>\n";
        }
    }
    out << "</g>\n</svg>\n";
    out.flush();
    if (!out) throw Error(SourceLocation{}, "cannot write SVG: output stream failed");
}

void writeDerivationDiagram(const DerivationDiagram& d, ImageFormat format,
                            const Destination& destination) {
    switch (format) {
        case ImageFormat::Svg:
            destination.write("SVG", [&](std::ostream& out) { writeDerivationDiagramSvg(d, out); });
            return;
        case ImageFormat::Png:
            destination.writeThroughFile(
                "PNG", [&](const std::filesystem::path& file) { writeDerivationDiagramPng(d, file); });
            return;
        case ImageFormat::Pdf:
            destination.writeThroughFile(
                "PDF", [&](const std::filesystem::path& file) { writeDerivationDiagramPdf(d, file); });
            return;
        case ImageFormat::Obj:
        case ImageFormat::Ply:
        case ImageFormat::Glb:
            break;
    }
    throw Error(SourceLocation{destination.name(), 0, 0},
                "a derivation diagram is drawn to .svg, .png or .pdf");
}

void writeDerivationDiagram(const DerivationDiagram& d, const std::filesystem::path& path) {
    const std::optional<ImageFormat> format = imageFormatFor(path);
    if (!format)
        throw Error(SourceLocation{path.string(), 0, 0},
                    "unknown image file extension '" + path.extension().string() +
                        "'; a derivation diagram is drawn to .svg, .png or .pdf");
    writeDerivationDiagram(d, *format, Destination::file(path));
}

void writeDerivationDiagram(const std::vector<ModuleString>& steps, const SymbolTable& symbols,
                            const RenderOptions& o, const std::filesystem::path& path) {
    writeDerivationDiagram(layoutDerivationDiagram(steps, symbols, o), path);
}

void writeDerivationDiagram(const std::vector<ModuleString>& steps, const SymbolTable& symbols,
                            const RenderOptions& o, ImageFormat format,
                            const Destination& destination) {
    writeDerivationDiagram(layoutDerivationDiagram(steps, symbols, o), format, destination);
}

}  // namespace graftal
