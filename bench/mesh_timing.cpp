// The 3D turtle and the mesher, timed inside one process (bench/run.sh, the "3D mesh" row):
//
//   mesh_timing FILE STEPS [REPEATS] [THREADS]
//
// Loads FILE, derives STEPS steps (not timed), then REPEATS times (default 3) interprets the
// string with the turtle and builds the instanced mesh scene (MeshOptions defaults: 8 tube
// sides, THREADS threads, default one per core). Prints one line of JSON: the segments,
// the fastest turtle and mesh times, segments per second through both, the mesh's size
// and the process's peak resident memory. The fastest wall-clock times are the ones the
// rate is computed from; the processor times (all threads together) say how much of a
// busy machine's share the run got.
#include <sys/resource.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>

#include "graftal/geometry/mesh_scene.hpp"
#include "graftal/geometry/surface.hpp"
#include "graftal/graftal.hpp"

namespace {

double seconds(std::chrono::steady_clock::time_point since) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

double cpuSeconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double peakMiB() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return static_cast<double>(u.ru_maxrss) / 1024;  // kilobytes on Linux
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: mesh_timing FILE STEPS [REPEATS] [THREADS]\n");
        return 2;
    }
    const int steps = std::atoi(argv[2]);
    const int repeats = argc > 3 ? std::max(1, std::atoi(argv[3])) : 3;
    try {
        const graftal::Model model = graftal::loadModel(argv[1]).orThrow();
        graftal::DerivationOptions derivation;
        derivation.memoryLimit = std::size_t(16) << 30;
        const graftal::ModuleString shown = graftal::applyHomomorphism(
            model.lsystem, graftal::derive(model.lsystem, steps, derivation));
        const graftal::SurfaceLibrary surfaces = graftal::SurfaceLibrary::builtin();
        graftal::MeshOptions options;
        if (argc > 4) options.threads = static_cast<unsigned>(std::atoi(argv[4]));
        double turtle = 1e30, mesh = 1e30, turtleCpu = 1e30, meshCpu = 1e30;
        std::size_t segments = 0, vertices = 0, triangles = 0;
        graftal::MeshScene built;  // reused: the warm runs write into mapped memory
        for (int r = 0; r < repeats; ++r) {
            auto t0 = std::chrono::steady_clock::now();
            double c0 = cpuSeconds();
            const graftal::Scene scene = graftal::interpret(model, shown);
            turtle = std::min(turtle, seconds(t0));
            turtleCpu = std::min(turtleCpu, cpuSeconds() - c0);
            t0 = std::chrono::steady_clock::now();
            c0 = cpuSeconds();
            graftal::buildMeshScene(scene, options, &surfaces, built);
            mesh = std::min(mesh, seconds(t0));
            meshCpu = std::min(meshCpu, cpuSeconds() - c0);
            segments = scene.segments.size();
            vertices = built.vertexCount();
            triangles = built.triangleCount();
        }
        std::printf(
            "{\"segments\": %zu, \"turtle_s\": %.6f, \"mesh_s\": %.6f, \"segments_per_s\": %.0f, "
            "\"turtle_cpu_s\": %.6f, \"mesh_cpu_s\": %.6f, \"vertices\": %zu, "
            "\"triangles\": %zu, \"peak_mib\": %.0f}\n",
            segments, turtle, mesh, static_cast<double>(segments) / (turtle + mesh), turtleCpu,
            meshCpu, vertices, triangles, peakMiB());
    } catch (const graftal::Error& e) {
        std::cerr << e.what() << "\n";
        return 1;
    }
    return 0;
}
