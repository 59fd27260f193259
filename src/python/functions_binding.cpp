// Python callables where cpfg reads graphical functions: load(..., functions={"light": f})
// makes func(LIGHT, x) call f(x) during the derivation (LSystem::userFunctions, the library's
// hook). A key is the function's id (func(1, x)), or a name the model knows as one: a
// #define whose value is the id (cpfg defines each item of the view file's function set by
// its name), or the name of an item of the function set; or a name the model calls, as
// L-Py's models call Python functions: light(x) in an expression is written func(id, x) by
// the preprocessor (a function-like macro), so the expression language itself is unchanged.
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "bindings.hpp"

namespace graftal::python {

namespace {

// The first id of the functions called by name: above every func() id a model gives by hand
// or through its view file's function set.
constexpr int kFirstNamedId = 1001;

bool identifierChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

bool isIdentifier(const std::string& name) {
    return !name.empty() && !std::isdigit(static_cast<unsigned char>(name[0])) &&
           std::all_of(name.begin(), name.end(), identifierChar);
}

// The model's own text: the file, the .l files of a model folder, or parse()'s text.
std::string sourceText(const ModelSource& source) {
    namespace fs = std::filesystem;
    if (source.path.empty()) return source.text;
    std::error_code error;
    std::vector<fs::path> files;
    if (fs::is_directory(source.path, error)) {
        for (const auto& entry : fs::directory_iterator(source.path, error))
            if (entry.path().extension() == ".l") files.push_back(entry.path());
    } else {
        files.push_back(source.path);
    }
    std::string text;
    for (const auto& file : files) {
        std::ifstream in(file, std::ios::binary);
        text.append(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
        text += '\n';
    }
    return text;
}

// Whether `text` calls `name(` (a whole word) and whether a line #defines it.
void findName(const std::string& text, const std::string& name, bool& called, bool& defined) {
    called = defined = false;
    for (std::size_t at = text.find(name); at != std::string::npos;
         at = text.find(name, at + 1)) {
        if (at > 0 && identifierChar(text[at - 1])) continue;
        std::size_t end = at + name.size();
        if (end < text.size() && identifierChar(text[end])) continue;
        std::size_t next = end;
        while (next < text.size() && (text[next] == ' ' || text[next] == '\t')) ++next;
        if (next < text.size() && text[next] == '(') called = true;
        // `#define name`: the word before is `define`, after a `#` that starts the line.
        std::size_t before = at;
        while (before > 0 && (text[before - 1] == ' ' || text[before - 1] == '\t')) --before;
        if (before >= 6 && text.compare(before - 6, 6, "define") == 0) {
            std::size_t hash = before - 6;
            while (hash > 0 && (text[hash - 1] == ' ' || text[hash - 1] == '\t')) --hash;
            if (hash > 0 && text[hash - 1] == '#') defined = true;
        }
    }
}

// "1", " 2 ", "3.0" -> the id; anything else -> 0.
int idFromText(const std::string& text) {
    std::size_t used = 0;
    double v = 0;
    try {
        v = std::stod(text, &used);
    } catch (const std::exception&) {
        return 0;
    }
    while (used < text.size() && std::isspace(static_cast<unsigned char>(text[used]))) ++used;
    if (used != text.size() || !(v >= 1) || v > 1e6 || v != static_cast<int>(v)) return 0;
    return static_cast<int>(v);
}

// The id `key` names in `model`; a ValueError says which names it knows when none.
int functionId(const Model& model, py::handle key, const NamedFunctions& named) {
    if (py::isinstance<py::int_>(key) && !py::isinstance<py::bool_>(key)) {
        const long long id = key.cast<long long>();
        if (id < 1 || id > 1000000)
            throw py::value_error("functions: the id " + std::to_string(id) +
                                  " is not a func() id (counted from 1)");
        return static_cast<int>(id);
    }
    if (!py::isinstance<py::str>(key))
        throw py::type_error("functions: a key is func()'s id (int) or a name (str)");
    const std::string name = key.cast<std::string>();
    const LSystem& ls = model.lsystem;
    if (const auto d = ls.defines.find(name); d != ls.defines.end()) {
        if (const int id = idFromText(d->second)) return id;
    }
    std::string known;
    for (std::size_t i = 0; i < ls.functions.size(); ++i) {
        std::string item = ls.functions[i].name();
        if (item.size() > 5 && item.ends_with(".func")) item.resize(item.size() - 5);
        if (item == name || ls.functions[i].name() == name) return static_cast<int>(i) + 1;
        if (!item.empty()) known += (known.empty() ? "" : ", ") + item;
    }
    if (const auto n = named.ids.find(name); n != named.ids.end()) return n->second;
    throw py::value_error("functions: the model knows no function '" + name +
                          "' (name a #define whose value is func()'s id, an item of the view "
                          "file's function set" +
                          (known.empty() ? std::string(": it has none") : " (" + known + ")") +
                          ", a name its expressions call as " + name +
                          "(x), or give the id as an int)");
}

// How the error of a callable reads: "the Python function light raised ValueError: ...".
std::string failure(const std::string& label, py::error_already_set& e) {
    std::string type = "exception";
    std::string text;
    try {
        type = py::str(e.type().attr("__name__")).cast<std::string>();
        text = py::str(e.value()).cast<std::string>();
    } catch (const std::exception&) {
    }
    return "the Python function " + label + " raised " + type + (text.empty() ? "" : ": " + text);
}

UserFunction callableFunction(py::object callable, std::string label) {
    std::shared_ptr<py::object> held = heldForThreads(std::move(callable));
    return [held, label](double x) -> double {
        py::gil_scoped_acquire gil;
        py::object result;
        try {
            result = (*held)(x);
        } catch (py::error_already_set& e) {
            const std::string message = failure(label, e);
            rememberCause(e.value(), message);
            throw Error(SourceLocation{}, message);
        }
        // A number (a NumPy scalar too); not a str float() would read, nor a bool.
        if (PyNumber_Check(result.ptr()) && !py::isinstance<py::bool_>(result)) {
            const double y = PyFloat_AsDouble(result.ptr());
            if (!PyErr_Occurred()) return y;
            PyErr_Clear();
        }
        throw Error(SourceLocation{}, "the Python function " + label + " returned " +
                                          py::repr(result).cast<std::string>() + ", not a number");
    };
}

}  // namespace

std::shared_ptr<py::object> heldForThreads(py::object object) {
    return std::shared_ptr<py::object>(new py::object(std::move(object)), [](py::object* p) {
        if (Py_IsInitialized()) {
            py::gil_scoped_acquire gil;
            delete p;
        } else {
            p->release();  // the interpreter is gone: nothing to give it back to
            delete p;
        }
    });
}

NamedFunctions namedFunctions(const ModelSource& source) {
    NamedFunctions named;
    if (!source.functions) return named;
    std::string text;
    bool read = false;
    for (const auto& [key, value] : source.functions->cast<py::dict>()) {
        if (!py::isinstance<py::str>(key)) continue;
        const std::string name = key.cast<std::string>();
        if (!isIdentifier(name) || source.defines.count(name)) continue;
        if (!read) text = sourceText(source), read = true;
        bool called = false, defined = false;
        findName(text, name, called, defined);
        if (!called || defined) continue;
        const int id = kFirstNamedId + static_cast<int>(named.ids.size());
        named.ids[name] = id;
        named.macros[name + "(x)"] = "func(" + std::to_string(id) + ",x)";
    }
    return named;
}

std::shared_ptr<const std::vector<UserFunction>> userFunctionTable(const Model& model,
                                                                   const py::object& functions,
                                                                   const NamedFunctions& named) {
    if (functions.is_none()) return nullptr;
    if (!py::isinstance<py::dict>(functions))
        throw py::type_error("functions: expected a dict such as {'light': f} or {1: f}");
    auto table = std::make_shared<std::vector<UserFunction>>();
    for (const auto& [key, value] : functions.cast<py::dict>()) {
        const int id = functionId(model, key, named);
        const std::string label =
            py::isinstance<py::str>(key) ? key.cast<std::string>() : "func " + std::to_string(id);
        if (!PyCallable_Check(value.ptr()))
            throw py::type_error("functions['" + label + "']: expected a callable f(x) -> float");
        if (table->size() < static_cast<std::size_t>(id)) table->resize(id);
        table->at(id - 1) = callableFunction(py::reinterpret_borrow<py::object>(value), label);
    }
    return table;
}

}  // namespace graftal::python
