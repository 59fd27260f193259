// The de Does and Lindenmayer interpretation: vertices settle where the walls pulling on
// them balance. At equilibrium every interior vertex is the centre of gravity of its
// neighbours, a linear system (the graph Laplacian of the interior vertices, with the
// outline fixed) that is solved by conjugate gradients (preconditioned by the vertex
// degrees) instead of by iterating the averaging itself: the averaging needs about as many
// iterations as the layer has cells across, squared; conjugate gradients about as many as
// it has cells across. The outline is placed by its own rule (map_outline.cpp) between
// solves.
//
// Speed: the work is memory-bound (a few flops per neighbour read), so the unknowns are
// numbered in breadth-first order from the outline (Cuthill-McKee without the degree sort):
// the neighbours of a vertex are then a few hundred entries away in every array instead of
// anywhere, and the rows' neighbour lists are compressed arrays of unknown numbers, the
// outline's pull gathered once per solve. The iteration is the Chronopoulos-Gear form of
// conjugate gradients, whose update and product fuse into one sweep over the vertices with
// one reduction point, where the textbook form needs three passes, each a wait for the
// slowest thread.
//
// Every sum is formed per block of a fixed number of vertices and the blocks' sums are
// added in block order, so the result is the same bit for bit for any number of threads.
#include <algorithm>
#include <cmath>

#include "graftal/core/huge_pages.hpp"
#include "graftal/core/parallel.hpp"
#include "graftal/core/thread_pool.hpp"
#include "map_outline.hpp"

namespace graftal {

namespace {

constexpr std::size_t kBlock = 1024;
// Below this many unknowns a second thread costs more (waiting for it twice an iteration)
// than it saves.
constexpr std::size_t kParallelFrom = 16 * kBlock;
constexpr std::uint32_t kFixed = 0xFFFFFFFFu;

struct XY {
    double x = 0, y = 0;
};

// A block's (r, u), (w, u) and (r, r).
struct Sums {
    double ru = 0, wu = 0, rr = 0;
};

Sums sumInOrder(const std::vector<Sums>& parts) {
    Sums s;
    for (const Sums& v : parts) {
        s.ru += v.ru;
        s.wu += v.wu;
        s.rr += v.rr;
    }
    return s;
}

// The interior's Laplacian in breadth-first order: row i is vertex vertexOf[i]; its interior
// neighbours are column numbers, its outline neighbours vertex numbers (their pull is the
// right-hand side).
struct Rows {
    std::vector<std::uint32_t> vertexOf;
    std::vector<std::uint32_t> start, col;            // interior neighbours
    std::vector<std::uint32_t> fixedStart, fixedCol;  // outline neighbours
    std::vector<double> degree;
    // Per block of kBlock rows, the first and last block its rows' interior neighbours lie
    // in (the block itself included).
    std::vector<std::uint32_t> reachFrom, reachTo;
    std::size_t size() const { return vertexOf.size(); }
};

Rows buildRows(const PlaneMap& m) {
    const std::size_t nv = m.vertexCount(), ne = m.edgeCount();
    // Vertex adjacency, all vertices.
    std::vector<std::uint32_t> aStart(nv + 1, 0), adj;
    for (std::size_t e = 0; e < ne; ++e) {
        if (m.tail[e] == m.head[e]) continue;
        ++aStart[m.tail[e] + 1];
        ++aStart[m.head[e] + 1];
    }
    for (std::size_t v = 0; v < nv; ++v) aStart[v + 1] += aStart[v];
    adj.resize(aStart[nv]);
    {
        std::vector<std::uint32_t> fill(aStart.begin(), aStart.end() - 1);
        for (std::size_t e = 0; e < ne; ++e) {
            const std::uint32_t a = m.tail[e], b = m.head[e];
            if (a == b) continue;
            adj[fill[a]++] = b;
            adj[fill[b]++] = a;
        }
    }
    // Breadth-first from the outline, in the outline's order: the interior is numbered in
    // rings inwards.
    Rows rows;
    std::vector<std::uint32_t> number(nv, kFixed);
    std::vector<char> seen(nv, 0);
    std::vector<std::uint32_t> queue;
    queue.reserve(nv);
    for (std::uint32_t v = 0; v < nv; ++v)
        if (m.vertexSide[v] != kNotOnOutline) seen[v] = 1;
    for (std::uint32_t h : m.boundary(kOutside)) queue.push_back(m.origin(h));
    for (std::size_t head = 0; head < queue.size(); ++head) {
        const std::uint32_t v = queue[head];
        for (std::uint32_t s = aStart[v]; s < aStart[v + 1]; ++s) {
            const std::uint32_t u = adj[s];
            if (seen[u]) continue;
            seen[u] = 1;
            number[u] = static_cast<std::uint32_t>(rows.vertexOf.size());
            rows.vertexOf.push_back(u);
            queue.push_back(u);
        }
    }
    const std::size_t n = rows.size();
    rows.col.reserve(adj.size());
    rows.fixedCol.reserve(adj.size());
    rows.start.assign(n + 1, 0);
    rows.fixedStart.assign(n + 1, 0);
    rows.degree.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t v = rows.vertexOf[i];
        rows.degree[i] = static_cast<double>(aStart[v + 1] - aStart[v]);
        for (std::uint32_t s = aStart[v]; s < aStart[v + 1]; ++s) {
            if (number[adj[s]] != kFixed)
                rows.col.push_back(number[adj[s]]);
            else
                rows.fixedCol.push_back(adj[s]);
        }
        rows.start[i + 1] = static_cast<std::uint32_t>(rows.col.size());
        rows.fixedStart[i + 1] = static_cast<std::uint32_t>(rows.fixedCol.size());
    }
    const std::size_t blocks = (n + kBlock - 1) / kBlock;
    rows.reachFrom.resize(blocks);
    rows.reachTo.resize(blocks);
    for (std::size_t k = 0; k < blocks; ++k) {
        std::uint32_t lo = static_cast<std::uint32_t>(k), hi = lo;
        for (std::uint32_t c = rows.start[k * kBlock];
             c < rows.start[std::min(n, (k + 1) * kBlock)]; ++c) {
            lo = std::min(lo, static_cast<std::uint32_t>(rows.col[c] / kBlock));
            hi = std::max(hi, static_cast<std::uint32_t>(rows.col[c] / kBlock));
        }
        rows.reachFrom[k] = lo;
        rows.reachTo[k] = hi;
    }
    return rows;
}

double meanWallLength(const PlaneMap& m) {
    double sum = 0;
    for (std::size_t e = 0; e < m.edgeCount(); ++e) {
        const Vec3 d = m.position[m.head[e]] - m.position[m.tail[e]];
        sum += std::sqrt(d.x * d.x + d.y * d.y);
    }
    return sum / static_cast<double>(std::max<std::size_t>(1, m.edgeCount()));
}

// The solver's vectors, kept for every solve of one relaxation: fresh memory costs this
// machine's kernel more than the arithmetic does. One buffer, so that it is large enough
// for huge pages (a page fault per 2 MiB instead of per 4 KiB).
struct Workspace {
    std::vector<XY> storage;
    XY *x, *b, *r, *u, *w, *p, *s;
    // Each block's three sums, for iterations of even and of odd number: a thread may write
    // the next iteration's sums while another still adds up this one's.
    std::vector<Sums> sums[2];
    Workspace(std::size_t n, std::size_t blocks)
        : sums{std::vector<Sums>(blocks), std::vector<Sums>(blocks)} {
        storage.reserve(7 * n);
        adviseHugePages(storage);
        storage.resize(7 * n);
        XY** vectors[] = {&x, &b, &r, &u, &w, &p, &s};
        for (std::size_t k = 0; k < 7; ++k) *vectors[k] = storage.data() + k * n;
    }
};

// Solves the interior for the outline where it is now, starting from the interior's
// present positions, until the root-mean-square force left on a vertex is below
// `tolerance` times the mean wall length. Returns the iterations done.
//
// The whole solve is one run of the pool: each thread owns a contiguous run of blocks, and
// an iteration is one sweep over them (each block updated, then multiplied as soon as the
// blocks its rows read are updated) and two barriers: one before the blocks that read
// another thread's rows are multiplied, one before the reduction. After that every thread
// adds the blocks' sums in block order itself, so all take the same decisions with the same
// numbers, and the blocks do not depend on the number of threads.
int solveInterior(PlaneMap& m, const Rows& rows, Workspace& ws, double tolerance, int maxIterations,
                  ThreadPool& pool) {
    const std::size_t n = rows.size();
    if (n == 0) return 0;
    const std::size_t blocks = (n + kBlock - 1) / kBlock;
    const double wall = meanWallLength(m);
    const double stop = tolerance * tolerance * wall * wall * static_cast<double>(n);
    XY *x = ws.x, *b = ws.b, *r = ws.r, *u = ws.u, *w = ws.w, *p = ws.p, *s = ws.s;
    auto range = [&](std::size_t k) {
        return std::pair{k * kBlock, std::min(n, (k + 1) * kBlock)};
    };
    // x, b (the outline's pull), p = s = 0.
    auto load = [&](std::size_t k) {
        auto [lo, hi] = range(k);
        for (std::size_t i = lo; i < hi; ++i) {
            const Vec3& q = m.position[rows.vertexOf[i]];
            x[i] = {q.x, q.y};
            XY pull{0, 0};
            for (std::uint32_t c = rows.fixedStart[i]; c < rows.fixedStart[i + 1]; ++c) {
                pull.x += m.position[rows.fixedCol[c]].x;
                pull.y += m.position[rows.fixedCol[c]].y;
            }
            b[i] = pull;
            p[i] = s[i] = XY{};
        }
    };
    // r = b - A x, u = r / degree.
    auto residual = [&](std::size_t k) {
        auto [lo, hi] = range(k);
        for (std::size_t i = lo; i < hi; ++i) {
            XY acc{b[i].x - rows.degree[i] * x[i].x, b[i].y - rows.degree[i] * x[i].y};
            for (std::uint32_t c = rows.start[i]; c < rows.start[i + 1]; ++c) {
                acc.x += x[rows.col[c]].x;
                acc.y += x[rows.col[c]].y;
            }
            r[i] = acc;
            u[i] = {acc.x / rows.degree[i], acc.y / rows.degree[i]};
        }
    };
    // w = A u and the block's (r, u), (w, u) and (r, r).
    auto multiply = [&](std::size_t k, int parity) {
        auto [lo, hi] = range(k);
        double ru = 0, wu = 0, rr = 0;
        for (std::size_t i = lo; i < hi; ++i) {
            XY acc{rows.degree[i] * u[i].x, rows.degree[i] * u[i].y};
            for (std::uint32_t c = rows.start[i]; c < rows.start[i + 1]; ++c) {
                acc.x -= u[rows.col[c]].x;
                acc.y -= u[rows.col[c]].y;
            }
            w[i] = acc;
            ru += r[i].x * u[i].x + r[i].y * u[i].y;
            wu += acc.x * u[i].x + acc.y * u[i].y;
            rr += r[i].x * r[i].x + r[i].y * r[i].y;
        }
        ws.sums[parity][k] = {ru, wu, rr};
    };
    // The step along p and the next direction.
    auto update = [&](std::size_t k, double alpha, double beta) {
        auto [lo, hi] = range(k);
        for (std::size_t i = lo; i < hi; ++i) {
            p[i] = {u[i].x + beta * p[i].x, u[i].y + beta * p[i].y};
            s[i] = {w[i].x + beta * s[i].x, w[i].y + beta * s[i].y};
            x[i].x += alpha * p[i].x;
            x[i].y += alpha * p[i].y;
            r[i].x -= alpha * s[i].x;
            r[i].y -= alpha * s[i].y;
            u[i] = {r[i].x / rows.degree[i], r[i].y / rows.degree[i]};
        }
    };
    int done = 0;
    pool.run([&](unsigned thread) {
        const auto [first, last] = pool.share(thread, blocks);
        for (std::size_t k = first; k < last; ++k) load(k);
        pool.barrier();
        for (std::size_t k = first; k < last; ++k) residual(k);
        pool.barrier();
        for (std::size_t k = first; k < last; ++k) multiply(k, 0);
        pool.barrier();
        const Sums initial = sumInOrder(ws.sums[0]);
        double gamma = initial.ru, delta = initial.wu, rr = initial.rr;
        double alpha = delta > 0 ? gamma / delta : 0, beta = 0;
        int iterations = 0;
        std::vector<std::size_t> deferred;
        while (iterations < maxIterations && rr > stop && delta > 0) {
            ++iterations;
            // One sweep: block k updated, then every block whose neighbours are all updated
            // is multiplied while its rows are still in the cache. Blocks that read rows of
            // another thread's share wait for the barrier.
            deferred.clear();
            std::size_t pending = first;
            for (std::size_t k = first; k < last; ++k) {
                update(k, alpha, beta);
                for (; pending <= k && rows.reachTo[pending] <= k; ++pending) {
                    if (rows.reachFrom[pending] >= first)
                        multiply(pending, iterations % 2);
                    else
                        deferred.push_back(pending);
                }
            }
            for (; pending < last; ++pending) deferred.push_back(pending);
            pool.barrier();
            for (std::size_t k : deferred) multiply(k, iterations % 2);
            pool.barrier();
            const Sums sums = sumInOrder(ws.sums[iterations % 2]);
            const double next = sums.ru;
            delta = sums.wu;
            rr = sums.rr;
            beta = next / gamma;
            const double denominator = delta - beta * next / alpha;
            if (!(denominator > 0)) break;
            alpha = next / denominator;
            gamma = next;
        }
        // Every thread writes back its own rows; no other thread reads them any more.
        for (std::size_t k = first; k < last; ++k) {
            auto [lo, hi] = range(k);
            for (std::size_t i = lo; i < hi; ++i) {
                m.position[rows.vertexOf[i]].x = x[i].x;
                m.position[rows.vertexOf[i]].y = x[i].y;
            }
        }
        if (thread == 0) done = iterations;
    });
    return done;
}

}  // namespace

int relaxMap(PlaneMap& map, const MapDerivationOptions& options) {
    const unsigned threads = options.threads == 0 ? defaultThreadCount() : options.threads;
    const Rows rows = buildRows(map);
    Workspace ws(rows.size(), (rows.size() + kBlock - 1) / kBlock);
    // One team for all the solves of this relaxation; small maps are solved by the caller
    // alone.
    ThreadPool pool(rows.size() < kParallelFrom ? 1u : threads);
    if (options.outline == MapOutline::Polygon) {
        placeOutlineOnPolygon(map);
        return solveInterior(map, rows, ws, options.relaxTolerance, options.relaxIterations, pool);
    }
    // The growing outline: rounds of (interior settled roughly, outline moved), then the
    // interior settled for the outline where it ends.
    int iterations = 0;
    for (int round = 0; round < options.outlineRounds; ++round) {
        iterations += solveInterior(map, rows, ws, std::max(options.relaxTolerance, 3e-2),
                                    options.relaxIterations, pool);
        moveGrowingOutline(map);
    }
    return iterations +
           solveInterior(map, rows, ws, options.relaxTolerance, options.relaxIterations, pool);
}

}  // namespace graftal
