// The map as text: `graftal derive` prints it, readMapText reads it back.
//
//   map: step 2, 7 vertices, 9 edges, 3 cells
//   cell 1: a0 ~x8 c3 ...
//   outside: ~a1 ...
//
// Each cell is the cycle of its walls counter-clockwise; `a12` is edge 12 labelled a,
// traversed along its direction, `~a12` against it. The outside goes round the layer
// clockwise (the outside is on the left of its walk, as every cell is on the left of its).
#include <sstream>

#include "graftal/maps/plane_map.hpp"

namespace graftal {

void writeMapText(const PlaneMap& m, std::ostream& out) {
    out << "map: step " << m.step << ", " << m.vertexCount() << " vertices, " << m.edgeCount()
        << " edges, " << m.cellCount() << " cells\n";
    std::string line;
    for (std::uint32_t r = 1; r <= m.regionCount(); ++r) {
        const std::uint32_t region = r == m.regionCount() ? kOutside : r;
        line = region == kOutside ? "outside:" : "cell " + std::to_string(region) + ":";
        for (std::uint32_t h : m.boundary(region)) {
            line += ' ';
            if (!PlaneMap::forward(h)) line += '~';
            line += m.label[PlaneMap::edgeOf(h)];
            line += std::to_string(PlaneMap::edgeOf(h));
        }
        line += '\n';
        out << line;
    }
}

std::vector<MapTextRegion> readMapText(std::istream& in) {
    std::vector<MapTextRegion> regions;
    std::string line;
    int number = 0;
    auto fail = [&](const std::string& what) {
        throw Error(SourceLocation{"map text", number, 1}, what);
    };
    while (std::getline(in, line)) {
        ++number;
        if (line.empty() || line.rfind("map:", 0) == 0) continue;
        const std::size_t colon = line.find(':');
        if (colon == std::string::npos) fail("expected 'cell N:' or 'outside:'");
        MapTextRegion r;
        const std::string head = line.substr(0, colon);
        if (head == "outside")
            r.outside = true;
        else if (head.rfind("cell ", 0) != 0)
            fail("expected 'cell N:' or 'outside:', got '" + head + "'");
        std::istringstream words(line.substr(colon + 1));
        std::string w;
        while (words >> w) {
            std::size_t i = 0;
            bool along = true;
            if (w[i] == '~') along = false, ++i;
            if (i + 1 >= w.size()) fail("expected an edge such as a12 or ~a12, got '" + w + "'");
            const char label = w[i++];
            std::uint32_t id = 0;
            for (; i < w.size(); ++i) {
                if (w[i] < '0' || w[i] > '9') fail("expected an edge number in '" + w + "'");
                id = id * 10 + static_cast<std::uint32_t>(w[i] - '0');
            }
            r.edges.push_back(id);
            r.labels.push_back(label);
            r.along.push_back(along);
        }
        if (r.edges.empty()) fail("a region without edges");
        regions.push_back(std::move(r));
    }
    return regions;
}

}  // namespace graftal
