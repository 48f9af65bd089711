// SPDX-License-Identifier: MIT
// occu-bench-real-scenes: the targets of culling on scenes occu did not
// make (issue 29; docs/real-scenes.md): Quake III levels from Debian's
// OpenArena data and buildings from assimp-testmodels, every strategy side
// by side on each scene's own route (a level's spawn points, a model's
// orbit) and on random eyes in its open space (a level's open BSP leaves,
// a building's rooms), judged against:
//   - the floor: the best conservative strategy within 1.5x of `ideal`
//     (the oracle's visible leaves alone);
//   - culling efficiency (occluded leaves culled / occluded leaves, Poon
//     and Wang, section 6) at least 80% for every strategy where the floor
//     hides at least half of the frustum's triangles (ideal's triangles at
//     most half of vfc's);
//   - a level's own PVS (`bsp-pvs`: q3map -vis, Teller and Sequin's
//     cell-portal visibility): the best strategy at least 1.5x faster than
//     `bsp-pvs` alone where the PVS leaves depth complexity (the floor is
//     1.5x faster than it, so that 1.5x can be had), and every strategy
//     within 1.05x of it where nothing can gain over it (the floor within
//     1.05x of it); between the two only reported;
//   - no visible pixel lost: every strategy's frames, conservative or not,
//     compared with the unculled frame (evaluation/lost_pixels.h);
//   - loading the largest levels, pk3 to hierarchy, in at most 1 s.
// Each scene and route is one measurement session
// (evaluation/measurement_session.h: every strategy draws frame f before
// any draws f + 1, the order shuffled per frame; walkthrough's traversal
// policies on the scene's own route; on random eyes, which are unrelated
// views, no temporal coherence and no switch-off). What a level holds is printed first (bench/level_statistics.h:
// the figures its kind was chosen by). Prints per scene and route a table
// of every strategy, then the targets table and one table per route kind
// of every strategy on every scene; --out DIR gets the CSVs. All that once
// per table of frames (--tables): by default the frame a player sees,
// 1280x720 with the scene's look (a level's textures, lightmaps and sky, a
// model's materials), then 512x512 flat, each scene's routes measured in
// both before the next scene, and per scene and route the ratio of vfc's
// frame in the first table to its frame in the second (what the look and
// the pixels cost, against which culling's savings are weighed). Timing only:
// the tests that hold the strategies to 0 lost pixels on such scenes are
// tests/integration/demos/{building,level}-views.sh and level-pvs.sh.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/arguments.h"
#include "culling/registry.h"
#include "evaluation/allocator.h"
#include "evaluation/measurement_session.h"
#include "evaluation/session_command_line.h"
#include "gl/offscreen_context.h"
#include "level_statistics.h"
#include "scene/scene_file.h"

namespace {

using namespace occu;

constexpr double floor_target = 1.5, efficiency_target = 80.0, hidden_share = 0.5, pvs_gain_target = 1.5,
                 pvs_noise = 1.05, load_target_ms = 1000.0;

const std::string openarena = "/usr/share/games/openarena/baseoa/";
const std::string models = "/usr/share/assimp/models/";

// One table of frames: their size and look (render/scene_renderer.h).
struct Table {
    int width = 1280, height = 720;
    Look look = Look::scene;

    std::string size_name() const { return std::to_string(width) + "x" + std::to_string(height); }
    std::string name() const { return size_name() + (look == Look::scene ? " with the look" : " flat"); }
};

struct Options {
    std::vector<std::string> scenes = {
        // Six kinds of level, chosen by their statistics (docs/real-scenes.md).
        openarena + "pak6-patch088.pk3:maps/aggressor.bsp",
        openarena + "pak6-patch088.pk3:maps/oa_minia.bsp",
        openarena + "pak6-patch088.pk3:maps/czest2ctf.bsp",
        openarena + "pak6-patch088.pk3:maps/oa_thor.bsp",
        openarena + "pak6-patch088.pk3:maps/pul1ctf.bsp",
        openarena + "pak6-patch088.pk3:maps/pul1duel-oa.bsp",
        openarena + "pak6-patch088.pk3:maps/am_thornish.bsp",
        // The buildings of tests/integration/demos/building-views.sh.
        models + "IFC/AC14-FZK-Haus.ifc",
        models + "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb",
        models + "Collada/teapots.DAE",
    };
    // The largest level file (10 MB) and the level of the most triangles
    // (96,256) of Debian's 100 (occu-bench-level-load --all-debian).
    std::vector<std::string> load_levels = {openarena + "pak6-patch085.pk3:maps/ctf_compromise.bsp",
                                            openarena + "pak1-maps.pk3:maps/oa_dm5.bsp"};
    // --strategies (empty: every strategy once, and bsp-pvs's chains),
    // --set, --size, --driver, --allocator, --batch, --coherence,
    // --switch-off, --databases, --make-databases (all: no database is
    // made inside a frame's time).
    SessionCommandLine session = [] {
        SessionCommandLine s;
        s.make_databases = DatabaseProvider::Makes::all;
        return s;
    }();
    int spawn_views = 2, orbit_frames = 60, random_views = 200;
    unsigned long seed = 2026;
    int repeat = 3;
    std::uint32_t leaf_triangles = HierarchyOptions{}.max_leaf_triangles;
    std::string out;
    // --tables: the frame a player sees first, then the flat 512x512
    // frame, where drawing a pixel costs least against culling's tests.
    std::vector<Table> tables = {{1280, 720, Look::scene}, {512, 512, Look::flat}};
};

[[noreturn]] void usage(const std::string &error)
{
    std::FILE *to = error.empty() ? stdout : stderr;
    if (!error.empty())
        std::fprintf(to, "occu-bench-real-scenes: %s\n", error.c_str());
    std::fprintf(to,
                 "usage: occu-bench-real-scenes [--scenes SCENE,...] [--strategies NAME,...] [--set KEY=VALUE]...\n"
                 "                              [--spawn-views K] [--orbit-frames N] [--random-views N] [--seed S]\n"
                 "                              [--size PIXELS|WxH] [--driver llvmpipe|softpipe] [--leaf-triangles N|auto]\n"
                 "                              [--batch N] [--switch-off F] [--coherence on|off] [--allocator keep|system]\n"
                 "                              [--load-levels LEVEL,...] [--repeat N] [--databases DIR]\n"
                 "                              [--make-databases required|all] [--tables WxH:LOOK,...]\n"
                 "                              [--look flat|scene] [--out DIR]\n"
                 "Every strategy (default: every name of the registry once, and bsp-pvs+ou-shared, bsp-pvs+om-ps)\n"
                 "on each scene (default: seven OpenArena levels and three assimp-testmodels buildings) along its\n"
                 "own route (a level: spawn:K, K views a spawn point, default 2; a model: orbit, default 60 frames)\n"
                 "and random:N:SEED (default 200 eyes in the scene's open space, seed %lu, one more a scene),\n"
                 "in each table of frames (--tables, default 1280x720:scene,512x512:flat: the frame a player sees,\n"
                 "the scene's textures, lightmaps and sky or a model's materials, then the flat frames of 512x512;\n"
                 "--size and --look instead: that one table, 1280x720 and scene where not given), llvmpipe, every\n"
                 "frame compared with the unculled one (--coherence and --switch-off, default on and 0.5, apply to\n"
                 "the own routes; random eyes run without either). With two tables or more, per scene and route\n"
                 "vfc's frame in the first against its frame in each other (what the look and the size cost).\n"
                 "Prints each run, the targets (best conservative strategy within %.1fx of the floor; >= %.0f%%\n"
                 "efficiency where the floor hides >= half the frustum's triangles; best >= %.1fx over bsp-pvs\n"
                 "where it can be; no lost pixel) met or not, the tables of every strategy, and each --load-levels level's time\n"
                 "from pk3 to hierarchy (best of --repeat, default 3; target %.0f ms). A strategy the scene\n"
                 "refuses is left out of it, with why. --out DIR writes runs.csv, levels.csv and loads.csv.\n",
                 Options{}.seed, floor_target, efficiency_target, pvs_gain_target, load_target_ms);
    std::exit(error.empty() ? 0 : 2);
}

// --tables: WxH:LOOK (or PIXELS:LOOK) items, each checked as --size and
// --look check theirs; a bad item throws std::invalid_argument naming it.
std::vector<Table> tables_option(const std::string &name, const std::string &value)
{
    std::vector<Table> tables;
    for (const std::string &item : list_items(value, ',')) {
        const std::size_t colon = item.find(':');
        if (colon == std::string::npos)
            throw std::invalid_argument(name + " wants SIZE:LOOK items (e.g. 1280x720:scene,512:flat), got '" + item + "'");
        SessionCommandLine scratch;
        try {
            scratch.take("--size", item.substr(0, colon));
            scratch.take("--look", item.substr(colon + 1));
        } catch (const std::invalid_argument &e) {
            throw std::invalid_argument(name + ": item '" + item + "': " + e.what());
        }
        tables.push_back({scratch.width, scratch.height, *scratch.look});
    }
    if (tables.empty())
        throw std::invalid_argument(name + " is empty");
    return tables;
}

Options parse(int argc, char **argv)
{
    Options o;
    bool size_given = false, look_given = false, tables_given = false;
    for_each_option(argc, argv, usage, [&](const std::string &a, const std::string &v) {
        size_given = size_given || a == "--size";
        look_given = look_given || a == "--look";
        if (o.session.take(a, v)) return true;
        else if (a == "--tables") { o.tables = tables_option(a, v); tables_given = true; }
        else if (a == "--scenes") o.scenes = list_items(v, ',');
        else if (a == "--spawn-views") o.spawn_views = int(integer_option(a, v, 1, 360));
        else if (a == "--orbit-frames") o.orbit_frames = int(integer_option(a, v, 1, 100000));
        else if (a == "--random-views") o.random_views = int(integer_option(a, v, 0, 100000));
        else if (a == "--seed") o.seed = (unsigned long)integer_option(a, v, 0, 1L << 40);
        else if (a == "--leaf-triangles") o.leaf_triangles = leaf_triangles_option(a, v);
        else if (a == "--load-levels") o.load_levels = list_items(v, ',');
        else if (a == "--repeat") o.repeat = int(integer_option(a, v, 1, 100));
        else if (a == "--out") o.out = v;
        else
            return false;
        return true;
    });
    try {
        if (o.scenes.empty())
            usage("--scenes is empty");
        if (tables_given && (size_given || look_given))
            usage("--tables names every table's size and look: give it or --size/--look, not both");
        // --size and --look: that one table, the first default's size or
        // look where one of them is not given.
        if (size_given || look_given)
            o.tables = {{size_given ? o.session.width : 1280, size_given ? o.session.height : 720,
                         o.session.look.value_or(Look::scene)}};
        std::vector<std::string> &strategies = o.session.strategies;
        if (strategies.empty()) {
            strategies = distinct_strategy_names();
            strategies.erase(std::remove(strategies.begin(), strategies.end(), "none"), strategies.end());
            strategies.push_back("bsp-pvs+ou-shared");
            strategies.push_back("bsp-pvs+om-ps");
        }
        for (const char *reference : {"vfc", "ideal"})
            if (std::find(strategies.begin(), strategies.end(), reference) == strategies.end())
                strategies.insert(strategies.begin(), reference);
        o.session.check_strategies(strategies);
    } catch (const std::invalid_argument &e) {
        usage(e.what());
    }
    return o;
}

bool is_level(const Scene &scene) { return scene.level != nullptr; }

// A scene's short name: a level's NAME of maps/NAME.bsp, a file's name.
std::string short_name(const std::string &scene)
{
    std::string n = std::filesystem::path(scene.substr(scene.rfind(':') == std::string::npos ? 0 : scene.rfind(':') + 1))
                        .filename()
                        .string();
    if (n.size() > 4 && n.compare(n.size() - 4, 4, ".bsp") == 0)
        n.resize(n.size() - 4);
    return n;
}

struct Row {
    std::string label;
    bool reference = false;      // vfc or ideal
    bool conservative = false;   // StrategyChoice::conservative()
    double mean = 0, median = 0, x_vfc = 0, x_floor = 0, x_pvs = 0, triangles = 0, test_ms = 0, setup_ms = 0;
    std::optional<double> efficiency;
    std::uint64_t visible_culled = 0, lost = 0, tied = 0;
    double lost_per_frame = 0;
    bool low_efficiency = false;   // below the target where it applies
};

struct Run {
    std::string scene, name, route;
    std::size_t table = 0;   // Options::tables
    bool level = false;
    std::size_t frames = 0, triangles = 0, leaves = 0;
    double vfc_ms = 0, ideal_ms = 0, vfc_triangles = 0, ideal_triangles = 0;
    std::optional<double> pvs_ms;
    std::vector<Row> rows;
    std::vector<std::string> left_out, notes;
    double seconds = 0;

    // The share of the frustum's triangles the floor does not draw.
    double floor_hides() const { return vfc_triangles > 0 ? 1.0 - ideal_triangles / vfc_triangles : 0.0; }
    const Row *best(bool conservative_only) const
    {
        const Row *b = nullptr;
        for (const Row &r : rows)
            if (!r.reference && (!conservative_only || r.conservative) && r.label != "bsp-pvs" &&
                (!b || r.mean < b->mean))
                b = &r;
        return b;
    }
    std::uint64_t conservative_lost() const
    {
        std::uint64_t n = 0;
        for (const Row &r : rows)
            n += r.conservative ? r.lost : 0;
        return n;
    }
};

std::string percent(const std::optional<double> &p)
{
    if (!p)
        return "-";
    char t[32];
    std::snprintf(t, sizeof(t), "%.1f%%", *p);
    return t;
}

std::string ratio(double x)
{
    char t[32];
    std::snprintf(t, sizeof(t), "%.2fx", x);
    return t;
}

// One scene and route in table `table` of frames (`session_line`: the
// program's session options with that table's size and look).
Run run_route(const Options &o, const SessionCommandLine &session_line, std::size_t table, const SceneSetup &setup,
              const std::string &route_name, gl::OffscreenContext &ctx)
{
    const auto start = std::chrono::steady_clock::now();
    Run run;
    run.table = table;
    run.scene = setup.name();
    run.name = short_name(setup.name());
    run.route = route_name;
    run.level = is_level(setup.scene());
    run.triangles = setup.scene().triangle_count();
    run.leaves = setup.hierarchy().leaf_count();
    const std::vector<Camera> route = setup.route(route_name, o.orbit_frames, session_line.aspect());
    run.frames = route.size();

    DatabaseProvider databases = session_line.database_provider();
    SessionOptions so = session_line.session_options(databases);
    // Random eyes are unrelated views (camera/route.h): neither temporal
    // coherence nor the switch-off applies (as occu-random-views runs them).
    const bool unrelated = unrelated_views(route_name);
    so.coherence = so.coherence && !unrelated;
    so.switch_off = unrelated ? 0.0 : so.switch_off;
    so.lost_pixels = SessionOptions::PixelCheck::all;
    MeasurementSession session(setup, ctx, so);
    for (const std::string &spec : session_line.strategies) {
        if (const std::string why = session.add_unless_refused(spec, session_line.common); !why.empty())
            run.left_out.push_back(spec + ": " + why);
        // vfc a second time: the ratio of two identical strategies is the run's noise.
        if (spec == "vfc")
            session.add("vfc", session_line.common, "vfc again");
    }
    std::printf("\n%s (%zu triangles, %zu leaves of at most %u), route %s: %zu frames, %zu strategies, %s, %s\n",
                run.scene.c_str(), run.triangles, run.leaves, unsigned(setup.hierarchy().max_leaf_triangles()),
                route_name.c_str(), route.size(), session.strategies().size(), o.tables[table].name().c_str(),
                ctx.renderer().c_str());
    for (const std::string &l : run.left_out)
        std::printf("left out: %s\n", l.c_str());
    std::fflush(stdout);
    session.walk(route, run.name + " " + route_name);

    for (const SessionStrategy &s : session.strategies()) {
        const Measured &m = s.measured;
        const std::string &family = s.strategy.choice.family->name;
        if (s.label == "vfc") {
            run.vfc_ms = m.mean_ms();
            run.vfc_triangles = m.per_frame(m.triangles);
        } else if (s.label == "ideal") {
            run.ideal_ms = m.mean_ms();
            run.ideal_triangles = m.per_frame(m.triangles);
        } else if (s.label == "bsp-pvs") {
            run.pvs_ms = m.mean_ms();
        }
        Row r;
        r.label = s.label;
        r.reference = family == "vfc" || family == "ideal";
        r.conservative = s.strategy.choice.conservative();
        r.mean = m.mean_ms();
        r.median = m.median_ms();
        r.triangles = m.per_frame(m.triangles);
        r.test_ms = m.per_frame(m.test_ms);
        r.setup_ms = m.per_frame(m.setup_ms);
        r.efficiency = m.efficiency_percent();
        r.visible_culled = m.visible_culled;
        r.lost = m.lost_pixels;
        r.tied = m.tied_pixels;
        r.lost_per_frame = m.per_frame(double(m.lost_pixels));
        run.rows.push_back(r);
    }
    for (Row &r : run.rows) {
        r.x_vfc = r.mean > 0 ? run.vfc_ms / r.mean : 0.0;
        r.x_floor = run.ideal_ms > 0 ? r.mean / run.ideal_ms : 0.0;
        r.x_pvs = run.pvs_ms && r.mean > 0 ? *run.pvs_ms / r.mean : 0.0;
        r.low_efficiency = !r.reference && run.floor_hides() >= hidden_share && r.efficiency &&
                           *r.efficiency < efficiency_target;
    }
    run.notes = session.notes();
    run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    std::printf("\n%-20s %8s %8s %7s %8s %9s %9s %10s %8s %11s %8s %8s\n", "strategy", "mean ms", "median", "x vfc",
                "x floor", "x bsp-pvs", "triangles", "efficiency", "vis cull", "lost px/fr", "test ms", "setup ms");
    for (const Row &r : run.rows)
        std::printf("%-20s %8.2f %8.2f %7s %8s %9s %9.0f %10s %8llu %11.1f %8.2f %8.2f%s\n", r.label.c_str(), r.mean,
                    r.median, ratio(r.x_vfc).c_str(), ratio(r.x_floor).c_str(),
                    run.pvs_ms ? ratio(r.x_pvs).c_str() : "-", r.triangles, percent(r.efficiency).c_str(),
                    (unsigned long long)r.visible_culled, r.lost_per_frame, r.test_ms, r.setup_ms,
                    r.conservative ? "" : "  (approximate)");
    for (const std::string &n : run.notes)
        std::printf("%s\n", n.c_str());
    std::printf("(%.0f s)\n", run.seconds);
    std::fflush(stdout);
    return run;
}

// The targets of one run, as table cells.
struct Verdicts {
    std::string floor, efficiency, pvs, lost;
    int met = 0, missed = 0;
};

Verdicts verdicts(const Run &run)
{
    Verdicts v;
    auto mark = [&](bool met, const std::string &text) {
        (met ? v.met : v.missed) += 1;
        return std::string(met ? "**met**: " : "not met: ") + text;
    };
    char t[400];
    if (const Row *b = run.best(true)) {
        std::snprintf(t, sizeof(t), "`%s` %.2f ms, %.2fx vfc, %.2fx floor", b->label.c_str(), b->mean, b->x_vfc,
                      b->x_floor);
        v.floor = mark(b->x_floor <= floor_target, t);
    } else {
        v.floor = "no conservative strategy ran";
    }
    if (run.floor_hides() < hidden_share) {
        std::snprintf(t, sizeof(t), "n/a (floor hides %.0f%%)", 100.0 * run.floor_hides());
        v.efficiency = t;
    } else {
        // The strategies at or above the target by name, and the highest.
        std::string above;
        const Row *highest = nullptr;
        int judged = 0, below = 0;
        for (const Row &r : run.rows) {
            if (r.reference || !r.efficiency)
                continue;
            ++judged;
            if (!highest || *r.efficiency > *highest->efficiency)
                highest = &r;
            if (r.low_efficiency) {
                ++below;
            } else {
                std::snprintf(t, sizeof(t), "%s`%s` %.0f%%", above.empty() ? "" : ", ", r.label.c_str(), *r.efficiency);
                above += t;
            }
        }
        std::snprintf(t, sizeof(t), "%d of %d below%s%s", below, judged, above.empty() ? "" : "; at or above: ",
                      above.c_str());
        std::string text = t;
        if (highest && above.empty()) {
            std::snprintf(t, sizeof(t), "; highest `%s` %.0f%%", highest->label.c_str(), *highest->efficiency);
            text += t;
        }
        std::snprintf(t, sizeof(t), "%s", text.c_str());
        v.efficiency = mark(below == 0, t);
    }
    if (!run.pvs_ms) {
        v.pvs = "-";
    } else {
        const double floor_gain = *run.pvs_ms / run.ideal_ms;
        const Row *b = run.best(false);
        if (floor_gain >= pvs_gain_target && b) {
            std::snprintf(t, sizeof(t), "`%s` %.2fx over bsp-pvs (%.2f ms; floor %.2fx)", b->label.c_str(), b->x_pvs,
                          *run.pvs_ms, floor_gain);
            v.pvs = mark(b->x_pvs >= pvs_gain_target, t);
        } else if (floor_gain <= pvs_noise) {
            const Row *worst = nullptr;
            for (const Row &r : run.rows)
                if (!r.reference && r.label != "bsp-pvs" && (!worst || r.mean > worst->mean))
                    worst = &r;
            std::snprintf(t, sizeof(t), "floor %.2fx over bsp-pvs: slowest `%s` %.2fx of it", floor_gain,
                          worst ? worst->label.c_str() : "-", worst ? worst->mean / *run.pvs_ms : 0.0);
            v.pvs = mark(!worst || worst->mean <= pvs_noise * *run.pvs_ms, t);
        } else {
            std::snprintf(t, sizeof(t), "n/a: floor only %.2fx over bsp-pvs (%.2f ms); best `%s` %.2fx", floor_gain,
                          *run.pvs_ms, b ? b->label.c_str() : "-", b ? b->x_pvs : 0.0);
            v.pvs = t;
        }
    }
    std::uint64_t approximate = 0;
    for (const Row &r : run.rows)
        approximate += r.conservative ? 0 : r.lost;
    std::snprintf(t, sizeof(t), "%llu px%s", (unsigned long long)run.conservative_lost(),
                  approximate ? (" (approximate ones: " + std::to_string(approximate) + " px)").c_str() : "");
    v.lost = mark(run.conservative_lost() == 0, t);
    return v;
}

std::string csv_field(const std::string &text)
{
    if (text.find_first_of(",\"") == std::string::npos)
        return text;
    std::string q = "\"";
    for (char c : text)
        q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

double ms_since(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char **argv)
{
    const Options o = parse(argc, argv);
    try {
        control_allocator(o.session.allocator);
        gl::select_driver(o.session.driver);
        const auto start = std::chrono::steady_clock::now();
        std::ofstream runs_csv, levels_csv, loads_csv;
        if (!o.out.empty()) {
            std::filesystem::create_directories(o.out);
            runs_csv.open(o.out + "/runs.csv");
            levels_csv.open(o.out + "/levels.csv");
            loads_csv.open(o.out + "/loads.csv");
            if (!runs_csv || !levels_csv || !loads_csv)
                throw std::runtime_error("cannot write the CSVs in '" + o.out + "'");
            runs_csv << "scene,route,size,look,frames,strategy,conservative,mean_ms,median_ms,x_vfc,x_floor,x_bsp_pvs,triangles,"
                        "efficiency_percent,visible_leaves_culled,lost_pixels,tied_pixels,test_ms,setup_ms\n";
            levels_csv << "level," << LevelStatistics::columns() << '\n';
            loads_csv << "level,load_ms,hierarchy_ms,total_ms,triangles\n";
        }

        // Loading: pk3 to scene, then to hierarchy, the best of --repeat;
        // with the textures where a table has the look (the load a player waits for).
        const bool any_look = std::any_of(o.tables.begin(), o.tables.end(), [](const Table &t) {
            return t.look == Look::scene;
        });
        std::vector<std::string> load_lines;
        for (const std::string &level : o.load_levels) {
            double load = 1e30, build = 1e30;
            std::size_t triangles = 0;
            for (int r = 0; r < o.repeat; ++r) {
                auto t0 = std::chrono::steady_clock::now();
                Quake3Options read;
                read.look = any_look;
                const Scene scene = load_scene(level, nullptr, read);
                load = std::min(load, ms_since(t0));
                t0 = std::chrono::steady_clock::now();
                HierarchyOptions h;
                h.max_leaf_triangles = o.leaf_triangles;
                const Hierarchy hierarchy = Hierarchy::build(scene, h);
                build = std::min(build, ms_since(t0));
                triangles = scene.triangle_count();
            }
            char line[600];
            std::snprintf(line, sizeof(line), "`%s` (%zu triangles%s): %.1f ms from pk3 to scene, %.1f ms to hierarchy, "
                          "%.1f ms: %s", short_name(level).c_str(), triangles, any_look ? ", with its textures" : "",
                          load, build, load + build, load + build <= load_target_ms ? "**met**" : "not met");
            load_lines.push_back(line);
            std::printf("load %s\n", line);
            if (loads_csv.is_open())
                loads_csv << csv_field(level) << ',' << load << ',' << build << ',' << load + build << ','
                          << triangles << '\n';
        }

        // A context per table (its frames' size), each made current for its runs.
        std::vector<std::unique_ptr<gl::OffscreenContext>> contexts;
        std::vector<SessionCommandLine> session_lines;
        for (const Table &t : o.tables) {
            contexts.push_back(std::make_unique<gl::OffscreenContext>(t.width, t.height));
            SessionCommandLine line = o.session;
            line.width = t.width;
            line.height = t.height;
            line.look = t.look;
            session_lines.push_back(line);
        }
        std::vector<Run> runs;
        // Per scene and route, vfc's frame in the first table over its frame in table k (k >= 1).
        std::vector<std::string> look_cost_rows;
        for (std::size_t i = 0; i < o.scenes.size(); ++i) {
            // The scene read once per look its tables draw: with the look
            // a level's pictures and lightmaps, a model's textures.
            std::map<Look, std::unique_ptr<SceneSetup>> setups;
            for (const Table &t : o.tables)
                if (!setups.count(t.look)) {
                    SceneChoice choice(o.scenes[i], 1, o.leaf_triangles);
                    choice.quake3.look = t.look == Look::scene;
                    setups[t.look] = std::make_unique<SceneSetup>(choice);
                }
            const SceneSetup &first = *setups.begin()->second;
            if (is_level(first.scene())) {
                const LevelStatistics s = level_statistics(first.scene());
                std::printf("\nlevel %s: %s\n  (%s)\n", short_name(o.scenes[i]).c_str(), s.row().c_str(),
                            LevelStatistics::columns());
                if (levels_csv.is_open())
                    levels_csv << csv_field(o.scenes[i]) << ',' << s.row() << '\n';
            }
            std::vector<std::string> routes = {is_level(first.scene()) ? "spawn:" + std::to_string(o.spawn_views)
                                                                       : "orbit"};
            if (o.random_views > 0)
                routes.push_back("random:" + std::to_string(o.random_views) + ":" + std::to_string(o.seed + i));
            for (const std::string &route : routes) {
                // Every table of this route before the next route: the
                // tables' vfc frames measured close together in time.
                const std::size_t first_run = runs.size();
                for (std::size_t t = 0; t < o.tables.size(); ++t) {
                    contexts[t]->make_current();
                    runs.push_back(run_route(o, session_lines[t], t, *setups.at(o.tables[t].look), route, *contexts[t]));
                    const Run &run = runs.back();
                    if (runs_csv.is_open()) {
                        for (const Row &r : run.rows)
                            runs_csv << csv_field(run.scene) << ',' << route << ',' << o.tables[t].size_name() << ','
                                     << (o.tables[t].look == Look::scene ? "scene" : "flat") << ',' << run.frames
                                     << ',' << csv_field(r.label) << ',' << (r.conservative ? "yes" : "no") << ','
                                     << r.mean << ',' << r.median << ',' << r.x_vfc << ',' << r.x_floor << ','
                                     << r.x_pvs << ',' << r.triangles << ','
                                     << (r.efficiency ? *r.efficiency : -1.0) << ',' << r.visible_culled << ','
                                     << r.lost << ',' << r.tied << ',' << r.test_ms << ',' << r.setup_ms << '\n';
                        runs_csv.flush();
                    }
                }
                const Run &a = runs[first_run];
                for (std::size_t t = 1; t < o.tables.size(); ++t) {
                    const Run &b = runs[first_run + t];
                    char row[600];
                    std::snprintf(row, sizeof(row), "| `%s` | %s | %.2f | %.2f | %.2fx | %.2fx | %.2fx |",
                                  a.name.c_str(), route.c_str(), a.vfc_ms, b.vfc_ms,
                                  b.vfc_ms > 0 ? a.vfc_ms / b.vfc_ms : 0.0, a.ideal_ms > 0 ? a.vfc_ms / a.ideal_ms : 0.0,
                                  b.ideal_ms > 0 ? b.vfc_ms / b.ideal_ms : 0.0);
                    std::printf("\nlook cost: `%s` %s: vfc at %s %.2f ms against %s %.2f ms: %.2fx\n",
                                a.name.c_str(), route.c_str(), o.tables[0].name().c_str(), a.vfc_ms,
                                o.tables[t].name().c_str(), b.vfc_ms, b.vfc_ms > 0 ? a.vfc_ms / b.vfc_ms : 0.0);
                    std::fflush(stdout);
                    look_cost_rows.push_back(o.tables.size() > 2 ? row + (" " + o.tables[t].name() + " |") : row);
                }
            }
        }

        int met = 0, missed = 0;
        for (std::size_t t = 0; t < o.tables.size(); ++t) {
            const std::string table = o.tables[t].name();
            // The targets, a row per scene and route.
            std::printf("\n## The targets, %s\n\n| scene | route (frames) | vfc ms (vfc again) | floor: x vfc, hides | best conservative "
                        "within %.1fx floor | every strategy >= %.0f%% efficiency where the floor hides >= half | "
                        "best >= %.1fx over bsp-pvs | conservative lost pixels |\n|---|---|---|---|---|---|---|---|\n",
                        table.c_str(), floor_target, efficiency_target, pvs_gain_target);
            for (const Run &run : runs) {
                if (run.table != t)
                    continue;
                const Verdicts v = verdicts(run);
                met += v.met;
                missed += v.missed;
                const auto again = std::find_if(run.rows.begin(), run.rows.end(),
                                                [](const Row &r) { return r.label == "vfc again"; });
                std::printf("| `%s` | %s (%zu) | %.2f (%s) | %.2fx, %.0f%% | %s | %s | %s | %s |\n", run.name.c_str(),
                            run.route.c_str(), run.frames, run.vfc_ms,
                            again == run.rows.end() ? "-" : ratio(again->x_vfc).c_str(), run.vfc_ms / run.ideal_ms,
                            100.0 * run.floor_hides(), v.floor.c_str(), v.efficiency.c_str(), v.pvs.c_str(),
                            v.lost.c_str());
            }

            // Every strategy on every scene, a table per route kind.
            for (const bool random : {false, true}) {
                std::vector<const Run *> kind;
                for (const Run &run : runs)
                    if (run.table == t && (run.route.rfind("random:", 0) == 0) == random)
                        kind.push_back(&run);
                if (kind.empty())
                    continue;
                std::printf("\n## %s, %s: x vfc / x floor / efficiency (lost px per frame where any)\n\n| strategy |",
                            random ? "Random eyes" : "Spawn points and orbits", table.c_str());
                for (const Run *run : kind)
                    std::printf(" `%s` %s |", run->name.c_str(), run->route.c_str());
                std::printf("\n|---|");
                for (std::size_t i = 0; i < kind.size(); ++i)
                    std::printf("---|");
                std::printf("\n");
                std::vector<std::string> labels = o.session.strategies;
                labels.insert(std::find(labels.begin(), labels.end(), "vfc") + 1, "vfc again");
                for (const std::string &label : labels) {
                    std::printf("| `%s` |", label.c_str());
                    for (const Run *run : kind) {
                        const auto r = std::find_if(run->rows.begin(), run->rows.end(),
                                                    [&](const Row &x) { return x.label == label; });
                        if (r == run->rows.end()) {
                            std::printf(" (refused) |");
                            continue;
                        }
                        std::string lost;
                        if (r->lost)
                            lost = " (" + std::to_string(std::llround(r->lost_per_frame)) + " px)";
                        std::printf(" %.2f / %.2f / %s%s%s |", r->x_vfc, r->x_floor, percent(r->efficiency).c_str(),
                                    r->low_efficiency ? "*" : "", lost.c_str());
                    }
                    std::printf("\n");
                }
            }
        }
        if (!look_cost_rows.empty()) {
            // Separate sessions (a context per size), run one after the
            // other: this ratio carries the load's drift between them,
            // which the interleaved ratios within a table do not.
            std::printf("\n## What the look costs: vfc's frame %s against %s\n\n"
                        "| scene | route | vfc ms %s | vfc ms %s | look / flat | floor x vfc %s | floor x vfc %s |%s\n"
                        "|---|---|---|---|---|---|---|%s\n",
                        o.tables[0].name().c_str(), o.tables.size() > 2 ? "each other table" : o.tables[1].name().c_str(),
                        o.tables[0].name().c_str(), o.tables.size() > 2 ? "other" : o.tables[1].name().c_str(),
                        o.tables[0].name().c_str(), o.tables.size() > 2 ? "other" : o.tables[1].name().c_str(),
                        o.tables.size() > 2 ? " other table |" : "", o.tables.size() > 2 ? "---|" : "");
            for (const std::string &row : look_cost_rows)
                std::printf("%s\n", row.c_str());
        }
        for (const std::string &l : load_lines)
            std::printf("\nload: %s", l.c_str());
        std::printf("\n\n%d targets met, %d not met (over scenes, routes and tables)\n", met, missed);
        std::printf("\nx vfc: vfc's mean frame ms / the strategy's (vfc again: vfc run a second time, its ratio\n"
                    "the run's noise); x floor: the strategy's / ideal's (the oracle's visible leaves alone);\n"
                    "efficiency: occluded leaves culled / occluded leaves (the oracle's), * below %.0f%% where the\n"
                    "floor hides at least half the frustum's triangles; lost px: pixels where a culled leaf is\n"
                    "strictly nearer than what the frame drew (evaluation/lost_pixels.h), every strategy's frames\n"
                    "compared; bsp-pvs and its chains are approximate (the compiler's PVS).\n"
                    "%.0f s in all.\n",
                    efficiency_target, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        return 0;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "occu-bench-real-scenes: %s\n", e.what());
        return 1;
    }
}
