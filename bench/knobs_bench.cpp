// SPDX-License-Identifier: MIT
// occu-bench-knobs: what accuracy costs in time, for every knob of every
// strategy in the registry, in one command (docs/knobs.md).
//
// Per strategy, every setting whose role is approximation or cost
// (culling/settings.h) is swept over values derived from its declared
// range and default, and so are the two common knobs of every strategy:
// the traversal's batch (nodes tested together) and the hierarchy's leaf
// size (triangles per leaf). Each variant is the strategy spec
// "NAME:setting=value", run side by side frame by frame with vfc and ideal
// (the floor) in one measurement session per route
// (evaluation/measurement_session.h; leaf sizes: one per route and size,
// every strategy at its default). Wrong pixels are
// counted for every variant, exact or not, against the unculled frame
// (evaluation/lost_pixels.h: depth ties are not wrong); efficiency is
// occluded leaves culled / occluded leaves against the oracle.
//
// Values (derived, not listed per strategy):
//   approximation (`tolerance`, exact at 0): 0 and a geometric series x4:
//     integers 1, 4, 16, 64; numbers from max/100 (two digits) up to max;
//   cost, numeric: default/4, default/2, default, 2 default, 4 default, kept
//     within the range (integers rounded), and the value that turns it off;
//   cost, on/off: off and on; cost, a choice (coverage=whole|merged):
//     every choice;
//   batch: 8, 16, 32 (walkthrough's), 64, 128; leaf size: 64, 128, 256,
//     512, 1024 and auto (the size chosen per scene, spatial/hierarchy.h).
// Other choices and paths (databases) are not swept: listed as left out,
// with why.
//
// Scenes: the city (default) or any others --scenes names (a level, a
// building read from a file: docs/real-scenes.md), every route on every
// scene; a run is one scene's route, named by the route alone on a single
// scene and "SCENE ROUTE" (the file's short name) on several.
//
// Writes DIR/knobs.csv (one row per strategy, setting, value and run, and
// route "all": the means over the runs), DIR/<strategy>.png (frame time
// against wrong pixels and against efficiency, the Pareto fronts and the
// default marked; gnuplot), and prints a markdown table per strategy.
// Exits 1 when an approximation knob has no value with 0 wrong pixels on
// every route.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <set>
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

constexpr int default_batch = 32;
// The walkthrough's leaf size (auto_leaf_triangles for auto).
constexpr int default_leaf = int(HierarchyOptions{}.max_leaf_triangles);
const char *const batch_knob = "batch (traversal)";
const char *const leaf_knob = "leaf-triangles (hierarchy)";

struct Options {
    // --strategies (empty: every family with a knob), --size, --driver,
    // --allocator, --databases, --make-databases; the traversal and the
    // settings are what it sweeps, so it takes no --batch, --coherence,
    // --switch-off nor --set.
    SessionCommandLine session = [] {
        SessionCommandLine s;
        s.traversal_options = false;
        return s;
    }();
    std::vector<std::string> scenes = {"city"};
    std::vector<std::string> routes = {"dense", "medium", "open"};
    // Every route on every scene, made by parse(): a run is one of them.
    struct Run {
        std::size_t scene;
        std::string route, label;
    };
    std::vector<Run> runs;
    std::map<std::string, std::vector<std::string>> knobs;   // --knob: only these, with these values
    int frames = 20;
    std::string out = "knobs-out";
    bool plots = true;
};

[[noreturn]] void usage(const std::string &error)
{
    std::FILE *to = error.empty() ? stdout : stderr;
    if (!error.empty())
        std::fprintf(to, "occu-bench-knobs: %s\n", error.c_str());
    std::fprintf(to,
                 "usage: occu-bench-knobs [--scenes SCENE,...] [--routes ROUTE,...] [--strategies NAME,...]\n"
                 "                        [--knob SETTING=V1,V2,...]...\n"
                 "                        [--frames N] [--size PIXELS|WxH] [--driver llvmpipe|softpipe] [--out DIR]\n"
                 "                        [--allocator keep|system]\n"
                 "                        [--plots on|off] [--databases DIR] [--make-databases required|all]\n"
                 "Sweeps every approximation and cost setting of each strategy (default: every registered family\n"
                 "with one), and the common knobs batch and leaf-triangles, on each route (default\n"
                 "dense,medium,open; 20 frames, 512x512), beside vfc and ideal, on each scene (default the city;\n"
                 "a level PAK.pk3:maps/NAME.bsp or a model file: every route on every scene, the means over all\n"
                 "of these runs). --knob keeps only the named\n"
                 "settings (repeat it for several), with the given values. Writes DIR/knobs.csv and DIR/<strategy>.png\n"
                 "(default DIR knobs-out) and prints a table per strategy; exits 1 when an approximation knob has\n"
                 "no value exact (0 wrong pixels) on every route. The databases the variants require are made\n"
                 "before their runs in --databases DIR (%s) and found there by later runs; --make-databases\n"
                 "all makes every one they read (a whole database per variant that reads one: long for some).\n\nstrategies:\n%s",
                 default_database_directory().c_str(), strategies_help().c_str());
    std::exit(error.empty() ? 0 : 2);
}

bool sweeps(const SettingSpec &s)
{
    return s.role != SettingSpec::Role::choice &&
           (s.kind == SettingSpec::Kind::integer || s.kind == SettingSpec::Kind::number ||
            s.kind == SettingSpec::Kind::on_off || s.kind == SettingSpec::Kind::choice);
}

// A family is worth sweeping when it has a knob of its own.
std::vector<std::string> default_strategies()
{
    std::vector<std::string> names;
    for (const StrategyFamily &f : strategy_families())
        if (std::any_of(f.settings.begin(), f.settings.end(), sweeps))
            names.push_back(f.name);
    return names;
}

std::string number_text(double x)
{
    char s[32];
    std::snprintf(s, sizeof(s), "%g", x);
    return s;
}

// Two significant digits.
double two_digits(double x)
{
    if (x <= 0)
        return x;
    const double scale = std::pow(10.0, std::floor(std::log10(x)) - 1.0);
    return std::round(x / scale) * scale;
}

// The values a setting is swept over (the rules in the header), `current`
// its value in the strategy (the family's default or the preset's).
std::vector<std::string> derived_values(const SettingSpec &s, const std::string &current)
{
    std::vector<std::string> v;
    const bool integer = s.kind == SettingSpec::Kind::integer;
    auto add = [&](double x) {
        x = std::clamp(x, s.min, s.max);
        if (integer)
            x = std::round(x);
        const std::string t = number_text(x);
        if (std::find(v.begin(), v.end(), t) == v.end())
            v.push_back(t);
    };
    if (s.kind == SettingSpec::Kind::on_off)
        return {"off", "on"};
    if (s.kind == SettingSpec::Kind::choice)
        return s.choices;
    if (s.role == SettingSpec::Role::approximation) {
        add(0.0);
        double x = integer ? 1.0 : two_digits(s.max / 100.0);
        for (int k = 0; k < 4 && x <= s.max; ++k, x *= 4.0)
            add(x);
        return v;
    }
    const double d = std::strtod(current.c_str(), nullptr);
    if (!s.off.empty())
        add(std::strtod(s.off.c_str(), nullptr));
    for (double f : {0.25, 0.5, 1.0, 2.0, 4.0})
        add(d == 0.0 ? s.min + f * (s.max - s.min) / 8.0 : d * f);
    std::sort(v.begin(), v.end(), [](const std::string &a, const std::string &b) {
        return std::strtod(a.c_str(), nullptr) < std::strtod(b.c_str(), nullptr);
    });
    return v;
}

bool same_value(const std::string &a, const std::string &b)
{
    if (a == b)
        return true;
    char *ea = nullptr, *eb = nullptr;
    const double x = std::strtod(a.c_str(), &ea), y = std::strtod(b.c_str(), &eb);
    return !a.empty() && !b.empty() && !*ea && !*eb && x == y;
}

// One configuration run: a strategy spec on a hierarchy of `leaf`
// triangles per leaf, traversed `batch` nodes at a time.
struct Variant {
    std::string strategy;   // as given (family or preset)
    std::string spec;       // strategy[:setting=value]
    int leaf = default_leaf, batch = default_batch;
    bool baseline = false;  // vfc or ideal
    std::string refused;    // why the strategy refused these settings when built (settings that must agree)
    // What it measured, per route.
    std::vector<Measured> routes;
};

// A row of the sweep: a strategy's setting at one value, which is variant `variant`.
struct Row {
    std::string strategy, setting, value, role;
    bool is_default = false;
    std::size_t variant = 0;
};

struct Sweep {
    std::vector<Variant> variants;
    std::vector<Row> rows;
    std::vector<std::string> left_out;   // "strategy setting: why"
};

std::size_t variant_index(Sweep &sweep, const Variant &v)
{
    for (std::size_t i = 0; i < sweep.variants.size(); ++i)
        if (sweep.variants[i].spec == v.spec && sweep.variants[i].leaf == v.leaf && sweep.variants[i].batch == v.batch)
            return i;
    sweep.variants.push_back(v);
    return sweep.variants.size() - 1;
}

Sweep plan(const Options &o)
{
    Sweep sweep;
    for (const char *b : {"vfc", "ideal"}) {
        Variant v;
        v.strategy = v.spec = b;
        v.baseline = true;
        variant_index(sweep, v);
    }
    std::set<std::string> used_knobs;
    auto wanted = [&o](const std::string &name) { return o.knobs.empty() || o.knobs.count(name); };
    for (const std::string &name : o.session.strategies) {
        const StrategyChoice c = choose_strategy(name);
        Variant base;
        base.strategy = base.spec = name;
        const std::size_t def = variant_index(sweep, base);
        auto row = [&](const std::string &setting, const std::string &value, const std::string &role, bool is_default,
                       std::size_t variant) {
            sweep.rows.push_back({name, setting, value, role, is_default, variant});
            used_knobs.insert(setting.substr(0, setting.find(' ')));
        };
        for (const SettingSpec &s : c.family->settings) {
            if (!sweeps(s)) {
                const std::string why = s.kind == SettingSpec::Kind::path
                                            ? "a database file, not a knob (" + s.help + ")"
                                            : "a choice of variant, not an approximation or cost";
                sweep.left_out.push_back(name + " " + s.name + ": " + why);
                continue;
            }
            if (!wanted(s.name))
                continue;
            const std::string current = c.settings.text(s.name);
            const std::vector<std::string> values = o.knobs.count(s.name) ? o.knobs.at(s.name) : derived_values(s, current);
            const std::string role = s.role == SettingSpec::Role::approximation ? "approximation" : "cost";
            for (const std::string &value : values) {
                if (same_value(value, current)) {
                    row(s.name, current, role, true, def);
                    continue;
                }
                Variant v = base;
                v.spec = name + ":" + s.name + "=" + value;
                choose_strategy(v.spec);   // refuses a value out of range, naming it
                row(s.name, value, role, false, variant_index(sweep, v));
            }
        }
        // The common knobs: the traversal's batch and the hierarchy's leaf size.
        auto common = [&](const char *knob, const std::string &key, std::vector<std::string> values, int current,
                          const std::function<int(const std::string &)> &parse, int Variant::*field) {
            if (!wanted(key))
                return;
            if (o.knobs.count(key))
                values = o.knobs.at(key);
            for (const std::string &value : values) {
                const int x = parse(value);
                if (x == current) {
                    row(knob, value, "cost", true, def);
                    continue;
                }
                Variant v = base;
                v.*field = x;
                row(knob, value, "cost", false, variant_index(sweep, v));
            }
        };
        common(batch_knob, "batch", {"8", "16", "32", "64", "128"}, default_batch,
               [](const std::string &v) { return int(integer_option("--knob batch", v, 1, 4096)); }, &Variant::batch);
        common(leaf_knob, "leaf-triangles", {"64", "128", "256", "512", "1024", "auto"}, default_leaf,
               [](const std::string &v) { return int(leaf_triangles_option("--knob leaf-triangles", v)); },
               &Variant::leaf);
    }
    for (const auto &[knob, values] : o.knobs)
        if (!used_knobs.count(knob))
            throw std::invalid_argument("--knob " + knob + ": no chosen strategy has an approximation or cost "
                                        "setting of that name (nor is it batch or leaf-triangles)");
    return sweep;
}

Options parse(int argc, char **argv)
{
    Options o;
    for_each_option(argc, argv, usage, [&](const std::string &a, const std::string &v) {
        if (o.session.take(a, v)) return true;
        else if (a == "--scenes") {
            o.scenes = list_items(v, ',');
            if (o.scenes.empty())
                usage("--scenes is empty");
        } else if (a == "--routes") {
            o.routes = list_items(v, ',');
            if (o.routes.empty())
                usage("--routes is empty");
        } else if (a == "--knob") {
            const std::size_t eq = v.find('=');
            if (eq == std::string::npos || eq == 0 || list_items(v.substr(eq + 1), ',').empty())
                usage("--knob wants SETTING=V1,V2,..., got '" + v + "'");
            o.knobs[v.substr(0, eq)] = list_items(v.substr(eq + 1), ',');
        } else if (a == "--frames") o.frames = int(integer_option(a, v, 1, 100000));
        else if (a == "--out") o.out = v;
        else if (a == "--plots") o.plots = switch_option(a, v);
        else
            return false;
        return true;
    });
    if (o.session.strategies.empty())
        o.session.strategies = default_strategies();
    for (std::size_t scene = 0; scene < o.scenes.size(); ++scene)
        for (const std::string &route : o.routes) {
            const std::string &name = o.scenes[scene];
            // A file's or a level's name without folder and extension.
            const std::size_t member = name.rfind(':');
            const std::string short_name =
                std::filesystem::path(name.substr(member == std::string::npos ? 0 : member + 1)).stem().string();
            o.runs.push_back({scene, route, o.scenes.size() == 1 ? route : short_name + " " + route});
        }
    try {
        for (const std::string &s : o.session.strategies) {
            const StrategyChoice c = choose_strategy(s);
            if (c.family->needs_truth || c.family->settings.empty() ||
                !std::any_of(c.family->settings.begin(), c.family->settings.end(), sweeps))
                usage("--strategies: " + s + " has no approximation or cost setting to sweep");
        }
    } catch (const std::invalid_argument &e) {
        usage(e.what());
    }
    return o;
}

// A leaf size as the reports print it: the size, or auto and the size it
// chose for the scene of `setup`.
std::string leaf_text(int leaf, const SceneSetup &setup)
{
    const std::string chosen = std::to_string(setup.hierarchy().max_leaf_triangles());
    return leaf == int(auto_leaf_triangles) ? "auto (" + chosen + ")" : chosen;
}

// One measurement session over a route: the variants of `leaf` triangles
// per leaf, frame by frame, as walkthrough runs them.
void walk(const Options &o, std::size_t route_index, int leaf, const SceneSetup &setup, Sweep &sweep,
          gl::OffscreenContext &ctx, std::set<std::string> &notes)
{
    const std::string &route_name = o.runs[route_index].route;
    const std::vector<Camera> route = setup.route(route_name, o.frames, o.session.aspect());
    DatabaseProvider databases = o.session.database_provider();
    SessionOptions so = o.session.session_options(databases);
    so.batch = default_batch;
    // Unrelated views (random eyes, camera/route.h): no policies across frames.
    so.coherence = !unrelated_views(route_name);
    so.switch_off = unrelated_views(route_name) ? 0.0 : so.switch_off;
    so.lost_pixels = SessionOptions::PixelCheck::all;
    MeasurementSession session(setup, ctx, so);
    std::vector<std::size_t> variant_of;   // per strategy of the session
    for (std::size_t i = 0; i < sweep.variants.size(); ++i) {
        Variant &v = sweep.variants[i];
        if (v.leaf != leaf || !v.refused.empty())
            continue;
        try {
            session.add(v.spec, {}, v.spec, std::size_t(v.batch));
            variant_of.push_back(i);
        } catch (const std::exception &e) {
            // Settings that must agree with each other (pvs: epsilon and pixel).
            v.refused = e.what();
        }
    }
    std::printf("route %s, leaves of %s triangles (%zu leaves): %zu variants, %zu frames\n",
                o.runs[route_index].label.c_str(), leaf_text(leaf, setup).c_str(), setup.hierarchy().leaf_count(),
                variant_of.size(), route.size());
    std::fflush(stdout);
    session.walk(route, "frames");
    for (std::size_t k = 0; k < variant_of.size(); ++k) {
        const SessionStrategy &s = session.strategies()[k];
        Variant &v = sweep.variants[variant_of[k]];
        v.routes[route_index] = s.measured;
        if (orders_frame(*s.strategy.culler) && v.batch != default_batch)
            notes.insert(v.spec + " at batch " + std::to_string(v.batch) +
                         ": orders its frame itself, the traversal's batch does not apply (its own `batch` setting does)");
    }
}

// Per variant over the routes: the means of the routes' figures, and the most wrong pixels of a route.
struct Figures {
    double ms = 0, median = 0, wrong = 0, efficiency = 0, triangles = 0, visible_culled = 0;
    std::uint64_t max_wrong = 0;
    bool any = false;
};

Figures figures(const Variant &v, std::optional<std::size_t> route)
{
    Figures f;
    int n = 0;
    for (std::size_t r = 0; r < v.routes.size(); ++r) {
        const Measured &m = v.routes[r];
        if ((route && r != *route) || m.ms.empty())
            continue;
        ++n;
        f.ms += m.mean_ms();
        f.median += m.median_ms();
        f.wrong += m.per_frame(double(m.lost_pixels));
        f.efficiency += m.efficiency_percent().value_or(100.0);
        f.triangles += m.per_frame(m.triangles);
        f.visible_culled += double(m.visible_culled);
        f.max_wrong = std::max(f.max_wrong, m.lost_pixels);
    }
    if (n) {
        f.any = true;
        f.ms /= n;
        f.median /= n;
        f.wrong /= n;
        f.efficiency /= n;
        f.triangles /= n;
        f.visible_culled /= n;
    }
    return f;
}

std::string fixed(double x, int digits)
{
    char s[48];
    std::snprintf(s, sizeof(s), "%.*f", digits, x);
    return s;
}

// The Pareto front of points (time, error): none other at most as slow and
// as wrong, and better in one. `error` is minimised.
std::vector<bool> pareto(const std::vector<std::pair<double, double>> &points)
{
    std::vector<bool> front(points.size(), true);
    for (std::size_t i = 0; i < points.size(); ++i)
        for (std::size_t j = 0; j < points.size() && front[i]; ++j)
            if (j != i && points[j].first <= points[i].first && points[j].second <= points[i].second &&
                (points[j].first < points[i].first || points[j].second < points[i].second))
                front[i] = false;
    return front;
}

// The variants `ids` as points (time, wrong pixels) and (time, -culling
// efficiency), means over the routes, and which of them lie on each front.
struct Fronts {
    std::vector<std::pair<double, double>> by_wrong, by_efficiency;
    std::vector<bool> front_w, front_e;
};

Fronts fronts(const Sweep &sweep, const std::vector<std::size_t> &ids)
{
    Fronts f;
    for (std::size_t id : ids) {
        const Figures v = figures(sweep.variants[id], std::nullopt);
        f.by_wrong.emplace_back(v.ms, v.wrong);
        f.by_efficiency.emplace_back(v.ms, -v.efficiency);
    }
    f.front_w = pareto(f.by_wrong);
    f.front_e = pareto(f.by_efficiency);
    return f;
}

std::string file_name(const std::string &label)
{
    std::string s = label;
    for (char &c : s)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '.')
            c = '_';
    return s;
}

std::string gnuplot_quoted(const std::string &text)
{
    std::string q = "'";
    for (char c : text)
        q += c == '\'' ? std::string("''") : std::string(1, c);
    return q + "'";
}

// DIR/<strategy>.png: its variants (means over the routes), one colour per
// setting, the fronts and the default marked.
bool plot(const Options &o, const std::string &strategy, const Sweep &sweep, double vfc_ms)
{
    const std::string dir = o.out + "/plot-data", base = dir + "/" + file_name(strategy);
    std::filesystem::create_directories(dir);
    std::vector<std::size_t> ids;   // the strategy's variants, each once
    std::vector<std::string> settings;
    for (const Row &r : sweep.rows)
        if (r.strategy == strategy) {
            if (std::find(ids.begin(), ids.end(), r.variant) == ids.end())
                ids.push_back(r.variant);
            if (std::find(settings.begin(), settings.end(), r.setting) == settings.end())
                settings.push_back(r.setting);
        }
    const auto &[by_wrong, by_efficiency, front_w, front_e] = fronts(sweep, ids);
    auto write_front = [&](const std::string &path, const std::vector<bool> &front, bool wrong) {
        std::vector<std::pair<double, double>> p;
        for (std::size_t i = 0; i < ids.size(); ++i)
            if (front[i])
                p.emplace_back(wrong ? by_wrong[i].second + 1.0 : -by_efficiency[i].second, by_wrong[i].first);
        std::sort(p.begin(), p.end());
        std::ofstream out(path);
        for (const auto &[x, y] : p)
            out << x << ' ' << y << '\n';
    };
    write_front(base + "-front-wrong.dat", front_w, true);
    write_front(base + "-front-efficiency.dat", front_e, false);
    {
        std::ofstream out(base + "-default.dat");
        std::size_t def = ids.front();
        for (std::size_t id : ids)
            if (sweep.variants[id].spec == strategy && sweep.variants[id].leaf == default_leaf &&
                sweep.variants[id].batch == default_batch)
                def = id;
        const Figures f = figures(sweep.variants[def], std::nullopt);
        out << f.wrong + 1.0 << ' ' << f.efficiency << ' ' << f.ms << '\n';
    }
    for (std::size_t s = 0; s < settings.size(); ++s) {
        std::ofstream out(base + "-" + std::to_string(s) + ".dat");
        for (const Row &r : sweep.rows)
            if (r.strategy == strategy && r.setting == settings[s]) {
                const Figures f = figures(sweep.variants[r.variant], std::nullopt);
                out << f.wrong + 1.0 << ' ' << f.efficiency << ' ' << f.ms << " \"" << r.value << "\"\n";
            }
    }
    const std::string png = o.out + "/" + file_name(strategy) + ".png";
    std::ofstream gp(base + ".gp");
    std::string routes;
    for (const Options::Run &r : o.runs)
        routes += (routes.empty() ? "" : ",") + r.label;
    gp << "set terminal pngcairo size 1400,620 font ',10' noenhanced\n"
       << "set output " << gnuplot_quoted(png) << "\n"
       << "set multiplot layout 1,2 title "
       << gnuplot_quoted(strategy + ": every knob, means over the routes " + routes + " (" + std::to_string(o.frames) +
                         " frames, " + std::to_string(o.session.width) + "x" + std::to_string(o.session.height) +
                         ", " + gl::driver_name(o.session.driver) + "); vfc " + fixed(vfc_ms, 2) + " ms")
       << "\nset grid\nset key outside bottom center horizontal\nset ylabel 'mean frame time, ms'\n";
    auto plots = [&](const std::string &x, const std::string &front) {
        std::string p = "plot ";
        for (std::size_t s = 0; s < settings.size(); ++s)
            p += gnuplot_quoted(base + "-" + std::to_string(s) + ".dat") + " using " + x + ":3 with points pt 7 ps 1.2 title " +
                 gnuplot_quoted(settings[s]) + ", ";
        p += gnuplot_quoted(base + front) + " using 1:2 with lines lw 2 lc rgb 'black' title 'Pareto front', ";
        p += gnuplot_quoted(base + "-default.dat") + " using " + x +
             ":3 with points pt 6 ps 3 lw 2 lc rgb 'red' title 'default'\n";
        return p;
    };
    gp << "set logscale x\nset xlabel 'wrong pixels per frame + 1 (log)'\n" << plots("1", "-front-wrong.dat")
       << "unset logscale x\nset xlabel 'culling efficiency, %'\n" << plots("2", "-front-efficiency.dat")
       << "unset multiplot\n";
    gp.close();
    const std::string command = "gnuplot " + gnuplot_quoted(base + ".gp") + " 2>" + gnuplot_quoted(base + ".log");
    if (std::system(command.c_str()) != 0) {
        std::fprintf(stderr, "occu-bench-knobs: gnuplot failed on %s.gp (see %s.log); no plot of %s\n", base.c_str(),
                     base.c_str(), strategy.c_str());
        return false;
    }
    std::printf("plot: %s\n", png.c_str());
    return true;
}

}  // namespace

int main(int argc, char **argv)
{
    const Options o = parse(argc, argv);
    Sweep sweep;
    try {
        sweep = plan(o);
    } catch (const std::invalid_argument &e) {
        usage(e.what());
    }
    try {
        gl::select_driver(o.session.driver);
        for (Variant &v : sweep.variants)
            v.routes.resize(o.runs.size());
        // Each scene, its hierarchy for each leaf size swept.
        std::vector<std::map<int, SceneSetup>> setups(o.scenes.size());
        for (std::size_t scene = 0; scene < o.scenes.size(); ++scene)
            for (const Variant &v : sweep.variants)
                if (!setups[scene].count(v.leaf)) {
                    HierarchyOptions leaf;
                    leaf.max_leaf_triangles = std::uint32_t(v.leaf);
                    if (setups[scene].empty()) {
                        SceneChoice choice;
                        choice.name = o.scenes[scene];
                        choice.hierarchy = leaf;
                        choice.quake3.look = o.session.look == Look::scene;   // flat unless --look scene
                        setups[scene].emplace(v.leaf, SceneSetup(choice));
                    } else {
                        setups[scene].emplace(v.leaf, setups[scene].begin()->second.with_hierarchy(leaf));
                    }
                }
        // Routes are checked before any run.
        for (const Options::Run &r : o.runs)
            setups[r.scene].begin()->second.route(r.route, o.frames, o.session.aspect());
        gl::OffscreenContext ctx(o.session.width, o.session.height);
        std::filesystem::create_directories(o.out);
        std::printf("occu-bench-knobs: %zu variants of %zu strategies, routes", sweep.variants.size() - 2,
                    o.session.strategies.size());
        for (const Options::Run &r : o.runs)
            std::printf(" %s", r.label.c_str());
        std::printf(", %d frames, %dx%d, %s\n", o.frames, o.session.width, o.session.height, ctx.renderer().c_str());
        for (const std::string &l : sweep.left_out)
            std::printf("left out: %s\n", l.c_str());
        std::set<std::string> notes;
        for (std::size_t r = 0; r < o.runs.size(); ++r)
            for (const auto &[leaf, setup] : setups[o.runs[r].scene])
                walk(o, r, leaf, setup, sweep, ctx, notes);

        // The CSV: per row and route, then the means over the routes.
        const std::string path = o.out + "/knobs.csv";
        std::ofstream csv(path);
        // The leaf size a variant was built with on a route's scene (auto:
        // the size it chose), or over all routes the sizes of their scenes,
        // "/" between them where the scenes' sizes differ.
        auto built_leaf = [&](const Variant &v, std::optional<std::size_t> route) {
            std::set<std::uint32_t> sizes;
            for (std::size_t r = 0; r < o.runs.size(); ++r)
                if (!route || r == *route)
                    sizes.insert(setups[o.runs[r].scene].at(v.leaf).hierarchy().max_leaf_triangles());
            std::string text;
            for (std::uint32_t size : sizes)
                text += (text.empty() ? "" : "/") + std::to_string(size);
            return text;
        };
        csv << "strategy,setting,value,is_default,role,spec,leaf_triangles,batch,route,frames,mean_ms,median_ms,vs_vfc,"
               "x_floor,efficiency_percent,wrong_pixels_per_frame,wrong_pixels_max_route_total,visible_leaves_culled,"
               "triangles\n";
        auto csv_row = [&](const std::string &strategy, const std::string &setting, const std::string &value,
                           bool is_default, const std::string &role, const Variant &v, std::optional<std::size_t> route) {
            const Figures f = figures(v, route), vfc = figures(sweep.variants[0], route),
                          ideal = figures(sweep.variants[1], route);
            csv << strategy << ',' << setting << ',' << value << ',' << (is_default ? "yes" : "no") << ',' << role << ','
                << v.spec << ',' << built_leaf(v, route) << ',' << v.batch << ',' << (route ? o.runs[*route].label : "all") << ','
                << o.frames << ',' << f.ms << ',' << f.median << ',' << fixed(vfc.ms / f.ms, 3) << ','
                << fixed(f.ms / ideal.ms, 3) << ',' << fixed(f.efficiency, 2) << ',' << fixed(f.wrong, 2) << ','
                << f.max_wrong << ',' << f.visible_culled << ',' << f.triangles << '\n';
        };
        for (const std::size_t b : {std::size_t(0), std::size_t(1)})
            for (std::size_t r = 0; r <= o.runs.size(); ++r)
                csv_row(sweep.variants[b].spec, "-", "-", true, "baseline", sweep.variants[b],
                        r < o.runs.size() ? std::optional<std::size_t>(r) : std::nullopt);
        for (const Variant &v : sweep.variants)
            if (!v.refused.empty())
                std::printf("left out: %s: %s\n", v.spec.c_str(), v.refused.c_str());
        sweep.rows.erase(std::remove_if(sweep.rows.begin(), sweep.rows.end(),
                                        [&sweep](const Row &r) { return !sweep.variants[r.variant].refused.empty(); }),
                         sweep.rows.end());
        for (const Row &row : sweep.rows)
            for (std::size_t r = 0; r <= o.runs.size(); ++r)
                csv_row(row.strategy, row.setting, row.value, row.is_default, row.role, sweep.variants[row.variant],
                        r < o.runs.size() ? std::optional<std::size_t>(r) : std::nullopt);
        if (!csv.flush())
            throw std::runtime_error("cannot write '" + path + "'");

        // The check: every approximation knob reaches 0 wrong pixels on every route.
        int violations = 0;
        std::map<std::pair<std::string, std::string>, bool> exact_reached;
        for (const Row &row : sweep.rows) {
            if (row.role != "approximation")
                continue;
            auto &reached = exact_reached[{row.strategy, row.setting}];
            reached = reached || figures(sweep.variants[row.variant], std::nullopt).max_wrong == 0;
        }
        for (const auto &[knob, reached] : exact_reached)
            if (!reached) {
                ++violations;
                std::fprintf(stderr, "occu-bench-knobs: VIOLATION: %s %s: no value reaches 0 wrong pixels on every route\n",
                             knob.first.c_str(), knob.second.c_str());
            }
        // A cost knob should never change a pixel (culling/settings.h): said, not failed.
        std::set<std::string> changed;
        for (const Row &row : sweep.rows)
            if (row.role == "cost" && figures(sweep.variants[row.variant], std::nullopt).max_wrong > 0)
                changed.insert(sweep.variants[row.variant].spec + " (leaves of " +
                               leaf_triangles_text(std::uint32_t(sweep.variants[row.variant].leaf)) + ", batch " +
                               std::to_string(sweep.variants[row.variant].batch) + ")");
        for (const std::string &c : changed)
            std::printf("note: a cost knob changed pixels: %s\n", c.c_str());
        for (const std::string &n : notes)
            std::printf("note: %s\n", n.c_str());

        const Figures vfc = figures(sweep.variants[0], std::nullopt), ideal = figures(sweep.variants[1], std::nullopt);
        std::printf("\nvfc %.2f ms, ideal (the floor) %.2f ms: means over the routes.\n\n", vfc.ms, ideal.ms);
        std::printf("| strategy | default (approximation) | default ms | x vfc | default on the front: time/wrong px | "
                    "time/efficiency | exact (0 wrong px) ms | fastest with 0 wrong px | fastest of all (wrong px/frame) |\n"
                    "|---|---|---|---|---|---|---|---|---|\n");
        for (const std::string &strategy : o.session.strategies) {
            std::vector<std::size_t> ids;
            for (const Row &r : sweep.rows)
                if (r.strategy == strategy && std::find(ids.begin(), ids.end(), r.variant) == ids.end())
                    ids.push_back(r.variant);
            if (ids.empty())
                continue;
            const auto &[by_wrong, by_efficiency, front_w, front_e] = fronts(sweep, ids);
            std::size_t def = ids.size();
            for (std::size_t i = 0; i < ids.size(); ++i)
                if (sweep.variants[ids[i]].spec == strategy && sweep.variants[ids[i]].leaf == default_leaf &&
                    sweep.variants[ids[i]].batch == default_batch)
                    def = i;
            const StrategyChoice c = choose_strategy(strategy);
            std::string approximation;
            for (const SettingSpec &s : c.family->settings)
                if (s.role == SettingSpec::Role::approximation)
                    approximation += (approximation.empty() ? "" : ", ") + s.name + "=" + c.settings.text(s.name);
            // Exact: the variant with every approximation knob at 0, the
            // default if it is; the fastest of those with 0 wrong pixels on every route.
            std::optional<std::size_t> exact, best_exact, best;
            for (std::size_t i = 0; i < ids.size(); ++i) {
                const Variant &v = sweep.variants[ids[i]];
                const Figures f = figures(v, std::nullopt);
                if (v.leaf == default_leaf && v.batch == default_batch && choose_strategy(v.spec).settings.exact() &&
                    (!exact || v.spec == strategy))
                    exact = i;
                if (f.max_wrong == 0 && (!best_exact || f.ms < by_wrong[*best_exact].first))
                    best_exact = i;
                if (!best || f.ms < by_wrong[*best].first)
                    best = i;
            }
            auto name = [&](std::size_t i) {
                const Variant &v = sweep.variants[ids[i]];
                std::string n = v.spec;
                if (v.leaf != default_leaf)
                    n += " leaf-triangles=" + leaf_triangles_text(std::uint32_t(v.leaf));
                if (v.batch != default_batch)
                    n += " batch=" + std::to_string(v.batch);
                return "`" + n + "`";
            };
            const bool has_default = def < ids.size();
            std::printf("| %s | %s | %s | %s | %s | %s | %s | %s %s | %s %s (%s) |\n", strategy.c_str(),
                        approximation.empty() ? "(none)" : approximation.c_str(),
                        has_default ? fixed(by_wrong[def].first, 2).c_str() : "-",
                        has_default ? fixed(vfc.ms / by_wrong[def].first, 2).c_str() : "-",
                        has_default ? (front_w[def] ? "yes" : "no") : "-", has_default ? (front_e[def] ? "yes" : "no") : "-",
                        exact ? (fixed(by_wrong[*exact].first, 2) + (figures(sweep.variants[ids[*exact]], std::nullopt).max_wrong
                                                                        ? " (NOT 0 wrong px)"
                                                                        : ""))
                                    .c_str()
                              : "-",
                        best_exact ? name(*best_exact).c_str() : "-",
                        best_exact ? fixed(by_wrong[*best_exact].first, 2).c_str() : "",
                        best ? name(*best).c_str() : "-", best ? fixed(by_wrong[*best].first, 2).c_str() : "",
                        best ? fixed(by_wrong[*best].second, 1).c_str() : "");
        }
        std::printf("\nms: mean frame time, the mean over the routes; x vfc: vfc's ms / the default's; the fronts: no\n"
                    "variant at most as slow with at most as many wrong pixels (or as much efficiency), better in one.\n"
                    "csv: %s\n",
                    path.c_str());
        if (o.plots)
            for (const std::string &strategy : o.session.strategies)
                plot(o, strategy, sweep, vfc.ms);
        if (violations) {
            std::fprintf(stderr, "occu-bench-knobs: %d approximation knob(s) never exact: see VIOLATION above\n",
                         violations);
            return 1;
        }
        return 0;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "occu-bench-knobs: %s\n", e.what());
        return 1;
    }
}
