// An environment written in Python: the library's Environment interface
// (rewrite/environment.hpp) answered by a Python object, as cpfg's environmental processes
// and L-Py's Python code answer communication modules. After every step (and for the
// axiom) the derivation hands it every ?E module in string order; it sees them as NumPy
// arrays (the turtle's frame at each, the parameters) and writes its answers into the
// parameters.
#include "bindings.hpp"
#include "graftal/rewrite/environment.hpp"

namespace graftal::python {

namespace {

class PythonEnvironment : public Environment {
  public:
    explicit PythonEnvironment(py::object object) : object_(std::move(object)) {}
    ~PythonEnvironment() override {
        py::gil_scoped_acquire gil;
        object_ = py::object();
    }

    std::string name() const override { return "python"; }

    void respond(int step, std::span<CommunicationRequest> requests) override {
        py::gil_scoped_acquire gil;
        const auto n = static_cast<py::ssize_t>(requests.size());
        py::array_t<std::int64_t> index(n);
        py::array_t<double> position({n, py::ssize_t(3)}), heading({n, py::ssize_t(3)}),
            left({n, py::ssize_t(3)}), up({n, py::ssize_t(3)});
        std::size_t width = requests.empty() ? 0 : requests[0].params.size();
        bool rectangular = true;
        for (const CommunicationRequest& r : requests)
            rectangular = rectangular && r.params.size() == width;
        auto put = [](py::array_t<double>& a, py::ssize_t i, const Vec3& v) {
            double* p = a.mutable_data(i, 0);
            p[0] = v.x, p[1] = v.y, p[2] = v.z;
        };
        py::object parameters;
        py::list ragged;
        py::array_t<double> table(
            {rectangular ? n : py::ssize_t(0), py::ssize_t(rectangular ? width : 0)});
        for (py::ssize_t i = 0; i < n; ++i) {
            const CommunicationRequest& r = requests[static_cast<std::size_t>(i)];
            index.mutable_data()[i] = static_cast<std::int64_t>(r.module);
            put(position, i, r.frame.position);
            put(heading, i, r.frame.heading);
            put(left, i, r.frame.left);
            put(up, i, r.frame.up);
            if (rectangular) {
                std::copy(r.params.begin(), r.params.end(), table.mutable_data(i, 0));
            } else {
                py::array_t<double> row(py::ssize_t(r.params.size()));
                std::copy(r.params.begin(), r.params.end(), row.mutable_data());
                ragged.append(row);
            }
        }
        if (rectangular)
            parameters = table;
        else
            parameters = ragged;
        py::object queries = py::module_::import("types").attr("SimpleNamespace")(
            py::arg("step") = step, py::arg("index") = index, py::arg("position") = position,
            py::arg("heading") = heading, py::arg("left") = left, py::arg("up") = up,
            py::arg("parameters") = parameters);
        py::object answer = py::hasattr(object_, "respond") ? object_.attr("respond")(step, queries)
                                                            : object_(step, queries);
        if (answer.is_none()) answer = queries.attr("parameters");
        writeBack(answer, requests);
    }

  private:
    // The answers into the modules' parameters: a (modules, parameters) array, or one
    // sequence per module. Each module keeps the parameters it had past those answered.
    static void writeBack(py::handle answer, std::span<CommunicationRequest> requests) {
        if (!py::isinstance<py::array>(answer) && py::isinstance<py::sequence>(answer)) {
            py::sequence list = py::reinterpret_borrow<py::sequence>(answer);
            if (py::len(list) != requests.size())
                throw py::value_error("the environment answered " + std::to_string(py::len(list)) +
                                      " modules; the string has " +
                                      std::to_string(requests.size()) + " ?E modules");
            for (std::size_t i = 0; i < requests.size(); ++i) {
                std::vector<double> row;
                try {
                    row = list[i].cast<std::vector<double>>();
                } catch (const py::cast_error&) {
                    throw py::type_error("the environment's answer for ?E module " +
                                         std::to_string(i) + ": expected a sequence of numbers");
                }
                auto& params = requests[i].params;
                std::copy_n(row.begin(), std::min(row.size(), params.size()), params.begin());
            }
            return;
        }
        auto values =
            py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(answer);
        if (!values || values.ndim() != 2 || std::size_t(values.shape(0)) != requests.size())
            throw py::value_error(
                "the environment's answer: expected an array of shape (modules, parameters) "
                "with one row per ?E module (" +
                std::to_string(requests.size()) + "), or None");
        const std::size_t width = std::size_t(values.shape(1));
        for (std::size_t i = 0; i < requests.size(); ++i) {
            auto& params = requests[i].params;
            std::copy_n(values.data(py::ssize_t(i), 0), std::min(width, params.size()),
                        params.begin());
        }
    }

    py::object object_;
};

}  // namespace

std::shared_ptr<Environment> pythonEnvironment(py::object environment) {
    return std::make_shared<PythonEnvironment>(std::move(environment));
}

}  // namespace graftal::python
