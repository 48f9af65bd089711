// occu-bench-ou: what an Occlusion Unit query costs against the ARB
// occlusion query it replaces, on one driver, side by side in one process.
//
//   box      one box tested in a brief pass vs in a GL_SAMPLES_PASSED query
//   tiles N  N tiles tested in one brief pass vs N scissored ARB queries
//            (each query draws the geometry again, scissored to its tile)
//   render   GL_RENDER frame time of a draw-heavy scene (no occlusion at
//            all): run it once per Mesa build to compare patched/unpatched
//
// Each measurement alternates the variants it compares, repeats them and
// reports medians, because these machines are shared and noisy.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "gl/extensions.h"
#include "gl/gl_headers.h"
#include "gl/offscreen_context.h"
#include "GL/mesax_occlusion_unit.h"

namespace {

using Clock = std::chrono::steady_clock;
using occu::gl::get_proc_address;

struct Options {
    occu::gl::Driver driver = occu::gl::Driver::softpipe;
    int size = 256;
    int repeat = 15;
    std::vector<std::string> cases;
};

PFNGLGENQUERIESPROC GenQueries;
PFNGLBEGINQUERYPROC BeginQuery;
PFNGLENDQUERYPROC EndQuery;
PFNGLGETQUERYOBJECTUIVPROC GetQueryObjectuiv;
PFNGLSCISSORSMESAXPROC ScissorsMESAX;
PFNGLOCCLUSIONBUFFERSMESAXPROC OcclusionBuffersMESAX;

// An axis-aligned box in window coordinates (x, y pixels; z window depth),
// drawn as 6 quads: the proxy the papers test.
void draw_box(float x0, float y0, float x1, float y1, float z0, float z1)
{
    glBegin(GL_QUADS);
    const float x[2] = {x0, x1}, y[2] = {y0, y1}, z[2] = {z0, z1};
    for (int face = 0; face < 3; ++face)
        for (int side = 0; side < 2; ++side)
            for (int corner = 0; corner < 4; ++corner) {
                const int a = corner == 1 || corner == 2, b = corner >= 2;
                float v[3];
                v[face] = (face == 0 ? x : face == 1 ? y : z)[side];
                v[(face + 1) % 3] = ((face + 1) % 3 == 0 ? x : (face + 1) % 3 == 1 ? y : z)[a];
                v[(face + 2) % 3] = ((face + 2) % 3 == 0 ? x : (face + 2) % 3 == 1 ? y : z)[b];
                glVertex3fv(v);
            }
    glEnd();
}

// A grid of n boxes, one per tile of an s x s grid over the window.
void draw_grid(int n, int size)
{
    const int side = int(std::ceil(std::sqrt(double(n))));
    const float cell = float(size) / float(side);
    for (int i = 0; i < n; ++i) {
        const float cx = (i % side) * cell, cy = (i / side) * cell;
        draw_box(cx + 0.1f * cell, cy + 0.1f * cell, cx + 0.9f * cell, cy + 0.9f * cell, 0.4f, 0.6f);
    }
}

void grid_tiles(int n, int size, std::vector<GLint> &tiles)
{
    const int side = int(std::ceil(std::sqrt(double(n))));
    const int cell = size / side;
    tiles.clear();
    for (int i = 0; i < n; ++i) {
        tiles.insert(tiles.end(), {(i % side) * cell, (i / side) * cell, cell, cell});
    }
}

// A scene that fills the depth buffer: a wall in front of half the boxes.
void draw_occluder(int size)
{
    glBegin(GL_QUADS);
    glVertex3f(0, 0, 0.2f);
    glVertex3f(float(size) / 2, 0, 0.2f);
    glVertex3f(float(size) / 2, float(size), 0.2f);
    glVertex3f(0, float(size), 0.2f);
    glEnd();
}

double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

// Runs each variant `repeat` times, alternating, each time `iterations`
// times; returns the median milliseconds per iteration of each.
std::vector<double> compare(const std::vector<std::function<void()>> &variants, int repeat, int iterations)
{
    std::vector<std::vector<double>> samples(variants.size());
    for (int r = 0; r < repeat; ++r)
        for (std::size_t v = 0; v < variants.size(); ++v) {
            const auto start = Clock::now();
            for (int i = 0; i < iterations; ++i)
                variants[v]();
            glFinish();
            samples[v].push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count() / iterations);
        }
    std::vector<double> medians;
    for (auto &s : samples)
        medians.push_back(median(s));
    return medians;
}

void setup_frame(int size)
{
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glOrtho(0, size, 0, size, 0, -1);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glEnable(GL_DEPTH_TEST);
    glEnable(GL_CULL_FACE);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    draw_occluder(size);
}

void case_box(const Options &o)
{
    setup_frame(o.size);
    GLuint record[8], query = 0, samples = 0;
    GLuint *buffers[1] = {record};
    GLsizei sizes[1] = {8};
    GenQueries(1, &query);
    const float s = float(o.size);
    auto occlusion_unit = [&] {
        OcclusionBuffersMESAX(1, sizes, buffers);
        glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
        draw_box(0.25f * s, 0.25f * s, 0.75f * s, 0.75f * s, 0.4f, 0.6f);
        glRenderMode(GL_RENDER);
    };
    auto arb_query = [&] {
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glDepthMask(GL_FALSE);
        BeginQuery(GL_SAMPLES_PASSED, query);
        draw_box(0.25f * s, 0.25f * s, 0.75f * s, 0.75f * s, 0.4f, 0.6f);
        EndQuery(GL_SAMPLES_PASSED);
        GetQueryObjectuiv(query, GL_QUERY_RESULT, &samples);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glDepthMask(GL_TRUE);
    };
    const auto t = compare({occlusion_unit, arb_query}, o.repeat, 20);
    if (record[0] != samples)
        std::fprintf(stderr, "occu-bench-ou: NOHC %u but SAMPLES_PASSED %u\n", record[0], samples);
    std::printf("box,%s,%d,1,%.4f,%.4f,%.3f\n", occu::gl::driver_name(o.driver), o.size, t[0], t[1], t[0] / t[1]);
}

void case_tiles(const Options &o, int n)
{
    setup_frame(o.size);
    std::vector<GLint> tiles;
    grid_tiles(n, o.size, tiles);
    std::vector<GLuint> records(8 * std::size_t(n));
    std::vector<GLuint *> buffers(n);
    std::vector<GLsizei> sizes(n, 8);
    for (int i = 0; i < n; ++i)
        buffers[i] = &records[8 * std::size_t(i)];
    std::vector<GLuint> queries(n), samples(n);
    GenQueries(n, queries.data());
    auto occlusion_unit = [&] {
        OcclusionBuffersMESAX(n, sizes.data(), buffers.data());
        ScissorsMESAX(n, tiles.data());
        glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
        draw_grid(n, o.size);
        glRenderMode(GL_RENDER);
        ScissorsMESAX(0, nullptr);
    };
    auto arb_queries = [&] {
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glDepthMask(GL_FALSE);
        glEnable(GL_SCISSOR_TEST);
        for (int i = 0; i < n; ++i) {
            glScissor(tiles[4 * i], tiles[4 * i + 1], tiles[4 * i + 2], tiles[4 * i + 3]);
            BeginQuery(GL_SAMPLES_PASSED, queries[i]);
            draw_grid(n, o.size);
            EndQuery(GL_SAMPLES_PASSED);
        }
        for (int i = 0; i < n; ++i)
            GetQueryObjectuiv(queries[i], GL_QUERY_RESULT, &samples[i]);
        glDisable(GL_SCISSOR_TEST);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glDepthMask(GL_TRUE);
    };
    const auto t = compare({occlusion_unit, arb_queries}, o.repeat, 2);
    for (int i = 0; i < n; ++i)
        if (records[8 * std::size_t(i)] != samples[i])
            std::fprintf(stderr, "occu-bench-ou: tile %d: NOHC %u but SAMPLES_PASSED %u\n", i,
                         records[8 * std::size_t(i)], samples[i]);
    std::printf("tiles,%s,%d,%d,%.4f,%.4f,%.3f\n", occu::gl::driver_name(o.driver), o.size, n, t[0], t[1],
                t[0] / t[1]);
}

// GL_RENDER frame: 4096 lit-free boxes (49k triangles) with depth test.
void case_render(const Options &o)
{
    auto frame = [&] {
        setup_frame(o.size);
        for (int layer = 0; layer < 4; ++layer)
            draw_grid(1024, o.size);
    };
    const auto t = compare({frame}, o.repeat, 2);
    std::printf("render,%s,%d,4096,%.4f\n", occu::gl::driver_name(o.driver), o.size, t[0]);
}

[[noreturn]] void usage(const char *error)
{
    if (error)
        std::fprintf(stderr, "occu-bench-ou: %s\n", error);
    std::fprintf(error ? stderr : stdout,
                 "usage: occu-bench-ou [--driver softpipe|llvmpipe] [--size PIXELS] [--repeat N] CASE...\n"
                 "cases: box, tiles:N (N = 1..64), render\n"
                 "prints CSV: case,driver,size,n,ms_occlusion_unit,ms_arb,ratio (render: case,driver,size,boxes,ms)\n");
    std::exit(error ? 2 : 0);
}

int parse_int(const char *s, const char *what, int lo, int hi)
{
    char *end = nullptr;
    const long v = std::strtol(s, &end, 10);
    if (!*s || *end || v < lo || v > hi)
        usage((std::string(what) + " must be an integer in " + std::to_string(lo) + ".." + std::to_string(hi) +
               ", got '" + s + "'").c_str());
    return int(v);
}

}  // namespace

int main(int argc, char **argv)
{
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "-h" || a == "--help")
            usage(nullptr);
        else if ((a == "--driver" || a == "--size" || a == "--repeat") && i + 1 >= argc)
            usage((a + " needs a value").c_str());
        else if (a == "--driver") {
            try {
                o.driver = occu::gl::parse_driver(argv[++i]);
            } catch (const std::exception &e) {
                usage(e.what());
            }
        } else if (a == "--size")
            o.size = parse_int(argv[++i], "--size", 16, 4096);
        else if (a == "--repeat")
            o.repeat = parse_int(argv[++i], "--repeat", 1, 1000);
        else if (a == "box" || a == "render" || a.rfind("tiles:", 0) == 0)
            o.cases.push_back(a);
        else
            usage(("unknown argument '" + a + "'").c_str());
    }
    if (o.cases.empty())
        usage("no case given");

    occu::gl::select_driver(o.driver);
    occu::gl::OffscreenContext ctx(o.size, o.size);
    GenQueries = reinterpret_cast<PFNGLGENQUERIESPROC>(get_proc_address("glGenQueries"));
    BeginQuery = reinterpret_cast<PFNGLBEGINQUERYPROC>(get_proc_address("glBeginQuery"));
    EndQuery = reinterpret_cast<PFNGLENDQUERYPROC>(get_proc_address("glEndQuery"));
    GetQueryObjectuiv = reinterpret_cast<PFNGLGETQUERYOBJECTUIVPROC>(get_proc_address("glGetQueryObjectuiv"));
    ScissorsMESAX = reinterpret_cast<PFNGLSCISSORSMESAXPROC>(get_proc_address("glScissorsMESAX"));
    OcclusionBuffersMESAX = reinterpret_cast<PFNGLOCCLUSIONBUFFERSMESAXPROC>(get_proc_address("glOcclusionBuffersMESAX"));
    const bool has_unit = occu::gl::has_extension("GL_MESAX_occlusion_unit");

    for (const std::string &c : o.cases) {
        if (c == "render")
            case_render(o);
        else if (!has_unit)
            std::fprintf(stderr, "occu-bench-ou: %s: %s lacks GL_MESAX_occlusion_unit, case skipped\n", c.c_str(),
                         ctx.renderer().c_str());
        else if (c == "box")
            case_box(o);
        else
            case_tiles(o, parse_int(c.c_str() + 6, "tiles:N", 1, 64));
    }
    return 0;
}
