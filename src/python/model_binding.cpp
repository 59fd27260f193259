// graftal.load() and graftal.parse(), and the Model they return: derive it (the pipeline's
// derived()), measure it (measured(), what `graftal stats` reports), predict its growth
// (predictGrowth()) and export it in any format of the registry (exportModel()).
#include <functional>
#include <sstream>

#include "bindings.hpp"
#include "graftal/pipeline/stages.hpp"
#include "graftal/pipeline/statistics.hpp"
#include "graftal/rewrite/growth.hpp"

namespace graftal::python {

std::map<std::string, std::string> defineMap(const py::object& defines) {
    std::map<std::string, std::string> map;
    if (defines.is_none()) return map;
    if (!py::isinstance<py::dict>(defines))
        throw py::type_error("defines: expected a dict such as {'N': 3}");
    for (const auto& [name, value] : defines.cast<py::dict>()) {
        if (!py::isinstance<py::str>(name)) throw py::type_error("defines: names must be str");
        if (py::isinstance<py::bool_>(value) ||
            !(py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value) ||
              py::isinstance<py::str>(value)))
            throw py::type_error("defines['" + name.cast<std::string>() +
                                 "']: expected a number or an expression as str");
        map[name.cast<std::string>()] = py::str(value).cast<std::string>();
    }
    return map;
}

namespace {

std::string pathText(const py::object& path) {
    return py::str(py::module_::import("os").attr("fspath")(path)).cast<std::string>();
}

// Reads the model a source describes, with `defines` as the overrides and the macros of the
// functions it calls by name.
ParseResult read(const ModelSource& source, const std::map<std::string, std::string>& defines,
                 const NamedFunctions& named) {
    ParseOptions options;
    options.defines = defines;
    options.defines.insert(named.macros.begin(), named.macros.end());
    if (!source.path.empty()) {
        if (source.view) options.viewFile = *source.view;
        return loadModel(source.path, options);
    }
    options.fileName = source.file;
    if (!source.view) return parse(source.text, options);
    return parse(source.text, *source.view,
                 source.viewFile.empty() ? std::string("view.v") : source.viewFile, options);
}

// An override of a constant the model does not define would change nothing the user can
// see (the command takes it silently): from Python it is an error naming the constants
// there are. The model is read once more without the overrides to learn them.
// `known`: the constants, when the caller knows them (a model read before).
void checkDefines(const ModelSource& source, const std::map<std::string, std::string>* known,
                  const NamedFunctions& named) {
    if (source.defines.empty()) return;
    ParseResult parsed;
    if (!known) {
        {
            py::gil_scoped_release release;
            parsed = read(source, {}, named);
        }
        if (!parsed.ok()) raiseParseError(parsed.errors());
        known = &parsed.model.lsystem.defines;
    }
    for (const auto& [name, value] : source.defines) {
        if (known->count(name)) continue;
        std::string names;
        for (const auto& [k, v] : *known) names += (names.empty() ? "" : ", ") + k;
        throw py::value_error(
            "defines: the model has no #define " + name +
            (names.empty() ? std::string(" (it defines none)") : " (it defines " + names + ")"));
    }
}

ModelHandle handleOf(ModelSource source,
                     const std::map<std::string, std::string>* known = nullptr) {
    const NamedFunctions named = namedFunctions(source);
    checkDefines(source, known, named);
    ParseResult parsed;
    {
        py::gil_scoped_release release;
        parsed = read(source, source.defines, named);
    }
    if (!parsed.ok()) raiseParseError(parsed.errors());
    // The macros are the module's means, not the model's constants.
    for (const auto& [macro, body] : named.macros) parsed.model.lsystem.defines.erase(macro);
    if (source.random) parsed.model.lsystem.random = *source.random;
    if (source.functions)
        parsed.model.lsystem.userFunctions =
            userFunctionTable(parsed.model, *source.functions, named);
    ModelHandle h;
    h.warnings = parsed.warnings();
    h.model = std::make_shared<const Model>(std::move(parsed.model));
    h.source = std::make_shared<const ModelSource>(std::move(source));
    return h;
}

// load(functions=...): kept as the dict given (None: none), read again with the model.
std::shared_ptr<py::object> functionDict(py::object functions) {
    if (functions.is_none()) return nullptr;
    if (!py::isinstance<py::dict>(functions))
        throw py::type_error("functions: expected a dict such as {'light': f} or {1: f}");
    return heldForThreads(py::dict(functions));
}

py::object load(py::object path, py::object defines, py::object view, py::object functions,
                py::object random) {
    ModelSource source;
    source.random = randomStreams(random);
    source.path = pathText(path);
    source.defines = defineMap(defines);
    source.functions = functionDict(std::move(functions));
    if (!view.is_none()) source.view = pathText(view);
    if (isMapSource(source)) return loadMapModel(std::move(source));
    return py::cast(handleOf(std::move(source)));
}

py::object parseText(const std::string& text, const std::string& file, py::object defines,
                     py::object viewText, const std::string& viewFile, py::object functions,
                     py::object random) {
    ModelSource source;
    source.random = randomStreams(random);
    source.functions = functionDict(std::move(functions));
    source.text = text;
    source.file = file;
    source.defines = defineMap(defines);
    if (!viewText.is_none()) source.view = viewText.cast<std::string>();
    source.viewFile = viewFile;
    if (isMapSource(source)) return loadMapModel(std::move(source));
    return py::cast(handleOf(std::move(source)));
}

// The same model read with more (or other) constants overridden.
ModelHandle withDefines(const ModelHandle& h, py::object defines) {
    ModelSource source = *h.source;
    for (auto& [name, value] : defineMap(defines)) source.defines[name] = value;
    // The model's constants are those of its file (its own overrides were checked).
    return handleOf(std::move(source), &h.model->lsystem.defines);
}

py::tuple sourceState(const ModelHandle& h) {
    const ModelSource& s = *h.source;
    return py::make_tuple(s.path, s.text, s.file, s.view ? py::cast(*s.view) : py::none(),
                          s.viewFile, s.defines, s.functions ? *s.functions : py::none(),
                          s.random ? py::cast(static_cast<int>(*s.random)) : py::none());
}

ModelHandle fromState(const py::tuple& t) {
    if (t.size() != 6 && t.size() != 8) throw py::value_error("not a pickled graftal.Model");
    ModelSource s;
    s.path = t[0].cast<std::string>();
    s.text = t[1].cast<std::string>();
    s.file = t[2].cast<std::string>();
    if (!t[3].is_none()) s.view = t[3].cast<std::string>();
    s.viewFile = t[4].cast<std::string>();
    s.defines = t[5].cast<std::map<std::string, std::string>>();
    if (t.size() == 8) {
        s.functions = functionDict(t[6]);
        if (!t[7].is_none()) s.random = static_cast<RandomStreams>(t[7].cast<int>());
    }
    return handleOf(std::move(s));
}

py::object pythonCount(const BigCount& c) {
    return py::reinterpret_steal<py::object>(PyLong_FromString(c.toString().c_str(), nullptr, 10));
}

// The growth prediction as a dict: exact/expected, reason, modules per step.
py::dict prediction(const ModelHandle& h, py::object steps) {
    const int n = steps.is_none() ? h.model->lsystem.derivationLength : steps.cast<int>();
    DeriveRequest check;
    check.steps = n;
    requestedSteps(*h.model, check);  // the one check of a step count
    GrowthPrediction g;
    {
        py::gil_scoped_release release;
        g = predictGrowth(h.model->lsystem, n);
    }
    py::dict d;
    d["steps"] = n;
    d["exact"] = g.exact;
    d["expected"] = g.expected;
    d["reason"] = g.reason;
    py::list modules;
    if (g.exact)
        for (const BigCount& c : g.modules) modules.append(pythonCount(c));
    else
        for (double v : g.expectedModules) modules.append(v);
    d["modules"] = modules;
    py::dict symbols;
    for (std::size_t s = 0; s < g.symbolsAtEnd.size(); ++s)
        if (!(g.symbolsAtEnd[s] == BigCount()))
            symbols[py::str(h.model->lsystem.symbols.name(static_cast<Symbol>(s)))] =
                pythonCount(g.symbolsAtEnd[s]);
    d["symbols"] = symbols;
    return d;
}

py::dict symbolDict(const SymbolTable& table, const std::vector<std::uint64_t>& counts) {
    std::vector<std::pair<std::string, std::uint64_t>> present;
    for (std::size_t s = 0; s < counts.size(); ++s)
        if (counts[s]) present.emplace_back(table.name(static_cast<Symbol>(s)), counts[s]);
    std::sort(present.begin(), present.end());
    py::dict d;
    for (const auto& [name, count] : present) d[py::str(name)] = count;
    return d;
}

py::object boundsTuple(const Bounds& b) {
    if (b.empty()) return py::none();
    return py::make_tuple(py::make_tuple(b.min.x, b.min.y, b.min.z),
                          py::make_tuple(b.max.x, b.max.y, b.max.z));
}

}  // namespace

py::dict statisticsDict(const SymbolTable& table, const ModelStatistics& stats) {
    py::dict d;
    d["steps"] = stats.steps;
    d["modules"] = stats.modules;
    d["symbols"] = symbolDict(table, stats.symbolCounts);
    if (stats.measured) {
        d["segments"] = stats.segments;
        d["polygons"] = stats.polygons;
        d["bounds"] = boundsTuple(stats.bounds);
    }
    d["streamed"] = stats.streamed;
    return d;
}

void bindModel(py::module_& m) {
    py::class_<ModelHandle>(m, "Model",
                            "A parsed L-system model: its grammar and how it is drawn. Made "
                            "by graftal.load() or graftal.parse(); derive(), statistics(), "
                            "predict() and export() run the library's pipeline on it.")
        .def_property_readonly(
            "name", [](const ModelHandle& h) { return h.model->lsystem.name; },
            "the `Lsystem:` label (the file's name when there is none)")
        .def_property_readonly(
            "file", [](const ModelHandle& h) { return h.model->lsystem.file; },
            "the file it was read from, as diagnostics name it")
        .def_property_readonly(
            "derivation_length",
            [](const ModelHandle& h) { return h.model->lsystem.derivationLength; },
            "the file's `derivation length:`, the steps derive() makes by default")
        .def_property_readonly(
            "defines", [](const ModelHandle& h) { return h.model->lsystem.defines; },
            "the #define constants, name to text, after the overrides")
        .def_property_readonly(
            "symbols",
            [](const ModelHandle& h) {
                py::list names;
                const SymbolTable& t = h.model->lsystem.symbols;
                for (std::size_t s = 0; s < t.size(); ++s)
                    names.append(t.name(static_cast<Symbol>(s)));
                return names;
            },
            "every module name, indexed by symbol id (ModuleString.symbols' values)")
        .def_property_readonly(
            "warnings", [](const ModelHandle& h) { return diagnosticList(h.warnings); },
            "the parse's warnings and notes (graftal.Diagnostic), returned, never printed")
        .def(
            "derive",
            [](const ModelHandle& h, py::object steps, py::object seed, unsigned threads,
               py::object memoryLimit, const std::string& precision, py::object environment,
               py::object random) {
                DerivedString d;
                d.model = h.model;
                d.source = h.source;
                d.settings = deriveSettings(steps, seed, threads, memoryLimit, precision,
                                            std::move(environment), std::move(random));
                CancellationToken cancel;
                const DeriveRequest request = deriveRequest(d.settings, cancel);
                Derived derivedModel =
                    interruptible(cancel, [&] { return derived(*h.model, request); });
                d.steps = derivedModel.steps;
                d.modules = std::move(derivedModel.modules);
                return d;
            },
            py::arg("steps") = py::none(), py::kw_only(), py::arg("seed") = py::none(),
            py::arg("threads") = 0u, py::arg("memory_limit") = py::none(),
            py::arg("precision") = "single", py::arg("environment") = py::none(),
            py::arg("random") = py::none(),
            "Derives the model `steps` steps (default: its derivation length) and returns the "
            "ModuleString. seed overrides the file's; threads=0 uses every core (the result "
            "never depends on it); memory_limit (bytes, or '512M', default 2G) bounds the "
            "strings; precision 'single' stores parameters as float32 (as cpfg), 'double' as "
            "float64; environment answers ?E modules (see graftal.Environment); random "
            "'cpfg' draws cpfg's random numbers in cpfg's order (the string cpfg gives, as "
            "--random cpfg), 'graftal' graftal's streams (default: the model's choice). The "
            "GIL is released; Ctrl-C stops it with KeyboardInterrupt.")
        .def(
            "statistics",
            [](const ModelHandle& h, py::object steps, py::object seed, unsigned threads,
               py::object memoryLimit, bool geometry, bool stream, py::object environment,
               py::object random) {
                const DeriveSettings settings =
                    deriveSettings(steps, seed, threads, memoryLimit, "single",
                                   std::move(environment), std::move(random));
                CancellationToken cancel;
                DeriveRequest request = deriveRequest(settings, cancel);
                if (stream) request.stream = StreamPolicy::Always;
                const ModelStatistics stats =
                    interruptible(cancel, [&] { return measured(*h.model, request, geometry); });
                return statisticsDict(h.model->lsystem.symbols, stats);
            },
            py::arg("steps") = py::none(), py::kw_only(), py::arg("seed") = py::none(),
            py::arg("threads") = 0u, py::arg("memory_limit") = py::none(),
            py::arg("geometry") = true, py::arg("stream") = false,
            py::arg("environment") = py::none(), py::arg("random") = py::none(),
            "What `graftal stats` reports, as a dict: steps, modules, symbols (count per "
            "module name) and, with geometry, segments, polygons and bounds ((min xyz), "
            "(max xyz)) measured without keeping the drawing; streamed says whether the "
            "string was too large to hold and was measured as it streamed.")
        .def("predict", &prediction, py::arg("steps") = py::none(),
             "The module counts of every step computed from the productions, without "
             "deriving: a dict with exact (counts are exact ints), expected (expected values "
             "of a stochastic L-system), reason (why neither, when so), modules (one count "
             "per step 0..steps) and symbols (exact counts per module at the last step).")
        .def(
            "export",
            [](const ModelHandle& h, py::object path, py::object format, py::object steps,
               py::object seed, unsigned threads, py::object memoryLimit, py::object environment,
               py::object random, py::object notes, py::kwargs options) -> py::object {
                const DeriveSettings settings =
                    deriveSettings(steps, seed, threads, memoryLimit, "single",
                                   std::move(environment), std::move(random));
                CancellationToken cancel;
                ExportRequest request;
                static_cast<DeriveRequest&>(request) = deriveRequest(settings, cancel);
                applyExportOptions(request, options);
                std::string bytes;
                const bool toMemory = path.is_none();
                const Destination destination = exportDestination(
                    request, path, format, bytes, h.model->lsystem.name, "png");
                const ExportResult result = interruptible(
                    cancel, [&] { return exportModel(*h.model, destination, request); });
                if (!notes.is_none()) {
                    if (!py::isinstance<py::list>(notes))
                        throw py::type_error("notes: expected a list");
                    py::list list = notes.cast<py::list>();
                    for (py::handle d : diagnosticList(result.notes)) list.append(d);
                }
                if (!toMemory) return py::none();
                return py::bytes(bytes);
            },
            py::arg("path") = py::none(), py::kw_only(), py::arg("format") = py::none(),
            py::arg("steps") = py::none(), py::arg("seed") = py::none(), py::arg("threads") = 0u,
            py::arg("memory_limit") = py::none(), py::arg("environment") = py::none(),
            py::arg("random") = py::none(), py::arg("notes") = py::none(),
            "Writes the model as `graftal render`, `animate` and `music` would, in any format "
            "of graftal.export_formats(): to `path` (its extension names the format unless "
            "format= does; written atomically) or, with no path, returned as bytes. Options "
            "are the pipeline's request fields in snake_case: size=(w, h), line_width, margin, "
            "background, line_color, view ('front', 'side', ...), viewpoint, target, up, "
            "light, field_of_view, samples_per_pixel, ground, quality, tube_sides, spline, "
            "kolam_dots, derivation_diagram, glb_instancing, glb_compression, first, last, "
            "frames_per_step, fps, hold_seconds, turntable_degrees, stream. Notes and "
            "warnings are appended to `notes` when it is a list.")
        .def("with_defines", &withDefines, py::arg("defines"),
             "The same model read again with these #define constants overridden too "
             "({'R2': 0.8}); the overrides it was read with stay unless named again.")
        .def_property_readonly(
            "overrides", [](const ModelHandle& h) { return h.source->defines; },
            "the #define overrides it was read with")
        .def(py::pickle(&sourceState, &fromState))
        .def("__str__",
             [](const ModelHandle& h) {
                 std::ostringstream os;
                 os << *h.model;
                 return os.str();
             })
        .def("__repr__", [](const ModelHandle& h) {
            return "<graftal.Model '" + h.model->lsystem.name +
                   "' derivation_length=" + std::to_string(h.model->lsystem.derivationLength) + ">";
        });

    m.def("load", &load, py::arg("path"), py::kw_only(), py::arg("defines") = py::none(),
          py::arg("view") = py::none(), py::arg("functions") = py::none(),
          py::arg("random") = py::none(),
          "Reads a model: an .l file, or a model folder (its one .l file with its one .v "
          "view file). defines overrides #define constants ({'N': 4}, as -D N=4); view names "
          "a cpfg view file read after it. functions gives Python callables f(x) -> float "
          "for func(id, x): keyed by the id, or by a name the model gives one (a #define "
          "such as LIGHT whose value is the id, or an item of the view file's function set), "
          "or by a name its expressions call (light(x)); they are called during every "
          "derivation. random ('graftal' or 'cpfg') chooses "
          "whose random numbers its derivations draw, as `random:` in the file (a model "
          "read with a view file draws cpfg's unless it says otherwise). Raises "
          "graftal.ParseError when it does not parse; its warnings are in Model.warnings. A "
          "map L-system (a file that starts `map L-system:`) is a graftal.MapModel.");
    m.def("parse", &parseText, py::arg("text"), py::kw_only(), py::arg("file") = "",
          py::arg("defines") = py::none(), py::arg("view_text") = py::none(),
          py::arg("view_file") = "", py::arg("functions") = py::none(),
          py::arg("random") = py::none(),
          "Parses .l text (file names it in diagnostics and finds the files it names). "
          "view_text is a view file's text read after it; functions and random as for load(). "
          "Raises graftal.ParseError.");
    m.def(
        "export_formats",
        [] {
            py::list list;
            for (const ExportFormat& f : exportFormats()) {
                static const char* kinds[] = {"picture", "mesh", "animation", "music"};
                py::dict d;
                d["name"] = std::string(f.name);
                d["extension"] = std::string(f.extension);
                d["kind"] = kinds[static_cast<int>(f.kind)];
                d["description"] = std::string(f.description);
                d["binary"] = f.binary;
                d["file_only"] = f.fileOnly;
                list.append(d);
            }
            return list;
        },
        "Every format export() writes, from the library's registry: name, extension, kind "
        "(picture, mesh, animation, music), description, binary, file_only (a folder, or "
        "files beside it: a path is needed).");
}

}  // namespace graftal::python
