// walkthrough: renders a route through a scene with several culling
// strategies, frame by frame side by side, and reports what each drew,
// how long it took, and how it compares with the exact-visibility oracle,
// view-frustum culling (vfc) and the floor (ideal: the oracle's visible
// leaves alone). `walkthrough --help` lists the strategies and settings.
//
// Writes DIR/summary.csv (one row per strategy), DIR/frames.csv (one row
// per strategy and frame), DIR/<strategy>-NNNN.png and the top view with its
// title and legend DIR/<strategy>-top-NNNN.png every --png-every frames, and
// prints the summary. Setup and test ms: time in the culler
// (traversal/traversal.h). tools/plot-walkthrough.sh DIR plots frames.csv.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "camera/route.h"
#include "cli/arguments.h"
#include "cli/progress.h"
#include "culling/registry.h"
#include "evaluation/oracle.h"
#include "evaluation/side_by_side.h"
#include "gl/offscreen_context.h"
#include "gl/state.h"
#include "image/png.h"
#include "render/top_view.h"
#include "scene/city.h"
#include "scene/scene_file.h"
#include "traversal/traversal.h"

namespace {

using namespace occu;

struct Options {
    std::string route = "dense";
    std::string scene;   // empty or "city": the procedural city; "field": the flat field (no occlusion); else a file
    std::vector<std::string> strategies = {"none", "vfc", "ideal", "ou", "ou-shared", "om-ps"};
    std::vector<std::string> common;   // --set key=value, for every strategy that has the key
    int frames = 60;
    int size = 512;
    std::string driver = "llvmpipe";
    int city_copies = 1;
    int patch_segments = Quake3Options{}.patch_segments;
    int leaf_triangles = 256;
    int batch = 32;
    int png_every = 20;
    bool oracle = true;
    bool coherence = true;
    double switch_off = 0.5;
    std::string out = "walkthrough-out";
    bool report = true;                 // plots and index.html in `out` at the end
    std::vector<std::string> video;     // strategies of route.mp4; empty: none
};

[[noreturn]] void usage(const std::string &error)
{
    std::FILE *to = error.empty() ? stdout : stderr;
    if (!error.empty())
        std::fprintf(to, "walkthrough: %s\n", error.c_str());
    std::fprintf(to,
                 "usage: walkthrough [--scene city|field|FILE|PAK.pk3:maps/LEVEL.bsp]\n"
                 "                   [--route dense|street|medium|open|orbit|overhead|random:N:SEED|spawn[:K]|FILE]\n"
                 "                   [--strategies NAME[:key=value...],...] [--set key=value]...\n"
                 "                   [--occluder-db FILE (= --set database=FILE)]\n"
                 "                   [--frames N] [--size PIXELS] [--driver llvmpipe|softpipe] [--city-copies N]\n"
                 "                   [--patch-segments N] [--leaf-triangles N] [--batch N] [--coherence on|off]\n"
                 "                   [--switch-off F]\n"
                 "                   [--png-every N] [--oracle on|off] [--out DIR] [--report on|off]\n"
                 "                   [--video STRATEGY,...]\n"
                 "       walkthrough --list-strategies [--markdown]\n"
                 "--report (on) ends the run with the plots of frames.csv (tools/plot-walkthrough.sh, gnuplot)\n"
                 "and DIR/index.html, a page of the summary, the plots and the frames beside their top views\n"
                 "(tools/report-walkthrough.sh); --video makes DIR/route.mp4 of the named strategies' frames and\n"
                 "top views (tools/video-walkthrough.sh, ffmpeg; needs --png-every 1).\n"
                 "--patch-segments (8): quads along each way of a Quake III level's Bezier patch pieces.\n"
                 "--set applies to every chosen strategy that has the setting. --coherence (temporal coherence)\n"
                 "applies to the strategies that query the rasterizer; --switch-off (least share of triangles\n"
                 "occlusion tests must cull; 0 never switches off) to those and to the strategies whose CPU\n"
                 "work costs time each frame. ideal needs the oracle.\n\nstrategies:\n%s",
                 strategies_help().c_str());
    std::exit(error.empty() ? 0 : 2);
}

Options parse(int argc, char **argv)
{
    // The registry's strategies, as --help lists them or as README's table.
    if (argc >= 2 && std::strcmp(argv[1], "--list-strategies") == 0) {
        const bool markdown = argc == 3 && std::strcmp(argv[2], "--markdown") == 0;
        if (argc > 2 && !markdown)
            usage("--list-strategies takes --markdown alone");
        std::fputs((markdown ? strategies_markdown() : strategies_help()).c_str(), stdout);
        std::exit(0);
    }
    Options o;
    for_each_option(argc, argv, usage, [&](const std::string &a, const std::string &v) {
        if (a == "--route") o.route = v;
        else if (a == "--scene") o.scene = v;
        else if (a == "--strategies") {
            o.strategies = list_items(v, ',');
            if (o.strategies.empty())
                usage("--strategies is empty");
        }
        else if (a == "--set") o.common.push_back(v);
        else if (a == "--occluder-db") o.common.push_back("database=" + v);
        else if (a == "--frames") o.frames = int(integer_option(a, v, 1, 100000));
        else if (a == "--size") o.size = int(integer_option(a, v, 16, 8192));
        else if (a == "--driver") o.driver = v;
        else if (a == "--city-copies") o.city_copies = int(integer_option(a, v, 1, 64));
        else if (a == "--patch-segments") o.patch_segments = int(integer_option(a, v, 1, 64));
        else if (a == "--leaf-triangles") o.leaf_triangles = int(integer_option(a, v, 1, 1 << 20));
        else if (a == "--batch") o.batch = int(integer_option(a, v, 1, 4096));
        else if (a == "--png-every") o.png_every = int(integer_option(a, v, 0, 100000));
        else if (a == "--out") o.out = v;
        else if (a == "--switch-off") o.switch_off = number_option(a, v, 0.0, 1.0);
        else if (a == "--coherence") o.coherence = switch_option(a, v);
        else if (a == "--oracle") o.oracle = switch_option(a, v);
        else if (a == "--report") o.report = switch_option(a, v);
        else if (a == "--video") {
            o.video = list_items(v, ',');
            if (o.video.empty())
                usage("--video is empty");
        }
        else
            return false;
        return true;
    });
    // Strategies and settings are checked before anything is built.
    try {
        std::vector<StrategyChoice> chosen;
        for (const std::string &s : o.strategies) {
            chosen.push_back(choose_strategy(s, o.common));
            if (chosen.back().family->needs_truth && !o.oracle)
                usage(s + " needs the oracle (--oracle on)");
        }
        check_common_settings(chosen, o.common);
    } catch (const std::invalid_argument &e) {
        usage(e.what());
    }
    for (const std::string &v : o.video)
        if (std::find(o.strategies.begin(), o.strategies.end(), v) == o.strategies.end())
            usage("--video names '" + v + "', which --strategies does not");
    if (!o.video.empty() && o.png_every != 1)
        usage("--video needs an image of every frame: --png-every 1");
    return o;
}

// Per strategy: its culler, its traversal policies and what it measured.
struct Run {
    Strategy strategy;
    TraversalPolicies policies;
    std::vector<double> ms;
    double triangles = 0, passes = 0, setup_ms = 0, test_ms = 0;
    std::uint64_t occluded = 0, occluded_culled = 0, visible_culled = 0, wrong_pixels = 0;

    double mean_ms() const { return occu::mean_ms(ms); }
    double median_ms() const { return occu::median_ms(ms); }
    std::string label() const { return strategy.choice.label(); }
};

using Drawn = TimedFrame;

std::string file_name(const std::string &label)
{
    std::string s = label;
    for (char &c : s)
        if (c == ':' || c == '/' || c == '=')
            c = '_';
    return s;
}

void write_summary(const Options &o, const std::vector<Run> &runs)
{
    auto mean_of = [&runs](const char *family) {
        for (const Run &r : runs)
            if (r.strategy.choice.family->name == family && r.strategy.choice.settings.changed().empty())
                return r.mean_ms();
        return 0.0;
    };
    const double vfc_ms = mean_of("vfc"), ideal_ms = mean_of("ideal");
    const std::string path = o.out + "/summary.csv";
    std::ofstream csv(path);
    csv << "strategy,family,conservative,frames,mean_ms,median_ms,triangles,passes,vs_vfc,x_floor,"
           "efficiency_percent,visible_leaves_culled,wrong_pixels_per_frame,setup_ms,test_ms,route,size\n";
    std::printf("\n%-22s %9s %9s %10s %7s %7s %8s %10s %8s %8s %8s %8s\n", "strategy", "mean ms", "median", "triangles",
                "passes", "vs vfc", "x floor", "efficiency", "vis cull", "wrong px", "setup ms", "test ms");
    for (const Run &r : runs) {
        const double n = double(std::max<std::size_t>(1, r.ms.size())), mean = r.mean_ms();
        const bool conservative = r.strategy.choice.conservative();
        auto ratio = [](double a, double b) -> std::string {
            if (a <= 0 || b <= 0)
                return "-";
            char s[32];
            std::snprintf(s, sizeof(s), "%.2f", a / b);
            return s;
        };
        const std::string vs_vfc = ratio(vfc_ms, mean), x_floor = ratio(mean, ideal_ms);
        char efficiency[32] = "-", wrong[32] = "-";
        if (o.oracle && r.occluded)
            std::snprintf(efficiency, sizeof(efficiency), "%.1f", 100.0 * double(r.occluded_culled) / double(r.occluded));
        if (!conservative)
            std::snprintf(wrong, sizeof(wrong), "%.1f", double(r.wrong_pixels) / n);
        csv << r.label() << ',' << r.strategy.choice.family->name << ',' << (conservative ? "yes" : "no") << ','
            << r.ms.size() << ',' << mean << ',' << r.median_ms() << ',' << r.triangles / n << ',' << r.passes / n
            << ',' << vs_vfc << ',' << x_floor << ',' << efficiency << ','
            << (o.oracle ? std::to_string(r.visible_culled) : "-") << ',' << wrong << ',' << r.setup_ms / n << ','
            << r.test_ms / n << ',' << o.route << ',' << o.size << '\n';
        std::printf("%-22s %9.2f %9.2f %10.0f %7.1f %7s %8s %9s%s %8s %8s %8.2f %8.2f\n", r.label().c_str(), mean,
                    r.median_ms(), r.triangles / n, r.passes / n, (vs_vfc == "-" ? vs_vfc : vs_vfc + "x").c_str(),
                    (x_floor == "-" ? x_floor : x_floor + "x").c_str(), efficiency, std::strcmp(efficiency, "-") ? "%" : " ",
                    o.oracle ? std::to_string(r.visible_culled).c_str() : "-", wrong, r.setup_ms / n, r.test_ms / n);
    }
    if (!csv.flush())
        throw std::runtime_error("cannot write '" + path + "'");
    for (const Run &r : runs)
        if (const std::string note = r.strategy.culler->note(); !note.empty())
            std::printf("%s: %s\n", r.label().c_str(), note.c_str());
    std::printf("\nvs vfc: vfc's mean ms / the strategy's; x floor: the strategy's mean ms / ideal's (the oracle's\n"
                "visible leaves alone); efficiency: occluded leaves culled / occluded leaves.\n"
                "summary: %s/summary.csv; per frame: %s/frames.csv; frames and top views: %s/<strategy>-NNNN.png\n",
                o.out.c_str(), o.out.c_str(), o.out.c_str());
}

// A shell word for `text`.
std::string quoted(const std::string &text)
{
    std::string q = "'";
    for (char c : text)
        q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

// Runs one of occu's tools on the results; false (the tool said why on
// stderr) when it fails.
bool run_tool(const std::string &tool, const std::string &arguments)
{
    const std::string path = std::string(OCCU_TOOLS_DIR) + "/" + tool;
    const std::string command = quoted(path) + " " + arguments + " >/dev/null";
    return std::system(command.c_str()) == 0;
}

// The plots, the video and the report page (tools/*-walkthrough.sh), in
// that order, so that the page shows the plots and links the video. A tool
// that fails leaves its part out and says why; the results stand.
void write_report(const Options &o)
{
    const std::string dir = quoted(o.out);
    if (!run_tool("plot-walkthrough.sh", dir))
        std::printf("no plots (the message above says why)\n");
    if (!o.video.empty()) {
        std::string names;
        for (const std::string &v : o.video)
            names += " " + quoted(v);
        if (run_tool("video-walkthrough.sh", dir + names))
            std::printf("video: %s/route.mp4\n", o.out.c_str());
        else
            std::printf("no video (the message above says why)\n");
    }
    if (run_tool("report-walkthrough.sh", dir))
        std::printf("report: %s/index.html\n", o.out.c_str());
    else
        std::printf("no report page (the message above says why)\n");
}

// The strategies with their traversal policies: temporal coherence for the
// families whose tests query the rasterizer, switch-off for those and for
// the families whose CPU work costs time every frame.
std::vector<Run> make_runs(const Options &o, const StrategyContext &context)
{
    std::vector<Run> runs;
    for (const std::string &spec : o.strategies) {
        Run r{make_strategy(spec, context, o.common), {}, {}};
        r.policies = TraversalPolicies(*r.strategy.choice.family, o.coherence, o.switch_off);
        runs.push_back(std::move(r));
    }
    return runs;
}

// The share of the scene's triangles a frame did not draw, in percent.
double culled_percent(std::uint64_t triangles, std::size_t scene_triangles)
{
    return 100.0 * (1.0 - double(triangles) / double(std::max<std::size_t>(1, scene_triangles)));
}

// One row per strategy and frame. leaves_conditional: of leaves_drawn, those
// issued under conditional rendering on a tile (chc), which the GL drew only
// where its test found them visible; every other column counts them as drawn.
class FramesCsv {
public:
    explicit FramesCsv(const std::string &path) : path_(path), out_(path)
    {
        if (!out_)
            throw std::runtime_error("cannot write '" + path + "'");
        out_ << "strategy,route,frame,ms,triangles,leaves_drawn,nodes_tested,passes,view_culled,occluded,"
                "culled_percent,oracle_visible_leaves,oracle_occluded_leaves,occluded_leaves_culled,"
                "visible_leaves_culled,wrong_pixels,setup_ms,test_ms,leaves_conditional\n";
    }
    void row(const Run &run, const std::string &route, std::size_t frame, const Drawn &d, std::size_t scene_triangles,
             const VisibilityTruth *truth, const CullingQuality &q, std::uint64_t wrong)
    {
        const FrameStats &st = d.stats;
        out_ << run.label() << ',' << route << ',' << frame << ',' << d.ms << ',' << st.triangles << ','
             << st.leaves_drawn << ',' << st.nodes_tested << ',' << st.passes << ',' << st.nodes_view_culled << ','
             << st.nodes_occluded << ',' << culled_percent(st.triangles, scene_triangles) << ','
             << (truth ? truth->visible.size() : 0) << ',' << q.occluded << ',' << q.occluded_culled << ','
             << q.visible_culled << ',' << wrong << ',' << st.setup_ms << ',' << st.test_ms << ','
             << st.leaves_conditional << '\n';
    }
    void close()
    {
        if (!out_.flush())
            throw std::runtime_error("cannot write '" + path_ + "'");
    }

private:
    std::string path_;
    std::ofstream out_;
};

// Everything one walkthrough renders with.
struct Walk {
    const Options &o;
    const Scene &scene;
    const Hierarchy &hierarchy;
    const SceneRenderer &renderer;
    gl::OffscreenContext &ctx;
    const Strategy &reference;   // none: the unculled frame
    FramesCsv &csv;

    // Strategy `run` draws frame f; what it did joins its totals, frames.csv and the images.
    void draw(Run &run, std::size_t f, const Frame &frame)
    {
        const TraversalOptions traversal = run.policies.options(std::size_t(o.batch));
        const Drawn d = draw_timed_frame(renderer, hierarchy, *run.strategy.culler, frame, traversal);
        run.ms.push_back(d.ms);
        run.triangles += double(d.stats.triangles);
        run.passes += d.stats.passes;
        run.setup_ms += d.stats.setup_ms;
        run.test_ms += d.stats.test_ms;
        const std::uint64_t wrong = run.strategy.choice.conservative() ? 0 : wrong_pixels(frame);
        run.wrong_pixels += wrong;
        CullingQuality q;
        if (frame.truth) {
            q = compare_with_truth(*frame.truth, d.stats.drawn);
            run.occluded += q.occluded;
            run.occluded_culled += q.occluded_culled;
            run.visible_culled += q.visible_culled;
        }
        if (o.png_every > 0 && f % std::size_t(o.png_every) == 0)
            write_images(run, f, frame, d, q);
        csv.row(run, o.route, f, d, scene.triangle_count(), frame.truth, q, wrong);
    }

    // Pixels of the frame just drawn that differ from the unculled frame
    // (drawn untimed, after the measured one); the culled frame is put back.
    std::uint64_t wrong_pixels(const Frame &frame)
    {
        const std::size_t bytes = std::size_t(o.size) * std::size_t(o.size) * 4;
        const std::vector<std::uint8_t> culled(ctx.pixels(), ctx.pixels() + bytes);
        draw_timed_frame(renderer, hierarchy, *reference.culler, frame, TraversalOptions{});
        std::uint64_t wrong = 0;
        for (std::size_t i = 0; i < bytes; i += 4)
            wrong += std::memcmp(&culled[i], ctx.pixels() + i, 4) != 0;
        std::memcpy(ctx.pixels_mutable(), culled.data(), bytes);
        return wrong;
    }

    // The frame, then its top view with a title and a legend.
    void write_images(const Run &run, std::size_t f, const Frame &frame, const Drawn &d, const CullingQuality &q)
    {
        char number[24];
        std::snprintf(number, sizeof(number), "%04zu", f);
        const std::string base = o.out + "/" + file_name(run.label());
        write_png(base + "-" + number + ".png", o.size, o.size, ctx.pixels());

        TopViewCaption caption;
        caption.strategy = run.label();
        caption.frame = f;
        caption.ms = d.ms;
        caption.culled_percent = culled_percent(d.stats.triangles, scene.triangle_count());
        std::vector<std::uint32_t> wrongly_culled;
        if (frame.truth) {
            std::vector<std::uint32_t> drawn = d.stats.drawn;
            std::sort(drawn.begin(), drawn.end());
            std::set_difference(frame.truth->visible.begin(), frame.truth->visible.end(), drawn.begin(), drawn.end(),
                                std::back_inserter(wrongly_culled));
            caption.wrongly_culled = wrongly_culled.size();
            if (q.occluded)
                caption.efficiency_percent = 100.0 * q.efficiency();
        }
        render_top_view(hierarchy, frame.camera, d.stats.drawn, wrongly_culled, top_view_map_area(o.size, o.size));
        glFinish();
        // Top row first, for the caption.
        const std::size_t row = std::size_t(o.size) * 4;
        std::vector<std::uint8_t> top(row * std::size_t(o.size));
        for (std::size_t y = 0; y < std::size_t(o.size); ++y)
            std::memcpy(&top[y * row], ctx.pixels() + (std::size_t(o.size) - 1 - y) * row, row);
        caption_top_view({top.data(), o.size, o.size}, caption);
        write_png(base + "-top-" + number + ".png", o.size, o.size, top.data(), false);
    }
};

}  // namespace

int main(int argc, char **argv)
{
    const Options o = parse(argc, argv);
    try {
        gl::select_driver(gl::parse_driver(o.driver));
        CityOptions city;
        city.copies = o.city_copies;
        // A user scene (OBJ, glTF, ... through assimp; PLY or a Quake III level) or the default city.
        Quake3Options quake3;
        quake3.patch_segments = o.patch_segments;
        const Scene scene = scene_by_name(o.scene, city, quake3);
        HierarchyOptions ho;
        ho.max_leaf_triangles = std::uint32_t(o.leaf_triangles);
        const Hierarchy hierarchy = Hierarchy::build(scene, ho);
        const std::vector<Camera> route = make_route(o.route, scene.bounds, city, o.frames, 1.0f, scene.quake3.get());

        gl::OffscreenContext ctx(o.size, o.size);
        SceneRenderer renderer(scene, hierarchy);
        const StrategyContext context{scene, hierarchy, renderer};
        std::vector<Run> runs = make_runs(o, context);
        const Strategy reference = make_strategy("none", context);
        std::optional<Oracle> oracle;
        if (o.oracle)
            oracle.emplace(renderer, hierarchy);
        std::filesystem::create_directories(o.out);
        FramesCsv csv(o.out + "/frames.csv");
        Walk walk{o, scene, hierarchy, renderer, ctx, reference, csv};
        std::printf("scene: %zu triangles, %zu leaves; route %s, %zu frames, %dx%d, %s\n", scene.triangle_count(),
                    hierarchy.leaf_count(), o.route.c_str(), route.size(), o.size, o.size, ctx.renderer().c_str());

        glEnable(GL_DEPTH_TEST);
        glEnable(GL_CULL_FACE);
        glClearColor(0.55f, 0.7f, 0.9f, 1.0f);
        // Every strategy renders frame f before any renders frame f + 1, so
        // that the machine's load, which drifts, weighs on all of them alike;
        // and the order rotates from frame to frame, because the strategy
        // that follows another's frame (or the oracle's) pays for what that
        // left behind in the caches and the rasterizer.
        for (std::size_t f = 0; f < route.size(); ++f) {
            // The oracle's answer first, untimed: ideal draws from it.
            std::optional<VisibilityTruth> truth;
            if (oracle)
                truth = oracle->see(route[f], o.size, o.size);
            const Frame frame(route[f], o.size, o.size, truth ? &*truth : nullptr);
            for (std::size_t k = 0; k < runs.size(); ++k)
                walk.draw(runs[(k + f) % runs.size()], f, frame);
            progress("frames", long(f + 1), long(route.size()));
        }
        csv.close();
        write_summary(o, runs);
        if (o.report)
            write_report(o);
        return 0;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "walkthrough: %s\n", e.what());
        return 1;
    }
}
