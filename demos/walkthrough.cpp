// SPDX-License-Identifier: MIT
// walkthrough: renders a route through a scene with several culling
// strategies, frame by frame side by side, and reports what each drew,
// how long it took, and how it compares with the exact-visibility oracle,
// view-frustum culling (vfc) and the floor (ideal: the oracle's visible
// leaves alone). `walkthrough --help` lists the strategies and settings.
//
// Writes DIR/summary.csv (one row per strategy), DIR/frames.csv (one row
// per strategy and frame), DIR/<strategy>-NNNN.png and the top view with its
// title and legend DIR/<strategy>-top-NNNN.png every --png-every frames, and
// prints the summary (evaluation/session_report.h). The strategies draw
// each frame in turn, in an order shuffled per frame
// (evaluation/measurement_session.h says why). Setup and test ms: time in
// the culler (traversal/traversal.h), on the wall clock or with --clock
// thread on the main thread's CPU time (traversal/clock.h); wrong px: the
// visible pixels an approximate strategy's frame lost
// (evaluation/lost_pixels.h).
// tools/plot-walkthrough.sh DIR plots frames.csv.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <iterator>
#include <string>
#include <vector>

#include "cli/arguments.h"
#include "culling/registry.h"
#include "evaluation/allocator.h"
#include "evaluation/measurement_session.h"
#include "evaluation/session_command_line.h"
#include "evaluation/session_report.h"
#include "gl/offscreen_context.h"
#include "image/png.h"
#include "render/top_view.h"

namespace {

using namespace occu;

struct Options {
    // --strategies, --set, --size, --driver, --allocator, --batch,
    // --coherence, --switch-off, --databases, --make-databases.
    SessionCommandLine session;
    std::string route = "dense";
    std::string scene;   // empty or "city": the procedural city; "field": the flat field (no occlusion); else a file
    int frames = 60;
    int city_copies = 1;
    int patch_segments = Quake3Options{}.patch_segments;
    std::uint32_t leaf_triangles = HierarchyOptions{}.max_leaf_triangles;
    int png_every = 20;
    bool oracle = true;
    std::string out = "walkthrough-out";
    bool report = true;                 // plots and index.html in `out` at the end
    std::vector<std::string> video;     // strategies of route.mp4; empty: none
    Clock clock = Clock::wall;          // what times the culling's setup and test ms
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
                 "                   [--frames N] [--size PIXELS|WIDTHxHEIGHT] [--driver llvmpipe|softpipe] [--city-copies N]\n"
                 "                   [--patch-segments N] [--leaf-triangles N|auto] [--batch N] [--coherence on|off]\n"
                 "                   [--switch-off F] [--allocator keep|system]\n"
                 "                   [--png-every N] [--oracle on|off] [--out DIR] [--report on|off]\n"
                 "                   [--video STRATEGY,...] [--databases DIR] [--make-databases required|all]\n"
                 "                   [--look flat|scene] [--clock wall|thread]\n"
                 "       walkthrough --list-strategies [--markdown]\n"
                 "--report (on) ends the run with the plots of frames.csv (tools/plot-walkthrough.sh, gnuplot)\n"
                 "and DIR/index.html, a page of the summary, the plots and the frames beside their top views\n"
                 "(tools/report-walkthrough.sh); --video makes DIR/route.mp4 of the named strategies' frames and\n"
                 "top views (tools/video-walkthrough.sh, ffmpeg; needs --png-every 1).\n"
                 "--route random:N:SEED: N eyes at random points of the scene's bounds, random headings; in a\n"
                 "Quake III level only in its open BSP leaves, in a model read from a file only inside it (a\n"
                 "point whose rays in 14 directions all hit the model: its rooms), an error when none is found.\n"
                 "--patch-segments (8): quads along each way of a Quake III level's Bezier patch pieces.\n"
                 "--look: scene (the default for a level or a model read from a file) draws a Quake III level's\n"
                 "textures modulated by its lightmaps, a model's materials' pictures times their colours; flat (the\n"
                 "city's and the field's) every mesh in one colour. The report's frames are drawn in the look.\n"
                 "--set applies to every chosen strategy that has the setting. --coherence (temporal coherence)\n"
                 "applies to the strategies that query the rasterizer; --switch-off (least share of triangles\n"
                 "occlusion tests must cull; 0 never switches off) to those and to the strategies whose CPU\n"
                 "work costs time each frame. ideal needs the oracle.\n"
                 "A database a strategy reads and was not given is made in --databases DIR (%s), named by\n"
                 "everything it depends on, and found there by later runs: those a strategy requires, and with\n"
                 "--make-databases all also those it would otherwise make during the run (inside its frame times).\n"
                 "--clock (wall) times the culling's setup ms and test ms; thread: the main thread's CPU time, which\n"
                 "leaves out the time other work on the machine took the core from it. A frame's ms (mean, median,\n"
                 "frames.csv's ms) stays on the wall clock: llvmpipe draws on threads of its own (LP_NUM_THREADS). The\n"
                 "thread clock suits strategies whose culling runs on the CPU in the calling thread (skins-triangles);\n"
                 "for those that draw or query through the GL it leaves out llvmpipe's work and the waits for it.\n"
                 "summary.csv's and frames.csv's column culling_clock says which timed them.\n"
                 "\nstrategies:\n%s",
                 default_database_directory().c_str(),
                 strategies_help().c_str());
    std::exit(error.empty() ? 0 : 2);
}

Options parse(int argc, char **argv)
{
    // The registry's strategies, as --help lists them or as docs/strategies.md's table.
    if (argc >= 2 && std::strcmp(argv[1], "--list-strategies") == 0) {
        const bool markdown = argc == 3 && std::strcmp(argv[2], "--markdown") == 0;
        if (argc > 2 && !markdown)
            usage("--list-strategies takes --markdown alone");
        std::fputs((markdown ? strategies_markdown() : strategies_help()).c_str(), stdout);
        std::exit(0);
    }
    Options o;
    o.session.strategies = {"none", "vfc", "ideal", "ou", "ou-shared", "om-ps"};
    for_each_option(argc, argv, usage, [&](const std::string &a, const std::string &v) {
        if (o.session.take(a, v)) return true;
        else if (a == "--route") o.route = v;
        else if (a == "--scene") o.scene = v;
        else if (a == "--occluder-db") o.session.common.push_back("database=" + v);
        else if (a == "--frames") o.frames = int(integer_option(a, v, 1, 100000));
        else if (a == "--city-copies") o.city_copies = int(integer_option(a, v, 1, 64));
        else if (a == "--patch-segments") o.patch_segments = int(integer_option(a, v, 1, 64));
        else if (a == "--leaf-triangles") o.leaf_triangles = leaf_triangles_option(a, v);
        else if (a == "--png-every") o.png_every = int(integer_option(a, v, 0, 100000));
        else if (a == "--out") o.out = v;
        else if (a == "--oracle") o.oracle = switch_option(a, v);
        else if (a == "--report") o.report = switch_option(a, v);
        else if (a == "--clock") o.clock = clock_option(a, v);
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
    const std::vector<std::string> &strategies = o.session.strategies;
    try {
        o.session.check_strategies(strategies);
        for (const std::string &s : strategies)
            if (choose_strategy(s, o.session.common).family->needs_truth && !o.oracle)
                usage(s + " needs the oracle (--oracle on)");
    } catch (const std::invalid_argument &e) {
        usage(e.what());
    }
    for (const std::string &v : o.video)
        if (std::find(strategies.begin(), strategies.end(), v) == strategies.end())
            usage("--video names '" + v + "', which --strategies does not");
    if (!o.video.empty() && o.png_every != 1)
        usage("--video needs an image of every frame: --png-every 1");
    return o;
}

std::string file_name(const std::string &label)
{
    std::string s = label;
    for (char &c : s)
        if (c == ':' || c == '/' || c == '=')
            c = '_';
    return s;
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

// Frame f of a strategy, then its top view with a title and a legend, into
// DIR/<strategy>-NNNN.png and DIR/<strategy>-top-NNNN.png.
void write_images(const Options &o, gl::OffscreenContext &ctx, const SceneSetup &setup, const SessionStrategy &s,
                  const StrategyFrame &f)
{
    char number[24];
    std::snprintf(number, sizeof(number), "%04zu", f.index);
    const std::string base = o.out + "/" + file_name(s.label);
    const int width = o.session.width, height = o.session.height;
    write_png(base + "-" + number + ".png", width, height, ctx.pixels());

    TopViewCaption caption;
    caption.strategy = s.label;
    caption.frame = f.index;
    caption.ms = f.ms;
    caption.culled_percent = culled_percent(f.stats.triangles, setup.scene().triangle_count());
    std::vector<std::uint32_t> wrongly_culled;
    if (const VisibilityTruth *truth = f.frame->truth) {
        std::vector<std::uint32_t> drawn = f.stats.drawn;
        std::sort(drawn.begin(), drawn.end());
        std::set_difference(truth->visible.begin(), truth->visible.end(), drawn.begin(), drawn.end(),
                            std::back_inserter(wrongly_culled));
        caption.wrongly_culled = wrongly_culled.size();
        if (f.quality.occluded)
            caption.efficiency_percent = 100.0 * f.quality.efficiency();
    }
    render_top_view(setup.hierarchy(), f.frame->camera, f.stats.drawn, wrongly_culled,
                    top_view_map_area(width, height));
    glFinish();
    // Top row first, for the caption.
    const std::size_t row = std::size_t(width) * 4;
    std::vector<std::uint8_t> top(row * std::size_t(height));
    for (std::size_t y = 0; y < std::size_t(height); ++y)
        std::memcpy(&top[y * row], ctx.pixels() + (std::size_t(height) - 1 - y) * row, row);
    caption_top_view({top.data(), width, height}, caption);
    write_png(base + "-top-" + number + ".png", width, height, top.data(), false);
}

}  // namespace

int main(int argc, char **argv)
{
    const Options o = parse(argc, argv);
    try {
        gl::select_driver(o.session.driver);
        SceneChoice choice(o.scene, o.city_copies, o.leaf_triangles);
        choice.quake3.patch_segments = o.patch_segments;
        const Look look = o.session.look_for(o.scene);
        choice.quake3.look = look == Look::scene;
        const SceneSetup setup(choice);
        const std::vector<Camera> route = setup.route(o.route, o.frames, o.session.aspect());

        gl::OffscreenContext ctx(o.session.width, o.session.height);
        DatabaseProvider databases = o.session.database_provider();
        SessionOptions so = o.session.session_options(databases);
        so.oracle = o.oracle;
        so.look = look;
        so.culling_clock = o.clock;
        MeasurementSession session(setup, ctx, so);
        for (const std::string &spec : o.session.strategies)
            session.add(spec, o.session.common);
        std::filesystem::create_directories(o.out);
        FramesCsv csv(o.out + "/frames.csv", o.route, setup.scene().triangle_count(), o.clock);
        std::printf("scene: %zu triangles, %zu leaves of at most %u; route %s, %zu frames, %dx%d, %s; allocator %s\n",
                    setup.scene().triangle_count(), setup.hierarchy().leaf_count(),
                    unsigned(setup.hierarchy().max_leaf_triangles()), o.route.c_str(), route.size(),
                    o.session.width, o.session.height, ctx.renderer().c_str(), allocator_policy_name(o.session.allocator));
        session.walk(route, "frames", [&](const SessionStrategy &s, const StrategyFrame &f) {
            if (o.png_every > 0 && f.index % std::size_t(o.png_every) == 0)
                write_images(o, ctx, setup, s, f);
            csv.row(s, f);
        });
        csv.close();
        write_summary(session, o.out + "/summary.csv", o.route, o.session.size_name());
        std::printf("\nvs vfc: vfc's mean ms / the strategy's; x floor: the strategy's mean ms / ideal's (the oracle's\n"
                    "visible leaves alone); efficiency: occluded leaves culled / occluded leaves.\n"
                    "summary: %s/summary.csv; per frame: %s/frames.csv; frames and top views: %s/<strategy>-NNNN.png\n",
                    o.out.c_str(), o.out.c_str(), o.out.c_str());
        if (o.report)
            write_report(o);
        return 0;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "walkthrough: %s\n", e.what());
        return 1;
    }
}
