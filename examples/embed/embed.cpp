// A program that embeds graftal: parse an L-system, derive it, and write the picture
// `graftal render` would (ray traced for a 3D plant). Usage: embed PLANT.l OUT.png
#include <graftal/graftal.hpp>
#include <iostream>

int main(int argc, char** argv) try {
    if (argc != 3) return std::cerr << "usage: embed PLANT.l OUT.png\n", 2;
    graftal::ParseResult parsed = graftal::loadModel(argv[1]);
    if (!parsed.ok()) throw graftal::Error(parsed.errors());
    graftal::RenderRequest request;
    request.output = argv[2];
    request.picture.width = request.picture.height = 320;
    graftal::render(parsed.model, request);
} catch (const graftal::Error& e) {
    return std::cerr << e.what() << '\n', 1;
}
