// graftal.Derivation: a derivation step by step, as a Python iterator. It yields the
// axiom's string, then the string after every step up to `steps`, each a ModuleString of
// its own (the library's next step reuses its buffers, so a step's string is copied out).
// It derives with the options the pipeline gives every derivation (derivationOptions()).
#include "bindings.hpp"
#include "graftal/rewrite/derivation.hpp"

namespace graftal::python {

namespace {

class SteppedDerivation {
  public:
    SteppedDerivation(const ModelHandle& h, DeriveSettings settings)
        : model_(h.model), source_(h.source), settings_(std::move(settings)) {
        request_ = deriveRequest(settings_, cancel_);
        last_ = requestedSteps(*model_, request_);
        derivation_ = interruptible(cancel_, [&] {
            return std::make_unique<Derivation>(*model_, derivationOptions(*model_, request_));
        });
    }
    ~SteppedDerivation() {
        // The derivation may hold the Python environment: let it go with the GIL held.
        derivation_.reset();
        request_ = DeriveRequest{};
    }

    // The next string: the axiom's first, then one step more each time.
    DerivedString next() {
        if (!started_) {
            started_ = true;
            return current();
        }
        if (derivation_->stepsDone() >= last_) throw py::stop_iteration();
        step();
        return current();
    }

    void step() {
        interruptible(cancel_, [&] {
            derivation_->step();
            // After the last step the End: block runs, as derive() runs it.
            if (derivation_->stepsDone() == last_) derivation_->finish();
        });
        started_ = true;
    }

    DerivedString current() const {
        DerivedString d;
        d.model = model_;
        d.source = source_;
        d.settings = settings_;
        d.steps = derivation_->stepsDone();
        d.modules = derivation_->current();
        return d;
    }

    int stepsDone() const { return derivation_->stepsDone(); }
    int last() const { return last_; }

  private:
    std::shared_ptr<const Model> model_;
    std::shared_ptr<const ModelSource> source_;
    DeriveSettings settings_;
    CancellationToken cancel_;
    DeriveRequest request_;
    int last_ = 0;
    bool started_ = false;
    std::unique_ptr<Derivation> derivation_;
};

}  // namespace

void bindDerivation(py::module_& m) {
    py::class_<SteppedDerivation>(m, "Derivation",
                                  "A derivation step by step: iterating yields the axiom's "
                                  "ModuleString (step 0), then the string after each step up "
                                  "to `steps`. Made by Model.derivation().")
        .def("__iter__", [](py::object self) { return self; })
        .def("__next__", &SteppedDerivation::next)
        .def("step", &SteppedDerivation::step,
             "One more step (past `steps` too); the current string is then .current")
        .def_property_readonly("current", &SteppedDerivation::current,
                               "the current string (a copy of it)")
        .def_property_readonly("steps_done", &SteppedDerivation::stepsDone, "the steps done so far")
        .def_property_readonly("steps", &SteppedDerivation::last, "the step the iteration stops at")
        .def("__repr__", [](const SteppedDerivation& d) {
            return "<graftal.Derivation " + std::to_string(d.stepsDone()) + " of " +
                   std::to_string(d.last()) + " steps>";
        });

    // Model.derivation(): defined here, beside the class it returns.
    py::class_<ModelHandle> model = m.attr("Model");
    model.def(
        "derivation",
        [](const ModelHandle& h, py::object steps, py::object seed, unsigned threads,
           py::object memoryLimit, const std::string& precision, py::object environment,
           py::object random) {
            return std::make_unique<SteppedDerivation>(
                h, deriveSettings(steps, seed, threads, memoryLimit, precision,
                                  std::move(environment), std::move(random)));
        },
        py::arg("steps") = py::none(), py::kw_only(), py::arg("seed") = py::none(),
        py::arg("threads") = 0u, py::arg("memory_limit") = py::none(),
        py::arg("precision") = "single", py::arg("environment") = py::none(),
        py::arg("random") = py::none(),
        "The derivation step by step (graftal.Derivation): `for s in model.derivation(5)` "
        "yields the strings of steps 0 to 5. Same arguments as derive().");
}

}  // namespace graftal::python
