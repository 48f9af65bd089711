// SPDX-License-Identifier: MIT
// occu-bench-raster: the CPU depth rasterizer's throughput on the city's
// routes, its scalar and AVX2 loops side by side in one process.
//
//   occu-bench-raster [FRAMES] [SIZE]
//
// For each route frame, every triangle of every leaf in the frustum (what
// Intel's Masked Occlusion Culling renders as occluders when it takes
// every kept leaf) is rasterized into a buffer for a SIZE x SIZE frame
// (default 512) at divisors 1 and 2, and the route's skins (Leone et al.)
// as a second load; and the leaf triangles again with merged partial
// coverage (load leaf-triangles-merged: samples fused across triangles and
// along their shared edges, Masked Occlusion Culling's rule; the
// triangles across found once per mesh, outside the timing), at divisors
// 1 and 2. Each (route, load, divisor, path) is the best of 5 rounds
// over all its frames, the paths alternating round by round, because the
// machine is shared. Prints CSV:
//   route,load,divisor,isa,polygons,ms_per_frame,million_polygons_per_second
// and, for the leaf triangles at divisors 1 and 2 with the best loops, the
// same work split over two threads (each half the batches into a buffer
// of its own, then merged, nearest wins), best of 5 rounds:
//   route,two-threads,DIVISOR,ISA,polygons,ms_per_frame,million_polygons_per_second
// and last, per route and divisor (1 and 2) and loops, the occluder
// triangles per second of whole pixels and of merged coverage side by
// side, and the merged frame's time over the whole pixels' one (the
// cost of fusing samples, from the rows above):
//   route,divisor,isa,whole_million_triangles_per_second,merged_million_triangles_per_second,merged_over_whole
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "culling/culler.h"
#include "evaluation/allocator.h"
#include "evaluation/scene_setup.h"
#include "occluders/skin_occluders.h"
#include "raster/depth_rasterizer.h"

namespace {

using Clock = std::chrono::steady_clock;
using occu::DepthRasterizer;

}  // namespace

int main(int argc, char **argv)
{
    const int frames = argc > 1 ? std::atoi(argv[1]) : 30;
    const int size = argc > 2 ? std::atoi(argv[2]) : 512;
    if (frames < 1 || size < 1) {
        std::fprintf(stderr, "usage: occu-bench-raster [FRAMES >= 1] [SIZE >= 1]\n");
        return 2;
    }
    occu::control_allocator(occu::AllocatorPolicy::keep_freed);   // as every benchmark (evaluation/allocator.h)
    const occu::SceneSetup setup{occu::SceneChoice{}};
    const occu::Scene &scene = setup.scene();
    const occu::Hierarchy &hierarchy = setup.hierarchy();
    occu::SkinOccluders skins(scene, "", 8);
    std::vector<DepthRasterizer::Isa> isas{DepthRasterizer::Isa::scalar};
    if (DepthRasterizer::avx2_supported())
        isas.push_back(DepthRasterizer::Isa::avx2);

    std::printf("route,load,divisor,isa,polygons,ms_per_frame,million_polygons_per_second\n");
    // (route, load, divisor, isa) -> ms a frame and million polygons a second.
    std::map<std::tuple<std::string, std::string, int, int>, std::pair<double, double>> measured;
    for (const char *route : {"dense", "street", "medium", "open"}) {
        const auto cameras = setup.route(route, frames);
        // Per frame, the triangles of the leaves in the frustum, gathered
        // once: positions and indices of one mesh at a time.
        struct Batch {
            const occu::Mesh *mesh;
            std::vector<std::uint32_t> indices;
            std::vector<glm::vec3> across;   // shared_edge_opposites, 3 per triangle
        };
        std::vector<std::vector<Batch>> loads(cameras.size());
        // Per mesh, the triangle across each edge of each of its triangles.
        std::map<std::uint32_t, std::vector<glm::vec3>> opposites;
        const auto across = [&](std::uint32_t m) -> const std::vector<glm::vec3> & {
            auto it = opposites.find(m);
            if (it == opposites.end()) {
                std::vector<glm::vec3> corners;
                for (std::uint32_t i : scene.meshes[m].indices)
                    corners.push_back(scene.meshes[m].positions[i]);
                it = opposites.emplace(m, occu::shared_edge_opposites(corners)).first;
            }
            return it->second;
        };
        std::uint64_t triangles = 0;
        for (std::size_t f = 0; f < cameras.size(); ++f) {
            const occu::Frustum frustum(cameras[f].view_projection());
            for (std::uint32_t leaf : occu::leaves_in_frustum(hierarchy, frustum)) {
                const occu::HierarchyNode &n = hierarchy.nodes()[leaf];
                for (std::uint32_t i = n.first_triangle; i < n.first_triangle + n.triangle_count; ++i) {
                    const occu::TriangleRef &t = hierarchy.triangles()[i];
                    const occu::Mesh *mesh = &scene.meshes[t.mesh];
                    if (loads[f].empty() || loads[f].back().mesh != mesh)
                        loads[f].push_back({mesh, {}, {}});
                    auto &idx = loads[f].back().indices;
                    idx.insert(idx.end(), mesh->indices.begin() + t.first_index,
                               mesh->indices.begin() + t.first_index + 3);
                    const std::vector<glm::vec3> &opposite = across(t.mesh);
                    loads[f].back().across.insert(loads[f].back().across.end(),
                                                  opposite.begin() + std::ptrdiff_t(t.first_index),
                                                  opposite.begin() + std::ptrdiff_t(t.first_index) + 3);
                    ++triangles;
                }
            }
        }
        for (const char *load : {"leaf-triangles", "skins", "leaf-triangles-merged"}) {
            const bool leaf_triangles = load[0] == 'l';
            const bool merged = std::string(load) == "leaf-triangles-merged";
            for (int divisor : {1, 2, 64}) {
                if (merged && divisor > 8)
                    continue;   // a mask holds 8 x 8 samples at most
                std::vector<double> best(isas.size(), 1e30);
                std::uint64_t polygons = 0;
                for (int round = 0; round < 5; ++round)
                    for (std::size_t i = 0; i < isas.size(); ++i) {
                        DepthRasterizer r(isas[i]);
                        const auto t0 = Clock::now();
                        for (std::size_t f = 0; f < cameras.size(); ++f) {
                            const occu::Frame frame(cameras[f], size, size);
                            r.begin(frame.view_projection, size, size, {divisor, true, merged});
                            if (leaf_triangles)
                                for (const Batch &b : loads[f])
                                    r.render_triangles(b.mesh->positions.data(), b.indices.data(),
                                                       b.indices.size() / 3, merged ? b.across.data() : nullptr);
                            else
                                skins.render(frame, r, 0);
                            polygons += r.stats().polygons;
                        }
                        best[i] = std::min(best[i],
                                           std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
                    }
                polygons /= 5 * isas.size();
                for (std::size_t i = 0; i < isas.size(); ++i) {
                    std::printf("%s,%s,%d,%s,%llu,%.3f,%.1f\n", route, load, divisor,
                                isas[i] == DepthRasterizer::Isa::avx2 ? "avx2" : "scalar",
                                (unsigned long long)(polygons / cameras.size()), best[i] / double(cameras.size()),
                                double(polygons) / (best[i] * 1e3));
                    measured[{route, load, divisor, int(isas[i])}] = {best[i] / double(cameras.size()),
                                                                      double(polygons) / (best[i] * 1e3)};
                }
            }
        }
        // The second core: the frame's batches split in two halves, one per
        // thread, each into a rasterizer of its own, merged at the end.
        for (int divisor : {1, 2}) {
            const DepthRasterizer::Isa isa = isas.back();
            DepthRasterizer a(isa), b(isa);
            double best = 1e30;
            std::uint64_t polygons = 0;
            for (int round = 0; round < 5; ++round) {
                const auto t0 = Clock::now();
                for (std::size_t f = 0; f < cameras.size(); ++f) {
                    const occu::Frame frame(cameras[f], size, size);
                    const std::size_t half = loads[f].size() / 2;
                    auto work = [&](DepthRasterizer &r, std::size_t from, std::size_t to) {
                        r.begin(frame.view_projection, size, size, {divisor, true});
                        for (std::size_t i = from; i < to; ++i)
                            r.render_triangles(loads[f][i].mesh->positions.data(), loads[f][i].indices.data(),
                                               loads[f][i].indices.size() / 3);
                    };
                    std::thread other(work, std::ref(b), half, loads[f].size());
                    work(a, 0, half);
                    other.join();
                    a.merge_nearest(b);
                    polygons += a.stats().polygons;
                }
                best = std::min(best, std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
            }
            polygons /= 5;
            std::printf("%s,two-threads,%d,%s,%llu,%.3f,%.1f\n", route, divisor,
                        isa == DepthRasterizer::Isa::avx2 ? "avx2" : "scalar",
                        (unsigned long long)(polygons / cameras.size()), best / double(cameras.size()),
                        double(polygons) / (best * 1e3));
        }
        (void)triangles;
    }
    std::printf("route,divisor,isa,whole_million_triangles_per_second,merged_million_triangles_per_second,"
                "merged_over_whole\n");
    for (const char *route : {"dense", "street", "medium", "open"})
        for (int divisor : {1, 2})
            for (DepthRasterizer::Isa isa : isas) {
                const auto whole = measured[{route, "leaf-triangles", divisor, int(isa)}];
                const auto merged = measured[{route, "leaf-triangles-merged", divisor, int(isa)}];
                std::printf("%s,%d,%s,%.1f,%.1f,%.2f\n", route, divisor,
                            isa == DepthRasterizer::Isa::avx2 ? "avx2" : "scalar", whole.second, merged.second,
                            merged.first / whole.first);
            }
    return 0;
}
