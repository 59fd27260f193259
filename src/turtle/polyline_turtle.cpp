// The turtle writing polylines (polyline_scene.hpp): a sink that keeps a point per segment
// and a run per change of width or colour, and everything that is not a segment in a Scene.
#include "graftal/turtle/polyline_scene.hpp"

#include "graftal/core/huge_pages.hpp"
#include "planar_length.hpp"
#include "turtle_machine.hpp"

namespace graftal {

namespace {

class PolylineSink {
  public:
    explicit PolylineSink(PolylineScene& out) : out_(out), scene_(out.rest) {}

    std::uint32_t segment(const Segment& s) {
        auto& runs = out_.runs;
        if (out_.points.empty() || !(s.a == lastEnd_)) {
            if (!out_.points.empty()) runs.push_back({1, 0, 0, true});
            out_.points.push_back(s.a);
            if (isFinite(s.a)) out_.segmentBounds.extend(s.a);
        }
        if (!runs.empty() && !runs.back().jump && runs.back().width == s.width &&
            runs.back().color == s.color)
            ++runs.back().links;
        else
            runs.push_back({1, s.width, s.color, false});
        out_.points.push_back(s.b);
        if (isFinite(s.b)) out_.segmentBounds.extend(s.b);
        lastEnd_ = s.b;
        out_.ink += turtle::inkTerm(length_(s.b.x - s.a.x, s.b.y - s.a.y),
                                    turtle::inkWeight(s.width, scene_.baseWidth));
        return static_cast<std::uint32_t>(out_.segments++);
    }
    void polygon(std::span<const Vec3> v, std::uint16_t color) { scene_.addPolygon(v, color); }
    void surface(const std::string& name, const SurfaceInstance& s) { rest_.surface(name, s); }
    void disc(const Disc& d) { scene_.discs.push_back(d); }
    void sphere(const Sphere& s) { scene_.spheres.push_back(s); }
    void sweptTube(SweptTube t) { scene_.sweptTubes.push_back(std::move(t)); }
    void baseWidth(float w) { scene_.baseWidth = w; }
    void finish(bool is3D) { scene_.is3D = is3D; }

  private:
    PolylineScene& out_;
    Scene& scene_;
    turtle::SceneSink rest_{scene_};  // surfaces are named as interpret() names them
    Vec3 lastEnd_;
    turtle::PlanarLength length_;
};

}  // namespace

Bounds PolylineScene::bounds() const {
    Bounds b = segmentBounds;
    b.extend(rest.bounds());
    return b;
}

void PolylineScene::clear() {
    points.clear();
    runs.clear();
    segments = 0;
    segmentBounds = Bounds{};
    ink = 0;
    rest = Scene{};
}

void interpretPolylines(const Model& model, const ModuleString& modules, PolylineScene& out) {
    out.clear();
    // Room for every point at once: a segment per F or G, and a jump before each at most.
    // Growing the buffer instead would copy it into fresh pages several times, which costs
    // more than the walk; room never written costs no memory.
    const std::array<turtle::TurtleOp, kMaxSymbols> ops = turtle::opTable(model.lsystem);
    std::size_t forward = 0;
    for (Symbol s : modules.symbols())
        forward +=
            ops[s] == turtle::TurtleOp::Forward || ops[s] == turtle::TurtleOp::ForwardNoVertex;
    if (out.points.capacity() < 2 * forward + 1) {
        out.points = std::vector<Vec3>();
        out.points.reserve(2 * forward + 1);
        adviseHugePages(out.points);
    }
    PolylineSink sink(out);
    turtle::TurtleMachine<PolylineSink> machine(model.lsystem, model.view, sink);
    machine.run(modules);
}

}  // namespace graftal
