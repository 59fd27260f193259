// Turtle interpretation of a whole module string (see turtle_machine.hpp).
#include "graftal/turtle.hpp"

#include "turtle_machine.hpp"

namespace graftal {

Scene interpret(const LSystem& lsystem, const ModuleString& modules) {
    Scene scene;
    turtle::SceneSink sink(scene);
    turtle::TurtleMachine<turtle::SceneSink> machine(lsystem, sink);
    machine.run(modules);
    return scene;
}

void traceTurtle(const LSystem& lsystem, const ModuleString& modules,
                 const std::vector<bool>& wanted,
                 const std::function<void(std::size_t, const TurtleFrame&)>& visit) {
    turtle::NullSink sink;
    turtle::TurtleMachine<turtle::NullSink> machine(lsystem, sink);
    machine.run(modules, &wanted, &visit);
}

}  // namespace graftal
