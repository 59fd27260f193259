// Reading cpfg's contour files (.con); see graftal/contour.hpp for the layouts.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "contour_setting.hpp"
#include "graftal/lang/contour_file.hpp"
#include "setting_file.hpp"

namespace graftal {

namespace {

constexpr int kMaxContourPoints = 100000;

struct Word {
    std::string_view text;
    int column = 1;  // 1-based
};

// The file as lines of white-space separated words, each with its column, so that every
// complaint can point at the word it is about.
class ContourReader {
  public:
    ContourReader(std::string_view text, const std::string& file) : file_(file) {
        std::size_t start = 0;
        while (start <= text.size()) {
            std::size_t end = text.find('\n', start);
            if (end == std::string_view::npos) end = text.size();
            std::string_view line = text.substr(start, end - start);
            std::vector<Word> words;
            std::size_t i = 0;
            while (i < line.size()) {
                while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
                std::size_t b = i;
                while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
                if (i > b) words.push_back({line.substr(b, i - b), static_cast<int>(b) + 1});
            }
            lines_.push_back(std::move(words));
            if (end == text.size()) break;
            start = end + 1;
        }
    }

    // The next line with words on it (its words), or fails naming `expected`.
    const std::vector<Word>& line(const std::string& expected) {
        while (next_ < lines_.size() && lines_[next_].empty()) ++next_;
        if (next_ >= lines_.size()) {
            // Said at the end of the last line with words on it.
            std::size_t last = lines_.size();
            while (last > 0 && lines_[last - 1].empty()) --last;
            int column = 1;
            if (last > 0) {
                const Word& w = lines_[last - 1].back();
                column = w.column + static_cast<int>(w.text.size());
            }
            fail(last, column, "expected " + expected + ", found the end of the file");
        }
        return lines_[next_++];
    }
    bool atEnd() {
        while (next_ < lines_.size() && lines_[next_].empty()) ++next_;
        return next_ >= lines_.size();
    }
    const std::vector<Word>& peek() {
        static const std::vector<Word> none;
        return atEnd() ? none : lines_[next_];
    }
    std::size_t lineNumber() const { return next_; }  // of the line line() gave last

    double number(const Word& w, const std::string& what) const {
        std::string s(w.text);
        char* stop = nullptr;
        double d = std::strtod(s.c_str(), &stop);
        if (stop == s.c_str() || *stop || !std::isfinite(d))
            fail(next_, w.column, "expected " + what + ", found '" + s + "'");
        return d;
    }
    int count(const Word& w, const std::string& what, int least) const {
        double d = number(w, what);
        if (d != std::floor(d) || d < least || d > kMaxContourPoints)
            fail(next_, w.column,
                 what + " must be a whole number from " + std::to_string(least) + " to " +
                     std::to_string(kMaxContourPoints) + ", not '" + std::string(w.text) + "'");
        return static_cast<int>(d);
    }
    // A `key: value...` line: its words after the key.
    std::vector<Word> keyed(const std::string& key, std::size_t values) {
        const std::vector<Word>& l = line("'" + key + "'");
        if (l[0].text != key)
            fail(next_, l[0].column,
                 "expected '" + key + "', found '" + std::string(l[0].text) + "'");
        if (l.size() < 1 + values)
            fail(next_, l.back().column + static_cast<int>(l.back().text.size()),
                 "expected " + std::to_string(values) + " value" + (values == 1 ? "" : "s") +
                     " after '" + key + "'");
        return {l.begin() + 1, l.end()};
    }

    [[noreturn]] void fail(std::size_t line, int column, const std::string& message) const {
        throw Error(SourceLocation{file_, static_cast<int>(std::max<std::size_t>(line, 1)), column},
                    message);
    }

  private:
    std::string file_;
    std::vector<std::vector<Word>> lines_;
    std::size_t next_ = 0;
};

bool closedWord(ContourReader& in, const Word& w, bool twoLetters) {
    std::string_view t = w.text;
    if (!twoLetters) {
        if (t == "closed") return true;
        if (t == "open") return false;
        in.fail(in.lineNumber(), w.column,
                "expected 'open' or 'closed', found '" + std::string(t) + "'");
    }
    if (t.size() == 2 && (t[0] == 'o' || t[0] == 'c') && (t[1] == 'r' || t[1] == 'e'))
        return t[0] == 'c';  // end-point interpolation is drawn as regular, as cpfg does
    in.fail(in.lineNumber(), w.column,
            "expected 'or', 'cr', 'oe' or 'ce' (open or closed, regular or end points), found '" +
                std::string(t) + "'");
}

// `N DIM closed|open` and N points.
void readOldLayout(ContourReader& in, const std::vector<Word>& first, Contour& c) {
    if (first.size() < 3)
        in.fail(in.lineNumber(), 1,
                "expected 'POINTS DIMENSION closed|open' or 'cver 1 1' on the first line");
    int n = in.count(first[0], "the number of points", 3);
    int dim = in.count(first[1], "the dimension (2 or 3)", 2);
    if (dim > 3)
        in.fail(in.lineNumber(), first[1].column,
                "the dimension is 2 or 3, not " + std::to_string(dim));
    // cpfg: anything but "closed" is open
    c.closed = first[2].text == "closed";
    // the coordinates may be spread over lines: read them as one stream
    std::vector<double> values;
    while (static_cast<int>(values.size()) < n * dim) {
        const std::vector<Word>& l =
            in.line(std::to_string(n) + " points of " + std::to_string(dim) + " numbers");
        for (const Word& w : l) values.push_back(in.number(w, "a coordinate"));
    }
    if (static_cast<int>(values.size()) > n * dim)
        in.fail(in.lineNumber(), 1,
                "expected " + std::to_string(n) + " points of " + std::to_string(dim) +
                    " numbers, found " + std::to_string(values.size()) + " numbers");
    for (int i = 0; i < n; ++i)
        c.controlPoints.push_back(
            {values[i * dim], values[i * dim + 1], dim == 3 ? values[i * dim + 2] : 0.0});
}

void readVersioned(ContourReader& in, int version, Contour& c) {
    std::vector<Word> name = in.keyed("name:", 0);
    c.name.clear();
    for (const Word& w : name) c.name += (c.name.empty() ? "" : " ") + std::string(w.text);
    std::vector<Word> points = in.keyed("points:", 2);
    int lines = in.count(points[0], "the number of point lines", 1);
    int total = in.count(points[1], "the number of points", 3);
    std::vector<Word> type = in.keyed("type:", 1);
    c.closed = closedWord(in, type[0], version >= 102);
    if (version >= 103) {
        in.keyed("samples:", 1);
        if (!in.peek().empty() && in.peek()[0].text.starts_with("background")) in.line("");
        if (!in.peek().empty() && in.peek()[0].text == "markers:") {
            int markers = in.count(in.keyed("markers:", 1)[0], "the number of markers", 0);
            for (int i = 0; i < markers; ++i) in.line("a marker line");
        }
    }
    for (int i = 0; i < lines; ++i) {
        const std::vector<Word>& l = in.line("a point 'x y z multiplicity'");
        if (l.size() != 4)
            in.fail(in.lineNumber(), l.size() > 4 ? l[4].column : 1,
                    "expected a point 'x y z multiplicity' (4 numbers), found " +
                        std::to_string(l.size()) + " words");
        Vec3 p{in.number(l[0], "x"), in.number(l[1], "y"), in.number(l[2], "z")};
        int m = in.count(l[3], "the multiplicity", 1);
        for (int k = 0; k < m; ++k) c.controlPoints.push_back(p);
        if (static_cast<int>(c.controlPoints.size()) > total)
            in.fail(in.lineNumber(), l[3].column,
                    "the points add up to more than the " + std::to_string(total) +
                        " the 'points:' line announces");
    }
    if (static_cast<int>(c.controlPoints.size()) != total)
        in.fail(in.lineNumber(), 1,
                "the points add up to " + std::to_string(c.controlPoints.size()) +
                    ", but the 'points:' line announces " + std::to_string(total));
}

// `cver MAJOR MINOR` (already read as `first`) and the contour after it.
void readCver(ContourReader& in, const std::vector<Word>& first, Contour& c) {
    if (first.size() != 3) in.fail(in.lineNumber(), first[0].column, "expected 'cver MAJOR MINOR'");
    int version = 100 * in.count(first[1], "the major version", 0) +
                  in.count(first[2], "the minor version", 0);
    if (version < 101 || version > 103)
        in.fail(in.lineNumber(), first[1].column,
                "contour version " + std::string(first[1].text) + " " + std::string(first[2].text) +
                    " is not supported (1 1, 1 2 and 1 3 are)");
    readVersioned(in, version, c);
}

void checkPointCount(ContourReader& in, const Contour& c) {
    if (c.controlPoints.size() < (c.closed ? 3u : 4u))
        in.fail(in.lineNumber(), 1,
                std::string("a ") + (c.closed ? "closed" : "open") + " contour needs at least " +
                    (c.closed ? "3" : "4") + " points");
}

}  // namespace

Contour parseContourFile(std::string_view text, const std::string& fileName, int id) {
    ContourReader in(text, fileName);
    Contour c;
    c.id = id;
    c.name = fileName;
    const std::vector<Word>& first = in.line("'cver 1 1' or 'POINTS DIMENSION closed|open'");
    if (first[0].text == "cver")
        readCver(in, first, c);
    else
        readOldLayout(in, first, c);
    checkPointCount(in, c);
    if (!in.atEnd())
        in.fail(in.lineNumber() + 1, in.peek()[0].column,
                "unexpected '" + std::string(in.peek()[0].text) + "' after the last point");
    return c;
}

std::vector<Contour> parseContourSet(std::string_view text, const std::string& fileName) {
    ContourReader in(text, fileName);
    const std::vector<Word>& head = in.line("'contourgalleryver 1 1'");
    if (head[0].text != "contourgalleryver" || head.size() != 3 || head[1].text != "1" ||
        head[2].text != "1")
        in.fail(in.lineNumber(), head[0].column,
                "expected 'contourgalleryver 1 1' (a contour set), found '" +
                    std::string(head[0].text) + "'");
    const std::vector<Word> items = in.keyed("items:", 1);
    const int count = in.count(items[0], "the number of contours", 1);
    std::vector<Contour> out;
    for (int i = 0; i < count; ++i) {
        const std::vector<Word>& first = in.line("'cver 1 1' (contour " + std::to_string(i + 1) +
                                                 " of " + std::to_string(count) + ")");
        if (first[0].text != "cver")
            in.fail(in.lineNumber(), first[0].column,
                    "expected 'cver 1 1' to begin contour " + std::to_string(i + 1) + " of " +
                        std::to_string(count) + ", found '" + std::string(first[0].text) + "'");
        Contour c;
        c.id = i + 1;
        readCver(in, first, c);
        checkPointCount(in, c);
        out.push_back(std::move(c));
    }
    if (!in.atEnd())
        in.fail(in.lineNumber() + 1, in.peek()[0].column,
                "unexpected '" + std::string(in.peek()[0].text) + "' after the last of the " +
                    std::to_string(count) + " contours 'items:' announces");
    return out;
}

// `contour: ID FILE`: the id @# names the contour by (a whole number; 0 is the circle and
// cannot be redefined) and the file, relative to the view file.
void loadContourSetting(ViewSettings& view, const ViewSetting& setting,
                        DiagnosticList& diagnostics) {
    const auto* text = std::get_if<std::string>(&setting.value);
    std::istringstream words(text ? *text : std::string());
    std::string idWord, file, extra;
    words >> idWord >> file >> extra;
    char* stop = nullptr;
    const double id = std::strtod(idWord.c_str(), &stop);
    if (idWord.empty() || *stop || id != std::floor(id) || id < 1 || id > 1e6 || file.empty() ||
        !extra.empty()) {
        diagnostics.error(setting.location,
                          "'contour:' expects an id (a whole number from 1) and a .con file, "
                          "e.g. 'contour: 1 leaf.con', found '" +
                              (text ? *text : std::string()) + "'");
        return;
    }
    const std::filesystem::path path = settingFilePath(setting, file);
    const std::optional<std::string> bytes = readSettingFile(setting, path, "contour", diagnostics);
    if (!bytes) return;
    try {
        Contour contour = parseContourFile(*bytes, path.string(), static_cast<int>(id));
        contour.file = file;
        // A later line with the same id replaces the earlier one.
        for (Contour& c : view.materials.contours)
            if (c.id == contour.id) {
                c = std::move(contour);
                return;
            }
        view.materials.contours.push_back(std::move(contour));
    } catch (const Error& e) {
        for (const auto& d : e.diagnostics()) diagnostics.add(d);
    }
}

}  // namespace graftal
