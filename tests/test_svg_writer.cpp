// The SVG writer and what it stands on: Scene helpers, ImageTransform, the line width rule
// and the extension table. Scenes are built by hand so these tests need no parser.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "graftal/core/diagnostics.hpp"
#include "graftal/output/output.hpp"

namespace graftal {
namespace {

// ---- scenes ------------------------------------------------------------------------------

Scene unitSquare() {
    Scene s;
    const Vec3 p[] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    for (int i = 0; i < 4; ++i) s.segments.push_back({p[i], p[(i + 1) % 4]});
    return s;
}

Scene triangle(std::uint16_t color = 1) {
    Scene s;
    const std::vector<Vec3> v = {{0, 0, 0}, {2, 0, 0}, {1, 1, 0}};
    s.addPolygon(v, color);
    return s;
}

Scene verticalLine() {
    Scene s;
    s.segments.push_back({{3, -1, 0}, {3, 4, 0}});
    return s;
}

// A Koch curve of 4^level segments, each starting where the previous one ended.
Scene kochCurve(int level) {
    Scene s;
    std::vector<Vec3> pts = {{0, 0, 0}, {1, 0, 0}};
    for (int l = 0; l < level; ++l) {
        std::vector<Vec3> next;
        for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
            const Vec3 a = pts[i], b = pts[i + 1];
            const double dx = (b.x - a.x) / 3, dy = (b.y - a.y) / 3;
            const Vec3 p1{a.x + dx, a.y + dy, 0}, p3{a.x + 2 * dx, a.y + 2 * dy, 0};
            const double c = 0.5, sn = std::sqrt(3.0) / 2;
            const Vec3 p2{p1.x + dx * c - dy * sn, p1.y + dx * sn + dy * c, 0};
            next.insert(next.end(), {a, p1, p2, p3});
        }
        next.push_back(pts.back());
        pts = std::move(next);
    }
    for (std::size_t i = 0; i + 1 < pts.size(); ++i) s.segments.push_back({pts[i], pts[i + 1]});
    return s;
}

std::string svgOf(const Scene& scene, const RenderOptions& o = {}) {
    std::ostringstream out;
    writeSvg(scene, o, out);
    return out.str();
}

// ---- a tiny XML checker ------------------------------------------------------------------

struct XmlElement {
    std::string name;
    std::map<std::string, std::string> attrs;
    int depth = 0;
};

struct XmlDoc {
    std::string error;  // empty when well-formed
    std::vector<XmlElement> elements;

    std::vector<const XmlElement*> all(const std::string& name) const {
        std::vector<const XmlElement*> r;
        for (const auto& e : elements)
            if (e.name == name) r.push_back(&e);
        return r;
    }
};

bool isNameStart(char c) {
    return std::isalpha(static_cast<unsigned char>(c)) || c == '_' || c == ':';
}
bool isNameChar(char c) {
    return isNameStart(c) || std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '.';
}

// Checks what matters for our output: a prolog, exactly one root element, balanced and
// properly nested tags, quoted attributes without duplicates, no stray '<' or bare '&'.
XmlDoc parseXml(const std::string& t) {
    XmlDoc doc;
    std::size_t i = 0;
    std::vector<std::string> stack;
    int roots = 0;
    auto fail = [&](const std::string& why) {
        doc.error = why + " at offset " + std::to_string(i);
        return doc;
    };
    auto skipSpace = [&] {
        while (i < t.size() && std::isspace(static_cast<unsigned char>(t[i]))) ++i;
    };
    auto name = [&] {
        std::size_t b = i;
        if (i < t.size() && isNameStart(t[i]))
            while (i < t.size() && isNameChar(t[i])) ++i;
        return t.substr(b, i - b);
    };
    if (t.compare(0, 5, "<?xml") == 0) {
        i = t.find("?>");
        if (i == std::string::npos) return fail("unterminated prolog");
        i += 2;
    }
    while (true) {
        const std::size_t textStart = i;
        while (i < t.size() && t[i] != '<') {
            if (t[i] == '&' && t.find(';', i) == std::string::npos) return fail("bare &");
            ++i;
        }
        const std::string text = t.substr(textStart, i - textStart);
        if (stack.empty())
            for (char c : text)
                if (!std::isspace(static_cast<unsigned char>(c)))
                    return fail("text outside the root element");
        if (i >= t.size()) break;
        if (t.compare(i, 4, "<!--") == 0) {
            i = t.find("-->", i);
            if (i == std::string::npos) return fail("unterminated comment");
            i += 3;
            continue;
        }
        ++i;  // '<'
        if (i < t.size() && t[i] == '/') {
            ++i;
            const std::string n = name();
            skipSpace();
            if (i >= t.size() || t[i] != '>') return fail("bad end tag");
            ++i;
            if (stack.empty() || stack.back() != n) return fail("unbalanced </" + n + ">");
            stack.pop_back();
            continue;
        }
        XmlElement e;
        e.name = name();
        if (e.name.empty()) return fail("bad tag name");
        e.depth = static_cast<int>(stack.size());
        if (e.depth == 0 && ++roots > 1) return fail("second root element");
        bool selfClosing = false;
        while (true) {
            const std::size_t before = i;
            skipSpace();
            if (i >= t.size()) return fail("unterminated tag");
            if (t[i] == '>') {
                ++i;
                break;
            }
            if (t.compare(i, 2, "/>") == 0) {
                i += 2;
                selfClosing = true;
                break;
            }
            if (i == before) return fail("attributes must be separated by space");
            const std::string an = name();
            if (an.empty()) return fail("bad attribute name");
            skipSpace();
            if (i >= t.size() || t[i] != '=') return fail("attribute without =");
            ++i;
            skipSpace();
            if (i >= t.size() || (t[i] != '"' && t[i] != '\'')) return fail("unquoted attribute");
            const char q = t[i++];
            const std::size_t end = t.find(q, i);
            if (end == std::string::npos) return fail("unterminated attribute value");
            const std::string value = t.substr(i, end - i);
            if (value.find('<') != std::string::npos) return fail("'<' in attribute value");
            if (!e.attrs.emplace(an, value).second) return fail("duplicate attribute " + an);
            i = end + 1;
        }
        if (!selfClosing) stack.push_back(e.name);
        doc.elements.push_back(std::move(e));
    }
    if (!stack.empty()) return fail("unclosed <" + stack.back() + ">");
    if (roots != 1) return fail("no root element");
    return doc;
}

// Absolute points of an SVG path's data (M, L, H, V, Z and their relative forms).
struct PathData {
    std::vector<std::pair<double, double>> points;
    int moves = 0;
};

PathData parsePathData(const std::string& d) {
    PathData r;
    double x = 0, y = 0, startX = 0, startY = 0;
    char cmd = 0;
    std::size_t i = 0;
    auto skip = [&] {
        while (i < d.size() && (std::isspace(static_cast<unsigned char>(d[i])) || d[i] == ',')) ++i;
    };
    auto number = [&] {
        skip();
        std::size_t used = 0;
        const double v = std::stod(d.substr(i, 32), &used);
        i += used;
        return v;
    };
    for (skip(); i < d.size(); skip()) {
        if (std::isalpha(static_cast<unsigned char>(d[i]))) cmd = d[i++];
        const bool relative = std::islower(static_cast<unsigned char>(cmd));
        const char upper = static_cast<char>(std::toupper(static_cast<unsigned char>(cmd)));
        const double baseX = relative ? x : 0, baseY = relative ? y : 0;
        if (upper == 'Z') {
            x = startX, y = startY;
            cmd = 0;  // a number right after Z is an error
            continue;
        } else if (upper == 'M' || upper == 'L') {
            x = baseX + number();
            y = baseY + number();
        } else if (upper == 'H') {
            x = baseX + number();
        } else if (upper == 'V') {
            y = baseY + number();
        } else {
            ADD_FAILURE() << "unexpected path data at " << i << ": " << d.substr(i, 20);
            return r;
        }
        if (upper == 'M') {
            startX = x, startY = y;
            ++r.moves;
            cmd = relative ? 'l' : 'L';  // pairs after a move are line-tos
        }
        r.points.emplace_back(x, y);
    }
    return r;
}

std::vector<const XmlElement*> strokedPaths(const XmlDoc& doc) {
    std::vector<const XmlElement*> r;
    for (const auto* e : doc.all("path"))
        if (e->attrs.count("stroke")) r.push_back(e);
    return r;
}

std::vector<const XmlElement*> filledPaths(const XmlDoc& doc) {
    std::vector<const XmlElement*> r;
    for (const auto* e : doc.all("path"))
        if (e->attrs.count("fill") && e->attrs.at("fill") != "none") r.push_back(e);
    return r;
}

// ---- Scene -------------------------------------------------------------------------------

TEST(SceneGeometry, Vec3PrintsAsTuple) {
    std::ostringstream os;
    os << Vec3{1, 2, 0} << ' ' << Vec3{-0.0, 0.5, -3};
    EXPECT_EQ(os.str(), "(1, 2, 0) (0, 0.5, -3)");
}

TEST(SceneGeometry, EmptyBoundsPrintAsEmpty) {
    std::ostringstream os;
    os << Bounds{};
    EXPECT_EQ(os.str(), "empty");
    EXPECT_TRUE(Scene{}.bounds().empty());
}

TEST(SceneGeometry, BoundsCoverSegmentsAndPolygons) {
    Scene s = unitSquare();
    const std::vector<Vec3> v = {{-1, 0.5, 2}, {0.5, 3, 0}, {0, 0, -1}};
    s.addPolygon(v, 2);
    const Bounds b = s.bounds();
    EXPECT_EQ(b.min, (Vec3{-1, 0, -1}));
    EXPECT_EQ(b.max, (Vec3{1, 3, 2}));
    std::ostringstream os;
    os << b;
    EXPECT_EQ(os.str(), "(-1, 0, -1) .. (1, 3, 2)");
}

TEST(SceneGeometry, BoundsIgnoreNonFinitePoints) {
    Scene s = unitSquare();
    const double inf = std::numeric_limits<double>::infinity();
    s.segments.push_back({{0, 0, 0}, {inf, std::nan(""), 0}});
    const Bounds b = s.bounds();
    EXPECT_EQ(b.max, (Vec3{1, 1, 0}));
}

TEST(SceneGeometry, ExtendByEmptyBoundsChangesNothing) {
    Bounds b;
    b.extend(Vec3{1, 2, 3});
    b.extend(Bounds{});
    EXPECT_EQ(b.min, (Vec3{1, 2, 3}));
    EXPECT_EQ(b.max, (Vec3{1, 2, 3}));
}

TEST(SceneGeometry, AddPolygonAppendsVerticesAndColour) {
    Scene s = triangle(3);
    const std::vector<Vec3> quad = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    s.addPolygon(quad, 5);
    ASSERT_EQ(s.polygonCount(), 2u);
    EXPECT_EQ(s.polygon(0).size(), 3u);
    EXPECT_EQ(s.polygon(1).size(), 4u);
    EXPECT_EQ(s.polygon(1)[2], (Vec3{1, 1, 0}));
    EXPECT_EQ(s.polygonColor[0], 3);
    EXPECT_EQ(s.polygonColor[1], 5);
}

TEST(SceneGeometry, ColourIndexWrapsAroundPalette) {
    Scene s;
    s.palette = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    EXPECT_EQ(s.colorOf(1), (Rgb{0, 1, 0}));
    EXPECT_EQ(s.colorOf(4), (Rgb{0, 1, 0}));
    s.palette.clear();
    EXPECT_EQ(s.colorOf(7), (Rgb{0, 0, 0}));
}

TEST(SceneGeometry, DefaultPaletteIsInkThenLeafGreens) {
    const auto p = Scene::defaultPalette();
    ASSERT_GE(p.size(), 16u);
    EXPECT_LT(p[0].r + p[0].g + p[0].b, 0.6f);                      // dark ink
    EXPECT_GT(p[1].g, std::max(p[1].r, p[1].b));                    // leaf green
    EXPECT_GT(p[2].g, std::max(p[2].r, p[2].b));                    // another green...
    EXPECT_GT(p[2].r + p[2].g + p[2].b, p[1].r + p[1].g + p[1].b);  // ...and lighter
    EXPECT_GT(p[3].r, p[3].g);                                      // a flower colour, not green
}

TEST(SceneGeometry, PrintSummarisesCountsAndBounds) {
    Scene s = unitSquare();
    const std::vector<Vec3> v = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
    s.addPolygon(v, 1);
    std::ostringstream os;
    os << s;
    EXPECT_NE(os.str().find("4 segments"), std::string::npos) << os.str();
    EXPECT_NE(os.str().find("1 polygon"), std::string::npos) << os.str();
    EXPECT_NE(os.str().find("(0, 0, 0) .. (1, 1, 0)"), std::string::npos) << os.str();
}

// ---- ImageTransform ----------------------------------------------------------------------

TEST(ImageTransformFit, SquareFillsSmallerSideAndIsCentred) {
    RenderOptions o;
    o.width = 400;
    o.height = 200;
    o.margin = 0.1;  // 20 px on every side
    const ImageTransform t = ImageTransform::fit(unitSquare().bounds(), o);
    EXPECT_DOUBLE_EQ(t.scale, 160);
    EXPECT_DOUBLE_EQ(t.x({0, 0, 0}), 120);
    EXPECT_DOUBLE_EQ(t.x({1, 0, 0}), 280);
    EXPECT_DOUBLE_EQ(t.y({0, 1, 0}), 20);  // model top is image top: y is flipped
    EXPECT_DOUBLE_EQ(t.y({0, 0, 0}), 180);
}

TEST(ImageTransformFit, WideBoundsAreLimitedByWidth) {
    RenderOptions o;
    o.width = 200;
    o.height = 400;
    o.margin = 0;
    Bounds b;
    b.extend(Vec3{-10, 0, 0});
    b.extend(Vec3{10, 1, 0});
    const ImageTransform t = ImageTransform::fit(b, o);
    EXPECT_DOUBLE_EQ(t.scale, 10);
    EXPECT_DOUBLE_EQ(t.x({-10, 0, 0}), 0);
    EXPECT_DOUBLE_EQ(t.y({0, 0.5, 0}), 200);
}

TEST(ImageTransformFit, VerticalLineIsFiniteCentredAndScaledByHeight) {
    RenderOptions o;  // 800 x 800, margin 40 px
    const ImageTransform t = ImageTransform::fit(verticalLine().bounds(), o);
    ASSERT_TRUE(std::isfinite(t.scale));
    ASSERT_TRUE(std::isfinite(t.offsetX));
    ASSERT_TRUE(std::isfinite(t.offsetY));
    EXPECT_DOUBLE_EQ(t.x({3, 0, 0}), 400);
    EXPECT_DOUBLE_EQ(t.y({3, 4, 0}), 40);
    EXPECT_DOUBLE_EQ(t.y({3, -1, 0}), 760);
}

TEST(ImageTransformFit, HorizontalLineIsCentredAndScaledByWidth) {
    RenderOptions o;
    o.width = 300;
    o.height = 100;
    o.margin = 0;
    Bounds b;
    b.extend(Vec3{0, 7, 0});
    b.extend(Vec3{3, 7, 0});
    const ImageTransform t = ImageTransform::fit(b, o);
    EXPECT_DOUBLE_EQ(t.x({0, 7, 0}), 0);
    EXPECT_DOUBLE_EQ(t.x({3, 7, 0}), 300);
    EXPECT_DOUBLE_EQ(t.y({0, 7, 0}), 50);
}

TEST(ImageTransformFit, SinglePointLandsInTheCentre) {
    RenderOptions o;
    o.width = 640;
    o.height = 480;
    Bounds b;
    b.extend(Vec3{5, -2, 1});
    const ImageTransform t = ImageTransform::fit(b, o);
    ASSERT_TRUE(std::isfinite(t.scale));
    EXPECT_GT(t.scale, 0);
    EXPECT_DOUBLE_EQ(t.x({5, -2, 1}), 320);
    EXPECT_DOUBLE_EQ(t.y({5, -2, 1}), 240);
}

TEST(ImageTransformFit, EmptyBoundsPutOriginInTheCentre) {
    RenderOptions o;
    const ImageTransform t = ImageTransform::fit(Bounds{}, o);
    EXPECT_DOUBLE_EQ(t.x({0, 0, 0}), 400);
    EXPECT_DOUBLE_EQ(t.y({0, 0, 0}), 400);
}

TEST(ImageTransformFit, TinyExtentsStayFinite) {
    RenderOptions o;
    Bounds b;
    b.extend(Vec3{0, 0, 0});
    b.extend(Vec3{1e-320, 1e-320, 0});
    const ImageTransform t = ImageTransform::fit(b, o);
    EXPECT_TRUE(std::isfinite(t.scale));
    EXPECT_TRUE(std::isfinite(t.offsetX));
    EXPECT_TRUE(std::isfinite(t.offsetY));
}

// ---- line width and formats --------------------------------------------------------------

TEST(DefaultLineWidth, ExplicitWidthWins) {
    RenderOptions o;
    o.lineWidth = 3.5;
    EXPECT_DOUBLE_EQ(defaultLineWidth(unitSquare(), o), 3.5);
}

TEST(DefaultLineWidth, GrowsWithImageWithinLimits) {
    RenderOptions small, medium, huge;
    small.width = small.height = 100;
    medium.width = medium.height = 800;
    huge.width = huge.height = 8000;
    const Scene s = unitSquare();
    const double a = defaultLineWidth(s, small), b = defaultLineWidth(s, medium),
                 c = defaultLineWidth(s, huge);
    EXPECT_GE(a, 0.5);
    EXPECT_LE(a, b);
    EXPECT_LE(b, c);
    EXPECT_LE(c, 2.0);
}

TEST(DefaultLineWidth, DenseCurvesGetThinnerLines) {
    RenderOptions o;
    // A square filled with 400 horizontal lines 1.8 px apart: at the normal width they
    // would merge into a solid block.
    Scene dense;
    for (int i = 0; i <= 400; ++i) dense.segments.push_back({{0, i / 400.0, 0}, {1, i / 400.0, 0}});
    const double sparse = defaultLineWidth(unitSquare(), o);
    const double thin = defaultLineWidth(dense, o);
    EXPECT_LT(thin, sparse);
    EXPECT_GT(thin, 0.2);
}

TEST(ImageFormatFor, RecognisesExtensionsIgnoringCase) {
    EXPECT_EQ(imageFormatFor("a.svg"), ImageFormat::Svg);
    EXPECT_EQ(imageFormatFor("dir.x/b.PNG"), ImageFormat::Png);
    EXPECT_EQ(imageFormatFor("c.Pdf"), ImageFormat::Pdf);
}

TEST(ImageFormatFor, UnknownOrMissingExtensionIsNullopt) {
    EXPECT_FALSE(imageFormatFor("x.bmp"));
    EXPECT_FALSE(imageFormatFor("svg"));
    EXPECT_FALSE(imageFormatFor("archive.png.gz"));
}

// ---- SVG ---------------------------------------------------------------------------------

TEST(SvgWriter, EmptySceneIsWellFormedSvg) {
    const XmlDoc doc = parseXml(svgOf(Scene{}));
    ASSERT_EQ(doc.error, "");
    ASSERT_FALSE(doc.elements.empty());
    EXPECT_EQ(doc.elements[0].name, "svg");
    EXPECT_TRUE(doc.all("path").empty());
}

TEST(SvgWriter, SquareAndTriangleDocumentIsWellFormedXml) {
    Scene s = unitSquare();
    const std::vector<Vec3> v = {{0.2, 0.2, 0}, {0.8, 0.2, 0}, {0.5, 0.8, 0}};
    s.addPolygon(v, 1);
    const std::string text = svgOf(s);
    const XmlDoc doc = parseXml(text);
    ASSERT_EQ(doc.error, "") << text;
    EXPECT_EQ(doc.elements[0].name, "svg");
    EXPECT_EQ(doc.elements[0].attrs.at("xmlns"), "http://www.w3.org/2000/svg");
    EXPECT_EQ(doc.elements[0].attrs.at("version"), "1.1");
    EXPECT_EQ(text.rfind("<?xml", 0), 0u);
}

TEST(SvgWriter, SizeAndViewBoxAreInPixels) {
    RenderOptions o;
    o.width = 640;
    o.height = 480;
    const XmlDoc doc = parseXml(svgOf(unitSquare(), o));
    ASSERT_EQ(doc.error, "");
    const auto& svg = doc.elements[0].attrs;
    EXPECT_EQ(svg.at("width"), "640");
    EXPECT_EQ(svg.at("height"), "480");
    EXPECT_EQ(svg.at("viewBox"), "0 0 640 480");
}

TEST(SvgWriter, BackgroundRectCoversTheImage) {
    RenderOptions o;
    o.width = 300;
    o.height = 200;
    o.background = {1, 0.5f, 0};
    const XmlDoc doc = parseXml(svgOf(unitSquare(), o));
    ASSERT_EQ(doc.error, "");
    const auto rects = doc.all("rect");
    ASSERT_EQ(rects.size(), 1u);
    EXPECT_EQ(rects[0]->attrs.at("width"), "300");
    EXPECT_EQ(rects[0]->attrs.at("height"), "200");
    EXPECT_EQ(rects[0]->attrs.at("fill"), "#ff8000");
    // The background is the first thing drawn.
    EXPECT_EQ(doc.elements[1].name, "rect");
}

TEST(SvgWriter, PathCoordinatesLieInsideTheMargins) {
    RenderOptions o;
    o.width = 640;
    o.height = 480;
    o.margin = 0.05;  // 24 px
    Scene s = unitSquare();
    const std::vector<Vec3> v = {{-0.2, 0, 0}, {1.2, 0.2, 0}, {0.5, 1.3, 0}};
    s.addPolygon(v, 2);
    const XmlDoc doc = parseXml(svgOf(s, o));
    ASSERT_EQ(doc.error, "");
    const double m = 24, tol = 0.01;
    double minX = 1e9, maxX = -1e9, minY = 1e9, maxY = -1e9;
    int count = 0;
    for (const auto* p : doc.all("path")) {
        for (auto [x, y] : parsePathData(p->attrs.at("d")).points) {
            EXPECT_GE(x, m - tol);
            EXPECT_LE(x, 640 - m + tol);
            EXPECT_GE(y, m - tol);
            EXPECT_LE(y, 480 - m + tol);
            minX = std::min(minX, x), maxX = std::max(maxX, x);
            minY = std::min(minY, y), maxY = std::max(maxY, y);
            ++count;
        }
    }
    EXPECT_GE(count, 7);
    // Height is the limiting side, so the picture touches the top and bottom margins and
    // is centred horizontally.
    EXPECT_NEAR(minY, m, tol);
    EXPECT_NEAR(maxY, 480 - m, tol);
    EXPECT_NEAR((minX + maxX) / 2, 320, tol);
}

TEST(SvgWriter, UnitSquareIsOneClosedPolyline) {
    RenderOptions o;
    o.width = o.height = 200;
    o.margin = 0.1;  // the square spans 20..180
    const XmlDoc doc = parseXml(svgOf(unitSquare(), o));
    ASSERT_EQ(doc.error, "");
    const auto paths = strokedPaths(doc);
    ASSERT_EQ(paths.size(), 1u);
    const PathData d = parsePathData(paths[0]->attrs.at("d"));
    EXPECT_EQ(d.moves, 1);
    ASSERT_EQ(d.points.size(), 5u);
    const std::vector<std::pair<double, double>> expected = {
        {20, 180}, {180, 180}, {180, 20}, {20, 20}, {20, 180}};
    for (std::size_t i = 0; i < expected.size(); ++i) {
        EXPECT_NEAR(d.points[i].first, expected[i].first, 0.01) << i;
        EXPECT_NEAR(d.points[i].second, expected[i].second, 0.01) << i;
    }
}

TEST(SvgWriter, ConnectedKochCurveIsOnePathWithOneMove) {
    const Scene s = kochCurve(6);  // 4096 segments
    ASSERT_EQ(s.segments.size(), 4096u);
    const std::string text = svgOf(s);
    const XmlDoc doc = parseXml(text);
    ASSERT_EQ(doc.error, "");
    const auto paths = strokedPaths(doc);
    ASSERT_EQ(paths.size(), 1u);
    const PathData d = parsePathData(paths[0]->attrs.at("d"));
    EXPECT_EQ(d.moves, 1);
    EXPECT_EQ(d.points.size(), 4097u);
    EXPECT_TRUE(doc.all("line").empty());
    EXPECT_LT(text.size(), 4096u * 16) << "about a dozen bytes per segment at most";
}

TEST(SvgWriter, VeryLongCurveIsSplitIntoPathsThatContinueEachOther) {
    // XML parsers such as libxml2 choke on megabyte attributes, so a huge curve is cut into
    // several paths; each must pick up exactly where the previous one stopped.
    Scene s;
    for (int i = 0; i < 30000; ++i)
        s.segments.push_back({{i * 1.0, (i % 2) * 1.0, 0}, {i + 1.0, ((i + 1) % 2) * 1.0, 0}});
    const XmlDoc doc = parseXml(svgOf(s));
    ASSERT_EQ(doc.error, "");
    const auto paths = strokedPaths(doc);
    ASSERT_GT(paths.size(), 1u);
    std::size_t points = 0;
    std::pair<double, double> previousEnd{};
    for (std::size_t k = 0; k < paths.size(); ++k) {
        const std::string& d = paths[k]->attrs.at("d");
        EXPECT_LT(d.size(), 200'000u);
        const PathData data = parsePathData(d);
        EXPECT_EQ(data.moves, 1);
        if (k > 0) {
            EXPECT_NEAR(data.points.front().first, previousEnd.first, 1e-9);
            EXPECT_NEAR(data.points.front().second, previousEnd.second, 1e-9);
        }
        previousEnd = data.points.back();
        points += data.points.size() - 1;  // segments in this path
    }
    EXPECT_EQ(points, 30000u);
}

TEST(SvgWriter, DisconnectedSegmentsStartNewSubpaths) {
    Scene s;
    s.segments.push_back({{0, 0, 0}, {1, 0, 0}});
    s.segments.push_back({{0, 1, 0}, {1, 1, 0}});
    s.segments.push_back({{1, 1, 0}, {1, 2, 0}});
    const XmlDoc doc = parseXml(svgOf(s));
    ASSERT_EQ(doc.error, "");
    const auto paths = strokedPaths(doc);
    ASSERT_EQ(paths.size(), 1u);
    const PathData d = parsePathData(paths[0]->attrs.at("d"));
    EXPECT_EQ(d.moves, 2);
    EXPECT_EQ(d.points.size(), 5u);
}

TEST(SvgWriter, ColourChangeStartsNewPathInSceneOrder) {
    Scene s;
    s.segments.push_back({{0, 0, 0}, {1, 0, 0}, 1, 0});
    s.segments.push_back({{1, 0, 0}, {1, 1, 0}, 1, 3});
    s.segments.push_back({{1, 1, 0}, {0, 1, 0}, 1, 0});
    const XmlDoc doc = parseXml(svgOf(s));
    ASSERT_EQ(doc.error, "");
    const auto paths = strokedPaths(doc);
    ASSERT_EQ(paths.size(), 3u);
    EXPECT_EQ(paths[0]->attrs.at("stroke"), "#1f2a1f");
    EXPECT_NE(paths[1]->attrs.at("stroke"), "#1f2a1f");
    EXPECT_EQ(paths[2]->attrs.at("stroke"), "#1f2a1f");
}

TEST(SvgWriter, StrokeWidthIsLineWidthTimesSegmentWidth) {
    RenderOptions o;
    o.lineWidth = 2;
    Scene s;
    s.segments.push_back({{0, 0, 0}, {1, 0, 0}, 3});
    s.segments.push_back({{1, 0, 0}, {1, 1, 0}, 0.5f});
    const XmlDoc doc = parseXml(svgOf(s, o));
    ASSERT_EQ(doc.error, "");
    const auto paths = strokedPaths(doc);
    ASSERT_EQ(paths.size(), 2u);
    // Same colour, so the writer may order by width; both widths must be there.
    std::vector<std::string> widths = {paths[0]->attrs.at("stroke-width"),
                                       paths[1]->attrs.at("stroke-width")};
    std::sort(widths.begin(), widths.end());
    EXPECT_EQ(widths, (std::vector<std::string>{"1", "6"}));
}

TEST(SvgWriter, LinesHaveRoundCapsAndJoinsAndNoFill) {
    const std::string text = svgOf(unitSquare());
    const XmlDoc doc = parseXml(text);
    ASSERT_EQ(doc.error, "");
    bool found = false;
    for (const auto* g : doc.all("g")) {
        if (g->attrs.count("stroke-linecap")) {
            found = true;
            EXPECT_EQ(g->attrs.at("stroke-linecap"), "round");
            EXPECT_EQ(g->attrs.at("stroke-linejoin"), "round");
            EXPECT_EQ(g->attrs.at("fill"), "none");
        }
    }
    EXPECT_TRUE(found) << text;
}

TEST(SvgWriter, PolygonIsFilledWithItsPaletteColour) {
    const XmlDoc doc = parseXml(svgOf(triangle(1)));
    ASSERT_EQ(doc.error, "");
    const auto fills = filledPaths(doc);
    ASSERT_EQ(fills.size(), 1u);
    EXPECT_EQ(fills[0]->attrs.at("fill"), "#3a7d2c");
    EXPECT_EQ(parsePathData(fills[0]->attrs.at("d")).points.size(), 3u);
    EXPECT_TRUE(strokedPaths(doc).empty());
}

TEST(SvgWriter, ColourOverridesReplaceThePalette) {
    Scene s = triangle(1);
    s.segments.push_back({{0, 0, 0}, {1, 1, 0}, 1, 4});
    RenderOptions o;
    o.lineColor = Rgb{1, 0, 0};
    o.fillColor = Rgb{0, 0, 1};
    const XmlDoc doc = parseXml(svgOf(s, o));
    ASSERT_EQ(doc.error, "");
    ASSERT_EQ(filledPaths(doc).size(), 1u);
    ASSERT_EQ(strokedPaths(doc).size(), 1u);
    EXPECT_EQ(filledPaths(doc)[0]->attrs.at("fill"), "#0000ff");
    EXPECT_EQ(strokedPaths(doc)[0]->attrs.at("stroke"), "#ff0000");
}

TEST(SvgWriter, PolygonsAreDrawnBeforeSegments) {
    Scene s = unitSquare();
    const std::vector<Vec3> v = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
    s.addPolygon(v, 1);
    const XmlDoc doc = parseXml(svgOf(s));
    ASSERT_EQ(doc.error, "");
    int lastFill = -1, firstStroke = -1;
    for (int i = 0; i < static_cast<int>(doc.elements.size()); ++i) {
        const auto& e = doc.elements[i];
        if (e.name != "path") continue;
        if (e.attrs.count("stroke") && firstStroke < 0) firstStroke = i;
        if (!e.attrs.count("stroke")) lastFill = i;
    }
    ASSERT_GE(lastFill, 0);
    ASSERT_GE(firstStroke, 0);
    EXPECT_LT(lastFill, firstStroke);
}

TEST(SvgWriter, VerticalLineIsCentredAndSpansTheHeight) {
    RenderOptions o;
    o.width = 400;
    o.height = 300;
    o.margin = 0.1;  // 30 px
    const XmlDoc doc = parseXml(svgOf(verticalLine(), o));
    ASSERT_EQ(doc.error, "");
    const auto paths = strokedPaths(doc);
    ASSERT_EQ(paths.size(), 1u);
    const PathData d = parsePathData(paths[0]->attrs.at("d"));
    ASSERT_EQ(d.points.size(), 2u);
    EXPECT_NEAR(d.points[0].first, 200, 0.01);
    EXPECT_NEAR(d.points[1].first, 200, 0.01);
    EXPECT_NEAR(d.points[0].second, 270, 0.01);
    EXPECT_NEAR(d.points[1].second, 30, 0.01);
}

TEST(SvgWriter, NumbersHaveAtMostTwoDecimals) {
    const std::string text = svgOf(kochCurve(3));
    const XmlDoc doc = parseXml(text);
    ASSERT_EQ(doc.error, "");
    const std::string d = strokedPaths(doc).at(0)->attrs.at("d");
    int decimals = -1;
    for (char c : d) {
        if (c == '.') {
            decimals = 0;
        } else if (std::isdigit(static_cast<unsigned char>(c)) && decimals >= 0) {
            EXPECT_LT(++decimals, 3) << d;
        } else {
            decimals = -1;
        }
    }
    EXPECT_EQ(d.find('e'), std::string::npos) << "no exponent notation";
}

TEST(SvgWriter, NonFiniteSegmentsAreSkipped) {
    Scene s = unitSquare();
    const double inf = std::numeric_limits<double>::infinity();
    s.segments.push_back({{0, 0, 0}, {inf, std::nan(""), 0}});
    const std::string text = svgOf(s);
    const XmlDoc doc = parseXml(text);
    ASSERT_EQ(doc.error, "");
    EXPECT_EQ(text.find("nan"), std::string::npos);
    EXPECT_EQ(text.find("inf"), std::string::npos);
    EXPECT_EQ(parsePathData(strokedPaths(doc).at(0)->attrs.at("d")).points.size(), 5u);
}

TEST(SvgWriter, NonPositiveSizeThrows) {
    RenderOptions o;
    o.width = 0;
    std::ostringstream out;
    EXPECT_THROW(writeSvg(unitSquare(), o, out), Error);
}

TEST(SvgWriter, WriteImageWritesSvgFileAndNoTemporary) {
    namespace fs = std::filesystem;
    const fs::path dir =
        fs::temp_directory_path() / ("graftal-svg-test-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path file = dir / "square.svg";
    writeImage(unitSquare(), RenderOptions{}, file);
    std::ifstream in(file);
    std::stringstream buf;
    buf << in.rdbuf();
    EXPECT_EQ(parseXml(buf.str()).error, "");
    int entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++entries;
    EXPECT_EQ(entries, 1);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace graftal
