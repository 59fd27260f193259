// graftal.ModuleString: a derived string. It prints as `graftal derive` prints it, and lends
// its storage to NumPy without a copy (the buffer protocol gives the symbol ids; symbols,
// parameter_offsets and parameters are read-only arrays over the library's own buffers,
// alive as long as the ModuleString).
#include <algorithm>

#include "bindings.hpp"
#include "graftal/pipeline/stages.hpp"

namespace graftal::python {

namespace {

py::tuple moduleAt(const DerivedString& d, py::ssize_t index) {
    const auto n = static_cast<py::ssize_t>(d.modules.size());
    if (index < 0) index += n;
    if (index < 0 || index >= n) throw py::index_error("module index out of range");
    const auto i = static_cast<std::size_t>(index);
    const ParamView params = d.modules.params(i);
    py::tuple values(params.size());
    for (std::size_t k = 0; k < params.size(); ++k) values[k] = params[k];
    return py::make_tuple(d.model->lsystem.symbols.name(d.modules.symbol(i)), values);
}

}  // namespace

void bindModuleString(py::module_& m) {
    py::class_<DerivedString>(m, "ModuleString", py::buffer_protocol(),
                              "A derived module string. str() is the string as `graftal "
                              "derive` prints it; len() its modules; ms[i] a module as "
                              "(name, parameters). symbols, parameter_offsets and parameters "
                              "are NumPy arrays over the library's storage (no copy); "
                              "memoryview(ms) gives the symbol ids through the buffer "
                              "protocol.")
        .def_buffer([](DerivedString& d) {
            static const Symbol empty = 0;
            const Symbol* data = d.modules.empty() ? &empty : d.modules.symbols().data();
            return py::buffer_info(const_cast<Symbol*>(data), sizeof(Symbol),
                                   py::format_descriptor<Symbol>::format(), 1, {d.modules.size()},
                                   {sizeof(Symbol)}, true);
        })
        .def_property_readonly(
            "steps", [](const DerivedString& d) { return d.steps; }, "the derivation steps it took")
        .def("__len__", [](const DerivedString& d) { return d.modules.size(); })
        .def("__getitem__", &moduleAt)
        .def("__str__",
             [](const DerivedString& d) { return d.modules.toString(d.model->lsystem.symbols); })
        .def("__repr__",
             [](const DerivedString& d) {
                 return "<graftal.ModuleString steps=" + std::to_string(d.steps) +
                        " modules=" + std::to_string(d.modules.size()) + ">";
             })
        .def_property_readonly(
            "symbols",
            [](py::object self) {
                const auto& d = self.cast<const DerivedString&>();
                return viewOf(d.modules.symbols().data(), d.modules.size(), self);
            },
            "the symbol id of every module (uint8, Model.symbols names them); no copy")
        .def_property_readonly(
            "parameter_offsets",
            [](py::object self) -> py::array {
                const auto& d = self.cast<const DerivedString&>();
                const auto& starts = d.modules.paramStarts();
                // A string without parameters stores no offsets: every module's are empty.
                if (starts.empty()) {
                    py::array_t<std::uint32_t> zeros(py::ssize_t(d.modules.size() + 1));
                    std::fill(zeros.mutable_data(), zeros.mutable_data() + zeros.size(), 0u);
                    return zeros;
                }
                return viewOf(starts.data(), starts.size(), self);
            },
            "len()+1 offsets (uint32): module i's parameters are "
            "parameters[offsets[i]:offsets[i+1]]; no copy (zeros when no module has any)")
        .def_property_readonly(
            "parameters",
            [](py::object self) -> py::array {
                const auto& d = self.cast<const DerivedString&>();
                if (d.modules.precision() == Precision::Single)
                    return viewOf(d.modules.floatParams().data(), d.modules.paramCount(), self);
                return viewOf(d.modules.doubleParams().data(), d.modules.paramCount(), self);
            },
            "every module's parameters in one flat array: float32 (precision 'single', the "
            "default) or float64; no copy")
        .def_property_readonly(
            "derive_keywords",
            [](const DerivedString& d) { return deriveKeywords(d.settings, d.steps); },
            "steps, seed, threads, memory_limit and environment as derive() took them: "
            "model.export(**derive_keywords) draws this string")
        .def_property_readonly(
            "model",
            [](const DerivedString& d) {
                return ModelHandle{d.model, {}, d.source};
            },
            "the Model it was derived from")
        .def(
            "symbol_counts",
            [](const DerivedString& d) {
                std::vector<std::uint64_t> counts;
                {
                    py::gil_scoped_release release;
                    counts = countSymbols(d.modules, d.model->lsystem.symbols.size(),
                                          d.settings.threads);
                }
                py::dict out;
                std::vector<std::pair<std::string, std::uint64_t>> present;
                for (std::size_t s = 0; s < counts.size(); ++s)
                    if (counts[s])
                        present.emplace_back(d.model->lsystem.symbols.name(static_cast<Symbol>(s)),
                                             counts[s]);
                std::sort(present.begin(), present.end());
                for (const auto& [name, count] : present) out[py::str(name)] = count;
                return out;
            },
            "how many modules of each name the string holds (names in order)")
        .def(
            "scene", [](const DerivedString& d) { return sceneOf(d); },
            "What the turtle draws of it (after the homomorphism), as every front end draws "
            "it (the pipeline's drawn()): a graftal.Scene of NumPy arrays.")
        .def(
            "__eq__",
            [](const DerivedString& a, const DerivedString& b) { return a.modules == b.modules; },
            py::is_operator());
}

}  // namespace graftal::python
