// What the Python module's files share: the objects Python holds (a parsed model, a derived
// string, a scene, a mesh), the settings a call's keyword arguments make into the pipeline's
// requests, and running library work with the GIL released and Ctrl-C turned into the
// library's cancellation. The module is a front end: everything it makes comes from the
// pipeline's stages (stages.hpp, statistics.hpp) and export registry (export.hpp).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

#include "graftal/core/cancellation.hpp"
#include "graftal/core/diagnostics.hpp"
#include "graftal/core/module_string.hpp"
#include "graftal/geometry/mesh_scene.hpp"
#include "graftal/geometry/scene.hpp"
#include "graftal/lang/model.hpp"
#include "graftal/pipeline/export.hpp"
#include "graftal/pipeline/pipeline.hpp"

namespace graftal::python {

namespace py = pybind11;

// How to derive, as derive()'s keyword arguments say: the pipeline's DeriveRequest less its
// callbacks, plus the Python environment (an object answering ?E modules) it keeps alive.
struct DeriveSettings {
    std::optional<int> steps;
    std::optional<std::uint64_t> seed;
    unsigned threads = 0;
    std::size_t memoryLimit = std::size_t(2) << 30;
    Precision precision = Precision::Single;
    std::optional<RandomStreams> random;  // random='cpfg' or 'graftal'; none: the model's
    py::object environment;               // None: the file's `environment:` lines
};

// The pipeline's request for these settings, cancelled through `cancel`.
DeriveRequest deriveRequest(const DeriveSettings& settings, const CancellationToken& cancel);
// The settings from derive()'s arguments (steps, seed, threads, memory_limit, precision,
// environment); checks what Python alone can get wrong (a size's unit, a precision's name).
DeriveSettings deriveSettings(py::object steps, py::object seed, unsigned threads,
                              py::object memoryLimit, const std::string& precision,
                              py::object environment, py::object random);
// random='graftal' or 'cpfg' (as `--random`); None: nothing chosen.
std::optional<RandomStreams> randomStreams(const py::object& random);

// export()'s options (everything but the derivation's settings) into `request`; an unknown
// keyword is a TypeError naming the known ones.
void applyExportOptions(ExportRequest& request, const py::dict& options);

// Where export() writes: to `path` (a str or os.PathLike) or, with none, into `bytes`, named
// `stem` and the format's extension; format= (a str) sets the request's format first.
// `example` is the format a message suggests when neither is given.
Destination exportDestination(ExportRequest& request, const py::object& path,
                              const py::object& format, std::string& bytes,
                              const std::string& stem, const char* example);

// Where a model came from: enough to read it again (with other defines, or in another
// process: a Model pickles as its source, which is how a sweep sends it to Dask's workers).
struct ModelSource {
    std::string path;  // load(): the file or folder; empty for parse()
    std::string text;  // parse(): the text, `file` naming it
    std::string file;
    std::optional<std::string> view;  // load(): a view file's path; parse(): its text
    std::string viewFile;             // parse(): the view file's name
    std::map<std::string, std::string> defines;
    std::optional<RandomStreams> random;  // load(random=...): overrides the model's
    // load(functions=...): the dict of callables for func(id, x), or None.
    std::shared_ptr<py::object> functions;
};

// A parsed model, shared by everything derived from it.
struct ModelHandle {
    std::shared_ptr<const Model> model;
    std::vector<Diagnostic> warnings;  // the parse's warnings and notes, returned not printed
    std::shared_ptr<const ModelSource> source;
};

// A derived string and how it was made (for pictures of it and its scene).
struct DerivedString {
    std::shared_ptr<const Model> model;
    std::shared_ptr<const ModelSource> source;
    DeriveSettings settings;
    ModuleString modules;
    int steps = 0;
};

// A scene the turtle drew of a derived string, with how it was made.
struct SceneHandle {
    std::shared_ptr<const Model> model;
    std::shared_ptr<const ModelSource> source;
    DeriveSettings settings;
    int steps = 0;
    Scene scene;
};

// A meshed scene, its placements copied in (one mesh: vertices, normals, triangles).
struct MeshHandle {
    Mesh mesh;
};

// Runs `work` on a thread of its own with the GIL released, while the calling thread waits
// and looks for signals (PyErr_CheckSignals) every 50 ms. Ctrl-C cancels `cancel`: the work
// stops at its next check (as the command's Ctrl-C would), and the signal's exception
// (KeyboardInterrupt) is raised. Python code the work calls back (an environment) takes the
// GIL itself.
template <class F>
auto interruptible(CancellationToken cancel, F&& work) -> decltype(work()) {
    using Result = decltype(work());
    using Stored = std::conditional_t<std::is_void_v<Result>, bool, Result>;
    std::optional<Stored> result;
    std::exception_ptr failure;
    std::mutex mutex;
    std::condition_variable doneChanged;
    bool done = false;
    std::thread worker([&] {
        try {
            if constexpr (std::is_void_v<Result>) {
                work();
                result.emplace(true);
            } else {
                result.emplace(work());
            }
        } catch (...) {
            failure = std::current_exception();
        }
        std::lock_guard lock(mutex);
        done = true;
        doneChanged.notify_all();
    });
    bool interrupted = false;
    for (;;) {
        {
            py::gil_scoped_release release;
            std::unique_lock lock(mutex);
            if (doneChanged.wait_for(lock, std::chrono::milliseconds(50), [&] { return done; }))
                break;
        }
        if (PyErr_CheckSignals() != 0) {
            interrupted = true;
            cancel.cancel();
            break;
        }
    }
    {
        py::gil_scoped_release release;
        worker.join();
    }
    if (interrupted) throw py::error_already_set();
    if (failure) std::rethrow_exception(failure);
    if constexpr (!std::is_void_v<Result>) return std::move(*result);
}

// defines= as the library's overrides: names to text ({'N': 3} is N=3); a TypeError for
// anything but str names and number or str values.
std::map<std::string, std::string> defineMap(const py::object& defines);

// The keywords that derive the same string again (export(**keywords) draws it).
py::dict deriveKeywords(const DeriveSettings& settings, int steps);

// The parts of the module, each in its own file.
void bindErrors(py::module_& m);
void bindModel(py::module_& m);
void bindModuleString(py::module_& m);
void bindDerivation(py::module_& m);
void bindGeometry(py::module_& m);
void bindMaps(py::module_& m);

// Map L-systems (map_binding.cpp): whether a source is one (text starting `map L-system:`),
// and the graftal.MapModel it reads as.
bool isMapSource(const ModelSource& source);
py::object loadMapModel(ModelSource source);

// The Python environment object as the library's Environment (environment_binding.cpp).
std::shared_ptr<Environment> pythonEnvironment(py::object environment);

// Callables called by their own names in a model's expressions (light(x)): each name of
// `functions` that the model's text calls and does not #define becomes a function-like
// macro `light(x)` -> `func(id, x)` with an id of its own, given to the preprocessor with
// the overrides (functions_binding.cpp).
struct NamedFunctions {
    std::map<std::string, std::string> macros;  // "light(x)" -> "func(1001,x)"
    std::map<std::string, int> ids;             // "light" -> 1001
};
NamedFunctions namedFunctions(const ModelSource& source);

// Python callables as the model's functions for func(id, x) (functions_binding.cpp): the
// keys are func()'s ids, names the model gives them, or names it calls (`named`); None: no
// table.
std::shared_ptr<const std::vector<UserFunction>> userFunctionTable(const Model& model,
                                                                   const py::object& functions,
                                                                   const NamedFunctions& named);
// A Python object that any thread may hold: the last owner releases it with the GIL.
std::shared_ptr<py::object> heldForThreads(py::object object);
// The exception a Python callable raised while the library ran (the GIL held): the
// graftal.Error whose message contains `message` gets it as its __cause__ (errors.cpp).
void rememberCause(py::handle exception, const std::string& message);

// A diagnostic list as Python Diagnostic objects.
py::list diagnosticList(const std::vector<Diagnostic>& diagnostics);
// Raises graftal.ParseError with these diagnostics (the parse's errors).
[[noreturn]] void raiseParseError(const std::vector<Diagnostic>& diagnostics);

// A read-only NumPy array over `count` elements at `data` (no copy), kept alive by `owner`.
template <class T>
py::array viewOf(const T* data, std::size_t count, py::handle owner) {
    static const T empty{};
    py::array a(py::dtype::of<T>(), {count}, {sizeof(T)}, data ? data : &empty, owner);
    py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
    return a;
}

// Scenes and meshes (geometry_binding.cpp).
SceneHandle sceneOf(const DerivedString& derived);
MeshHandle meshOf(const SceneHandle& scene, int tubeSides);

}  // namespace graftal::python
