// occu-random-views: renders random cameras over several scenes with every
// conservative strategy of the registry and counts the visible pixels each
// frame lost against the unculled frame of the same camera (must be 0;
// evaluation/lost_pixels.h defines them), with culling efficiency against
// the exact-visibility oracle and frame times beside vfc and ideal.
//
// Cameras: the random route's (camera/route.h, random:N:SEED): eyes
// uniformly inside the scene's bounds (in the city: streets, courtyards,
// roofs and the insides of buildings alike, from the ground up to the
// tallest roof), random headings, pitch within 60 degrees of the horizon,
// and a field of view drawn from --fov.
//
// Writes DIR/views.csv (one row per scene, view and strategy, with the
// camera) and DIR/summary.csv (one row per scene and strategy), prints a
// table per scene, and exits with status 1 when any pixel was lost, naming
// the first strategy, scene and view that lost one.
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
#include "culling/registry.h"
#include "evaluation/lost_pixels.h"
#include "evaluation/oracle.h"
#include "gl/offscreen_context.h"
#include "gl/state.h"
#include "scene/city.h"
#include "scene/pk3_archive.h"
#include "scene/scene_file.h"
#include "strategies/poon_wang_opacity_maps/view_preprocessing.h"
#include "traversal/traversal.h"

namespace {

using namespace occu;

// The two real models of the default run, from Debian's assimp-testmodels:
// a two-storey house with its rooms, walls, stairs and furniture (IFC), and
// Khronos' two-cylinder engine, a few hundred nested parts (glTF binary).
const char *const default_models[] = {
    "/usr/share/assimp/models/IFC/AC14-FZK-Haus.ifc",
    "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb",
};

struct Options {
    std::vector<std::string> scenes;   // "city" or a file; empty: the city and default_models
    long views = 300;                  // over all scenes
    unsigned long seed = 2026;
    int size = 128;
    std::vector<std::string> strategies;   // empty: every conservative strategy (default_strategies)
    std::string driver = "llvmpipe";
    int leaf_triangles = 256;
    int batch = 32;
    bool coherence = false;
    double switch_off = 0.0;
    float fov_min = 20.0f, fov_max = 120.0f;
    glm::ivec3 mos_grid{4, 2, 4};   // the databases made at start: cells of the bounds
    int mos_headings = 4;
    std::string out = "random-views-out";
};

[[noreturn]] void usage(const std::string &error)
{
    std::FILE *to = error.empty() ? stdout : stderr;
    if (!error.empty())
        std::fprintf(to, "occu-random-views: %s\n", error.c_str());
    std::fprintf(to,
                 "usage: occu-random-views [--scene city|field|FILE[,...]]... [--views N] [--seed S]\n"
                 "                         [--size PIXELS] [--strategies NAME[:key=value...],...]\n"
                 "                         [--driver llvmpipe|softpipe] [--fov MIN,MAX] [--leaf-triangles N]\n"
                 "                         [--batch N] [--coherence on|off] [--switch-off F]\n"
                 "                         [--mos-grid NX,NY,NZ/HEADINGS] [--out DIR]\n"
                 "Renders --views random cameras (300; shared evenly among the scenes) with every strategy and\n"
                 "counts the visible pixels each frame lost against the unculled frame of the same camera.\n"
                 "Scenes (default: city,%s,%s):\n"
                 "'city' is the procedural city; a FILE is read through assimp. Strategies (default: every\n"
                 "conservative strategy of the registry, presets included; pvs runs only on the city, the one\n"
                 "scene with 2.5D occluders). om-mos and pc-mos without database=FILE take an occluder database\n"
                 "made at start for each scene: a view of each heading at the centre of each cell of the\n"
                 "scene's bounds (--mos-grid, 4,2,4/4). --fov: vertical fields of view in degrees (20,120).\n"
                 "--coherence (off) and\n"
                 "--switch-off (0: never) are walkthrough's traversal policies. Exit status 1 when a pixel\n"
                 "was lost, 2 on a bad option.\n\nstrategies:\n%s",
                 default_models[0], default_models[1], strategies_help().c_str());
    std::exit(error.empty() ? 0 : 2);
}

// Every conservative strategy the registry names (families and presets).
std::vector<std::string> default_strategies()
{
    std::vector<std::string> names;
    for (const std::string &name : strategy_names())
        if (choose_strategy(name).conservative())
            names.push_back(name);
    return names;
}

// A strategy that takes its occluders from a minimum-occluder-set database
// and was given none: the run makes one at start, per scene.
bool needs_database(const StrategyChoice &c)
{
    return c.settings.knows("selection") && c.settings.text("selection") == "mos" && c.settings.text("database").empty();
}

Options parse(int argc, char **argv)
{
    Options o;
    for_each_option(argc, argv, usage, [&](const std::string &a, const std::string &v) {
        if (a == "--scene") {
            const std::vector<std::string> s = list_items(v, ',');
            if (s.empty())
                usage("--scene is empty");
            o.scenes.insert(o.scenes.end(), s.begin(), s.end());
        }
        else if (a == "--views") o.views = integer_option(a, v, 1, 10000000);
        else if (a == "--seed") o.seed = (unsigned long)integer_option(a, v, 0, 0xffffffffL);
        else if (a == "--size") o.size = int(integer_option(a, v, 16, 4096));
        else if (a == "--strategies") {
            o.strategies = list_items(v, ',');
            if (o.strategies.empty())
                usage("--strategies is empty");
        }
        else if (a == "--driver") o.driver = v;
        else if (a == "--leaf-triangles") o.leaf_triangles = int(integer_option(a, v, 1, 1 << 20));
        else if (a == "--batch") o.batch = int(integer_option(a, v, 1, 4096));
        else if (a == "--coherence") o.coherence = switch_option(a, v);
        else if (a == "--switch-off") o.switch_off = number_option(a, v, 0.0, 1.0);
        else if (a == "--fov") {
            const std::vector<std::string> f = list_items(v, ',');
            if (f.size() != 2)
                usage("--fov is MIN,MAX in degrees, got '" + v + "'");
            o.fov_min = float(number_option(a, f[0], 1.0, 170.0));
            o.fov_max = float(number_option(a, f[1], 1.0, 170.0));
            if (o.fov_min > o.fov_max)
                usage("--fov is MIN,MAX: " + f[0] + " > " + f[1]);
        }
        else if (a == "--mos-grid") {
            std::istringstream in(v);
            char c1 = 0, c2 = 0, slash = 0;
            glm::ivec3 g;
            int h = 0;
            if (!(in >> g.x >> c1 >> g.y >> c2 >> g.z >> slash >> h) || c1 != ',' || c2 != ',' || slash != '/' ||
                !in.eof() || g.x < 1 || g.y < 1 || g.z < 1 || h < 1 || h > 64 || g.x * g.y * g.z > 4096)
                usage("--mos-grid is NX,NY,NZ/HEADINGS (at most 4096 points, 64 headings), got '" + v + "'");
            o.mos_grid = g;
            o.mos_headings = h;
        }
        else if (a == "--out") o.out = v;
        else
            return false;
        return true;
    });
    if (o.scenes.empty())
        o.scenes = {"city", default_models[0], default_models[1]};
    if (o.views < long(o.scenes.size()))
        usage("--views " + std::to_string(o.views) + " gives some of the " + std::to_string(o.scenes.size()) +
              " scenes no view");
    try {
        gl::parse_driver(o.driver);
    } catch (const std::exception &e) {
        usage(e.what());
    }
    // Strategies are checked before anything is built.
    if (o.strategies.empty())
        o.strategies = default_strategies();
    try {
        for (const std::string &s : o.strategies)
            choose_strategy(s);
    } catch (const std::invalid_argument &e) {
        usage(e.what());
    }
    return o;
}

// Per scene and strategy: its culler and what it measured.
struct Run {
    Strategy strategy;
    std::optional<VisibleNodeList> coherence;
    std::optional<SwitchOff> switch_off;
    double ms = 0, triangles = 0;
    std::uint64_t views = 0, occluded = 0, occluded_culled = 0, visible_culled = 0, lost = 0, tied = 0;
    double mean_ms() const { return views ? ms / double(views) : 0.0; }
    std::string label() const { return strategy.choice.label(); }
};

struct Failure {
    std::string strategy, scene;
    long view = -1;
    std::uint64_t pixels = 0;
    Camera camera;
};

struct Totals {
    long views = 0, frames = 0;
    std::uint64_t lost = 0;
    std::optional<Failure> first;
};

std::string csv_field(const std::string &text)
{
    if (text.find_first_of(",\"") == std::string::npos)
        return text;
    std::string q = "\"";
    for (char c : text)
        q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

// One scene: its cameras through every strategy.
void run_scene(const Options &o, std::size_t scene_index, const std::string &scene_name, const Scene &scene,
               long views, unsigned long seed, std::ofstream &csv, std::ofstream &summary, Totals &totals)
{
    HierarchyOptions ho;
    ho.max_leaf_triangles = std::uint32_t(o.leaf_triangles);
    const Hierarchy hierarchy = Hierarchy::build(scene, ho);
    const std::vector<Camera> cameras = random_views(scene.bounds, views, seed, 1.0f, o.fov_min, o.fov_max, scene.quake3.get());

    gl::OffscreenContext ctx(o.size, o.size);
    SceneRenderer renderer(scene, hierarchy);
    const StrategyContext context{scene, hierarchy, renderer};
    // Occluder databases for the strategies that need one, one per map
    // resolution (the frame's size / the strategy's map divisor).
    std::map<int, std::string> databases;
    for (const std::string &spec : o.strategies) {
        const StrategyChoice c = choose_strategy(spec);
        if (!needs_database(c))
            continue;
        const int resolution = o.size / int(c.settings.integer("map-divisor"));
        if (databases.count(resolution))
            continue;
        const auto start = std::chrono::steady_clock::now();
        PreprocessOptions pre;
        pre.stacks.resolution = resolution;
        pre.stacks.map_divisor = int(c.settings.integer("map-divisor"));
        Camera lens;
        lens.near_plane = 1e-3f * std::max(glm::length(scene.bounds.extent()), 1e-3f);
        lens.far_plane = 2.0f * std::max(glm::length(scene.bounds.extent()), 1e-3f);
        const OccluderDatabase db =
            preprocess_database(renderer, hierarchy, scene.bounds, o.mos_grid, o.mos_headings, lens, pre);
        const std::string path = o.out + "/occluders-" + std::to_string(scene_index) + "-" +
                                 std::to_string(resolution) + ".db";
        db.save(path);
        databases[resolution] = path;
        std::printf("occluder database at start (for %s and the other mos strategies of its maps): %u views (%dx%dx%d points, %d headings), %dx%d maps, %.1f s: %s\n",
                    spec.c_str(), db.grid.view_count(), o.mos_grid.x, o.mos_grid.y, o.mos_grid.z, o.mos_headings,
                    resolution, resolution,
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), path.c_str());
    }
    // The frames' state, set after the preprocessing, which draws with its own.
    glViewport(0, 0, o.size, o.size);
    glEnable(GL_DEPTH_TEST);
    glEnable(GL_CULL_FACE);
    glClearColor(0.55f, 0.7f, 0.9f, 1.0f);
    std::vector<Run> runs;
    std::vector<std::string> left_out;
    for (const std::string &spec : o.strategies) {
        // pvs serves scenes with 2.5D occluders (the city's buildings) and refuses the others.
        if (choose_strategy(spec).family->name == "pvs" && scene.prism_occluders.empty()) {
            left_out.push_back(spec);
            continue;
        }
        const StrategyChoice c = choose_strategy(spec);
        std::vector<std::string> common;
        if (needs_database(c))
            common.push_back("database=" + databases.at(o.size / int(c.settings.integer("map-divisor"))));
        Run r{make_strategy(spec, context, common), {}, {}};
        const StrategyFamily &family = *r.strategy.choice.family;
        if (family.queries_rasterizer && o.coherence)
            r.coherence.emplace();
        if ((family.queries_rasterizer || family.costs_per_frame) && o.switch_off > 0.0) {
            SwitchOff::Settings s;
            s.min_gain = o.switch_off * family.switch_off_share;
            r.switch_off.emplace(s);
        }
        runs.push_back(std::move(r));
    }
    const Strategy none = make_strategy("none", context);
    Oracle oracle(renderer, hierarchy);
    std::printf("\nscene %s: %zu triangles, %zu leaves; %ld random views (seed %lu), %dx%d, fov %g..%g, %s\n",
                scene_name.c_str(), scene.triangle_count(), hierarchy.leaf_count(), views, seed, o.size, o.size,
                double(o.fov_min), double(o.fov_max), ctx.renderer().c_str());
    for (const std::string &s : left_out)
        std::printf("left out: %s (it needs a scene with 2.5D occluders, as the city's buildings)\n", s.c_str());
    std::fflush(stdout);

    const std::size_t pixels = std::size_t(o.size) * std::size_t(o.size);
    std::vector<std::uint8_t> unculled(pixels * 4);
    TraversalOptions plain;
    plain.batch = std::size_t(o.batch);
    for (long v = 0; v < views; ++v) {
        const Camera &camera = cameras[std::size_t(v)];
        // The oracle's answer first (it overwrites the framebuffer), then the
        // unculled frame in the common traversal's order.
        const VisibilityTruth truth = oracle.see(camera, o.size, o.size);
        const Frame frame(camera, o.size, o.size, &truth);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        gl::load_camera(camera);
        render_hierarchy(renderer, hierarchy, *none.culler, frame, plain);
        glFinish();
        std::memcpy(unculled.data(), ctx.pixels(), pixels * 4);
        // The order rotates from view to view, as in walkthrough.
        for (std::size_t k = 0; k < runs.size(); ++k) {
            Run &run = runs[(k + std::size_t(v)) % runs.size()];
            TraversalOptions traversal = plain;
            traversal.coherence = run.coherence ? &*run.coherence : nullptr;
            traversal.switch_off = run.switch_off ? &*run.switch_off : nullptr;
            const auto start = std::chrono::steady_clock::now();
            glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
            gl::load_camera(camera);
            const FrameStats stats = render_hierarchy(renderer, hierarchy, *run.strategy.culler, frame, traversal);
            glFinish();
            const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
            // A strategy that orders the frame itself is always compared with
            // its reference; the others first with the common unculled frame.
            const PixelLoss loss =
                count_lost_pixels(renderer, hierarchy, camera, stats.drawn,
                                  run.strategy.culler->orders_frame() ? nullptr : unculled.data(), ctx.pixels(), pixels);
            const std::uint64_t lost = loss.lost;
            const CullingQuality q = compare_with_truth(truth, stats.drawn);
            run.views += 1;
            run.ms += ms;
            run.triangles += double(stats.triangles);
            run.occluded += q.occluded;
            run.occluded_culled += q.occluded_culled;
            run.visible_culled += q.visible_culled;
            run.lost += lost;
            run.tied += loss.tied;
            totals.frames += 1;
            totals.lost += lost;
            if (lost && !totals.first)
                totals.first = Failure{run.label(), scene_name, v, lost, camera};
            csv << csv_field(scene_name) << ',' << v << ',' << csv_field(run.label()) << ',' << camera.position.x << ','
                << camera.position.y << ',' << camera.position.z << ',' << camera.target.x << ',' << camera.target.y
                << ',' << camera.target.z << ',' << camera.fovy_degrees << ',' << ms << ',' << stats.triangles << ','
                << stats.leaves_drawn << ',' << truth.visible.size() << ',' << q.occluded << ',' << q.occluded_culled
                << ',' << q.visible_culled << ',' << lost << ',' << loss.tied << '\n';
        }
        totals.views += 1;
        progress("views of " + scene_name, v + 1, views);
    }

    auto mean_of = [&runs](const char *name) {
        for (const Run &r : runs)
            if (r.label() == name)
                return r.mean_ms();
        return 0.0;
    };
    const double vfc_ms = mean_of("vfc"), ideal_ms = mean_of("ideal");
    std::uint64_t scene_lost = 0;
    std::printf("%-20s %6s %9s %7s %8s %10s %10s %8s %11s %9s\n", "strategy", "views", "mean ms", "vs vfc", "x ideal",
                "triangles", "efficiency", "vis cull", "lost pixels", "tied px");
    for (const Run &r : runs) {
        const double n = double(std::max<std::uint64_t>(1, r.views)), mean = r.mean_ms();
        char vs_vfc[32] = "-", x_ideal[32] = "-", efficiency[32] = "-";
        if (vfc_ms > 0 && mean > 0)
            std::snprintf(vs_vfc, sizeof(vs_vfc), "%.2fx", vfc_ms / mean);
        if (ideal_ms > 0 && mean > 0)
            std::snprintf(x_ideal, sizeof(x_ideal), "%.2fx", mean / ideal_ms);
        if (r.occluded)
            std::snprintf(efficiency, sizeof(efficiency), "%.1f%%", 100.0 * double(r.occluded_culled) / double(r.occluded));
        std::printf("%-20s %6llu %9.2f %7s %8s %10.0f %10s %8llu %11llu %9llu\n", r.label().c_str(),
                    (unsigned long long)r.views, mean, vs_vfc, x_ideal, r.triangles / n, efficiency,
                    (unsigned long long)r.visible_culled, (unsigned long long)r.lost, (unsigned long long)r.tied);
        summary << csv_field(scene_name) << ',' << csv_field(r.label()) << ',' << r.views << ',' << mean << ','
                << (vfc_ms > 0 && mean > 0 ? vfc_ms / mean : 0.0) << ',' << (ideal_ms > 0 ? mean / ideal_ms : 0.0)
                << ',' << r.triangles / n << ',' << r.occluded << ',' << r.occluded_culled << ','
                << (r.occluded ? 100.0 * double(r.occluded_culled) / double(r.occluded) : 0.0) << ','
                << r.visible_culled << ',' << r.lost << ',' << r.tied << '\n';
        scene_lost += r.lost;
    }
    for (const Run &r : runs)
        if (const std::string note = r.strategy.culler->note(); !note.empty())
            std::printf("%s: %s\n", r.label().c_str(), note.c_str());
    std::printf("scene %s: %ld views, %zu strategies, %llu visible pixels lost\n", scene_name.c_str(), views,
                runs.size(), (unsigned long long)scene_lost);
    std::fflush(stdout);
}

}  // namespace

int main(int argc, char **argv)
{
    const Options o = parse(argc, argv);
    try {
        gl::select_driver(gl::parse_driver(o.driver));
        // Every scene is read before any is rendered: an unreadable one is named at once.
        std::vector<Scene> scenes;
        for (const std::string &s : o.scenes) {
            // A level in a pk3 archive is no file of its own: load_scene names what is missing.
            std::string archive, member;
            if (!generated_scene_name(s) && !split_pk3_path(s, archive, member) && !std::ifstream(s))
                throw std::runtime_error("cannot read scene '" + s + "'" +
                                         (std::filesystem::exists(s) ? "" : ": no such file"));
            scenes.push_back(scene_by_name(s));
        }
        std::filesystem::create_directories(o.out);
        const std::string views_path = o.out + "/views.csv", summary_path = o.out + "/summary.csv";
        std::ofstream csv(views_path), summary(summary_path);
        if (!csv || !summary)
            throw std::runtime_error("cannot write '" + views_path + "' and '" + summary_path + "'");
        csv << "scene,view,strategy,px,py,pz,tx,ty,tz,fovy,ms,triangles,leaves_drawn,oracle_visible_leaves,"
               "oracle_occluded_leaves,occluded_leaves_culled,visible_leaves_culled,lost_pixels,tied_pixels\n";
        summary << "scene,strategy,views,mean_ms,vs_vfc,x_ideal,triangles,occluded_leaves,occluded_leaves_culled,"
                   "efficiency_percent,visible_leaves_culled,lost_pixels,tied_pixels\n";
        std::printf("random views: %ld over %zu scenes, %zu strategies, %dx%d; views.csv and summary.csv in %s\n",
                    o.views, o.scenes.size(), o.strategies.size(), o.size, o.size, o.out.c_str());
        Totals totals;
        const auto start = std::chrono::steady_clock::now();
        for (std::size_t i = 0; i < o.scenes.size(); ++i) {
            const long share = o.views / long(o.scenes.size()) + (long(i) < o.views % long(o.scenes.size()) ? 1 : 0);
            run_scene(o, i, o.scenes[i], scenes[i], share, o.seed + i, csv, summary, totals);
        }
        if (!csv.flush() || !summary.flush())
            throw std::runtime_error("cannot write '" + views_path + "' and '" + summary_path + "'");
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::printf("\nefficiency: occluded leaves culled / occluded leaves (the oracle's); vs vfc: vfc's mean ms /\n"
                    "the strategy's; x ideal: the strategy's mean ms / ideal's; vis cull: leaves the oracle sees that\n"
                    "were not drawn; lost pixels: pixels where a leaf the strategy culled is strictly nearer than\n"
                    "what it drew (the frame differs from its leaves drawn in its order, then the culled ones);\n"
                    "tied px: pixels that differ from the common unculled frame through depth ties alone (not lost).\n");
        std::printf("total: %ld views, %ld frames, %llu visible pixels lost, %.1f s (%.1f ms per view)\n", totals.views,
                    totals.frames, (unsigned long long)totals.lost, seconds, 1000.0 * seconds / double(totals.views));
        if (totals.first) {
            const Failure &f = *totals.first;
            std::fprintf(stderr,
                         "occu-random-views: visible pixels lost: first by %s on scene %s, view %ld (%llu pixels; "
                         "camera %g %g %g looking at %g %g %g, fov %g)\n",
                         f.strategy.c_str(), f.scene.c_str(), f.view, (unsigned long long)f.pixels,
                         double(f.camera.position.x), double(f.camera.position.y), double(f.camera.position.z),
                         double(f.camera.target.x), double(f.camera.target.y), double(f.camera.target.z),
                         double(f.camera.fovy_degrees));
            return 1;
        }
        return 0;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "occu-random-views: %s\n", e.what());
        return 1;
    }
}
