// SPDX-License-Identifier: MIT
// occu-collide: collision detection with occlusion tiles (Bartz, Meissner
// and Huettner 1998, section 5, figure 7; applications/collision_detection.h)
// along a route. At every camera of the route it checks a step of --step
// metres in the view direction (forward, and with --direction backward or
// both the step back, the paper's second pass) twice: with the GL check
// (the step's far face in one GL_BRIEF_OCCLUSION_MESAX pass over figure 7's
// 3 x 3 tiles) and with the exact CPU test (the same volume against the
// triangles, through the hierarchy), and reports a confusion table of the
// GL check against the exact test, per tile and overall, why they differ
// where they do, and the time per check of each.
//
// Writes DIR/steps.csv (one row per step, direction and tile) and, every
// --png-every cameras, DIR/forward-NNNN.png (and DIR/backward-NNNN.png: the
// turned view) with the tiles tinted by their result.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "applications/collision_detection.h"
#include "cli/arguments.h"
#include "cli/progress.h"
#include "evaluation/scene_setup.h"
#include "gl/offscreen_context.h"
#include "image/png.h"

namespace {

using namespace occu;

struct Options {
    std::string route = "dense";
    std::string scene;   // empty: the procedural city
    int frames = 200;
    double step = 2.0;
    int size = 384;
    std::string driver = "llvmpipe";
    int city_copies = 1;
    std::uint32_t leaf_triangles = HierarchyOptions{}.max_leaf_triangles;
    bool forward = true, backward = false;
    int png_every = 25;
    std::string out = "collide-out";
};

[[noreturn]] void usage(const std::string &error)
{
    std::FILE *to = error.empty() ? stdout : stderr;
    if (!error.empty())
        std::fprintf(to, "occu-collide: %s\n", error.c_str());
    std::fprintf(to,
                 "usage: occu-collide [--scene city|field|FILE|PAK.pk3:maps/LEVEL.bsp]\n"
                 "                    [--route dense|street|medium|open|orbit|overhead|random:N:SEED|spawn[:K]|FILE]\n"
                 "                    [--frames N] [--step METRES] [--direction forward|backward|both]\n"
                 "                    [--size PIXELS] [--driver llvmpipe|softpipe] [--city-copies N]\n"
                 "                    [--leaf-triangles N|auto] [--png-every N] [--out DIR]\n"
                 "At every camera of the route, checks a step of --step metres (beyond the cameras' near plane)\n"
                 "along the view direction, or back from it, with the Occlusion Unit (Bartz et al. 1998, section\n"
                 "5: the step's far face drawn in one GL_BRIEF_OCCLUSION_MESAX pass over figure 7's 3x3 tiles;\n"
                 "a tile collides where NOHC != PHC) and with the exact CPU test of the same volume against the\n"
                 "scene's triangles. Prints the confusion table of the GL check against the exact test (positive:\n"
                 "collision), per tile and overall, why they differ (sub-pixel geometry, depth precision, or\n"
                 "unexplained), and the mean time per check: the GL check's pass and its readback, not the\n"
                 "frame it tests (forward), but with the second pass's drawing (backward); the exact test's\n"
                 "hierarchy traversal and triangle clipping.\n"
                 "Writes DIR/steps.csv and, every --png-every cameras (0: none), DIR/forward-NNNN.png (and\n"
                 "DIR/backward-NNNN.png, the turned view) with the tiles tinted: red where both methods find a\n"
                 "collision, green where both find the step free, yellow where they disagree.\n");
    std::exit(error.empty() ? 0 : 2);
}

Options parse(int argc, char **argv)
{
    Options o;
    for_each_option(argc, argv, usage, [&](const std::string &a, const std::string &v) {
        if (a == "--route") o.route = v;
        else if (a == "--scene") o.scene = v;
        else if (a == "--frames") o.frames = int(integer_option(a, v, 1, 1000000));
        else if (a == "--step") o.step = number_option(a, v, 0.0, 1e6, true);
        else if (a == "--size") o.size = int(integer_option(a, v, 3, 8192));
        else if (a == "--driver") o.driver = v;
        else if (a == "--city-copies") o.city_copies = int(integer_option(a, v, 1, 64));
        else if (a == "--leaf-triangles") o.leaf_triangles = leaf_triangles_option(a, v);
        else if (a == "--png-every") o.png_every = int(integer_option(a, v, 0, 1000000));
        else if (a == "--out") o.out = v;
        else if (a == "--direction") {
            if (v != "forward" && v != "backward" && v != "both")
                usage("--direction wants forward, backward or both, got '" + v + "'");
            o.forward = v != "backward";
            o.backward = v != "forward";
        } else {
            return false;
        }
        return true;
    });
    return o;
}

// Per tile and overall: the GL check's answers against the exact test's.
struct Confusion {
    long tp = 0, fp = 0, fn = 0, tn = 0;
    long sub_pixel = 0, precision = 0, unexplained = 0;
    void add(bool gl, bool exact, Agreement why)
    {
        (gl ? (exact ? tp : fp) : (exact ? fn : tn)) += 1;
        sub_pixel += why == Agreement::sub_pixel;
        precision += why == Agreement::depth_precision;
        unexplained += why == Agreement::unexplained;
    }
    Confusion &operator+=(const Confusion &c)
    {
        tp += c.tp, fp += c.fp, fn += c.fn, tn += c.tn;
        sub_pixel += c.sub_pixel, precision += c.precision, unexplained += c.unexplained;
        return *this;
    }
};

struct Times {
    std::vector<double> ms;
    double mean() const
    {
        double t = 0;
        for (double x : ms)
            t += x;
        return ms.empty() ? 0.0 : t / double(ms.size());
    }
    double median() const
    {
        std::vector<double> s = ms;
        std::sort(s.begin(), s.end());
        return s.empty() ? 0.0 : s[s.size() / 2];
    }
};

// One direction's totals.
struct Direction {
    StepDirection direction;
    std::array<Confusion, collision_tile_count> tiles;
    Times gl, exact;
    long steps = 0, steps_gl = 0, steps_exact = 0;   // steps with any tile colliding
};

double ms_since(std::chrono::steady_clock::time_point start)
{
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// The frame in the context's colour buffer with each tile tinted by its
// result, and a dark line along the tile edges.
void write_tinted(const std::string &path, const gl::OffscreenContext &ctx, const CollisionResult &gl,
                  const std::array<bool, collision_tile_count> &exact)
{
    const int w = ctx.width(), h = ctx.height();
    std::vector<std::uint8_t> rgba(ctx.pixels(), ctx.pixels() + std::size_t(w) * std::size_t(h) * 4);
    const auto tiles = heading_tiles({0, 0, w, h});
    for (int k = 0; k < collision_tile_count; ++k) {
        const bool g = gl.tiles[std::size_t(k)].collides, e = exact[std::size_t(k)];
        const std::uint8_t red[3] = {230, 40, 40}, green[3] = {40, 200, 60}, yellow[3] = {245, 220, 0};
        const std::uint8_t *tint = g != e ? yellow : g ? red : green;
        const PixelRect &t = tiles[std::size_t(k)];
        for (int y = t.y0; y < t.y1; ++y)
            for (int x = t.x0; x < t.x1; ++x) {
                std::uint8_t *p = &rgba[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * 4];
                const bool edge = x == t.x0 || y == t.y0;
                for (int c = 0; c < 3; ++c)
                    p[c] = edge ? std::uint8_t(p[c] / 4) : std::uint8_t((p[c] * 3 + tint[c] * 2) / 5);
            }
    }
    write_png(path, w, h, rgba.data());
}

void print_table(const Direction &d)
{
    std::printf("\n%s steps: %ld; with a collision: GL %ld, exact %ld\n", step_direction_name(d.direction), d.steps,
                d.steps_gl, d.steps_exact);
    std::printf("%-20s %7s %7s %7s %7s %9s %9s   %s\n", "tile", "TP", "FP", "FN", "TN", "precision", "recall",
                "disagreements: sub-pixel / depth precision / unexplained");
    Confusion all;
    auto row = [](const char *name, const Confusion &c) {
        char precision[16] = "-", recall[16] = "-";
        if (c.tp + c.fp)
            std::snprintf(precision, sizeof(precision), "%.4f", double(c.tp) / double(c.tp + c.fp));
        if (c.tp + c.fn)
            std::snprintf(recall, sizeof(recall), "%.4f", double(c.tp) / double(c.tp + c.fn));
        std::printf("%-20s %7ld %7ld %7ld %7ld %9s %9s   %ld / %ld / %ld\n", name, c.tp, c.fp, c.fn, c.tn, precision,
                    recall, c.sub_pixel, c.precision, c.unexplained);
    };
    for (int k = 0; k < collision_tile_count; ++k) {
        row(heading_name(k), d.tiles[std::size_t(k)]);
        all += d.tiles[std::size_t(k)];
    }
    row("all tiles", all);
    std::printf("time per check, ms: GL mean %.3f median %.3f; exact mean %.3f median %.3f\n", d.gl.mean(),
                d.gl.median(), d.exact.mean(), d.exact.median());
}

}  // namespace

int main(int argc, char **argv)
{
    const Options o = parse(argc, argv);
    try {
        gl::select_driver(gl::parse_driver(o.driver));
        const SceneSetup setup({o.scene, o.city_copies, o.leaf_triangles});
        const Scene &scene = setup.scene();
        const Hierarchy &hierarchy = setup.hierarchy();
        const std::vector<Camera> route = setup.route(o.route, o.frames);
        // Every camera must have a check volume for the step, before any work.
        for (std::size_t f = 0; f < route.size(); ++f)
            if (!(o.step > double(route[f].near_plane)) || !(o.step < double(route[f].far_plane))) {
                char why[256];
                std::snprintf(why, sizeof(why),
                              "--step %g m has no check volume at camera %zu of route '%s': a step must reach "
                              "beyond its near plane (%g m) and stay before its far plane (%g m)",
                              o.step, f, o.route.c_str(), double(route[f].near_plane), double(route[f].far_plane));
                usage(why);
            }

        gl::OffscreenContext ctx(o.size, o.size);
        SceneRenderer renderer(scene, hierarchy);
        CollisionCheck check(renderer, hierarchy);
        const ExactCollisionTest exact(scene, hierarchy);
        std::filesystem::create_directories(o.out);
        const std::string csv_path = o.out + "/steps.csv";
        std::ofstream csv(csv_path);
        if (!csv)
            throw std::runtime_error("cannot write '" + csv_path + "'");
        csv << "camera,direction,tile,heading,nohc,phc,gl,exact,agreement,gl_ms,exact_ms\n";
        std::printf("scene: %zu triangles, %zu leaves of at most %u; route %s, %zu cameras, step %g m, %dx%d, %s\n",
                    scene.triangle_count(), hierarchy.leaf_count(), unsigned(hierarchy.max_leaf_triangles()),
                    o.route.c_str(), route.size(), o.step, o.size,
                    o.size, ctx.renderer().c_str());

        glViewport(0, 0, o.size, o.size);
        glClearColor(0.55f, 0.7f, 0.9f, 1.0f);
        std::vector<Direction> directions;
        if (o.forward)
            directions.push_back({StepDirection::forward, {}, {}, {}});
        if (o.backward)
            directions.push_back({StepDirection::backward, {}, {}, {}});
        const float step = float(o.step);
        for (std::size_t f = 0; f < route.size(); ++f) {
            const Camera &camera = route[f];
            const bool png = o.png_every > 0 && f % std::size_t(o.png_every) == 0;
            for (Direction &d : directions) {
                // The frame the forward check tests, untimed and finished
                // before the check's clock starts.
                if (d.direction == StepDirection::forward) {
                    draw_collision_frame(renderer, hierarchy, camera);
                    glFinish();
                }
                auto start = std::chrono::steady_clock::now();
                const CollisionResult gl = check.check(camera, step, d.direction);
                d.gl.ms.push_back(ms_since(start));
                start = std::chrono::steady_clock::now();
                const auto truth = exact.check(camera, step, d.direction, o.size, o.size);
                d.exact.ms.push_back(ms_since(start));
                const auto why = exact.explain(camera, step, d.direction, o.size, o.size, gl, truth);
                ++d.steps;
                d.steps_gl += gl.any();
                d.steps_exact += std::any_of(truth.begin(), truth.end(), [](bool b) { return b; });
                for (int k = 0; k < collision_tile_count; ++k) {
                    const TileCheck &t = gl.tiles[std::size_t(k)];
                    d.tiles[std::size_t(k)].add(t.collides, truth[std::size_t(k)], why[std::size_t(k)]);
                    csv << f << ',' << step_direction_name(d.direction) << ',' << k << ',' << heading_name(k) << ','
                        << t.nohc << ',' << t.phc << ',' << t.collides << ',' << truth[std::size_t(k)] << ','
                        << agreement_name(why[std::size_t(k)]) << ',' << d.gl.ms.back() << ',' << d.exact.ms.back()
                        << '\n';
                }
                if (png) {
                    if (d.direction == StepDirection::backward)
                        draw_collision_frame(renderer, hierarchy, check_camera(camera, StepDirection::backward));
                    glFinish();
                    char name[64];
                    std::snprintf(name, sizeof(name), "/%s-%04zu.png", step_direction_name(d.direction), f);
                    write_tinted(o.out + name, ctx, gl, truth);
                }
            }
            progress("steps", long(f + 1), long(route.size()));
        }
        if (!csv.flush())
            throw std::runtime_error("cannot write '" + csv_path + "'");
        for (const Direction &d : directions)
            print_table(d);
        std::printf("\npositive: a collision; TP/FP/FN/TN: the GL check's answers against the exact test's.\n"
                    "GL time: the pass and its readback (forward: not the frame; backward: with the second pass's\n"
                    "drawing); exact: traversal and clipping. Per step and tile: %s\n",
                    csv_path.c_str());
        return 0;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "occu-collide: %s\n", e.what());
        return 1;
    }
}
