// The graftal extension module (graftal._graftal), which the package graftal (python/graftal/)
// re-exports with its pure-Python helpers: the parts are bound in the order they refer to
// each other.
#include "bindings.hpp"
#include "graftal/core/freed_memory.hpp"

PYBIND11_MODULE(_graftal, m) {
    using namespace graftal::python;
    m.doc() = "graftal's library: models, derivations, scenes, meshes and exports";
    // A notebook or a sweep derives again and again in one process.
    graftal::keepFreedMemoryForReuse();
    bindErrors(m);
    bindModel(m);
    bindModuleString(m);
    bindDerivation(m);
    bindGeometry(m);
    bindMaps(m);
}
