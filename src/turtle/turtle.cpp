// Turtle interpretation of a whole module string (see turtle_machine.hpp).
#include "graftal/turtle/turtle.hpp"

#include "graftal/core/huge_pages.hpp"
#include "turtle_machine.hpp"

namespace graftal {

namespace {

// At most one segment per F or G: the segments' room, reserved at once. Growing the vector
// instead would copy every segment several times into fresh pages, which cost more than
// the walk (a reservation beyond what is drawn is never touched, so it costs no memory).
std::size_t segmentsAtMost(const LSystem& lsystem, const ModuleString& modules) {
    const std::array<turtle::TurtleOp, kMaxSymbols> ops = turtle::opTable(lsystem);
    std::size_t n = 0;
    for (Symbol s : modules.symbols())
        n += ops[s] == turtle::TurtleOp::Forward || ops[s] == turtle::TurtleOp::ForwardNoVertex;
    return n;
}

}  // namespace

Scene interpret(const Model& model, const ModuleString& modules) {
    return interpret(model.lsystem, model.view, modules);
}

Scene interpret(const LSystem& lsystem, const ViewSettings& view, const ModuleString& modules) {
    Scene scene;
    scene.widthsInModelUnits = view.materials.widthsInModelUnits;
    scene.segments.reserve(segmentsAtMost(lsystem, modules));
    adviseHugePages(scene.segments);
    turtle::SceneSink sink(scene);
    turtle::TurtleMachine<turtle::SceneSink> machine(lsystem, view, sink);
    machine.run(modules);
    return scene;
}

void traceTurtle(const Model& model, const ModuleString& modules, const std::vector<bool>& wanted,
                 const std::function<void(std::size_t, const TurtleFrame&)>& visit) {
    traceTurtle(model.lsystem, model.view, modules, wanted, visit);
}

void traceTurtle(const LSystem& lsystem, const ViewSettings& view, const ModuleString& modules,
                 const std::vector<bool>& wanted,
                 const std::function<void(std::size_t, const TurtleFrame&)>& visit) {
    turtle::NullSink sink;
    turtle::TurtleMachine<turtle::NullSink> machine(lsystem, view, sink);
    machine.run(modules, &wanted, &visit);
}

QueryResolver turtleQueryResolver(ViewSettings view) {
    return [view = std::move(view)](
               const LSystem& lsystem, const ModuleString& modules, const std::vector<bool>& wanted,
               const std::function<void(std::size_t, const TurtleFrame&)>& visit) {
        traceTurtle(lsystem, view, modules, wanted, visit);
    };
}

ModuleString deriveWithQueries(const LSystem& lsystem, int steps, DerivationOptions options) {
    if (!options.queryResolver) options.queryResolver = turtleQueryResolver();
    return derive(lsystem, steps, std::move(options));
}

ModuleString deriveWithQueries(const Model& model, int steps, DerivationOptions options) {
    if (!options.queryResolver) options.queryResolver = turtleQueryResolver(model.view);
    return derive(model.lsystem, steps, std::move(options));
}

}  // namespace graftal
