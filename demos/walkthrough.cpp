// walkthrough: renders a route through a scene with several culling
// strategies and reports what each drew and how long it took.
//
//   walkthrough [--scene FILE] [--route dense|street|medium|open|FILE] [--strategies none,vfc,occu-hier]
//               [--frames N] [--size PIXELS] [--driver llvmpipe|softpipe]
//               [--city-copies N] [--leaf-triangles N] [--batch N]
//               [--threshold T] [--max-test-area A] [--coherent on|off] [--switch-off F]
//               [--occluders N] [--tolerance PIXELS] [--coverage-ratio R] [--occluder-db FILE]
//               [--leaf-geometry on|off] [--map-divisor N]
//               [--png-every N] [--oracle on|off] [--out DIR]
//
// Writes DIR/frames.csv (one row per strategy and frame), DIR/<strategy>-NNNN.png
// and the top view DIR/<strategy>-top-NNNN.png every --png-every frames, and
// prints a summary table. With the oracle (default), each frame is also
// drawn as an ID buffer to find the leaves that are really visible; the
// summary's culling efficiency is occluded leaves culled / occluded leaves.
// Setup and test ms: time in the culler (traversal.h, FrameStats).
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "camera/route.h"
#include "cli/arguments.h"
#include "cli/progress.h"
#include "culling/oracle.h"
#include "culling/traversal.h"
#include "gl/offscreen_context.h"
#include "image/png.h"
#include "mos/occluder_database.h"
#include "render/top_view.h"
#include "scene/city.h"
#include "scene/scene_file.h"

namespace {

struct Options {
    std::string route = "dense";
    std::string scene;   // empty: the procedural city
    std::vector<std::string> strategies = {"none", "vfc", "occu-hier", "occu-hier-shared", "om-ps"};
    int frames = 60;
    int size = 512;
    std::string driver = "llvmpipe";
    int city_copies = 1;
    int leaf_triangles = 256;
    int batch = 32;
    float threshold = 0.0f;
    double max_test_area = 0.25;
    int occluders = 64;
    int tolerance = 0;
    double coverage_ratio = 0.2;
    bool leaf_geometry = false;
    int map_divisor = 4;
    int png_every = 20;
    bool oracle = true;
    bool coherent = true;
    float switch_off = 0.5f;
    std::string out = "walkthrough-out";
    std::string occluder_db;   // mos-om, pc-mos
};

[[noreturn]] void usage(const std::string &error)
{
    std::fprintf(stderr,
                 "%s%susage: walkthrough [--scene FILE] [--route dense|street|medium|open|FILE]\n"
                 "                   [--strategies none,vfc,occu-hier,occu-hier-shared]\n"
                 "                   [--frames N] [--size PIXELS] [--driver llvmpipe|softpipe] [--city-copies N]\n"
                 "                   [--leaf-triangles N] [--batch N] [--threshold T] [--max-test-area A]\n"
                 "                   [--coherent on|off] [--switch-off F] [--occluders N] [--tolerance PIXELS]\n"
                 "                   [--coverage-ratio R (om-*, pc-*: adaptive overlap test, 0 off)]\n"
                 "                   [--leaf-geometry on|off (occu-hier*: test leaves by their triangles)]\n"
                 "                   [--map-divisor N (om-*, pc-*: frame pixels per map pixel, each way; 4)]\n"
                 "                   [--occluder-db FILE (mos-om, pc-mos; made by occu-preprocess)]\n"
                 "                   [--png-every N] [--oracle on|off]\n"
                 "                   [--out DIR]\n",
                 error.empty() ? "" : ("walkthrough: " + error + "\n").c_str(), "");
    std::exit(error.empty() ? 0 : 2);
}

Options parse(int argc, char **argv)
{
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "-h" || a == "--help")
            usage("");
        if (i + 1 >= argc)
            usage("unknown argument or missing value: '" + a + "'");
        const std::string v = argv[++i];
        try {
            if (a == "--route") o.route = v;
            else if (a == "--scene") o.scene = v;
            else if (a == "--strategies") {
                o.strategies.clear();
                std::stringstream ss(v);
                for (std::string s; std::getline(ss, s, ',');)
                    if (!s.empty())
                        o.strategies.push_back(s);
                if (o.strategies.empty())
                    usage("--strategies is empty");
                const auto known = occu::culler_names();
                for (const std::string &name : o.strategies)
                    if (std::find(known.begin(), known.end(), name) == known.end()) {
                        std::string list;
                        for (const std::string &k : known)
                            list += (list.empty() ? "" : ", ") + k;
                        usage("unknown strategy '" + name + "' (known: " + list + ")");
                    }
            }
            else if (a == "--frames") o.frames = int(occu::integer_option(a, v, 1, 100000));
            else if (a == "--size") o.size = int(occu::integer_option(a, v, 16, 8192));
            else if (a == "--driver") o.driver = v;
            else if (a == "--city-copies") o.city_copies = int(occu::integer_option(a, v, 1, 64));
            else if (a == "--leaf-triangles") o.leaf_triangles = int(occu::integer_option(a, v, 1, 1 << 20));
            else if (a == "--batch") o.batch = int(occu::integer_option(a, v, 1, 4096));
            else if (a == "--png-every") o.png_every = int(occu::integer_option(a, v, 0, 100000));
            else if (a == "--occluders") o.occluders = int(occu::integer_option(a, v, 1, 1 << 20));
            else if (a == "--tolerance") o.tolerance = int(occu::integer_option(a, v, 0, 1 << 20));
            else if (a == "--map-divisor") o.map_divisor = int(occu::integer_option(a, v, 1, 64));
            else if (a == "--coverage-ratio") o.coverage_ratio = occu::number_option(a, v, 0.0, 1.0);
            else if (a == "--out") o.out = v;
            else if (a == "--occluder-db") o.occluder_db = v;
            else if (a == "--switch-off") o.switch_off = float(occu::number_option(a, v, 0.0, 1.0));
            else if (a == "--leaf-geometry") o.leaf_geometry = occu::switch_option(a, v);
            else if (a == "--coherent") o.coherent = occu::switch_option(a, v);
            else if (a == "--oracle") o.oracle = occu::switch_option(a, v);
            else if (a == "--threshold") o.threshold = float(occu::number_option(a, v, 0.0, 1.0, false, true));
            else if (a == "--max-test-area") o.max_test_area = occu::number_option(a, v, 0.0, 1.0, true, false);
            else
                usage("unknown argument '" + a + "'");
        } catch (const std::invalid_argument &e) {
            usage(e.what());
        }
    }
    for (const std::string &name : o.strategies)
        if ((name == "mos-om" || name == "pc-mos") && o.occluder_db.empty())
            usage(name + " needs --occluder-db FILE (made by occu-preprocess)");
    return o;
}

}  // namespace

int main(int argc, char **argv)
{
    using namespace occu;
    const Options o = parse(argc, argv);
    try {
        gl::select_driver(gl::parse_driver(o.driver));
        CityOptions city;
        city.copies = o.city_copies;
        // A user scene (OBJ, glTF, ... through assimp) or the default city.
        const Scene scene = o.scene.empty() ? generate_city(city) : load_scene(o.scene);
        HierarchyOptions ho;
        ho.max_leaf_triangles = std::uint32_t(o.leaf_triangles);
        const Hierarchy hierarchy = Hierarchy::build(scene, ho);
        const std::vector<Camera> route = make_route(o.route, scene.bounds, city, o.frames, 1.0f);

        gl::OffscreenContext ctx(o.size, o.size);
        SceneRenderer renderer(scene, hierarchy);
        std::optional<OccluderDatabase> occluder_db;
        if (!o.occluder_db.empty()) {
            occluder_db = OccluderDatabase::load(o.occluder_db);
            if (occluder_db->scene_leaves != hierarchy.leaf_count() ||
                occluder_db->scene_triangles != scene.triangle_count())
                throw std::runtime_error(o.occluder_db + ": made for another scene or hierarchy (" +
                                         std::to_string(occluder_db->scene_triangles) + " triangles, " +
                                         std::to_string(occluder_db->scene_leaves) + " leaves)");
        }
        std::filesystem::create_directories(o.out);
        std::ofstream csv(o.out + "/frames.csv");
        if (!csv)
            throw std::runtime_error("cannot write '" + o.out + "/frames.csv'");
        csv << "strategy,route,frame,ms,triangles,leaves_drawn,nodes_tested,passes,view_culled,occluded,culled_percent,"
               "oracle_visible_leaves,oracle_occluded_leaves,occluded_leaves_culled,visible_leaves_culled,wrong_pixels,setup_ms,test_ms\n";
        std::vector<VisibilityTruth> truths(route.size());
        auto reference_culler = make_culler("none");
        std::vector<std::uint8_t> reference;
        std::printf("scene: %zu triangles, %zu leaves; route %s, %zu frames, %dx%d, %s\n", scene.triangle_count(),
                    hierarchy.leaf_count(), o.route.c_str(), route.size(), o.size, o.size, ctx.renderer().c_str());

        struct Summary {
            std::vector<double> ms;
            double triangles = 0, passes = 0, setup_ms = 0, test_ms = 0;
            std::uint64_t occluded = 0, occluded_culled = 0, visible_culled = 0, wrong_pixels = 0;
            bool conservative = true;
        };
        std::map<std::string, Summary> summary;
        TraversalOptions to;
        to.batch = std::size_t(o.batch);
        glEnable(GL_DEPTH_TEST);
        glEnable(GL_CULL_FACE);
        glClearColor(0.55f, 0.7f, 0.9f, 1.0f);
        // Every strategy renders frame f before any renders frame f + 1, so
        // that the machine's load, which drifts, weighs on all of them alike.
        struct Run {
            std::string name;
            std::unique_ptr<Culler> culler;
            Coherence coherence;   // temporal coherence, for the strategies that test occlusion
            bool coherent = false;
        };
        std::vector<Run> runs;
        for (const std::string &name : o.strategies) {
            CullerOptions co;
            co.adaptive_threshold = o.threshold;
            co.max_test_area = o.max_test_area;
            co.occluders = std::size_t(o.occluders);
            co.tolerance = std::uint32_t(o.tolerance);
            co.coverage_ratio = o.coverage_ratio;
            co.leaf_geometry = o.leaf_geometry;
            co.map_divisor = o.map_divisor;
            co.hierarchy = &hierarchy;
            co.renderer = &renderer;
            co.occluder_database = occluder_db ? &*occluder_db : nullptr;
            Run r;
            r.name = name;
            r.culler = make_culler(name, co);
            r.coherence.switch_off_fraction = o.switch_off;
            r.coherent = o.coherent && name.rfind("occu-", 0) == 0;
            runs.push_back(std::move(r));
        }
        for (std::size_t f = 0; f < route.size(); ++f) {
            for (Run &run : runs) {
                const std::string &name = run.name;
                Culler *culler = run.culler.get();
                Summary &s = summary[name];
                Coherence *use_coherence = run.coherent ? &run.coherence : nullptr;
                const auto start = std::chrono::steady_clock::now();
                glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
                load_camera(route[f]);
                const FrameStats st = render_hierarchy(renderer, hierarchy, *culler, route[f], to, use_coherence);
                glFinish();
                const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
                s.ms.push_back(ms);
                s.triangles += double(st.triangles);
                s.passes += st.passes;
                s.setup_ms += st.setup_ms;
                s.test_ms += st.test_ms;
                // Approximate strategies: count the pixels that differ from the
                // unculled frame (drawn untimed, after the measured one).
                std::uint64_t wrong = 0;
                s.conservative = culler->conservative();
                if (!culler->conservative()) {
                    const std::size_t n = std::size_t(o.size) * std::size_t(o.size) * 4;
                    const std::vector<std::uint8_t> culled(ctx.pixels(), ctx.pixels() + n);
                    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
                    render_hierarchy(renderer, hierarchy, *reference_culler, route[f], to);
                    glFinish();
                    for (std::size_t i = 0; i < n; i += 4)
                        wrong += std::memcmp(&culled[i], ctx.pixels() + i, 4) != 0;
                    s.wrong_pixels += wrong;
                    std::memcpy(ctx.pixels_mutable(), culled.data(), n);   // the PNG shows the culled frame
                }
                if (o.png_every > 0 && f % std::size_t(o.png_every) == 0) {
                    char file[80];
                    std::snprintf(file, sizeof(file), "/%s-%04zu.png", name.c_str(), f);
                    write_png(o.out + file, o.size, o.size, ctx.pixels());
                    render_top_view(hierarchy, route[f], st.drawn);
                    glFinish();
                    std::snprintf(file, sizeof(file), "/%s-top-%04zu.png", name.c_str(), f);
                    write_png(o.out + file, o.size, o.size, ctx.pixels());
                }
                CullingQuality q;
                if (o.oracle) {
                    if (truths[f].in_frustum.empty())   // the same for every strategy
                        truths[f] = exact_visibility(renderer, hierarchy, route[f], o.size, o.size);
                    q = compare_with_truth(truths[f], st.drawn);
                    s.occluded += q.occluded;
                    s.occluded_culled += q.occluded_culled;
                    s.visible_culled += q.visible_culled;
                }
                csv << name << ',' << o.route << ',' << f << ',' << ms << ',' << st.triangles << ',' << st.leaves_drawn
                    << ',' << st.nodes_tested << ',' << st.passes << ',' << st.nodes_view_culled << ','
                    << st.nodes_occluded << ',' << 100.0 * (1.0 - double(st.triangles) / double(scene.triangle_count()))
                    << ',' << truths[f].visible.size() << ',' << q.occluded << ',' << q.occluded_culled << ','
                    << q.visible_culled << ',' << wrong << ',' << st.setup_ms << ','
                    << st.test_ms << '\n';
                glEnable(GL_DEPTH_TEST);
                glEnable(GL_CULL_FACE);
            }
            progress("frames", long(f + 1), long(route.size()));
        }

        const double vfc_ms = summary.count("vfc") ? [&] {
            auto v = summary["vfc"].ms;
            double t = 0;
            for (double x : v) t += x;
            return t / double(v.size());
        }() : 0.0;
        std::printf("\n%-17s %10s %10s %12s %8s %8s %11s %14s %13s %8s %8s\n", "strategy", "mean ms", "median ms",
                    "triangles", "passes", "vs vfc", "efficiency", "visible culled", "wrong pixels", "setup ms", "test ms");
        for (const std::string &name : o.strategies) {
            Summary s = summary[name];
            double total = 0;
            for (double x : s.ms) total += x;
            const double mean = total / double(s.ms.size());
            std::sort(s.ms.begin(), s.ms.end());
            const double n = double(s.ms.size());
            char efficiency[32] = "-";
            if (o.oracle && s.occluded)
                std::snprintf(efficiency, sizeof(efficiency), "%.1f%%", 100.0 * double(s.occluded_culled) / double(s.occluded));
            char wrong[32] = "-";
            if (!s.conservative)
                std::snprintf(wrong, sizeof(wrong), "%.1f", double(s.wrong_pixels) / n);
            std::printf("%-17s %10.2f %10.2f %12.0f %8.1f %8s %11s %14llu %13s %8.2f %8.2f\n", name.c_str(), mean,
                        s.ms[s.ms.size() / 2], s.triangles / n, s.passes / n,
                        vfc_ms > 0 ? (std::to_string(vfc_ms / mean).substr(0, 5) + "x").c_str() : "-", efficiency,
                        (unsigned long long)s.visible_culled, wrong, s.setup_ms / n, s.test_ms / n);
        }
        std::printf("\nframes: %s/<strategy>-NNNN.png; top views: %s/<strategy>-top-NNNN.png; per-frame data: "
                    "%s/frames.csv\n",
                    o.out.c_str(), o.out.c_str(), o.out.c_str());
        return 0;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "walkthrough: %s\n", e.what());
        return 1;
    }
}
