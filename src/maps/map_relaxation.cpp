// The de Does and Lindenmayer interpretation: vertices settle where the walls pulling on
// them balance. At equilibrium every interior vertex is the centre of gravity of its
// neighbours, a linear system (the graph Laplacian of the interior vertices, with the
// outline fixed) that is solved by conjugate gradients (preconditioned by the vertex degrees)
// instead of by iterating the averaging itself: the averaging needs about as many iterations as the
// layer has cells across, squared; conjugate gradients about as many as it has cells across.
//
// Every sum is formed per block of a fixed number of vertices and the blocks' sums are
// added in block order, so the result is the same bit for bit for any number of threads.
#include <algorithm>
#include <cmath>

#include "core/parallel.hpp"
#include "graftal/plane_map.hpp"

namespace graftal {

namespace {

constexpr std::size_t kBlock = 2048;

// fn(block) for every block, the blocks shared among `threads` threads.
template <class Fn>
void forEachBlock(std::size_t blocks, unsigned threads, Fn&& fn) {
    forEachChunk(blocks, std::max(1u, threads), [&](std::size_t, std::size_t b, std::size_t e) {
        for (std::size_t k = b; k < e; ++k) fn(k);
    });
}

struct XY {
    double x = 0, y = 0;
};

// The outline: the corners of the axiom's polygon stay, and the vertices between two
// corners spread evenly along that side (where each is the middle of its two neighbours
// along the outline: the equilibrium of the one-dimensional rule).
void placeOutline(PlaneMap& m) {
    const auto walk = m.boundary(kOutside);
    std::vector<std::uint32_t> ring;
    ring.reserve(walk.size());
    for (std::uint32_t h : walk) ring.push_back(m.origin(h));
    const std::size_t n = ring.size();
    std::size_t first = n;
    for (std::size_t i = 0; i < n; ++i)
        if (m.vertexSide[ring[i]] == kCorner) {
            first = i;
            break;
        }
    if (first == n) return;
    std::size_t i = first;
    do {
        std::size_t j = (i + 1) % n;
        std::size_t between = 0;
        while (m.vertexSide[ring[j]] != kCorner) {
            j = (j + 1) % n;
            ++between;
        }
        const Vec3 a = m.position[ring[i]], b = m.position[ring[j]];
        for (std::size_t k = 1; k <= between; ++k)
            m.position[ring[(i + k) % n]] =
                a + (b - a) * (static_cast<double>(k) / static_cast<double>(between + 1));
        i = j;
    } while (i != first);
}

}  // namespace

int relaxMap(PlaneMap& map, const MapDerivationOptions& options) {
    placeOutline(map);
    const std::size_t nv = map.vertexCount(), ne = map.edgeCount();
    // Unknowns: the interior vertices, numbered in vertex order.
    std::vector<std::uint32_t> unknown(nv, 0xFFFFFFFFu);
    std::vector<std::uint32_t> vertexOf;
    for (std::uint32_t v = 0; v < nv; ++v)
        if (map.vertexSide[v] == kNotOnOutline) {
            unknown[v] = static_cast<std::uint32_t>(vertexOf.size());
            vertexOf.push_back(v);
        }
    const std::size_t n = vertexOf.size();
    if (n == 0) return 0;
    // Rows of the Laplacian in compressed form: degree on the diagonal, the interior
    // neighbours off it; the outline neighbours go to the right-hand side.
    std::vector<std::uint32_t> start(n + 1, 0);
    for (std::size_t e = 0; e < ne; ++e) {
        const std::uint32_t a = map.tail[e], b = map.head[e];
        if (a == b) continue;
        if (unknown[a] != 0xFFFFFFFFu) ++start[unknown[a] + 1];
        if (unknown[b] != 0xFFFFFFFFu) ++start[unknown[b] + 1];
    }
    for (std::size_t i = 0; i < n; ++i) start[i + 1] += start[i];
    std::vector<std::uint32_t> neighbour(start[n]);
    {
        std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
        for (std::size_t e = 0; e < ne; ++e) {
            const std::uint32_t a = map.tail[e], b = map.head[e];
            if (a == b) continue;
            if (unknown[a] != 0xFFFFFFFFu) neighbour[fill[unknown[a]]++] = b;
            if (unknown[b] != 0xFFFFFFFFu) neighbour[fill[unknown[b]]++] = a;
        }
    }
    const unsigned threads = options.threads == 0 ? defaultThreadCount() : options.threads;
    const std::size_t blocks = (n + kBlock - 1) / kBlock;
    const unsigned workers = blocks == 1 ? 1u : threads;
    auto blockRange = [&](std::size_t k) {
        return std::pair{k * kBlock, std::min(n, (k + 1) * kBlock)};
    };

    std::vector<XY> x(n), r(n), p(n), q(n);
    std::vector<double> partial(blocks), partial2(blocks);
    auto sumPartials = [](const std::vector<double>& parts) {
        double s = 0;
        for (double v : parts) s += v;
        return s;
    };
    for (std::size_t i = 0; i < n; ++i)
        x[i] = {map.position[vertexOf[i]].x, map.position[vertexOf[i]].y};
    // r = b - A x, with b the pull of the outline neighbours; z = r / degree (the diagonal
    // preconditioner: vertices differ in degree from 2 to 10 and more).
    forEachBlock(blocks, workers, [&](std::size_t k) {
        auto [b, e] = blockRange(k);
        double rz = 0, rr = 0;
        for (std::size_t i = b; i < e; ++i) {
            XY acc{0, 0};
            const double degree = static_cast<double>(start[i + 1] - start[i]);
            for (std::uint32_t s = start[i]; s < start[i + 1]; ++s) {
                const Vec3& pu = map.position[neighbour[s]];
                acc.x += pu.x;
                acc.y += pu.y;
            }
            r[i] = {acc.x - degree * x[i].x, acc.y - degree * x[i].y};
            p[i] = {r[i].x / degree, r[i].y / degree};
            rz += r[i].x * p[i].x + r[i].y * p[i].y;
            rr += r[i].x * r[i].x + r[i].y * r[i].y;
        }
        partial[k] = rz;
        partial2[k] = rr;
    });
    double rz = sumPartials(partial);
    double rr = sumPartials(partial2);
    // Settled when the root-mean-square force left on a vertex (the sum of its wall
    // vectors) is below the tolerance times the mean wall length: the vertices are then
    // that close to their neighbours' centre, a fraction of a wall.
    double wallLength = 0;
    for (std::size_t e = 0; e < ne; ++e) {
        const Vec3 d = map.position[map.head[e]] - map.position[map.tail[e]];
        wallLength += std::sqrt(d.x * d.x + d.y * d.y);
    }
    wallLength /= static_cast<double>(std::max<std::size_t>(1, ne));
    const double stop = options.relaxTolerance * options.relaxTolerance * wallLength * wallLength *
                        static_cast<double>(n);
    int iterations = 0;
    auto interiorOrOutline = [&](std::uint32_t u, const std::vector<XY>& v) {
        return unknown[u] != 0xFFFFFFFFu ? v[unknown[u]] : XY{0, 0};
    };
    while (iterations < options.relaxIterations && rr > stop) {
        ++iterations;
        forEachBlock(blocks, workers, [&](std::size_t k) {
            auto [b, e] = blockRange(k);
            double pq = 0;
            for (std::size_t i = b; i < e; ++i) {
                const double degree = static_cast<double>(start[i + 1] - start[i]);
                XY acc{degree * p[i].x, degree * p[i].y};
                for (std::uint32_t s = start[i]; s < start[i + 1]; ++s) {
                    const XY pu = interiorOrOutline(neighbour[s], p);
                    acc.x -= pu.x;
                    acc.y -= pu.y;
                }
                q[i] = acc;
                pq += p[i].x * acc.x + p[i].y * acc.y;
            }
            partial[k] = pq;
        });
        const double alpha = rz / sumPartials(partial);
        forEachBlock(blocks, workers, [&](std::size_t k) {
            auto [b, e] = blockRange(k);
            double sz = 0, sr = 0;
            for (std::size_t i = b; i < e; ++i) {
                x[i].x += alpha * p[i].x;
                x[i].y += alpha * p[i].y;
                r[i].x -= alpha * q[i].x;
                r[i].y -= alpha * q[i].y;
                const double degree = static_cast<double>(start[i + 1] - start[i]);
                sz += (r[i].x * r[i].x + r[i].y * r[i].y) / degree;
                sr += r[i].x * r[i].x + r[i].y * r[i].y;
            }
            partial[k] = sz;
            partial2[k] = sr;
        });
        const double next = sumPartials(partial);
        const double beta = next / rz;
        rz = next;
        rr = sumPartials(partial2);
        forEachBlock(blocks, workers, [&](std::size_t k) {
            auto [b, e] = blockRange(k);
            for (std::size_t i = b; i < e; ++i) {
                const double degree = static_cast<double>(start[i + 1] - start[i]);
                p[i].x = r[i].x / degree + beta * p[i].x;
                p[i].y = r[i].y / degree + beta * p[i].y;
            }
        });
    }
    for (std::size_t i = 0; i < n; ++i) {
        map.position[vertexOf[i]].x = x[i].x;
        map.position[vertexOf[i]].y = x[i].y;
    }
    return iterations;
}

}  // namespace graftal
