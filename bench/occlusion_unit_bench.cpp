// SPDX-License-Identifier: MIT
// occu-bench-ou: what an Occlusion Unit query costs against the ARB
// occlusion query it replaces, on one driver, side by side in one process.
//
//   box      one box tested in a brief pass vs in a GL_SAMPLES_PASSED query
//   tiles N  N tiles tested in one brief pass vs N scissored ARB queries
//            (up to 64 tiles each query draws every box again, scissored
//            to its tile; beyond, only its own box, as a query per object)
//   mesh:N   the same, with a 20k-triangle mesh over the window as the
//            geometry: ARB queries draw it N times, the brief pass once
//   vmesh:N  the same mesh through a 64-step vertex shader (vertex-bound
//            geometry, as skinned or procedural meshes are): scissoring
//            saves an ARB query its rasterization, not its vertex work
//   shaded   a window-sized object with an expensive fragment shader: a
//            brief pass over it vs drawing it in GL_RENDER
//   passes   brief passes per second over the mesh (run it with several
//            LP_NUM_THREADS values for the throughput table)
//   render   GL_RENDER frame time of a draw-heavy scene (no occlusion at
//            all): run it once per Mesa build to compare patched/unpatched
//   async:N  a frame of N batches, each a brief pass of 16 tiles over 16
//            boxes followed by drawing the mesh (the work a culling frame
//            does between tests): passes read by RenderMode (each waits for
//            its rasterization) vs pass objects read after the drawing
//            (GL_MESAX_occlusion_unit_async) vs no read at all, the boxes
//            drawn under conditional rendering on their tiles
//   passcost:N  what a brief pass of N tiles over N boxes costs the
//            application's thread: glRenderMode's pass (begin, draw, end
//            and its wait) vs a pass object's begin, draw and end, its
//            records read after the timed region
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
#include <utility>
#include <optional>
#include <vector>

#include "evaluation/allocator.h"
#include "gl/extensions.h"
#include "gl/gl_headers.h"
#include "gl/occlusion_unit.h"
#include "gl/offscreen_context.h"

namespace {

using Clock = std::chrono::steady_clock;
using occu::gl::get_proc_address;

// --only N runs only variant N of each comparison (0: the Occlusion Unit),
// for instruction counts under callgrind, which repeat exactly.
int g_only = -1;

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
std::optional<occu::gl::OcclusionUnit> unit;   // when the context has the extension

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
// Box i of draw_grid(n, size).
void draw_grid_box(int n, int size, int i)
{
    const int side = int(std::ceil(std::sqrt(double(n))));
    const float cell = float(size) / float(side);
    const float cx = (i % side) * cell, cy = (i / side) * cell;
    draw_box(cx + 0.1f * cell, cy + 0.1f * cell, cx + 0.9f * cell, cy + 0.9f * cell, 0.4f, 0.6f);
}

void draw_grid(int n, int size)
{
    for (int i = 0; i < n; ++i)
        draw_grid_box(n, size, i);
}

std::vector<occu::PixelRect> grid_tiles(int n, int size)
{
    const int side = int(std::ceil(std::sqrt(double(n))));
    const int cell = size / side;
    std::vector<occu::PixelRect> tiles;
    for (int i = 0; i < n; ++i) {
        const int x = (i % side) * cell, y = (i / side) * cell;
        tiles.push_back({x, y, x + cell, y + cell});
    }
    return tiles;
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
            if (g_only >= 0 && int(v) != g_only) {
                samples[v].push_back(1.0);
                continue;
            }
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

// A 100 x 100 grid of quads (20k triangles) over the window, its depth
// rolling between 0.3 and 0.7: geometry that costs vertex work.
const std::vector<float> &mesh_vertices(int size)
{
    static std::vector<float> v;
    if (!v.empty())
        return v;
    const int n = 100;
    const float step = float(size) / n;
    auto z = [](int i, int j) { return 0.5f + 0.2f * std::sin(0.3f * i) * std::cos(0.2f * j); };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const float x0 = i * step, y0 = j * step, x1 = x0 + step, y1 = y0 + step;
            const float q[6][3] = {{x0, y0, z(i, j)},         {x1, y0, z(i + 1, j)}, {x1, y1, z(i + 1, j + 1)},
                                   {x0, y0, z(i, j)},         {x1, y1, z(i + 1, j + 1)}, {x0, y1, z(i, j + 1)}};
            for (auto &p : q)
                v.insert(v.end(), p, p + 3);
        }
    return v;
}

void draw_mesh(int size)
{
    const auto &v = mesh_vertices(size);
    glEnableClientState(GL_VERTEX_ARRAY);
    glVertexPointer(3, GL_FLOAT, 0, v.data());
    glDrawArrays(GL_TRIANGLES, 0, GLsizei(v.size() / 3));
    glDisableClientState(GL_VERTEX_ARRAY);
}

GLuint build_program(const char *vertex_source, const char *fragment_source)
{
    auto CreateShader = reinterpret_cast<PFNGLCREATESHADERPROC>(get_proc_address("glCreateShader"));
    auto ShaderSource = reinterpret_cast<PFNGLSHADERSOURCEPROC>(get_proc_address("glShaderSource"));
    auto CompileShader = reinterpret_cast<PFNGLCOMPILESHADERPROC>(get_proc_address("glCompileShader"));
    auto CreateProgram = reinterpret_cast<PFNGLCREATEPROGRAMPROC>(get_proc_address("glCreateProgram"));
    auto AttachShader = reinterpret_cast<PFNGLATTACHSHADERPROC>(get_proc_address("glAttachShader"));
    auto LinkProgram = reinterpret_cast<PFNGLLINKPROGRAMPROC>(get_proc_address("glLinkProgram"));
    auto GetProgramiv = reinterpret_cast<PFNGLGETPROGRAMIVPROC>(get_proc_address("glGetProgramiv"));
    const GLuint program = CreateProgram();
    const std::pair<GLenum, const char *> stages[2] = {{GL_VERTEX_SHADER, vertex_source},
                                                       {GL_FRAGMENT_SHADER, fragment_source}};
    for (const auto &[stage, source] : stages) {
        if (!source)
            continue;
        const GLuint shader = CreateShader(stage);
        ShaderSource(shader, 1, &source, nullptr);
        CompileShader(shader);
        AttachShader(program, shader);
    }
    LinkProgram(program);
    GLint linked = GL_FALSE;
    GetProgramiv(program, GL_LINK_STATUS, &linked);
    if (!linked) {
        std::fprintf(stderr, "occu-bench-ou: a benchmark shader does not link\n");
        std::exit(1);
    }
    return program;
}

// N tiles over `draw`: one brief pass vs N scissored SAMPLES_PASSED queries,
// each over `draw`, or over `draw_in_tile(i)` when given (the objects in
// tile i alone: N queries over the whole scene cost N^2 draws, hours at
// thousands of tiles).
void compare_tiles(const Options &o, int n, const char *label, const std::function<void()> &draw,
                   const std::function<void(int)> &draw_in_tile = nullptr)
{
    setup_frame(o.size);
    const std::vector<occu::PixelRect> tiles = grid_tiles(n, o.size);
    std::vector<GLuint> nohc(n), queries(n), samples(n);
    GenQueries(n, queries.data());
    auto occlusion_unit = [&] {
        occu::gl::OcclusionPass pass(*unit, occu::gl::OcclusionMode::brief, tiles);
        draw();
        const auto &records = pass.end();
        for (int i = 0; i < n; ++i)
            nohc[i] = records[std::size_t(i)].nohc;
    };
    auto arb_queries = [&] {
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glDepthMask(GL_FALSE);
        glEnable(GL_SCISSOR_TEST);
        for (int i = 0; i < n; ++i) {
            const occu::PixelRect &t = tiles[std::size_t(i)];
            glScissor(t.x0, t.y0, t.width(), t.height());
            BeginQuery(GL_SAMPLES_PASSED, queries[i]);
            if (draw_in_tile)
                draw_in_tile(i);
            else
                draw();
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
        if (nohc[i] != samples[i])
            std::fprintf(stderr, "occu-bench-ou: %s tile %d: NOHC %u but SAMPLES_PASSED %u\n", label, i, nohc[i],
                         samples[i]);
    std::printf("%s,%s,%d,%d,%.4f,%.4f,%.3f\n", label, occu::gl::driver_name(o.driver), o.size, n, t[0], t[1],
                t[0] / t[1]);
}

// An expensive shader (a 300-step loop per fragment) on an object covering
// the window: a brief pass need not run it, GL_RENDER must.
void case_shaded(const Options &o)
{
    setup_frame(o.size);
    glClear(GL_DEPTH_BUFFER_BIT);
    const GLuint program = build_program(
        nullptr,
        "#version 110\n"
        "void main() {\n"
        "  vec2 p = gl_FragCoord.xy / 64.0; float a = 0.0;\n"
        "  for (int i = 0; i < 300; ++i) a += sin(p.x * float(i)) * cos(p.y + a);\n"
        "  gl_FragColor = vec4(fract(a));\n"
        "}\n");
    auto UseProgram = reinterpret_cast<PFNGLUSEPROGRAMPROC>(get_proc_address("glUseProgram"));
    const float s = float(o.size);
    glDepthFunc(GL_ALWAYS);
    UseProgram(program);
    auto occlusion_unit = [&] {
        occu::gl::OcclusionPass pass(*unit, occu::gl::OcclusionMode::brief, {});
        draw_box(0, 0, s, s, 0.4f, 0.6f);
        pass.end();
    };
    auto render = [&] {
        draw_box(0, 0, s, s, 0.4f, 0.6f);
        glFinish();
    };
    const auto t = compare({occlusion_unit, render}, o.repeat, 2);
    UseProgram(0);
    glDepthFunc(GL_LESS);
    std::printf("shaded,%s,%d,1,%.4f,%.4f,%.3f\n", occu::gl::driver_name(o.driver), o.size, t[0], t[1], t[0] / t[1]);
}

// async:N (see the top of the file).
void case_async(const Options &o, int batches)
{
    if (!occu::gl::has_extension("GL_MESAX_occlusion_unit_async")) {
        std::fprintf(stderr, "occu-bench-ou: async:%d: the context lacks GL_MESAX_occlusion_unit_async\n", batches);
        std::exit(1);
    }
    auto Scissors = reinterpret_cast<PFNGLSCISSORSMESAXPROC>(get_proc_address("glScissorsMESAX"));
    auto Buffers = reinterpret_cast<PFNGLOCCLUSIONBUFFERSMESAXPROC>(get_proc_address("glOcclusionBuffersMESAX"));
    auto GenPasses = reinterpret_cast<PFNGLGENOCCLUSIONPASSESMESAXPROC>(get_proc_address("glGenOcclusionPassesMESAX"));
    auto BeginPass = reinterpret_cast<PFNGLBEGINOCCLUSIONPASSMESAXPROC>(get_proc_address("glBeginOcclusionPassMESAX"));
    auto EndPass = reinterpret_cast<PFNGLENDOCCLUSIONPASSMESAXPROC>(get_proc_address("glEndOcclusionPassMESAX"));
    auto GetPass = reinterpret_cast<PFNGLGETOCCLUSIONPASSIVMESAXPROC>(get_proc_address("glGetOcclusionPassivMESAX"));
    auto BeginTile = reinterpret_cast<PFNGLBEGINCONDITIONALRENDEROCCLUSIONTILEMESAXPROC>(
        get_proc_address("glBeginConditionalRenderOcclusionTileMESAX"));
    auto EndTile = reinterpret_cast<PFNGLENDCONDITIONALRENDEROCCLUSIONTILEMESAXPROC>(
        get_proc_address("glEndConditionalRenderOcclusionTileMESAX"));

    setup_frame(o.size);
    constexpr int n = 16;
    const std::vector<occu::PixelRect> tiles = grid_tiles(n, o.size);
    std::vector<GLint> tile_words;
    for (const occu::PixelRect &t : tiles)
        tile_words.insert(tile_words.end(), {t.x0, t.y0, t.width(), t.height()});
    std::vector<std::vector<GLuint>> records(std::size_t(batches), std::vector<GLuint>(8 * n));
    const auto count = std::size_t(batches);
    std::vector<GLuint> passes(count);
    GenPasses(batches, passes.data());
    const float cell = float(o.size) / 4;
    auto draw_box_of = [&](int i) {
        const float cx = (i % 4) * cell, cy = (i / 4) * cell;
        draw_box(cx + 0.1f * cell, cy + 0.1f * cell, cx + 0.9f * cell, cy + 0.9f * cell, 0.4f, 0.6f);
    };
    auto set_state = [&](std::vector<GLuint> &words) {
        GLuint *buffers[n];
        GLsizei sizes[n];
        for (int i = 0; i < n; ++i) {
            buffers[i] = words.data() + 8 * i;
            sizes[i] = 8;
        }
        Buffers(n, sizes, buffers);
        Scissors(n, tile_words.data());
    };
    std::vector<int> visible_sync(count), visible_async(count);
    auto count_visible = [&](const std::vector<GLuint> &words) {
        int v = 0;
        for (int i = 0; i < n; ++i)
            v += words[std::size_t(8 * i)] > 0;
        return v;
    };
    auto sync = [&] {
        for (int b = 0; b < batches; ++b) {
            set_state(records[std::size_t(b)]);
            glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
            for (int i = 0; i < n; ++i)
                draw_box_of(i);
            glRenderMode(GL_RENDER);   // waits for the pass's rasterization
            visible_sync[std::size_t(b)] = count_visible(records[std::size_t(b)]);
            draw_mesh(o.size);
        }
        Scissors(0, nullptr);
    };
    auto async = [&] {
        for (int b = 0; b < batches; ++b) {
            set_state(records[std::size_t(b)]);
            BeginPass(GL_BRIEF_OCCLUSION_MESAX, passes[std::size_t(b)]);
            for (int i = 0; i < n; ++i)
                draw_box_of(i);
            EndPass();                 // returns at once
            draw_mesh(o.size);         // binned while the pass rasterizes
            GLint overflowed = 0;
            GetPass(passes[std::size_t(b)], GL_OCCLUSION_PASS_RESULT_MESAX, &overflowed);
            visible_async[std::size_t(b)] = count_visible(records[std::size_t(b)]);
        }
        Scissors(0, nullptr);
    };
    auto conditional = [&] {
        for (int b = 0; b < batches; ++b) {
            set_state(records[std::size_t(b)]);
            BeginPass(GL_BRIEF_OCCLUSION_MESAX, passes[std::size_t(b)]);
            for (int i = 0; i < n; ++i)
                draw_box_of(i);
            EndPass();
            draw_mesh(o.size);
            for (int i = 0; i < n; ++i) {   // the GL decides; nothing read back
                BeginTile(passes[std::size_t(b)], GLuint(i), 0, 0.0f, GL_QUERY_WAIT);
                draw_box_of(i);
                EndTile();
            }
        }
        Scissors(0, nullptr);
    };
    const auto t = compare({sync, async, conditional}, o.repeat, 1);
    for (int b = 0; b < batches; ++b)
        if (visible_sync[std::size_t(b)] != visible_async[std::size_t(b)])
            std::fprintf(stderr, "occu-bench-ou: async:%d batch %d: %d visible synchronously, %d asynchronously\n",
                         batches, b, visible_sync[std::size_t(b)], visible_async[std::size_t(b)]);
    const char *threads = std::getenv("LP_NUM_THREADS");
    std::printf("async,%s,%d,%s,%d,%.4f,%.4f,%.4f,%.3f,%.3f\n", occu::gl::driver_name(o.driver), o.size,
                threads ? threads : "default", batches, t[0], t[1], t[2], t[1] / t[0], t[2] / t[0]);
}

// passcost:N (see the top of the file).
void case_pass_cost(const Options &o, int n)
{
    if (!occu::gl::has_extension("GL_MESAX_occlusion_unit_async")) {
        std::fprintf(stderr, "occu-bench-ou: passcost:%d: the context lacks GL_MESAX_occlusion_unit_async\n", n);
        std::exit(1);
    }
    setup_frame(o.size);
    const std::vector<occu::PixelRect> tiles = grid_tiles(n, o.size);
    occu::gl::AsyncOcclusionPass async_pass(*unit);
    std::vector<double> sync_ms, async_ms;
    std::uint64_t sync_visible = 0, async_visible = 0;
    for (int r = 0; r < 4 * o.repeat; ++r) {
        glFinish();
        auto start = Clock::now();
        {
            occu::gl::OcclusionPass pass(*unit, occu::gl::OcclusionMode::brief, tiles);
            draw_grid(n, o.size);
            for (const auto &record : pass.end())
                sync_visible += record.nohc > 0;
        }
        sync_ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
        glFinish();
        start = Clock::now();
        async_pass.begin(occu::gl::OcclusionMode::brief, tiles);
        draw_grid(n, o.size);
        async_pass.end();
        async_ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
        for (const auto &record : async_pass.records())   // outside the timed region
            async_visible += record.nohc > 0;
    }
    if (sync_visible != async_visible)
        std::fprintf(stderr, "occu-bench-ou: passcost:%d: %llu visible tiles synchronously, %llu asynchronously\n", n,
                     (unsigned long long)sync_visible, (unsigned long long)async_visible);
    const char *threads = std::getenv("LP_NUM_THREADS");
    const double s = median(sync_ms), a = median(async_ms);
    std::printf("passcost,%s,%d,%s,%d,%.4f,%.4f,%.3f\n", occu::gl::driver_name(o.driver), o.size,
                threads ? threads : "default", n, s, a, a / s);
}

// Brief passes per second: 16 tiles over the mesh.
void case_passes(const Options &o)
{
    setup_frame(o.size);
    const std::vector<occu::PixelRect> tiles = grid_tiles(16, o.size);
    auto pass = [&] {
        occu::gl::OcclusionPass p(*unit, occu::gl::OcclusionMode::brief, tiles);
        draw_mesh(o.size);
        p.end();
    };
    const auto t = compare({pass}, o.repeat, 4);
    const char *threads = std::getenv("LP_NUM_THREADS");
    std::printf("passes,%s,%d,%s,%.4f,%.1f\n", occu::gl::driver_name(o.driver), o.size, threads ? threads : "default",
                t[0], 1000.0 / t[0]);
}

void case_box(const Options &o)
{
    setup_frame(o.size);
    GLuint nohc = 0, query = 0, samples = 0;
    GenQueries(1, &query);
    const float s = float(o.size);
    auto occlusion_unit = [&] {
        occu::gl::OcclusionPass pass(*unit, occu::gl::OcclusionMode::brief, {});
        draw_box(0.25f * s, 0.25f * s, 0.75f * s, 0.75f * s, 0.4f, 0.6f);
        nohc = pass.end()[0].nohc;
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
    if (nohc != samples)
        std::fprintf(stderr, "occu-bench-ou: NOHC %u but SAMPLES_PASSED %u\n", nohc, samples);
    std::printf("box,%s,%d,1,%.4f,%.4f,%.3f\n", occu::gl::driver_name(o.driver), o.size, t[0], t[1], t[0] / t[1]);
}

void case_tiles(const Options &o, int n)
{
    // Up to 64 tiles each query draws the whole grid (the figures of
    // docs/occlusion-unit-llvmpipe.md); beyond, each draws its own box,
    // as an application with a query per object would.
    if (n <= 64)
        compare_tiles(o, n, "tiles", [&] { draw_grid(n, o.size); });
    else
        compare_tiles(o, n, "tiles", [&] { draw_grid(n, o.size); }, [&](int i) { draw_grid_box(n, o.size, i); });
}

void case_mesh(const Options &o, int n)
{
    compare_tiles(o, n, "mesh", [&] { draw_mesh(o.size); });
}

void case_vertex_bound_mesh(const Options &o, int n)
{
    // `k` is 0 at run time, so the shader moves nothing, but the compiler
    // cannot know it and runs the loop for every vertex.
    const GLuint program = build_program(
        "#version 110\n"
        "uniform float k;\n"
        "void main() {\n"
        "  float a = 0.0;\n"
        "  for (int i = 0; i < 64; ++i) a += sin(gl_Vertex.x * float(i) + a) * k;\n"
        "  gl_Position = gl_ModelViewProjectionMatrix * (gl_Vertex + vec4(0.0, 0.0, a, 0.0));\n"
        "}\n",
        "#version 110\nvoid main() { gl_FragColor = vec4(1.0); }\n");
    auto UseProgram = reinterpret_cast<PFNGLUSEPROGRAMPROC>(get_proc_address("glUseProgram"));
    UseProgram(program);
    compare_tiles(o, n, "vmesh", [&] { draw_mesh(o.size); });
    UseProgram(0);
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
                 "usage: occu-bench-ou [--driver softpipe|llvmpipe] [--size PIXELS] [--repeat N] [--only 0|1]\n"
                 "                     [--allocator keep|system] CASE...\n"
                 "cases: box, tiles:N (N = 1..4096), mesh:N, vmesh:N (N = 1..64), shaded, passes, render, async:N,\n"
                 "       passcost:N\n"
                 "prints CSV: case,driver,size,n,ms_occlusion_unit,ms_other,ratio\n"
                 "  (passes: case,driver,size,threads,ms,passes_per_s; render: case,driver,size,boxes,ms;\n"
                 "   async: case,driver,size,threads,batches,sync_ms,async_ms,conditional_ms,async/sync,\n"
                 "   conditional/sync; passcost: case,driver,size,threads,tiles,render_mode_ms,pass_object_ms,\n"
                 "   pass_object/render_mode)\n");
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
    occu::AllocatorPolicy allocator = occu::AllocatorPolicy::keep_freed;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "-h" || a == "--help")
            usage(nullptr);
        else if ((a == "--driver" || a == "--size" || a == "--repeat" || a == "--only" || a == "--allocator") && i + 1 >= argc)
            usage((a + " needs a value").c_str());
        else if (a == "--driver") {
            try {
                o.driver = occu::gl::parse_driver(argv[++i]);
            } catch (const std::exception &e) {
                usage(e.what());
            }
        } else if (a == "--allocator") {
            try {
                allocator = occu::parse_allocator_policy(a, argv[++i]);
            } catch (const std::exception &e) {
                usage(e.what());
            }
        } else if (a == "--size")
            o.size = parse_int(argv[++i], "--size", 16, 4096);
        else if (a == "--repeat")
            o.repeat = parse_int(argv[++i], "--repeat", 1, 1000);
        else if (a == "--only")
            g_only = parse_int(argv[++i], "--only", 0, 1);
        else if (a == "box" || a == "render" || a == "shaded" || a == "passes" || a.rfind("tiles:", 0) == 0 ||
                 a.rfind("async:", 0) == 0 || a.rfind("passcost:", 0) == 0 ||
                 a.rfind("mesh:", 0) == 0 || a.rfind("vmesh:", 0) == 0)
            o.cases.push_back(a);
        else
            usage(("unknown argument '" + a + "'").c_str());
    }
    if (o.cases.empty())
        usage("no case given");

    occu::control_allocator(allocator);
    occu::gl::select_driver(o.driver);
    occu::gl::OffscreenContext ctx(o.size, o.size);
    GenQueries = reinterpret_cast<PFNGLGENQUERIESPROC>(get_proc_address("glGenQueries"));
    BeginQuery = reinterpret_cast<PFNGLBEGINQUERYPROC>(get_proc_address("glBeginQuery"));
    EndQuery = reinterpret_cast<PFNGLENDQUERYPROC>(get_proc_address("glEndQuery"));
    GetQueryObjectuiv = reinterpret_cast<PFNGLGETQUERYOBJECTUIVPROC>(get_proc_address("glGetQueryObjectuiv"));
    const bool has_unit = occu::gl::OcclusionUnit::available();
    if (has_unit)
        unit.emplace();

    for (const std::string &c : o.cases) {
        if (c == "render")
            case_render(o);
        else if (!has_unit)
            std::fprintf(stderr, "occu-bench-ou: %s: %s lacks GL_MESAX_occlusion_unit, case skipped\n", c.c_str(),
                         ctx.renderer().c_str());
        else if (c == "box")
            case_box(o);
        else if (c == "shaded")
            case_shaded(o);
        else if (c == "passes")
            case_passes(o);
        else if (c.rfind("passcost:", 0) == 0)
            case_pass_cost(o, parse_int(c.c_str() + 9, "passcost:N", 1, 64));
        else if (c.rfind("async:", 0) == 0)
            case_async(o, parse_int(c.c_str() + 6, "async:N", 1, 64));
        else if (c.rfind("mesh:", 0) == 0)
            case_mesh(o, parse_int(c.c_str() + 5, "mesh:N", 1, 64));
        else if (c.rfind("vmesh:", 0) == 0)
            case_vertex_bound_mesh(o, parse_int(c.c_str() + 6, "vmesh:N", 1, 64));
        else
            case_tiles(o, parse_int(c.c_str() + 6, "tiles:N", 1, 4096));
    }
    return 0;
}
