// The layout of a derivation diagram: which cells are drawn where, in what colour, with
// what text. The writers (derivation_diagram_writer.cpp) only paint what this decides, so
// the SVG, PNG and PDF pictures agree and the layout can be tested without decoding images.
//
// Every cell has the same size, as in the book's filament (Fig 1.4): a column of cells then
// lines up step after step. Text widths are estimated from character counts (the SVG writer
// cannot measure text), generously enough for DejaVu Sans and its usual substitutes.
#include "graftal/output/derivation_diagram.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "graftal/core/diagnostics.hpp"

namespace graftal {

namespace {

// Light colours, one per symbol in order of first appearance, that dark text stays
// readable on and that neighbours in the list tell apart.
constexpr std::array<std::uint32_t, 12> kPalette = {
    0x85c1e9, 0xf8c471, 0x82e0aa, 0xf1948a, 0xc39bd3, 0xf9e79f,
    0x76d7c4, 0xedbb99, 0x5dade2, 0xf5b7b1, 0xabebc6, 0xd2b4de,
};
constexpr std::uint32_t kBracketColor = 0xd5d8dc;
constexpr std::uint32_t kEllipsisColor = 0xffffff;

// Sizes in units of the cell height h.
constexpr double kLabelFont = 0.42;      // symbol names
constexpr double kParameterFont = 0.26;  // parameters, step numbers, "N more"
constexpr double kCharWidth = 0.64;      // a character's width per unit of font size
constexpr double kCellGap = 0.08;        // between the cells of a row
constexpr double kRowPitch = 1.35;       // from one row's top to the next one's
constexpr double kMinCellAspect = 0.8;   // narrowest cell, width over height
// Parameters longer than this are left out: the cells would get too wide to line up.
constexpr std::size_t kMaxParameterChars = 14;
// Only this many modules of a row can ever be shown (a 32767-pixel picture of the
// smallest cells); the rest is never looked at, so huge strings cost nothing here.
constexpr std::size_t kMaxShownModules = 4096;

Rgb fromHex(std::uint32_t c) {
    return {static_cast<float>((c >> 16) & 0xff) / 255.0f,
            static_cast<float>((c >> 8) & 0xff) / 255.0f, static_cast<float>(c & 0xff) / 255.0f};
}

std::string parameterText(const ModuleString& s, std::size_t i) {
    std::string text;
    ParamView params = s.params(i);
    for (std::size_t k = 0; k < params.size(); ++k) {
        if (!text.empty()) text += ',';
        text += formatParameter(params, k);
    }
    return text.size() <= kMaxParameterChars ? text : std::string();
}

// Characters of UTF-8 text (continuation bytes do not count).
std::size_t characters(const std::string& text) {
    return static_cast<std::size_t>(std::count_if(text.begin(), text.end(), [](char c) {
        return (static_cast<unsigned char>(c) & 0xc0) != 0x80;
    }));
}

std::string moreText(std::size_t hidden, const char* what) {
    return std::to_string(hidden) + " " + what;
}

}  // namespace

Rgb derivationCellColor(std::size_t k) {
    return fromHex(kPalette[k % kPalette.size()]);
}

std::size_t derivationPaletteSize() {
    return kPalette.size();
}

DerivationDiagram layoutDerivationDiagram(const std::vector<ModuleString>& steps,
                                          const SymbolTable& symbols, const RenderOptions& o) {
    if (steps.empty())
        throw Error(SourceLocation{}, "a derivation diagram needs at least the axiom");
    if (o.width <= 0 || o.height <= 0)
        throw Error(SourceLocation{}, "image size must be positive, not " +
                                          std::to_string(o.width) + "x" + std::to_string(o.height));
    DerivationDiagram d;
    d.width = o.width;
    d.height = o.height;
    d.background = o.background;
    const double side = std::min(d.width, d.height);
    const double margin = std::clamp(o.margin, 0.0, 0.45) * side;
    const double areaW = d.width - 2 * margin, areaH = d.height - 2 * margin;
    const double minH = std::max(16.0, side / 40), maxH = side / 10;

    // Which steps get a row: all, or when even the smallest cells cannot give every step
    // a row, the first ones, a gap row, and the last.
    const int total = static_cast<int>(steps.size());
    const int fitRows =
        std::max(3, static_cast<int>((areaH + (kRowPitch - 1) * minH) / (kRowPitch * minH)));
    std::vector<int> shown;  // step numbers, -1 for the gap row
    if (total <= fitRows) {
        for (int k = 0; k < total; ++k) shown.push_back(k);
    } else {
        for (int k = 0; k < fitRows - 2; ++k) shown.push_back(k);
        shown.push_back(-1);
        shown.push_back(total - 1);
    }

    // The widest label and parameter text decide the cell's width for all.
    std::size_t labelChars = 1, parameterChars = 0, longest = 1;
    for (int k : shown) {
        if (k < 0) continue;
        const ModuleString& s = steps[static_cast<std::size_t>(k)];
        longest = std::max(longest, s.size());
        const std::size_t n = std::min(s.size(), kMaxShownModules);
        for (std::size_t i = 0; i < n; ++i) {
            labelChars = std::max(labelChars, characters(symbols.name(s.symbol(i))));
            if (s.hasParameters())
                parameterChars = std::max(parameterChars, parameterText(s, i).size());
        }
    }
    const double aspect = std::max({kMinCellAspect, labelChars * kCharWidth * kLabelFont + 0.3,
                                    parameterChars * kCharWidth * kParameterFont + 0.2});
    const std::size_t stepDigits = std::to_string(total - 1).size();
    const double stepColumn = (stepDigits + 1) * kCharWidth * kParameterFont * 1.2 + 0.3;

    const double rowsH = kRowPitch * static_cast<double>(shown.size()) - (kRowPitch - 1);
    const double hByHeight = areaH / rowsH;
    const double hByWidth =
        areaW / (stepColumn + static_cast<double>(longest) * (aspect + kCellGap) - kCellGap);
    double h = std::min({hByHeight, hByWidth, maxH});
    if (h < minH) h = std::min(minH, hByHeight);  // rows get cut instead
    const double w = aspect * h, gap = kCellGap * h, pitch = w + gap;
    d.labelSize = kLabelFont * h;
    d.parameterSize = kParameterFont * h;

    // Cells that fit in a row, counting an ellipsis cell as wide as the text it holds.
    const double rowRoom = areaW - stepColumn * h;
    const std::size_t fitCells =
        std::max<std::size_t>(1, static_cast<std::size_t>((rowRoom + gap) / pitch + 1e-6));
    auto ellipsisSlots = [&](std::size_t hidden, const char* what) {
        const double textW =
            (characters(moreText(hidden, what)) + 1) * kCharWidth * d.parameterSize;
        return std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil((textW + gap) / pitch)));
    };

    // The block of rows is centred in the frame; rows start at its left edge.
    const std::size_t widest = std::min(longest, fitCells);
    const double blockW = stepColumn * h + static_cast<double>(widest) * pitch - gap;
    const double blockH = rowsH * h;
    const double left = (d.width - blockW) / 2, top = (d.height - blockH) / 2;
    const double cellsLeft = left + stepColumn * h;

    std::array<int, kMaxSymbols> colorOf;
    colorOf.fill(-1);
    std::size_t colorsUsed = 0;
    auto fillFor = [&](Symbol sym) {
        const std::string& name = symbols.name(sym);
        if (name == "[" || name == "]") return fromHex(kBracketColor);
        if (colorOf[sym] < 0) colorOf[sym] = static_cast<int>(colorsUsed++);
        return derivationCellColor(static_cast<std::size_t>(colorOf[sym]));
    };

    for (std::size_t r = 0; r < shown.size(); ++r) {
        DiagramRow row;
        const double y = top + static_cast<double>(r) * kRowPitch * h;
        row.labelX = cellsLeft - 0.25 * h;
        row.labelY = y + 0.5 * h;
        if (shown[r] < 0) {
            row.gap = true;
            row.step = shown[r - 1] + 1;
            const std::size_t hidden = static_cast<std::size_t>(shown[r + 1] - shown[r - 1] - 1);
            DiagramCell c;
            const std::size_t slots = ellipsisSlots(hidden, "steps");
            c.x = cellsLeft;
            c.y = y;
            c.width = static_cast<double>(slots) * pitch - gap;
            c.height = h;
            c.label = "\u22ee";  // vertical ellipsis
            c.parameters = moreText(hidden, "steps");
            c.fill = fromHex(kEllipsisColor);
            c.ellipsis = true;
            c.hidden = hidden;
            row.cells.push_back(std::move(c));
            d.rows.push_back(std::move(row));
            continue;
        }
        row.step = shown[r];
        const ModuleString& s = steps[static_cast<std::size_t>(row.step)];
        std::size_t drawn = s.size(), slots = 0;
        if (s.size() > fitCells) {
            // Leave room for the ellipsis cell; its text depends on what it hides.
            slots = ellipsisSlots(s.size(), "more");
            drawn = fitCells > slots ? fitCells - slots : 0;
        }
        for (std::size_t i = 0; i < drawn; ++i) {
            DiagramCell c;
            c.x = cellsLeft + static_cast<double>(i) * pitch;
            c.y = y;
            c.width = w;
            c.height = h;
            c.label = symbols.name(s.symbol(i));
            if (s.hasParameters()) c.parameters = parameterText(s, i);
            c.fill = fillFor(s.symbol(i));
            row.cells.push_back(std::move(c));
        }
        if (drawn < s.size()) {
            DiagramCell c;
            c.x = cellsLeft + static_cast<double>(drawn) * pitch;
            c.y = y;
            c.width = static_cast<double>(std::max<std::size_t>(slots, 1)) * pitch - gap;
            c.height = h;
            c.label = "\u2026";  // horizontal ellipsis
            c.hidden = s.size() - drawn;
            c.parameters = moreText(c.hidden, "more");
            c.fill = fromHex(kEllipsisColor);
            c.ellipsis = true;
            row.cells.push_back(std::move(c));
        }
        d.rows.push_back(std::move(row));
    }
    return d;
}

}  // namespace graftal
