// cpfg's .s surface files and the library of named surfaces. The reader follows cpfg's own
// (patch.c, which reads with fscanf): the same fields in the same order, any whitespace
// between them, and the same neighbour checks; docs/surfaces.md describes the format.
#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <system_error>

#include "graftal/core/file_reading.hpp"
#include "graftal/core/number_chars.hpp"
#include "graftal/geometry/surface.hpp"

#include <dlfcn.h>

// Where the built-in surfaces lie relative to the folder of the binary holding this code
// (the shared library, or a program linked with the static one): set by CMake from the
// install layout, "../share/graftal/surfaces" for the usual lib/ and share/.
#ifndef GRAFTAL_SURFACES_FROM_LIBDIR
#define GRAFTAL_SURFACES_FROM_LIBDIR "../share/graftal/surfaces"
#endif
#ifndef GRAFTAL_SURFACES_FROM_BINDIR
#define GRAFTAL_SURFACES_FROM_BINDIR "../share/graftal/surfaces"
#endif

namespace graftal {

namespace {

namespace fs = std::filesystem;

constexpr int kNeighbourCount = 8;
// In cpfg's order; the opposite of direction n is 7 - n (AL and BR, A and B, ...).
constexpr const char* kNeighbourLabels[kNeighbourCount] = {"AL", "A",  "AR", "L",
                                                           "R",  "BL", "B",  "BR"};
constexpr const char* kNeighbourNames[kNeighbourCount] = {
    "above-left", "above", "above-right", "left", "right", "below-left", "below", "below-right"};

bool isSpace(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}

char upper(char c) {
    return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c;
}

Vec3 scaled(const Vec3& v, double k) {
    return {v.x * k, v.y * k, v.z * k};
}

struct PatchNeighbours {
    std::string names[kNeighbourCount];
    std::size_t offsets[kNeighbourCount] = {};
};

// A cursor over the text that reads the way fscanf does (whitespace skipped before every
// item) but knows where it is, so that every error names the line and column and says
// what was expected there.
class SurfaceParser {
  public:
    SurfaceParser(std::string_view text, const std::string& fileName)
        : text_(text), fileName_(fileName) {
        lineStarts_.push_back(0);
        for (std::size_t i = 0; i < text_.size(); ++i)
            if (text_[i] == '\n') lineStarts_.push_back(i + 1);
    }

    Surface parse() {
        Surface s;
        s.name = fs::path(fileName_).stem().string();

        skipSpace();
        bool stedit = false;
        if (atKeyword("VERSION")) {
            keyword("VERSION", "at the start of the file");
            // bezieredit's "VERSION stedit" adds a direction after every neighbour name.
            stedit = word("the format version after VERSION") == "stedit";
        }
        for (const char* bound : {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"})
            number(std::string("the bounding box (") + bound + ") on the first line");
        skipSpace();
        if (atKeyword("PRECISION")) {
            keyword("PRECISION", "");
            label("S", "after PRECISION");
            integer("the s precision");
            label("T", "after the s precision");
            integer("the t precision");
        }

        keyword("CONTACT", "after the bounding box");
        keyword("POINT", "after CONTACT");
        s.contactPoint = point("CONTACT POINT");
        keyword("END", "after the contact point");
        keyword("POINT", "after END");
        s.endPoint = point("END POINT");
        std::size_t headingAt = keyword("HEADING", "after the end point");
        s.heading = point("HEADING");
        std::size_t upAt = keyword("UP", "after the heading");
        s.up = point("UP");
        std::size_t sizeAt = label("SIZE", "after the up vector");
        s.size = number("the surface size after SIZE:");
        normalizeFrame(s, headingAt, upAt);
        if (s.size <= 0)
            fail(sizeAt, "SIZE must be positive (it divides the placement scale), found " +
                             formatNumber(s.size));

        std::vector<PatchNeighbours> neighbours;
        while (true) {
            skipSpace();
            if (pos_ >= text_.size()) break;
            neighbours.emplace_back();
            s.patches.push_back(patch(stedit, neighbours.back()));
        }
        if (s.patches.empty())
            fail(contentEnd(),
                 "expected at least one patch after SIZE: (a name line, TOP "
                 "COLOR, the neighbours and 16 control points)");
        checkNeighbours(s.patches, neighbours);
        for (const BezierPatch& p : s.patches)
            for (const Vec3& v : p.points) s.bounds.extend(v);
        return s;
    }

  private:
    SourceLocation locationAt(std::size_t offset) const {
        auto it = std::upper_bound(lineStarts_.begin(), lineStarts_.end(), offset);
        auto line = static_cast<int>(std::distance(lineStarts_.begin(), it));
        auto column = static_cast<int>(offset - lineStarts_[static_cast<std::size_t>(line - 1)]);
        return {fileName_, line, column + 1};
    }

    [[noreturn]] void fail(std::size_t offset, const std::string& message) const {
        throw Error(locationAt(offset), message);
    }

    void skipSpace() {
        while (pos_ < text_.size() && isSpace(text_[pos_])) ++pos_;
    }

    // Just past the last non-blank character: where "the file ends" is reported, so that
    // the message points at the last line that has something on it.
    std::size_t contentEnd() const {
        std::size_t e = text_.size();
        while (e > 0 && isSpace(text_[e - 1])) --e;
        return e;
    }

    std::string_view tokenAt(std::size_t at) const {
        std::size_t e = at;
        while (e < text_.size() && !isSpace(text_[e])) ++e;
        return text_.substr(at, std::min<std::size_t>(e - at, 40));
    }

    std::string found() const {
        if (pos_ >= text_.size()) return "the end of the file";
        return "'" + std::string(tokenAt(pos_)) + "'";
    }

    bool matchesAt(std::size_t at, std::string_view word) const {
        if (text_.size() - at < word.size()) return false;
        for (std::size_t i = 0; i < word.size(); ++i)
            if (upper(text_[at + i]) != word[i]) return false;
        return true;
    }

    bool atKeyword(std::string_view kw) const {
        std::size_t e = pos_ + kw.size();
        return matchesAt(pos_, kw) && (e == text_.size() || isSpace(text_[e]));
    }

    [[noreturn]] void failExpected(const std::string& what, const std::string& context) const {
        std::size_t at = pos_ >= text_.size() ? contentEnd() : pos_;
        fail(at,
             "expected " + what + (context.empty() ? "" : " " + context) + ", found " + found());
    }

    // A keyword, matched without regard to case. Returns where it starts.
    std::size_t keyword(std::string_view kw, const std::string& context) {
        skipSpace();
        if (!atKeyword(kw)) failExpected("'" + std::string(kw) + "'", context);
        std::size_t at = pos_;
        pos_ += kw.size();
        return at;
    }

    // "NAME:", also written "NAME :" or glued to its value ("X:0.5"), as fscanf allows.
    std::size_t label(std::string_view name, const std::string& context) {
        skipSpace();
        std::size_t at = pos_;
        if (matchesAt(pos_, name)) {
            std::size_t p = pos_ + name.size();
            while (p < text_.size() && (text_[p] == ' ' || text_[p] == '\t')) ++p;
            if (p < text_.size() && text_[p] == ':') {
                pos_ = p + 1;
                return at;
            }
        }
        failExpected("'" + std::string(name) + ":'", context);
    }

    std::string_view word(const std::string& what) {
        skipSpace();
        if (pos_ >= text_.size()) failExpected(what, "");
        std::size_t e = pos_;
        while (e < text_.size() && !isSpace(text_[e])) ++e;
        std::string_view w = text_.substr(pos_, e - pos_);
        pos_ = e;
        return w;
    }

    // The extent of the next token, which must be followed by whitespace or the end.
    std::string_view numberToken(const std::string& what) {
        skipSpace();
        if (pos_ >= text_.size()) failExpected(what, "");
        std::size_t e = pos_;
        while (e < text_.size() && !isSpace(text_[e])) ++e;
        return text_.substr(pos_, e - pos_);
    }

    double number(const std::string& what) {
        std::string_view tok = numberToken(what);
        std::string_view digits = tok;
        if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
        double v = 0;
        auto r = numberFromChars(digits.data(), digits.data() + digits.size(), v);
        if (digits.empty() || digits.front() == '+' || r.ec != std::errc() ||
            r.ptr != digits.data() + digits.size() || !std::isfinite(v))
            fail(pos_, "expected " + what + " (a number), found '" + std::string(tok) + "'");
        pos_ += tok.size();
        return v;
    }

    int integer(const std::string& what) {
        std::string_view tok = numberToken(what);
        std::string_view digits = tok;
        if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
        int v = 0;
        auto r = std::from_chars(digits.data(), digits.data() + digits.size(), v);
        if (digits.empty() || digits.front() == '+' || r.ec != std::errc() ||
            r.ptr != digits.data() + digits.size())
            fail(pos_, "expected " + what + " (a whole number), found '" + std::string(tok) + "'");
        pos_ += tok.size();
        return v;
    }

    Vec3 point(const std::string& field) {
        Vec3 v;
        label("X", "after " + field);
        v.x = number("the x coordinate of " + field);
        label("Y", "after the x coordinate of " + field);
        v.y = number("the y coordinate of " + field);
        label("Z", "after the y coordinate of " + field);
        v.z = number("the z coordinate of " + field);
        return v;
    }

    static std::string formatNumber(double v) {
        std::ostringstream os;
        os << v;
        return os.str();
    }

    // cpfg normalises HEADING and UP and makes UP perpendicular to HEADING (left = H x U,
    // up = left x H); vectors that cannot be made a frame are errors here, not garbage.
    void normalizeFrame(Surface& s, std::size_t headingAt, std::size_t upAt) const {
        double h = std::sqrt(dot(s.heading, s.heading));
        if (!(h > 1e-12))
            fail(headingAt,
                 "HEADING must not be the zero vector: it is the direction the "
                 "surface is laid along the turtle's heading");
        s.heading = scaled(s.heading, 1 / h);
        double u = std::sqrt(dot(s.up, s.up));
        if (!(u > 1e-12)) fail(upAt, "UP must not be the zero vector");
        Vec3 up = scaled(s.up, 1 / u);
        Vec3 perpendicular = cross(cross(s.heading, up), s.heading);
        double p = std::sqrt(dot(perpendicular, perpendicular));
        if (!(p > 1e-6))
            fail(upAt,
                 "UP must not be parallel to HEADING: together they fix the surface's "
                 "orientation");
        s.up = scaled(perpendicular, 1 / p);
    }

    BezierPatch patch(bool stedit, PatchNeighbours& nb) {
        BezierPatch p;
        p.name = std::string(word("a patch name"));
        const std::string in = "in patch '" + p.name + "'";
        keyword("TOP", "after the patch name '" + p.name + "' (patch names are one word)");
        label("COLOR", "after TOP " + in);
        integer("the top colour index " + in);
        label("DIFFUSE", "after the top colour " + in);
        number("the top diffuse factor " + in);
        keyword("BOTTOM", "after the top diffuse factor " + in);
        label("COLOR", "after BOTTOM " + in);
        integer("the bottom colour index " + in);
        label("DIFFUSE", "after the bottom colour " + in);
        number("the bottom diffuse factor " + in);

        for (int n = 0; n < kNeighbourCount; ++n) {
            label(kNeighbourLabels[n],
                  n == 0 ? "after the colours " + in
                         : "(the " + std::string(kNeighbourNames[n]) + " neighbour) " + in);
            skipSpace();
            nb.offsets[n] = pos_;
            nb.names[n] = std::string(word("the name of the " + std::string(kNeighbourNames[n]) +
                                           " neighbour (or ~ for none) " + in));
            if (stedit)
                word("the direction of the " + std::string(kNeighbourNames[n]) + " neighbour " +
                     in);
        }

        for (int i = 0; i < 16; ++i) {
            static const char* kAxis[3] = {"x", "y", "z"};
            double c[3];
            for (int k = 0; k < 3; ++k) {
                skipSpace();
                if (pos_ >= text_.size())
                    fail(contentEnd(), "the file ends inside patch '" + p.name + "' after " +
                                           std::to_string(i) +
                                           " of its 16 control points: "
                                           "expected 48 numbers (4 points of x y z per line)");
                c[k] = number("the " + std::string(kAxis[k]) + " coordinate of control point " +
                              std::to_string(i + 1) + " of patch '" + p.name + "'");
            }
            p.points[static_cast<std::size_t>(i)] = {c[0], c[1], c[2]};
        }
        return p;
    }

    // cpfg refuses a surface whose neighbour names do not agree: every named neighbour must
    // exist and must name this patch back in the opposite direction.
    void checkNeighbours(const std::vector<BezierPatch>& patches,
                         const std::vector<PatchNeighbours>& neighbours) const {
        DiagnosticList diags;
        auto indexOf = [&](const std::string& name) -> std::ptrdiff_t {
            for (std::size_t i = 0; i < patches.size(); ++i)
                if (patches[i].name == name) return static_cast<std::ptrdiff_t>(i);
            return -1;
        };
        for (std::size_t p = 0; p < patches.size(); ++p) {
            for (int n = 0; n < kNeighbourCount; ++n) {
                const std::string& name = neighbours[p].names[n];
                if (name == "~") continue;
                std::ptrdiff_t q = indexOf(name);
                SourceLocation at = locationAt(neighbours[p].offsets[n]);
                if (q < 0) {
                    diags.error(at, "no patch '" + name + "' in this file: it is named as the " +
                                        kNeighbourNames[n] + " neighbour (" + kNeighbourLabels[n] +
                                        ") of patch '" + patches[p].name +
                                        "'; expected a patch name or ~ for none");
                    continue;
                }
                const std::string& back =
                    neighbours[static_cast<std::size_t>(q)].names[kNeighbourCount - 1 - n];
                if (back != patches[p].name)
                    diags.error(at, "neighbour mismatch: patch '" + patches[p].name + "' names '" +
                                        name + "' as its " + kNeighbourNames[n] + " neighbour (" +
                                        kNeighbourLabels[n] + "), so '" + name + "' must name '" +
                                        patches[p].name + "' as its " +
                                        kNeighbourNames[kNeighbourCount - 1 - n] + " neighbour (" +
                                        kNeighbourLabels[kNeighbourCount - 1 - n] +
                                        "), but it names '" + back + "'");
            }
        }
        if (diags.hasErrors()) throw Error(diags.items());
    }

    std::string_view text_;
    std::string fileName_;
    std::vector<std::size_t> lineStarts_;
    std::size_t pos_ = 0;
};

}  // namespace

Surface parseSurface(std::string_view text, const std::string& fileName) {
    return SurfaceParser(text, fileName).parse();
}

Surface loadSurface(const std::filesystem::path& path) {
    std::string problem;
    const std::optional<std::string> text = readUserFile(path, problem);
    if (!text) throw Error(SourceLocation{path.string(), 0, 0}, "the surface file " + problem);
    return parseSurface(*text, path.string());
}

std::filesystem::path builtinSurfacesDirectory() {
#ifdef GRAFTAL_BUILTIN_SURFACES_DIR
    // The web build has its surfaces in the module's own file system (cmake/web.cmake).
    return GRAFTAL_BUILTIN_SURFACES_DIR;
#endif
    // Found from where the code is, not from a path fixed at build time, so that an
    // installed copy works wherever its prefix was put. The build tree links its own
    // share/graftal/surfaces to the source folder.
    Dl_info info{};
    if (dladdr(reinterpret_cast<const void*>(&builtinSurfacesDirectory), &info) == 0 ||
        info.dli_fname == nullptr)
        throw Error(SourceLocation{}, "cannot tell where the graftal library is loaded from");
    std::error_code ec;
    const fs::path binary = fs::canonical(fs::path(info.dli_fname), ec);
    const fs::path folder = (ec ? fs::path(info.dli_fname) : binary).parent_path();
    for (const char* relative :
         {GRAFTAL_SURFACES_FROM_LIBDIR, GRAFTAL_SURFACES_FROM_BINDIR, "share/graftal/surfaces"}) {
        fs::path candidate = folder / relative;
        if (fs::is_directory(candidate, ec)) return candidate.lexically_normal();
    }
    throw Error(
        SourceLocation{(folder / GRAFTAL_SURFACES_FROM_LIBDIR).lexically_normal().string(), 0, 0},
        "the built-in surfaces are not installed here");
}

SurfaceLibrary SurfaceLibrary::builtin() {
    // Parsed once; a failed load throws out of the initialiser, which is then retried by
    // the next call rather than caching a half-built library.
    static const SurfaceLibrary kBuiltin = [] {
        SurfaceLibrary lib;
        lib.addDirectory(builtinSurfacesDirectory());
        return lib;
    }();
    return kBuiltin;
}

void SurfaceLibrary::add(Surface s) {
    if (s.name.empty())
        throw Error(SourceLocation{}, "a surface added to the library needs a name");
    std::string name = s.name;
    surfaces_.insert_or_assign(std::move(name), std::move(s));
}

void SurfaceLibrary::addDirectory(const std::filesystem::path& dir) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw Error(SourceLocation{dir.string(), 0, 0}, "cannot read surfaces: not a directory");
    // Sorted, so that which file wins when two differ only in case is not up to the OS.
    std::vector<fs::path> files;
    for (const fs::directory_entry& e : fs::directory_iterator(dir, ec))
        if (e.path().extension() == ".s" && e.is_regular_file(ec)) files.push_back(e.path());
    if (ec)
        throw Error(SourceLocation{dir.string(), 0, 0}, "cannot list surfaces: " + ec.message());
    std::sort(files.begin(), files.end());
    for (const fs::path& f : files) add(loadSurface(f));
}

const Surface* SurfaceLibrary::find(const std::string& name) const {
    auto it = surfaces_.find(name);
    return it == surfaces_.end() ? nullptr : &it->second;
}

std::vector<std::string> SurfaceLibrary::names() const {
    std::vector<std::string> out;
    out.reserve(surfaces_.size());
    for (const auto& [name, surface] : surfaces_) out.push_back(name);
    return out;
}

std::vector<std::string> removeUnknownSurfaces(Scene& scene, const SurfaceLibrary& library) {
    std::vector<std::string> unknown;
    std::vector<bool> known(scene.surfaceNames.size());
    for (std::size_t k = 0; k < scene.surfaceNames.size(); ++k)
        known[k] = library.find(scene.surfaceNames[k]) != nullptr;
    std::vector<bool> said(scene.surfaceNames.size(), false);
    std::erase_if(scene.surfaces, [&](const SurfaceInstance& s) {
        if (s.surface < known.size() && known[s.surface]) return false;
        if (s.surface < said.size() && !said[s.surface]) {
            said[s.surface] = true;
            unknown.push_back(scene.surfaceNames[s.surface]);
        }
        return s.surface < known.size();
    });
    return unknown;
}

}  // namespace graftal
