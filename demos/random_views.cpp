// SPDX-License-Identifier: MIT
// occu-random-views: renders random cameras over several scenes with every
// conservative strategy of the registry and counts the visible pixels each
// frame lost against the unculled frame of the same camera (must be 0;
// evaluation/lost_pixels.h defines them), with culling efficiency against
// the exact-visibility oracle and frame times beside vfc and ideal.
//
// Cameras: the random route's (camera/route.h, random:N:SEED): eyes
// uniformly inside the scene's bounds (in the city: streets, courtyards,
// roofs and the insides of buildings alike, from the ground up to the
// tallest roof; in a Quake III level only its open leaves; in a model read
// from a file only points inside it, where rays in 14 directions all hit
// it: spatial/inside_points.h), random headings, pitch within 60 degrees
// of the horizon, and a field of view drawn from --fov.
//
// Writes DIR/views.csv (one row per scene, view and strategy, with the
// camera) and DIR/summary.csv (one row per scene and strategy), prints a
// table per scene, and exits with status 1 when any pixel was lost, naming
// the first strategy, scene and view that lost one.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cli/arguments.h"
#include "culling/registry.h"
#include "evaluation/allocator.h"
#include "evaluation/measurement_session.h"
#include "evaluation/session_command_line.h"
#include "gl/offscreen_context.h"

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
    // --strategies (empty: every conservative strategy, default_strategies),
    // --set, --size, --driver, --allocator, --batch, --coherence,
    // --switch-off, --databases, --make-databases; with the defaults of
    // session_defaults().
    SessionCommandLine session;
    std::vector<std::string> scenes;   // "city" or a file; empty: the city and default_models
    long views = 300;                  // over all scenes
    unsigned long seed = 2026;
    std::uint32_t leaf_triangles = HierarchyOptions{}.max_leaf_triangles;
    float fov_min = 20.0f, fov_max = 120.0f;
    std::string out = "random-views-out";
};

// Unrelated views: no temporal coherence, no switch-off (each view is a
// frame of its own); small frames.
SessionCommandLine session_defaults()
{
    SessionCommandLine s;
    s.square(128);
    s.max_size = 4096;
    s.coherence = false;
    s.switch_off = 0.0;
    return s;
}

[[noreturn]] void usage(const std::string &error)
{
    std::FILE *to = error.empty() ? stdout : stderr;
    if (!error.empty())
        std::fprintf(to, "occu-random-views: %s\n", error.c_str());
    std::fprintf(to,
                 "usage: occu-random-views [--scene city|field|FILE[,...]]... [--views N] [--seed S]\n"
                 "                         [--size PIXELS|WxH] [--strategies NAME[:key=value...],...]\n"
                 "                         [--driver llvmpipe|softpipe] [--fov MIN,MAX] [--leaf-triangles N|auto]\n"
                 "                         [--batch N] [--coherence on|off] [--switch-off F] [--set key=value]...\n"
                 "                         [--allocator keep|system]\n"
                 "                         [--databases DIR] [--make-databases required|all] [--out DIR]\n"
                 "Renders --views random cameras (300; shared evenly among the scenes) with every strategy and\n"
                 "counts the visible pixels each frame lost against the unculled frame of the same camera.\n"
                 "Eyes: anywhere in the city's bounds; in a level's open leaves; inside a model read from a file\n"
                 "(rays in 14 directions from the eye all hit it).\n"
                 "Scenes (default: city,%s,%s):\n"
                 "'city' is the procedural city; a FILE is read through assimp. Strategies (default: every\n"
                 "conservative strategy of the registry, presets included; one whose family refuses a scene\n"
                 "is left out of it, with why). --set applies to every strategy that has the setting. A database\n"
                 "a strategy requires and was not given is made for each scene in --databases DIR (%s)\n"
                 "and found there by later runs (--make-databases all: every database a strategy reads).\n"
                 "--fov: vertical fields of view in degrees (20,120). --coherence (off) and\n"
                 "--switch-off (0: never) are walkthrough's traversal policies. Exit status 1 when a pixel\n"
                 "was lost, 2 on a bad option.\n\nstrategies:\n%s",
                 default_models[0], default_models[1], default_database_directory().c_str(), strategies_help().c_str());
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

Options parse(int argc, char **argv)
{
    Options o;
    o.session = session_defaults();
    for_each_option(argc, argv, usage, [&](const std::string &a, const std::string &v) {
        if (o.session.take(a, v)) return true;
        else if (a == "--scene") {
            const std::vector<std::string> s = list_items(v, ',');
            if (s.empty())
                usage("--scene is empty");
            o.scenes.insert(o.scenes.end(), s.begin(), s.end());
        }
        else if (a == "--views") o.views = integer_option(a, v, 1, 10000000);
        else if (a == "--seed") o.seed = (unsigned long)integer_option(a, v, 0, 0xffffffffL);
        else if (a == "--leaf-triangles") o.leaf_triangles = leaf_triangles_option(a, v);
        else if (a == "--fov") {
            const std::vector<std::string> f = list_items(v, ',');
            if (f.size() != 2)
                usage("--fov is MIN,MAX in degrees, got '" + v + "'");
            o.fov_min = float(number_option(a, f[0], 1.0, 170.0));
            o.fov_max = float(number_option(a, f[1], 1.0, 170.0));
            if (o.fov_min > o.fov_max)
                usage("--fov is MIN,MAX: " + f[0] + " > " + f[1]);
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
    // Strategies are checked before anything is built.
    if (o.session.strategies.empty())
        o.session.strategies = default_strategies();
    try {
        o.session.check_strategies(o.session.strategies);
    } catch (const std::invalid_argument &e) {
        usage(e.what());
    }
    return o;
}

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
void run_scene(const Options &o, const SceneSetup &setup, long views, unsigned long seed,
               std::ofstream &csv, std::ofstream &summary, Totals &totals)
{
    const std::string &scene_name = setup.name();
    const Scene &scene = setup.scene();
    const std::vector<Camera> cameras = setup.random_views(views, seed, o.fov_min, o.fov_max, o.session.aspect());

    gl::OffscreenContext ctx(o.session.width, o.session.height);
    DatabaseProvider databases = o.session.database_provider();
    SessionOptions so = o.session.session_options(databases);
    so.lost_pixels = SessionOptions::PixelCheck::all;
    MeasurementSession session(setup, ctx, so);
    // A strategy whose family refuses the scene is left out, with why.
    std::vector<std::string> left_out;
    for (const std::string &spec : o.session.strategies)
        if (const std::string why = session.add_unless_refused(spec, o.session.common); !why.empty())
            left_out.push_back(spec + " (" + why + ")");
    std::printf("\nscene %s: %zu triangles, %zu leaves of at most %u; %ld random views (seed %lu), %dx%d, fov %g..%g, %s\n",
                scene_name.c_str(), scene.triangle_count(), setup.hierarchy().leaf_count(),
                unsigned(setup.hierarchy().max_leaf_triangles()), views, seed, o.session.width,
                o.session.height, double(o.fov_min), double(o.fov_max), ctx.renderer().c_str());
    for (const std::string &s : left_out)
        std::printf("left out: %s\n", s.c_str());
    std::fflush(stdout);

    session.walk(cameras, "views of " + scene_name, [&](const SessionStrategy &s, const StrategyFrame &f) {
        const Camera &camera = f.frame->camera;
        const CullingQuality &q = f.quality;
        totals.frames += 1;
        totals.lost += f.loss.lost;
        if (f.loss.lost && !totals.first)
            totals.first = Failure{s.label, scene_name, long(f.index), f.loss.lost, camera};
        csv << csv_field(scene_name) << ',' << f.index << ',' << csv_field(s.label) << ',' << camera.position.x << ','
            << camera.position.y << ',' << camera.position.z << ',' << camera.target.x << ',' << camera.target.y << ','
            << camera.target.z << ',' << camera.fovy_degrees << ',' << f.ms << ',' << f.stats.triangles << ','
            << f.stats.leaves_drawn << ',' << f.frame->truth->visible.size() << ',' << q.occluded << ','
            << q.occluded_culled << ',' << q.visible_culled << ',' << f.loss.lost << ',' << f.loss.tied << '\n';
    });
    totals.views += views;

    const double vfc_ms = session.reference_ms("vfc"), ideal_ms = session.reference_ms("ideal");
    std::uint64_t scene_lost = 0;
    std::printf("%-20s %6s %9s %7s %8s %10s %10s %8s %11s %9s\n", "strategy", "views", "mean ms", "vs vfc", "x ideal",
                "triangles", "efficiency", "vis cull", "lost pixels", "tied px");
    for (const SessionStrategy &s : session.strategies()) {
        const Measured &m = s.measured;
        const double mean = m.mean_ms();
        char vs_vfc[32] = "-", x_ideal[32] = "-", efficiency[32] = "-";
        if (vfc_ms > 0 && mean > 0)
            std::snprintf(vs_vfc, sizeof(vs_vfc), "%.2fx", vfc_ms / mean);
        if (ideal_ms > 0 && mean > 0)
            std::snprintf(x_ideal, sizeof(x_ideal), "%.2fx", mean / ideal_ms);
        if (const auto e = m.efficiency_percent())
            std::snprintf(efficiency, sizeof(efficiency), "%.1f%%", *e);
        std::printf("%-20s %6zu %9.2f %7s %8s %10.0f %10s %8llu %11llu %9llu\n", s.label.c_str(), m.frames(), mean,
                    vs_vfc, x_ideal, m.per_frame(m.triangles), efficiency, (unsigned long long)m.visible_culled,
                    (unsigned long long)m.lost_pixels, (unsigned long long)m.tied_pixels);
        summary << csv_field(scene_name) << ',' << csv_field(s.label) << ',' << m.frames() << ',' << mean << ','
                << (vfc_ms > 0 && mean > 0 ? vfc_ms / mean : 0.0) << ',' << (ideal_ms > 0 ? mean / ideal_ms : 0.0)
                << ',' << m.per_frame(m.triangles) << ',' << m.occluded << ',' << m.occluded_culled << ','
                << m.efficiency_percent().value_or(0.0) << ',' << m.visible_culled << ',' << m.lost_pixels << ','
                << m.tied_pixels << '\n';
        scene_lost += m.lost_pixels;
    }
    for (const std::string &note : session.notes())
        std::printf("%s\n", note.c_str());
    std::printf("scene %s: %ld views, %zu strategies, %llu visible pixels lost\n", scene_name.c_str(), views,
                session.strategies().size(), (unsigned long long)scene_lost);
    std::fflush(stdout);
}

}  // namespace

int main(int argc, char **argv)
{
    const Options o = parse(argc, argv);
    try {
        gl::select_driver(o.session.driver);
        // Every scene is read before any is rendered: an unreadable one is named at once.
        std::vector<SceneSetup> scenes;
        for (const std::string &s : o.scenes) {
            // Flat unless --look scene (session_options: the frames' look).
            SceneChoice choice(s, 1, o.leaf_triangles);
            choice.quake3.look = o.session.look == Look::scene;
            scenes.emplace_back(choice);
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
                    o.views, o.scenes.size(), o.session.strategies.size(), o.session.width, o.session.height,
                    o.out.c_str());
        Totals totals;
        const auto start = std::chrono::steady_clock::now();
        for (std::size_t i = 0; i < o.scenes.size(); ++i) {
            const long share = o.views / long(o.scenes.size()) + (long(i) < o.views % long(o.scenes.size()) ? 1 : 0);
            run_scene(o, scenes[i], share, o.seed + i, csv, summary, totals);
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
