// SPDX-License-Identifier: MIT
// occu-bench-choice: what choosing the scene's own triangles as occluders
// (occluders/triangle_occluders.h) costs a frame, without GL, on the scene
// and route the walkthrough would take with the same options, as
// `skins-triangles` chooses them (occluder-triangles=1024 unless --budget
// says otherwise, leaf by leaf of the scene's hierarchy).
//
//   occu-bench-choice [--scene S] [--route R] [--frames N] [--size WxH]
//                     [--budget N] [--rounds N] [--leaf-triangles N|auto]
//                     [--raster none|whole|merged] [--divisor N] [--evict MB]
//                     [--clock wall|thread]
//
// Each round walks the route with occluders made afresh (the choice keeps
// last frame's triangles, so the first frame of each round is a cold one
// as in the walkthrough), timing choose() alone; the best round's time is
// printed, with a digest of every frame's chosen indices in the order
// drawn and of the set alone (sorted), so that two builds can be checked
// to choose the same triangles, and in the same order. With --raster
// whole|merged the rounds time TriangleOccluders::render instead, the
// choice and its rasterization as the strategies draw them (into a CPU
// depth buffer of --divisor, 2 by default as at 512x512, with that
// coverage rule), and the digest is of every frame's depth buffer.
// --evict MB writes that many megabytes before each frame, untimed, as
// the walkthrough's drawing does between two choices, so that the choice
// finds its data out of the caches near the core as it does there
// (0, the default: back to back, its data in them). --clock thread
// times the choice by the thread's CPU time rather than the wall clock's
// (traversal/clock.h, as the walkthrough's --clock): on a machine shared
// with other work, the time it was not run is left out.
// Counting instructions: valgrind --tool=callgrind --rounds 1
// --toggle-collect='occu::TriangleOccluders::choose*' (the choice), or
// with --raster 'occu::TriangleOccluders::render*' (both).
// Prints CSV:
//   scene,route,frames,budget,raster,triangles_a_frame,us_a_frame,set_digest,order_digest,buffer_digest
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "cli/arguments.h"
#include "culling/culler.h"
#include "evaluation/allocator.h"
#include "evaluation/scene_setup.h"
#include "occluders/sources.h"
#include "occluders/triangle_occluders.h"
#include "raster/depth_rasterizer.h"
#include "traversal/clock.h"

using namespace occu;

namespace {

struct Options {
    std::string scene = "city";
    std::string route = "dense";
    int frames = 60;
    int width = 512, height = 512;
    long budget = 1024;
    int rounds = 5;
    std::string raster = "none";
    int divisor = 2;
    std::uint32_t leaf_triangles = HierarchyOptions{}.max_leaf_triangles;
    long evict_mb = 0;
    Clock clock = Clock::wall;
};

[[noreturn]] void usage(const std::string &error)
{
    std::FILE *to = error.empty() ? stdout : stderr;
    if (!error.empty())
        std::fprintf(stderr, "occu-bench-choice: %s\n", error.c_str());
    std::fprintf(to, "usage: occu-bench-choice [--scene S] [--route R] [--frames N] [--size WxH] [--budget N]\n"
                     "                         [--rounds N] [--leaf-triangles N|auto] [--raster none|whole|merged]\n"
                     "                         [--divisor N] [--evict MB] [--clock wall|thread]\n");
    std::exit(error.empty() ? 0 : 2);
}

// FNV-1a over 32-bit words.
struct Digest {
    std::uint64_t h = 1469598103934665603ull;
    void add(std::uint32_t x)
    {
        for (int b = 0; b < 4; ++b) {
            h ^= (x >> (8 * b)) & 0xFFu;
            h *= 1099511628211ull;
        }
    }
};

}  // namespace

int main(int argc, char **argv)
{
    Options o;
    for_each_option(argc, argv, usage, [&](const std::string &a, const std::string &v) {
        if (a == "--scene") o.scene = v;
        else if (a == "--route") o.route = v;
        else if (a == "--frames") o.frames = int(integer_option(a, v, 1, 1000000));
        else if (a == "--budget") o.budget = integer_option(a, v, 1, 1L << 24);
        else if (a == "--rounds") o.rounds = int(integer_option(a, v, 1, 1000));
        else if (a == "--leaf-triangles") o.leaf_triangles = leaf_triangles_option(a, v);
        else if (a == "--divisor") o.divisor = int(integer_option(a, v, 1, 8));
        else if (a == "--evict") o.evict_mb = integer_option(a, v, 0, 4096);
        else if (a == "--clock") o.clock = clock_option(a, v);
        else if (a == "--raster") {
            if (v != "none" && v != "whole" && v != "merged")
                usage("--raster wants none, whole or merged, got '" + v + "'");
            o.raster = v;
        }
        else if (a == "--size") {
            const auto x = v.find('x');
            if (x == std::string::npos)
                usage("--size wants WxH, got '" + v + "'");
            o.width = int(integer_option(a, v.substr(0, x), 1, 16384));
            o.height = int(integer_option(a, v.substr(x + 1), 1, 16384));
        } else {
            return false;
        }
        return true;
    });
    control_allocator(AllocatorPolicy::keep_freed);   // as every benchmark (evaluation/allocator.h)
    try {
        const SceneSetup setup(SceneChoice(o.scene, 1, o.leaf_triangles));
        const std::vector<Camera> cameras = setup.route(o.route, o.frames, float(o.width) / float(o.height));
        std::vector<Frame> frames;
        for (const Camera &c : cameras)
            frames.emplace_back(c, o.width, o.height);
        std::vector<SettingSpec> specs{occluder_triangles_setting(), coverage_setting()};
        Settings settings("skins-triangles", &specs);
        settings.set("occluder-triangles", std::to_string(o.budget));
        settings.set("coverage", o.raster == "whole" ? "whole" : "merged");
        const bool rasterize = o.raster != "none";
        DepthRasterizer raster;
        DepthRasterizer::Options options;
        options.divisor = o.divisor;
        options.merge_partial_coverage = o.raster == "merged";
        std::vector<float> depth;
        const Stopwatch watch(o.clock);
        std::vector<std::uint64_t> evicted(std::size_t(o.evict_mb) << 17);
        const auto evict = [&]() {
            for (std::uint64_t &word : evicted)
                word += 1;
        };

        double best = 0;
        std::size_t chosen = 0;
        Digest set, order;   // with --raster: the buffers, in `set`
        for (int round = 0; round < o.rounds; ++round) {
            TriangleOccluders occluders(setup.scene(), settings, 0, &setup.hierarchy());
            double ms = 0;
            std::size_t count = 0;
            Digest round_set, round_order;
            std::vector<std::uint32_t> sorted;
            for (const Frame &f : frames) {
                evict();
                if (rasterize) {
                    raster.begin(f.view_projection, f.width, f.height, options);
                    watch.time(ms, [&] { count += occluders.render(f, raster); });
                    raster.read(depth);
                    for (float d : depth) {
                        std::uint32_t bits;
                        std::memcpy(&bits, &d, sizeof bits);
                        round_set.add(bits);
                    }
                    continue;
                }
                const std::vector<std::uint32_t> *chosen_now = nullptr;
                watch.time(ms, [&] { chosen_now = &occluders.choose(f); });
                const std::vector<std::uint32_t> &indices = *chosen_now;
                count += indices.size() / 3;
                sorted.assign(indices.begin(), indices.end());
                for (std::uint32_t i : sorted)
                    round_order.add(i);
                std::sort(sorted.begin(), sorted.end());
                for (std::uint32_t i : sorted)
                    round_set.add(i);
                round_set.add(~0u);
                round_order.add(~0u);
            }
            if (round > 0 && (round_set.h != set.h || round_order.h != order.h || count != chosen)) {
                std::fprintf(stderr, "occu-bench-choice: round %d chose other triangles than round 0\n", round);
                return 1;
            }
            set = round_set;
            order = round_order;
            chosen = count;
            best = round == 0 ? ms : std::min(best, ms);
        }
        std::printf("scene,route,frames,budget,raster,triangles_a_frame,us_a_frame,set_digest,order_digest,buffer_digest\n");
        const auto hex = [](const Digest &d) {
            char text[20];
            std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(d.h));
            return std::string(text);
        };
        std::printf("%s,%s,%zu,%ld,%s,%.1f,%.2f,%s,%s,%s\n", setup.name().c_str(), o.route.c_str(), frames.size(), o.budget,
                    o.raster.c_str(), double(chosen) / double(frames.size()), 1e3 * best / double(frames.size()),
                    rasterize ? "-" : hex(set).c_str(), rasterize ? "-" : hex(order).c_str(),
                    rasterize ? hex(set).c_str() : "-");
    } catch (const std::exception &e) {
        std::fprintf(stderr, "occu-bench-choice: %s\n", e.what());
        return 1;
    }
    return 0;
}
