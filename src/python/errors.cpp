// graftal's errors in Python: graftal.Error (and graftal.ParseError for a model that does
// not parse) carrying the library's diagnostics, worded as the command words them
// (Diagnostic::toString, "file:line:column: error: message") with the request's fields and
// remedies named as the keyword arguments that set them (memoryLimit -> memory_limit).
#include <cctype>

#include "bindings.hpp"

namespace graftal::python {

namespace {

// The Python classes, made once when the module is imported (they live as long as it).
PyObject* errorType = nullptr;
PyObject* parseErrorType = nullptr;

// A request's field as the keyword argument that sets it: camelCase to snake_case.
std::string keywordOf(const std::string& field) {
    std::string k;
    for (char c : field) {
        if (std::isupper(static_cast<unsigned char>(c))) {
            k += '_';
            k += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        } else {
            k += c;
        }
    }
    return k;
}

std::string remedyAsKeyword(Remedy r) {
    switch (r) {
        case Remedy::LowerSteps:
            return "lower steps";
        case Remedy::RaiseMemoryLimit:
            return "raise memory_limit";
        case Remedy::Stream:
            return "pass stream=True";
        case Remedy::RaiseStreamLimit:
            return "raise stream_limit";
    }
    return {};
}

const char* severityName(Severity s) {
    return s == Severity::Error ? "error" : s == Severity::Warning ? "warning" : "note";
}

// One diagnostic as Python sees it.
struct PyDiagnostic {
    std::string severity, file, message, text;
    int line = 0, column = 0, endLine = 0, endColumn = 0;
};

PyDiagnostic toPython(const Diagnostic& d) {
    return {severityName(d.severity),
            d.location.file,
            d.message,
            d.toString(remedyAsKeyword, keywordOf),
            d.location.line,
            d.location.column,
            d.location.endLine,
            d.location.endColumn};
}

std::string joined(const std::vector<Diagnostic>& diagnostics) {
    std::string text;
    for (const Diagnostic& d : diagnostics) {
        if (!text.empty()) text += '\n';
        text += d.toString(remedyAsKeyword, keywordOf);
    }
    return text;
}

// The exception of a Python callable the library called (rememberCause), and the words its
// error carries. Raw references: they never outlive the interpreter's GIL.
PyObject* pendingCause = nullptr;
std::string pendingMessage;

[[noreturn]] void raise(PyObject* type, const std::vector<Diagnostic>& diagnostics) {
    const std::string text = joined(diagnostics);
    py::object error =
        py::reinterpret_steal<py::object>(PyObject_CallFunction(type, "s", text.c_str()));
    if (!error) throw py::error_already_set();
    error.attr("diagnostics") = diagnosticList(diagnostics);
    if (pendingCause) {
        py::object cause = py::reinterpret_steal<py::object>(pendingCause);
        pendingCause = nullptr;
        if (text.find(pendingMessage) != std::string::npos) error.attr("__cause__") = cause;
    }
    PyErr_SetObject(type, error.ptr());
    throw py::error_already_set();
}

}  // namespace

void rememberCause(py::handle exception, const std::string& message) {
    Py_XDECREF(pendingCause);
    pendingCause = exception.inc_ref().ptr();
    pendingMessage = message;
}

py::list diagnosticList(const std::vector<Diagnostic>& diagnostics) {
    py::list list;
    for (const Diagnostic& d : diagnostics) list.append(py::cast(toPython(d)));
    return list;
}

void raiseParseError(const std::vector<Diagnostic>& diagnostics) {
    raise(parseErrorType, diagnostics);
}

void bindErrors(py::module_& m) {
    py::class_<PyDiagnostic>(m, "Diagnostic",
                             "A problem (or a warning, or a note) at a place in a file: what "
                             "graftal says, with its file, 1-based line and column and where "
                             "the offending text ends (0 when unknown).")
        .def_readonly("severity", &PyDiagnostic::severity, "'error', 'warning' or 'note'")
        .def_readonly("file", &PyDiagnostic::file, "the file's name ('' for text)")
        .def_readonly("line", &PyDiagnostic::line, "1-based; 0 for the file as a whole")
        .def_readonly("column", &PyDiagnostic::column, "1-based, in bytes")
        .def_readonly("end_line", &PyDiagnostic::endLine, "where the offending text ends")
        .def_readonly("end_column", &PyDiagnostic::endColumn, "just past its last byte")
        .def_readonly("message", &PyDiagnostic::message, "the message alone")
        .def("__str__", [](const PyDiagnostic& d) { return d.text; })
        .def("__repr__",
             [](const PyDiagnostic& d) { return "<graftal.Diagnostic " + d.text + ">"; });

    errorType = PyErr_NewExceptionWithDoc(
        "graftal.Error",
        "An error of graftal's: its message is every diagnostic as the graftal command prints "
        "it, and .diagnostics lists them (file, line, column, end_line, end_column, message).",
        PyExc_Exception, nullptr);
    parseErrorType = PyErr_NewExceptionWithDoc(
        "graftal.ParseError",
        "A model that does not parse: .diagnostics holds every error the parser found.", errorType,
        nullptr);
    m.attr("Error") = py::handle(errorType);
    m.attr("ParseError") = py::handle(parseErrorType);

    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const Error& e) {
            try {
                raise(errorType, e.diagnostics());
            } catch (py::error_already_set& set) {
                set.restore();
            }
        } catch (const py::cast_error& e) {
            // A value of the wrong type met where the module converts it: a TypeError, as
            // Python raises for its own functions.
            PyErr_SetString(PyExc_TypeError, e.what());
        }
    });
}

}  // namespace graftal::python
