// SPDX-License-Identifier: MIT
// occu-bench-no-occlusion: only the work the scene calls for (issue 18,
// item 6; docs/no-occlusion.md). Every strategy of the registry against
// vfc where occlusion culling has little or nothing to gain: the city's
// `open` route (150 m up, across the roofs: Poon and Wang's worst case) and
// the field (scene/field.h: small posts on a plane, seen from above on the
// `overhead` route, where nothing hides anything). The target: no strategy
// slower than 1.05x vfc on either, by switching its tests off or otherwise.
//
// Per scene and round one measurement session
// (evaluation/measurement_session.h): every strategy draws frame f before
// any draws frame f + 1, in an order shuffled per frame, so the machine's
// drifting load and what one frame leaves to the next weigh on all alike;
// a second vfc ("vfc again") runs beside the first, so that the table
// shows the noise of a ratio between two identical strategies. Traversal
// policies as the walkthrough's defaults: temporal coherence and
// switch-off 0.5 where the family takes them.
//
// Prints per scene and strategy the mean, median and least frame ms, mean /
// vfc's mean ("x vfc"), median / vfc's median, culling efficiency against
// the oracle, node tests per frame over the whole route and over its last
// quarter (0 there: the tests are switched off), and PASS or OVER against
// 1.05x vfc (judged on the mean, the figure the README's tables give);
// then one markdown table of both scenes. Timing only: no test runs this
// (tests/integration/no_occlusion_field_test.cpp checks what can be
// checked without a clock).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <map>
#include <memory>
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

constexpr double target = 1.05;

struct Options {
    // --strategies (empty: every strategy of the registry once,
    // distinct_strategy_names()), --set, --size, --driver, --allocator,
    // --batch, --coherence, --switch-off, --databases, --make-databases
    // (all: no database is made inside a frame's time).
    SessionCommandLine session = [] {
        SessionCommandLine s;
        s.make_databases = DatabaseProvider::Makes::all;
        return s;
    }();
    int frames = 120;
    int rounds = 1;   // walks of each route, strategies made anew for each
};

[[noreturn]] void usage(const std::string &error)
{
    std::FILE *to = error.empty() ? stdout : stderr;
    if (!error.empty())
        std::fprintf(to, "occu-bench-no-occlusion: %s\n", error.c_str());
    std::fprintf(to,
                 "usage: occu-bench-no-occlusion [--strategies NAME,...] [--set key=value]... [--frames N] [--rounds R]\n"
                 "                               [--size PIXELS|WxH] [--driver llvmpipe|softpipe] [--batch N] [--switch-off F]\n"
                 "                               [--allocator keep|system] [--coherence on|off] [--databases DIR]\n"
                 "                               [--make-databases required|all]\n"
                 "Runs every strategy (default: every name of the registry, a preset that repeats its family's\n"
                 "defaults once) side by side with vfc on the city's open route and on the field's overhead route\n"
                 "(default 120 frames each, 512x512, llvmpipe) and prints each one's frame time against vfc's with\n"
                 "PASS or OVER against %.2fx. --rounds R walks each route R times, the strategies made anew each\n"
                 "time (their first frame and probes included each time), and gives the figures of all frames\n"
                 "with the least and greatest round's mean against vfc's. The databases the strategies read are made\n"
                 "before the runs in --databases DIR (%s) and found there by later runs (--make-databases\n"
                 "all, the default here, so that no frame time includes making one). A strategy whose family\n"
                 "refuses a scene is left out of it, with why.\n",
                 target, default_database_directory().c_str());
    std::exit(error.empty() ? 0 : 2);
}

Options parse(int argc, char **argv)
{
    Options o;
    for_each_option(argc, argv, usage, [&](const std::string &a, const std::string &v) {
        if (o.session.take(a, v)) return true;
        else if (a == "--frames") o.frames = int(integer_option(a, v, 1, 100000));
        else if (a == "--rounds") o.rounds = int(integer_option(a, v, 1, 100));
        else
            return false;
        return true;
    });
    try {
        if (o.session.strategies.empty())
            o.session.strategies = distinct_strategy_names();
        o.session.check_strategies(o.session.strategies);
    } catch (const std::invalid_argument &e) {
        usage(e.what());
    }
    return o;
}

struct Result {
    std::string label;
    double mean = 0, median = 0, least = 0, x_vfc = 0, median_x_vfc = 0, efficiency = -1, tests = 0, tests_last = 0,
           triangles = 0;
    std::uint64_t visible_culled = 0;
    std::vector<double> round_x_vfc;   // each round's mean / vfc's mean in that round
    bool baseline = false;
    bool pass() const { return x_vfc <= target; }
    std::string mark() const
    {
        if (label == "none")
            return "baseline (no culling)";
        if (label == "ideal")
            return "floor";
        if (label == "vfc")
            return "reference";
        if (label == "vfc again")
            return pass() ? "noise control, within" : "noise control, OUTSIDE";
        return pass() ? "PASS" : "OVER";
    }
};

struct SceneResult {
    std::string scene, route;
    std::size_t triangles = 0, leaves = 0;
    std::vector<Result> results;
    std::vector<std::string> left_out;
};

// Whether `s` is a reference rather than a strategy judged against vfc.
bool baseline(const SessionStrategy &s)
{
    const std::string &f = s.strategy.choice.family->name;
    return f == "none" || f == "ideal" || s.label == "vfc";
}

SceneResult run_scene(const Options &o, const std::string &scene_name, const std::string &route_name,
                      gl::OffscreenContext &ctx)
{
    SceneResult out;
    out.scene = scene_name;
    out.route = route_name;
    SceneChoice choice(scene_name, 1, HierarchyOptions{}.max_leaf_triangles);
    choice.quake3.look = o.session.look == Look::scene;   // flat unless --look scene
    const SceneSetup setup(choice);
    const std::vector<Camera> route = setup.route(route_name, o.frames, o.session.aspect());
    out.triangles = setup.scene().triangle_count();
    out.leaves = setup.hierarchy().leaf_count();
    DatabaseProvider databases = o.session.database_provider();
    SessionOptions so = o.session.session_options(databases);
    so.lost_pixels = SessionOptions::PixelCheck::none;

    // One walk of the route by every strategy, made anew in a session of its own.
    auto walk = [&](bool first) {
        auto session = std::make_unique<MeasurementSession>(setup, ctx, so);
        auto add = [&](const std::string &label, const std::string &spec) {
            if (const std::string why = session->add_unless_refused(spec, o.session.common, label); !why.empty())
                if (first)
                    out.left_out.push_back(spec + ": " + why);
        };
        for (const std::string &s : o.session.strategies) {
            add(s, s);
            if (s == "vfc")
                add("vfc again", "vfc");
        }
        const auto &made = session->strategies();
        if (std::none_of(made.begin(), made.end(), [](const SessionStrategy &s) { return s.label == "vfc"; }))
            add("vfc", "vfc");
        if (first) {
            std::printf("%s (%zu triangles, %zu leaves), route %s: %zu strategies, %zu frames, %d round(s), %dx%d, %s\n",
                        scene_name.c_str(), out.triangles, out.leaves, route_name.c_str(), made.size(), route.size(),
                        o.rounds, o.session.width, o.session.height, ctx.renderer().c_str());
            for (const std::string &l : out.left_out)
                std::printf("left out: %s\n", l.c_str());
            std::fflush(stdout);
        }
        session->walk(route, scene_name);
        return session;
    };

    // Every round's frames pooled; per round its mean against vfc's, and
    // the node tests per frame over the route and over its last quarter.
    std::vector<std::string> labels;
    std::vector<Measured> pooled;
    std::unique_ptr<MeasurementSession> first_round;
    std::map<std::string, std::vector<double>> round_ratio;
    std::map<std::string, double> tests, tests_last;
    std::vector<bool> baselines;
    for (int round = 0; round < o.rounds; ++round) {
        std::unique_ptr<MeasurementSession> done = walk(round == 0);
        const auto &strategies = done->strategies();
        const double vfc_round =
            std::find_if(strategies.begin(), strategies.end(), [](const SessionStrategy &s) { return s.label == "vfc"; })
                ->measured.mean_ms();
        for (std::size_t i = 0; i < strategies.size(); ++i) {
            const SessionStrategy &s = strategies[i];
            const Measured &m = s.measured;
            round_ratio[s.label].push_back(m.mean_ms() / vfc_round);
            const std::size_t n = m.nodes_tested.size(), last = std::max<std::size_t>(1, n / 4);
            double all = 0, tail = 0;
            for (std::size_t j = 0; j < n; ++j) {
                all += m.nodes_tested[j];
                if (j >= n - last)
                    tail += m.nodes_tested[j];
            }
            tests[s.label] += all / double(n) / double(o.rounds);
            tests_last[s.label] += tail / double(last) / double(o.rounds);
            if (round == 0) {
                labels.push_back(s.label);
                baselines.push_back(baseline(s));
                pooled.push_back(m);
            } else {
                pooled[i].pool(m);
            }
        }
        if (round == 0)
            first_round = std::move(done);
    }

    const std::size_t vfc = std::size_t(std::find(labels.begin(), labels.end(), "vfc") - labels.begin());
    const double vfc_mean = pooled[vfc].mean_ms(), vfc_median = pooled[vfc].median_ms();
    for (std::size_t i = 0; i < labels.size(); ++i) {
        const Measured &m = pooled[i];
        Result x;
        x.label = labels[i];
        x.baseline = baselines[i];
        x.mean = m.mean_ms();
        x.median = m.median_ms();
        x.least = m.least_ms();
        x.x_vfc = x.mean / vfc_mean;
        x.median_x_vfc = x.median / vfc_median;
        x.efficiency = m.efficiency_percent().value_or(-1.0);
        x.tests = tests[x.label];
        x.tests_last = tests_last[x.label];
        x.triangles = m.per_frame(m.triangles);
        x.visible_culled = m.visible_culled;
        x.round_x_vfc = round_ratio[x.label];
        out.results.push_back(x);
    }
    std::printf("\n%-16s %9s %9s %9s %7s %9s %15s %10s %10s %10s %9s  %s\n", "strategy", "mean ms", "median", "least",
                "x vfc", "median x", "rounds x vfc", "efficiency", "tests/fr", "last 1/4", "triangles", "mark");
    for (const Result &x : out.results) {
        char efficiency[32] = "-";
        if (x.efficiency >= 0)
            std::snprintf(efficiency, sizeof(efficiency), "%.1f%%", x.efficiency);
        const auto [lo, hi] = std::minmax_element(x.round_x_vfc.begin(), x.round_x_vfc.end());
        char rounds[48];
        std::snprintf(rounds, sizeof(rounds), "%.3f-%.3fx", *lo, *hi);
        std::printf("%-16s %9.2f %9.2f %9.2f %6.3fx %8.3fx %15s %10s %10.1f %10.1f %9.0f  %s\n", x.label.c_str(), x.mean,
                    x.median, x.least, x.x_vfc, x.median_x_vfc, rounds, efficiency, x.tests, x.tests_last, x.triangles,
                    x.mark().c_str());
    }
    for (const std::string &note : first_round->notes())
        std::printf("%s\n", note.c_str());
    for (const Result &x : out.results)
        if (x.visible_culled && x.label != "ideal")
            std::printf("note: %s culled %llu visible leaves\n", x.label.c_str(), (unsigned long long)x.visible_culled);
    std::printf("\n");
    std::fflush(stdout);
    return out;
}

std::string cell(const SceneResult &s, const std::string &label)
{
    for (const Result &x : s.results)
        if (x.label == label) {
            char text[200];
            char efficiency[32] = "-";
            if (x.efficiency >= 0)
                std::snprintf(efficiency, sizeof(efficiency), "%.1f%%", x.efficiency);
            const auto [lo, hi] = std::minmax_element(x.round_x_vfc.begin(), x.round_x_vfc.end());
            char rounds[64] = "";
            if (x.round_x_vfc.size() > 1)
                std::snprintf(rounds, sizeof(rounds), "; rounds %.3f-%.3fx", *lo, *hi);
            std::snprintf(text, sizeof(text), "%.2f ms (%.3fx; median %.3fx%s) %s %s", x.mean, x.x_vfc, x.median_x_vfc,
                          rounds, efficiency,
                          x.baseline ? "" : x.label == "vfc again" ? "(noise)" : (x.pass() ? "PASS" : "**OVER**"));
            std::string t = text;
            while (!t.empty() && t.back() == ' ')
                t.pop_back();
            return t;
        }
    return "(left out)";
}

}  // namespace

int main(int argc, char **argv)
{
    const Options o = parse(argc, argv);
    try {
        gl::select_driver(o.session.driver);
        gl::OffscreenContext ctx(o.session.width, o.session.height);
        std::vector<SceneResult> scenes;
        scenes.push_back(run_scene(o, "city", "open", ctx));
        scenes.push_back(run_scene(o, "field", "overhead", ctx));

        std::printf("| strategy | city, open route | field, overhead route |\n|---|---|---|\n");
        std::vector<std::string> labels;
        for (const SceneResult &s : scenes)
            for (const Result &x : s.results)
                if (std::find(labels.begin(), labels.end(), x.label) == labels.end())
                    labels.push_back(x.label);
        int over = 0;
        for (const std::string &l : labels) {
            std::printf("| %s | %s | %s |\n", l.c_str(), cell(scenes[0], l).c_str(), cell(scenes[1], l).c_str());
            for (const SceneResult &s : scenes)
                for (const Result &x : s.results)
                    over += x.label == l && !x.baseline && x.label != "vfc again" && !x.pass();
        }
        std::printf("\ncells: mean frame ms (mean / vfc's mean; median / vfc's median) culling efficiency, and PASS or\n"
                    "OVER against %.2fx vfc on the mean; none (no culling) and ideal (the floor) are not judged; \"vfc\n"
                    "again\" is vfc a second time: its ratio is the noise of two identical strategies.\n"
                    "%d strategy-scene pairs over %.2fx vfc.\n",
                    target, over, target);
        return 0;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "occu-bench-no-occlusion: %s\n", e.what());
        return 1;
    }
}
