// Python callables where cpfg reads graphical functions: load(..., functions={"light": f})
// makes func(LIGHT, x) call f(x) during the derivation (LSystem::userFunctions, the library's
// hook). A key is the function's id (func(1, x)), or a name the model knows as one: a
// #define whose value is the id (cpfg defines each item of the view file's function set by
// its name), or the name of an item of the function set.
#include <cctype>

#include "bindings.hpp"

namespace graftal::python {

namespace {

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
int functionId(const Model& model, py::handle key) {
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
    throw py::value_error("functions: the model knows no function '" + name +
                          "' (name a #define whose value is func()'s id, an item of the view "
                          "file's function set" +
                          (known.empty() ? std::string(": it has none") : " (" + known + ")") +
                          ", or give the id as an int)");
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

std::shared_ptr<const std::vector<UserFunction>> userFunctionTable(const Model& model,
                                                                   const py::object& functions) {
    if (functions.is_none()) return nullptr;
    if (!py::isinstance<py::dict>(functions))
        throw py::type_error("functions: expected a dict such as {'light': f} or {1: f}");
    auto table = std::make_shared<std::vector<UserFunction>>();
    for (const auto& [key, value] : functions.cast<py::dict>()) {
        const int id = functionId(model, key);
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
