// The `obstacles` environment: solid spheres, boxes and half-spaces declared in the file.
// Each ?E learns whether it is inside (or near) one, how far away the nearest surface is and
// which way leads out of it.
#include <algorithm>
#include <cmath>
#include <limits>

#include "environment_detail.hpp"
#include "graftal/lang/lsystem.hpp"
#include "graftal/rewrite/environment.hpp"

namespace graftal {

namespace {

struct Obstacle {
    enum class Kind { Sphere, Box, Plane };
    Kind kind = Kind::Sphere;
    Vec3 centre;  // sphere and box centre; a point of the plane
    Vec3 half;    // box half extents
    Vec3 normal;  // plane: unit normal, pointing out of the solid
    double radius = 0;

    // Signed distance from p to the surface (negative inside) and the unit direction in
    // which it grows fastest, i.e. the way out. Both are exact for these shapes, so a step
    // shorter than the distance never enters an obstacle.
    double distance(const Vec3& p, Vec3& away) const {
        switch (kind) {
            case Kind::Sphere: {
                Vec3 d = p - centre;
                double r = length(d);
                away = r > 0 ? (1 / r) * d : Vec3{0, 1, 0};
                return r - radius;
            }
            case Kind::Plane:
                away = normal;
                return dot(p - centre, normal);
            case Kind::Box:
                break;
        }
        Vec3 d = p - centre;
        double q[3] = {std::fabs(d.x) - half.x, std::fabs(d.y) - half.y, std::fabs(d.z) - half.z};
        double s[3] = {d.x < 0 ? -1.0 : 1.0, d.y < 0 ? -1.0 : 1.0, d.z < 0 ? -1.0 : 1.0};
        double o[3] = {std::max(q[0], 0.0), std::max(q[1], 0.0), std::max(q[2], 0.0)};
        double outside = std::sqrt(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]);
        if (outside > 0) {
            away = {s[0] * o[0] / outside, s[1] * o[1] / outside, s[2] * o[2] / outside};
            return outside;
        }
        // Inside: the nearest face is the one whose slab is left soonest.
        int axis = 0;
        for (int k = 1; k < 3; ++k)
            if (q[k] > q[axis]) axis = k;
        double a[3] = {0, 0, 0};
        a[axis] = s[axis];
        away = {a[0], a[1], a[2]};
        return q[axis];
    }
};

class ObstacleEnvironment : public Environment {
  public:
    ObstacleEnvironment(std::vector<Obstacle> obstacles, double margin)
        : obstacles_(std::move(obstacles)), margin_(margin) {}

    std::string name() const override { return "obstacles"; }

    void respond(int, std::span<CommunicationRequest> requests) override {
        for (auto& r : requests) {
            if (r.params.empty()) continue;
            double nearest = std::numeric_limits<double>::infinity();
            Vec3 away{0, 1, 0};
            for (const Obstacle& o : obstacles_) {
                Vec3 a;
                double d = o.distance(r.frame.position, a);
                if (d < nearest) nearest = d, away = a;
            }
            double answer[5] = {nearest <= margin_ ? 1.0 : 0.0, nearest, away.x, away.y, away.z};
            for (std::size_t k = 0; k < r.params.size() && k < 5; ++k) r.params[k] = answer[k];
        }
    }

  private:
    std::vector<Obstacle> obstacles_;
    double margin_ = 0;
};

// Reads the words of one line, item by item; every item ends within its line.
class ObstacleReader {
  public:
    ObstacleReader(const LSystem& lsystem, const EnvironmentLine& line,
                   std::vector<EnvironmentLine> words, std::size_t first)
        : lsystem_(lsystem), line_(line), words_(std::move(words)), next_(first) {}

    bool done() const { return next_ >= words_.size(); }
    // Where the next word starts (or the end of the line): what a bad value points at.
    SourceLocation here() const {
        return done() ? environment_detail::endOfLine(line_) : words_[next_].location;
    }
    const EnvironmentLine& take() { return words_[next_++]; }

    double number(const std::string& what) {
        if (done())
            throw Error(environment_detail::endOfLine(line_),
                        "expected " + what + " (a number) before the end of the line");
        return environment_detail::numberWord(take(), what, lsystem_);
    }

    Vec3 point(const std::string& what) {
        Vec3 p;
        p.x = number(what + " x");
        p.y = number(what + " y");
        p.z = number(what + " z");
        return p;
    }

    void keyword(const std::string& word, const std::string& after) {
        if (done())
            throw Error(environment_detail::endOfLine(line_),
                        "expected '" + word + "' after " + after + " before the end of the line");
        const EnvironmentLine& w = take();
        if (w.text != word)
            throw Error(w.location,
                        "expected '" + word + "' after " + after + ", found '" + w.text + "'");
    }

  private:
    const LSystem& lsystem_;
    const EnvironmentLine& line_;
    std::vector<EnvironmentLine> words_;
    std::size_t next_ = 0;
};

}  // namespace

std::unique_ptr<Environment> environment_detail::makeObstacleEnvironment(const LSystem& lsystem) {
    std::vector<Obstacle> obstacles;
    double margin = 0;
    bool marginSeen = false;
    for (std::size_t i = 0; i < lsystem.environment.size(); ++i) {
        const EnvironmentLine& line = lsystem.environment[i];
        ObstacleReader in(lsystem, line, splitWords(line), i == 0 ? 1 : 0);
        while (!in.done()) {
            const EnvironmentLine& word = in.take();
            if (word.text == "margin") {
                if (marginSeen) throw Error(word.location, "the margin is given twice");
                marginSeen = true;
                SourceLocation at = in.here();
                margin = in.number("the margin after 'margin'");
                if (margin < 0) throw Error(at, "the margin must be >= 0");
            } else if (word.text == "sphere") {
                Obstacle o;
                o.kind = Obstacle::Kind::Sphere;
                o.centre = in.point("the sphere's centre");
                in.keyword("radius", "the sphere's centre");
                SourceLocation at = in.here();
                o.radius = in.number("the sphere's radius");
                if (o.radius <= 0) throw Error(at, "a sphere's radius must be > 0");
                obstacles.push_back(o);
            } else if (word.text == "box") {
                Vec3 a = in.point("the box's first corner");
                Vec3 b = in.point("the box's opposite corner");
                Obstacle o;
                o.kind = Obstacle::Kind::Box;
                o.centre = {(a.x + b.x) / 2, (a.y + b.y) / 2, (a.z + b.z) / 2};
                o.half = {std::fabs(b.x - a.x) / 2, std::fabs(b.y - a.y) / 2,
                          std::fabs(b.z - a.z) / 2};
                obstacles.push_back(o);
            } else if (word.text == "plane") {
                Obstacle o;
                o.kind = Obstacle::Kind::Plane;
                o.centre = in.point("a point of the plane");
                in.keyword("normal", "the plane's point");
                SourceLocation at = in.here();
                Vec3 n = in.point("the plane's normal");
                double len = length(n);
                if (len == 0) throw Error(at, "a plane's normal must not be 0 0 0");
                o.normal = (1 / len) * n;
                obstacles.push_back(o);
            } else {
                throw Error(word.location,
                            "expected an obstacle ('sphere X Y Z radius R', 'box X0 Y0 Z0 X1 "
                            "Y1 Z1' or 'plane X Y Z normal NX NY NZ') or 'margin M', found '" +
                                word.text + "'");
            }
        }
    }
    if (obstacles.empty()) {
        const EnvironmentLine& first = lsystem.environment.front();
        throw Error(first.location,
                    "the obstacles environment has no obstacles: add lines such as "
                    "'environment: sphere 0 5 0 radius 1.5'");
    }
    return std::make_unique<ObstacleEnvironment>(std::move(obstacles), margin);
}

}  // namespace graftal
