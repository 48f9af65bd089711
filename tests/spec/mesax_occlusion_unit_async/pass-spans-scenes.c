/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit: a pass counts every primitive drawn between its
 * begin and end, however much work that is (spec MESAX_occlusion_unit,
 * section 5.X). An implementation that batches work may have to cut a pass
 * into several batches (llvmpipe's scenes hold at most 36 MiB of commands
 * and primitives, about 200 bytes per triangle and bin): the pass must go
 * on in every batch after the first.
 *
 * 256 x 256 window, depth cleared to 1, LESS; an occluder drawn before the
 * pass at z 0.25 over the left half. The pass draws 8 layers of 2 x 2-pixel
 * quads tiling the window (131072 quads, 262144 triangles), alternately at
 * z 0.5 (hidden on the left half) and z 0.125 (visible everywhere); a pass
 * writes no depth, so each layer is tested against the occluder's depth.
 *
 * Tiles: the window; (124, 60) 8 x 8, across the bins at x 128 and y 64
 * and the occluder's edge; the right half. Expected:
 *   window      PHC 8 * 65536, NOHC 4 * 65536 + 4 * 32768
 *   (124, 60)   PHC 8 * 64,    NOHC 4 * 64 + 4 * 32
 *   right half  PHC = NOHC = 8 * 32768
 * Counts, extents and depth exact (0.5 and 0.125 map to themselves,
 * counts-analytic.c).
 *
 * That the pass was cut: a SAMPLES_PASSED query active during the first
 * layer only (it counts as in RENDER mode, section 5.X: the layer's right
 * half, 32768 samples), and GL_QUERY_RESULT_AVAILABLE asked once, still
 * inside the pass, after the last layer. llvmpipe answers from the fence of
 * the scene that holds the query's end (lp_query.c): signalled, TRUE; not
 * yet submitted, it submits the scene then and answers FALSE. At
 * LP_NUM_THREADS 0 a submitted scene is rasterized at once in the calling
 * thread, so the answer is TRUE exactly when that scene was submitted
 * before the question, during the pass: the pass spans scenes, and the
 * subtests require it there. With rasterizer threads a submitted scene may
 * still be rasterizing, so the answer is printed, not required; softpipe
 * has no scenes (it rasterizes each primitive as it is drawn).
 *
 * Subtests:
 *   brief-counts-every-primitive     the records, read with RenderMode, the
 *                                    query, and the cut at LP_NUM_THREADS 0
 *   async-counts-every-primitive     the same pass with Begin/EndOcclusionPassMESAX
 *                                    and a waiting read
 *
 * The test runs on llvmpipe with LP_NUM_THREADS 0, 1, 2 and 8 too
 * (tests/meson.build).
 */
#include "ou_util.h"

enum { S = 256, LAYERS = 8, TILES = 3 };

static struct ou_async_functions a;
static PFNGLGENQUERIESPROC GenQueries;
static PFNGLBEGINQUERYPROC BeginQuery;
static PFNGLENDQUERYPROC EndQuery;
static PFNGLGETQUERYOBJECTUIVPROC GetQueryObjectuiv;
static GLuint query;
static const GLint tiles[4 * TILES] = {0, 0, S, S, 124, 60, 8, 8, 128, 0, 128, S};
static GLuint records[TILES][OU_BRIEF_SIZE];

static void
draw_layers(int first, int end)
{
    glBegin(GL_QUADS);
    for (int l = first; l < end; ++l) {
        const float z = l % 2 ? 0.125f : 0.5f;
        for (int y = 0; y < S; y += 2)
            for (int x = 0; x < S; x += 2) {
                glVertex3f(x, y, z);
                glVertex3f(x + 2, y, z);
                glVertex3f(x + 2, y + 2, z);
                glVertex3f(x, y + 2, z);
            }
    }
    glEnd();
}

static void
prepare(void)
{
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glClearDepth(1.0);
    glClear(GL_DEPTH_BUFFER_BIT);
    ou_rect(0, 0, 128, S, 0.25f);
    GLuint *buffers[TILES];
    GLsizei sizes[TILES];
    for (int i = 0; i < TILES; ++i) {
        ou_fill(records[i], OU_BRIEF_SIZE);
        buffers[i] = records[i];
        sizes[i] = OU_BRIEF_SIZE;
    }
    OcclusionBuffersMESAX(TILES, sizes, buffers);
    ScissorsMESAX(TILES, tiles);
}

/* The layers, the first under the query; whether the query's result was
 * available after the last, asked inside the pass. */
static GLuint
draw_pass(void)
{
    BeginQuery(GL_SAMPLES_PASSED, query);
    draw_layers(0, 1);
    EndQuery(GL_SAMPLES_PASSED);
    draw_layers(1, LAYERS);
    GLuint available = 0;
    GetQueryObjectuiv(query, GL_QUERY_RESULT_AVAILABLE, &available);
    return available;
}

/* The query counted the first layer's visible half, and the pass was cut
 * after the query's end where that is observable (see the top comment). */
static bool
check_query_and_cut(const char *name, GLuint available)
{
    GLuint samples = 0;
    GetQueryObjectuiv(query, GL_QUERY_RESULT, &samples);
    bool ok = samples == S * S / 2;
    if (!ok)
        printf("%s: the query during the first layer counted %u samples, expected %u\n", name, samples, S * S / 2);
    const char *renderer = (const char *)glGetString(GL_RENDERER);
    const char *threads = getenv("LP_NUM_THREADS");
    if (renderer && strstr(renderer, "llvmpipe") && threads && strcmp(threads, "0") == 0) {
        if (!available) {
            printf("%s: the scene holding the query's end was not submitted before the pass's last layer was drawn: "
                   "the pass was not cut, so it did not span scenes\n",
                   name);
            ok = false;
        }
    } else {
        printf("%s: query available inside the pass after the last layer: %s (required only on llvmpipe at "
               "LP_NUM_THREADS 0)\n",
               name, available ? "yes" : "no");
    }
    return ok;
}

static bool
check(const char *name)
{
    const GLuint half = LAYERS / 2;
    GLuint e[TILES][OU_BRIEF_SIZE] = {
        {half * S * S + half * S * S / 2, LAYERS * S * S, 0, S - 1, 0, S - 1, ou_depth(0.125), ou_depth(0.5)},
        {half * 64 + half * 32, LAYERS * 64, 124, 131, 60, 67, ou_depth(0.125), ou_depth(0.5)},
        {LAYERS * S * S / 2, LAYERS * S * S / 2, 128, S - 1, 0, S - 1, ou_depth(0.125), ou_depth(0.5)},
    };
    bool ok = true;
    for (int t = 0; t < TILES; ++t) {
        char what[64];
        snprintf(what, sizeof(what), "%s tile %d", name, t);
        ok &= ou_check_record(what, records[t], e[t], 0);
    }
    return ok;
}

PIGLIT_GL_TEST_CONFIG_BEGIN

    config.supports_gl_compat_version = 10;
    config.window_width = S;
    config.window_height = S;
    config.window_visual = PIGLIT_GL_VISUAL_RGBA | PIGLIT_GL_VISUAL_DEPTH | PIGLIT_GL_VISUAL_STENCIL;
    config.khr_no_error_support = PIGLIT_NO_ERRORS;

PIGLIT_GL_TEST_CONFIG_END

enum piglit_result
piglit_display(void)
{
    /* piglit_init reports the result. */
    return PIGLIT_FAIL;
}

void
piglit_init(int argc, char **argv)
{
    a = ou_init_async();
    GenQueries = glGenQueries;
    BeginQuery = glBeginQuery;
    EndQuery = glEndQuery;
    GetQueryObjectuiv = glGetQueryObjectuiv;
    if (!GenQueries || !BeginQuery || !EndQuery || !GetQueryObjectuiv) {
        printf("OpenGL 1.5 occlusion queries are missing\n");
        piglit_report_result(PIGLIT_FAIL);
    }
    GenQueries(1, &query);

    prepare();
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    GLuint available = draw_pass();
    const GLint overflowed = glRenderMode(GL_RENDER);
    ScissorsMESAX(0, NULL);
    bool ok = overflowed == 0 && piglit_check_gl_error(GL_NO_ERROR) && check("RenderMode");
    subtest(check_query_and_cut("RenderMode", available) && ok, "brief-counts-every-primitive");

    GLuint pass;
    a.GenOcclusionPasses(1, &pass);
    prepare();
    a.BeginOcclusionPass(GL_BRIEF_OCCLUSION_MESAX, pass);
    available = draw_pass();
    a.EndOcclusionPass();
    ScissorsMESAX(0, NULL);
    GLint async_overflowed = -1;
    a.GetOcclusionPassiv(pass, GL_OCCLUSION_PASS_RESULT_MESAX, &async_overflowed);
    ok = async_overflowed == 0 && piglit_check_gl_error(GL_NO_ERROR) && check("async");
    subtest(check_query_and_cut("async", available) && ok, "async-counts-every-primitive");
    a.DeleteOcclusionPasses(1, &pass);
    piglit_report_result(result);
}
