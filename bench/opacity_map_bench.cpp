// SPDX-License-Identifier: MIT
// occu-bench-om: the run-time tests of Poon and Wang (sections 5.2, 5.4)
// against pixel-by-pixel comparison (their PC), side by side in one run.
//   overlap  is a W x W rectangle of a 128 x 128 coverage map fully covered?
//            opacity map: three additions/subtractions; PC: every pixel
//   depth    is a depth behind every map pixel of the rectangle? sparse
//            depth map (skips along non-decreasing runs) vs every pixel
// Rectangles lie where the map is covered, the case where PC cannot stop
// early and that decides culling. Prints CSV:
//   test,width,ns_map,ns_pixelwise,speedup
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "evaluation/allocator.h"
#include "strategies/poon_wang_opacity_maps/opacity_map.h"
#include "strategies/poon_wang_opacity_maps/sparse_depth_map.h"

namespace {

using Clock = std::chrono::steady_clock;

template <class F>
double ns_per_call(F &&f, int calls)
{
    double best = 1e30;
    for (int round = 0; round < 7; ++round) {   // best of 7: the machine is shared
        const auto t0 = Clock::now();
        for (int i = 0; i < calls; ++i)
            f(i);
        best = std::min(best, std::chrono::duration<double, std::nano>(Clock::now() - t0).count() / calls);
    }
    return best;
}

volatile bool sink;

}  // namespace

int main(int argc, char **argv)
{
    occu::control_allocator(occu::AllocatorPolicy::keep_freed);   // as every benchmark (evaluation/allocator.h)
    const int size = 128;
    std::vector<int> widths = {8, 16, 32, 64};
    if (argc > 1) {
        widths.clear();
        for (int i = 1; i < argc; ++i) {
            const int w = std::atoi(argv[i]);
            if (w < 1 || w > size) {
                std::fprintf(stderr, "occu-bench-om: widths are 1..%d, got '%s'\n", size, argv[i]);
                return 2;
            }
            widths.push_back(w);
        }
    }
    // Covered everywhere; depth rising along rows like the ground plane of a
    // street view (long non-decreasing runs, the sparse map's good case).
    std::vector<std::uint8_t> covered(std::size_t(size) * size, 1);
    std::vector<float> depth(covered.size());
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            depth[std::size_t(y) * size + std::size_t(x)] = 0.3f + 0.002f * float(x) + 0.0001f * float(y);
    const occu::OpacityMap om(size, size, covered);
    const occu::SparseDepthMap sdm(size, size, depth);
    std::printf("test,width,ns_map,ns_pixelwise,speedup\n");
    for (int w : widths) {
        const int span = size - w + 1;
        auto origin = [&](int i, int &x, int &y) { x = (i * 7) % span; y = (i * 13) % span; };
        const double map = ns_per_call([&](int i) {
            int x, y;
            origin(i, x, y);
            sink = om.overlaps_fully(x, x + w, y, y + w);
        }, 200000);
        const double pixelwise = ns_per_call([&](int i) {
            int x, y;
            origin(i, x, y);
            bool all = true;
            for (int yy = y; yy < y + w && all; ++yy)
                for (int xx = x; xx < x + w; ++xx)
                    all = all && covered[std::size_t(yy) * size + std::size_t(xx)];
            sink = all;
        }, 2000);
        std::printf("overlap,%d,%.1f,%.1f,%.1f\n", w, map, pixelwise, pixelwise / map);
        const double sparse = ns_per_call([&](int i) {
            int x, y;
            origin(i, x, y);
            sink = sdm.behind(0.9f, x, x + w - 1, y, y + w - 1);
        }, 20000);
        const double dense = ns_per_call([&](int i) {
            int x, y;
            origin(i, x, y);
            sink = sdm.behind_pixelwise(0.9f, x, x + w - 1, y, y + w - 1);
        }, 2000);
        std::printf("depth,%d,%.1f,%.1f,%.1f\n", w, sparse, dense, dense / sparse);
    }
    return 0;
}
