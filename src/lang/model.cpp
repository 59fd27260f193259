// Parsing to a Model with every diagnostic returned as a value.
#include "graftal/lang/model.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>

#include "graftal/core/file_reading.hpp"
#include "graftal/lang/contour_file.hpp"
#include "graftal/lang/parser_target.hpp"
#include "graftal/lang/source_text.hpp"
#include "graftal/lang/view_file.hpp"
#include "graftal/lang/vlab_specifications.hpp"
#include "parser.hpp"
#include "preprocessor.hpp"

namespace graftal {

namespace {

bool isWordByte(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.';
}

// A diagnostic that names only where the offending text starts ends with the token there:
// a word (letters, digits, '_', '.') or else the run up to the next blank.
void completeEnd(SourceLocation& loc, const SourceText& src) {
    if (loc.line <= 0 || loc.endLine > 0 || loc.file != src.fileName) return;
    auto it = std::lower_bound(src.lines.begin(), src.lines.end(), loc.line,
                               [](const SourceLine& l, int n) { return l.number < n; });
    loc.endLine = loc.line;
    loc.endColumn = loc.column + 1;
    if (it == src.lines.end() || it->number != loc.line || loc.column < 1) return;
    // A preprocessed line is numbered in the preprocessor's output, not in the file.
    if (!it->spans.empty() && it->spans.front().line != loc.line) return;
    const std::string& t = it->text;
    std::size_t b = static_cast<std::size_t>(loc.column - 1);
    if (b >= t.size()) return;
    std::size_t e = b + 1;
    if (isWordByte(t[b]))
        while (e < t.size() && isWordByte(t[e])) ++e;
    else
        while (e < t.size() && !std::isspace(static_cast<unsigned char>(t[e]))) ++e;
    loc.endColumn = static_cast<int>(e) + 1;
}

std::vector<Diagnostic> withSeverity(const std::vector<Diagnostic>& ds, Severity s) {
    std::vector<Diagnostic> out;
    for (const auto& d : ds)
        if (d.severity == s) out.push_back(d);
    return out;
}

}  // namespace

bool ParseResult::ok() const {
    return std::none_of(diagnostics.begin(), diagnostics.end(),
                        [](const Diagnostic& d) { return d.severity == Severity::Error; });
}

std::vector<Diagnostic> ParseResult::errors() const {
    return withSeverity(diagnostics, Severity::Error);
}

std::vector<Diagnostic> ParseResult::warnings() const {
    return withSeverity(diagnostics, Severity::Warning);
}

Model& ParseResult::orThrow() & {
    if (!ok()) throw Error(errors());
    return model;
}

Model ParseResult::orThrow() && {
    if (!ok()) throw Error(errors());
    return std::move(model);
}

void parseInto(std::string_view text, const ParseOptions& options, ParserTarget& target,
               DiagnosticList& diagnostics) {
    DiagnosticList diags;
    SourceText src;
    bool ready = prepareSource(text, options.fileName, src, diags);
    // Like cpfg, a file goes through the C preprocessor (preprocessor.hpp) before its lines
    // are read; only files with a directive or given -D need it.
    PreprocessOptions pp{options.fileName, options.defines, 0};
    if (ready && needsPreprocessing(text, pp)) ready = preprocessSource(text, pp, src, diags);
    if (ready) {
        joinBlockLines(src);
        parsing::Parser(src, options, diags, target).run();
    }
    for (Diagnostic d : diags.items()) {
        completeEnd(d.location, src);
        diagnostics.add(std::move(d));
    }
}

ParseResult parse(std::string_view text, const ParseOptions& options) {
    ParseResult result;
    DiagnosticList diags;
    ModelBuilder builder(diags);
    builder.model().lsystem.name = builder.model().lsystem.file = options.fileName;
    parseInto(text, options, builder, diags);
    result.model = std::move(builder.model());
    result.diagnostics = diags.items();
    return result;
}

namespace {

bool readWholeFile(const std::filesystem::path& path, std::string& text, std::string& problem) {
    std::optional<std::string> bytes = readUserFile(path, problem);
    if (!bytes) return false;
    text = std::move(*bytes);
    return true;
}

// The files in `folder` whose names end with `extension`, sorted.
std::vector<std::filesystem::path> filesEndingWith(const std::filesystem::path& folder,
                                                   const std::string& extension) {
    std::vector<std::filesystem::path> found;
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator(folder, ec))
        if (e.is_regular_file(ec) && e.path().extension() == extension) found.push_back(e.path());
    std::sort(found.begin(), found.end());
    return found;
}

}  // namespace

// What cpfg is given beside the .l and .v on its command line, found in a model folder:
// its one colour map (.map) and its one material file (.mat), unless the model names one,
// its one function set (.fset), unless the view file names functions, and its one contour
// set (.cset, ids 1, 2, ... in file order, as lpfg numbers them), unless the view file
// names contours.
namespace {

void addFolderFiles(const std::filesystem::path& folder, ParseResult& result) {
    Model& model = result.model;
    auto maps = filesEndingWith(folder, ".map");
    if (model.view.materials.colorMap.empty() && maps.size() == 1)
        model.view.materials.colorMap = maps[0].filename().string();
    auto materials = filesEndingWith(folder, ".mat");
    if (model.view.materials.materialFile.empty() && materials.size() == 1)
        model.view.materials.materialFile = materials[0].filename().string();
    auto contourSets = filesEndingWith(folder, ".cset");
    std::string contourText, problem;
    if (model.view.materials.contours.empty() && contourSets.size() == 1) {
        if (!readWholeFile(contourSets[0], contourText, problem))
            result.diagnostics.push_back({Severity::Error,
                                          SourceLocation{contourSets[0].string(), 0, 0},
                                          "the contour set " + problem});
        else
            try {
                model.view.materials.contours =
                    parseContourSet(contourText, contourSets[0].string());
            } catch (const Error& e) {
                for (const auto& d : e.diagnostics()) result.diagnostics.push_back(d);
            }
    }
    auto sets = filesEndingWith(folder, ".fset");
    if (sets.size() != 1 || !model.lsystem.functions.empty()) return;
    std::string text;
    if (!readWholeFile(sets[0], text, problem)) {
        result.diagnostics.push_back({Severity::Error, SourceLocation{sets[0].string(), 0, 0},
                                      "the function set " + problem});
        return;
    }
    try {
        model.lsystem.functions = parseFunctionSet(text, sets[0].string());
    } catch (const Error& e) {
        for (const auto& d : e.diagnostics()) result.diagnostics.push_back(d);
    }
}

// The colour map and materials the specifications' cpfg command names (-m, -M), when the
// view file named none and the files are there.
void addCommandFiles(const std::filesystem::path& folder, const VlabCommand& command,
                     Model& model) {
    std::error_code ec;
    if (model.view.materials.colorMap.empty() && !command.colorMap.empty() &&
        std::filesystem::is_regular_file(folder / command.colorMap, ec))
        model.view.materials.colorMap = command.colorMap;
    if (model.view.materials.materialFile.empty() && !command.materials.empty() &&
        std::filesystem::is_regular_file(folder / command.materials, ec))
        model.view.materials.materialFile = command.materials;
}

// Whether the text has `#define NAME` (NAME whole, not the start of a longer name).
bool definesMacro(std::string_view text, const std::string& name) {
    const std::string key = "define " + name;
    for (std::size_t at = text.find(key); at != std::string_view::npos;
         at = text.find(key, at + 1)) {
        const std::size_t after = at + key.size();
        if (after >= text.size() ||
            !(std::isalnum(static_cast<unsigned char>(text[after])) || text[after] == '_'))
            return true;
    }
    return false;
}

// cpfg runs the L-system through the preprocessor with -DNAME=i for the i-th item of the
// view file's function set (its `name:`, a `.func` suffix taken off), so that models call
// func(BR_ANGLE, t). A name the .l file #defines itself keeps the file's value.
void defineFunctionSetNames(std::string_view text, std::string_view viewText,
                            const std::string& viewFileName, ParseOptions& options) {
    const std::vector<std::string> sets = viewFileValues(viewText, "function set");
    if (sets.empty()) return;
    std::string name = sets.back().substr(0, sets.back().find_first_of(" \t"));
    const std::filesystem::path path = std::filesystem::path(viewFileName).parent_path() / name;
    std::string setText, problem;
    if (!readWholeFile(path, setText, problem)) return;  // the view file's reader says why
    std::vector<GraphicalFunction> functions;
    try {
        functions = parseFunctionSet(setText, path.string());
    } catch (const Error&) {
        return;
    }
    for (std::size_t i = 0; i < functions.size(); ++i) {
        std::string macro = functions[i].name();
        if (macro.size() > 5 && macro.ends_with(".func")) macro.resize(macro.size() - 5);
        const bool identifier = !macro.empty() &&
                                !std::isdigit(static_cast<unsigned char>(macro[0])) &&
                                std::all_of(macro.begin(), macro.end(), [](char c) {
                                    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
                                });
        if (!identifier || options.defines.count(macro)) continue;
        if (definesMacro(text, macro)) continue;
        options.defines[macro] = std::to_string(i + 1);
    }
}

}  // namespace

ParseResult loadModel(const std::filesystem::path& given, ParseOptions options) {
    std::filesystem::path path = given;
    auto failure = [&](const std::string& message) {
        ParseResult r;
        r.model.lsystem.name = r.model.lsystem.file = path.string();
        r.diagnostics.push_back({Severity::Error, SourceLocation{path.string(), 0, 0}, message});
        return r;
    };
    std::error_code ec;
    std::optional<VlabCommand> vlab;
    if (std::filesystem::is_directory(path, ec)) {
        // A vlab model folder: its `specifications` names the files cpfg is run on.
        std::string specText, specProblem;
        if (std::filesystem::is_regular_file(path / "specifications", ec) &&
            readWholeFile(path / "specifications", specText, specProblem))
            vlab = cpfgCommandOf(specText);
        if (vlab && !std::filesystem::is_regular_file(path / vlab->lFile, ec)) vlab.reset();
    }
    if (vlab) {
        if (options.viewFile.empty() && !vlab->viewFile.empty() &&
            std::filesystem::is_regular_file(path / vlab->viewFile, ec))
            options.viewFile = (path / vlab->viewFile).string();
        path = path / vlab->lFile;
        if (options.fileName.empty() || options.fileName == given.string())
            options.fileName = path.string();
    } else if (std::filesystem::is_directory(path, ec)) {
        // A model folder: its one L-system, and its one view file unless one is named.
        auto ls = filesEndingWith(path, ".l");
        if (ls.size() != 1)
            return failure(ls.empty() ? "is a folder with no .l file, expected an L-system file"
                                      : "is a folder with " + std::to_string(ls.size()) +
                                            " .l files; name the one to read");
        auto vs = filesEndingWith(path, ".v");
        if (options.viewFile.empty() && vs.size() == 1) options.viewFile = vs[0].string();
        if (options.viewFile.empty() && vs.size() > 1)
            return failure("is a folder with " + std::to_string(vs.size()) +
                           " .v files; name the L-system and the view file to read");
        path = ls[0];
        if (options.fileName.empty() || options.fileName == given.string())
            options.fileName = path.string();
    }
    if (options.fileName.empty()) options.fileName = path.string();
    std::string text;
    std::string problem;
    if (!readWholeFile(path, text, problem))
        return failure(
            std::filesystem::is_directory(path, ec) ? "is a directory, expected an L-system file"
            : std::filesystem::exists(path, ec)     ? problem
                                                    : "cannot open the file (does it exist?)");
    const bool folder = std::filesystem::is_directory(given, ec);
    if (options.viewFile.empty()) {
        ParseResult result = parse(text, options);
        if (vlab) addCommandFiles(given, *vlab, result.model);
        if (folder) addFolderFiles(given, result);
        return result;
    }
    std::string viewText;
    if (!readWholeFile(options.viewFile, viewText, problem)) {
        ParseResult result = parse(text, options);
        result.diagnostics.push_back({Severity::Error, SourceLocation{options.viewFile, 0, 0},
                                      std::filesystem::exists(options.viewFile, ec)
                                          ? "the view file " + problem
                                          : "cannot open the view file (does it exist?)"});
        return result;
    }
    ParseResult result = parse(text, viewText, options.viewFile, options);
    if (vlab) addCommandFiles(given, *vlab, result.model);
    if (folder) addFolderFiles(given, result);
    return result;
}

ParseResult parse(std::string_view text, std::string_view viewText, const std::string& viewFileName,
                  const ParseOptions& givenOptions) {
    ParseOptions options = givenOptions;
    options.surfaceLetters += viewFileSurfaceLetters(viewText);
    defineFunctionSetNames(text, viewText, viewFileName, options);
    ParseResult result = parse(text, options);
    // A model read with a view file is cpfg's: it draws cpfg's random numbers unless its
    // .l file says `random: graftal`.
    if (!result.model.lsystem.randomLine) result.model.lsystem.random = RandomStreams::Cpfg;
    result.model.lsystem.cpfgViewBox = viewFileGivesBox(viewText);
    DiagnosticList diags;
    ModelBuilder builder(diags);
    builder.model() = std::move(result.model);
    parseViewFileInto(viewText, viewFileName, builder, diags);
    result.model = std::move(builder.model());
    // cpfg forgives its view files: a value it cannot use leaves the setting as it was and
    // the model still runs. Only the .l file's errors stop a run, so here an error is a
    // warning, still at its file:line:column.
    for (Diagnostic d : diags.items()) {
        if (d.severity == Severity::Error) {
            d.severity = Severity::Warning;
            d.message += "; the line is ignored, as cpfg ignores it";
        }
        result.diagnostics.push_back(std::move(d));
    }
    return result;
}

std::ostream& operator<<(std::ostream& os, const Model& model) {
    model.lsystem.print(os, &model.view);
    return os;
}

}  // namespace graftal
