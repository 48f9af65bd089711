/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit on llvmpipe: the coarse depth test rejects only
 * blocks none of whose fragments pass, it rejects where it can, and it is
 * off where PHC or the fragments' depth need the shader.
 *
 * Under LP_PERF=ou_coarse_verify llvmpipe shades every block the coarse
 * test rejected anyway and aborts if one of its fragments passed the depth
 * test or its coverage differed from what the JIT counted; at context
 * destroy it prints "occlusion coarse depth rejected N of M pass blocks".
 * Each class of scenes runs in a child at LP_NUM_THREADS 0, 1, 2 and 8;
 * the child must exit 0, and
 *   occluded   (depth formats 16, 24, 24 + 8 stencil and 32-bit float; an
 *              occluder at z = 0.5 over part of the window, the rest at the
 *              cleared 1.0; passes of rectangles and triangles under
 *              LESS, LEQUAL, GREATER, GEQUAL, EQUAL and NEVER, at the
 *              occluder's own depth, behind it and in front of it, with
 *              depth clamping beyond near and far, with polygon offsets
 *              that move a rectangle across the occluder both ways, with
 *              a stencil test and early fragment tests, brief and verbose)
 *              must report N > 0;
 *   edges      (an occluder at 0.5 leaving the last columns and rows of
 *              the window at the cleared 1.0, so that the 16x16 blocks the
 *              framebuffer's right and top edges cut are visible only in
 *              their last pixels; triangles inside one 16x16 block whose
 *              depth crosses the occluder's inside the block, under LESS
 *              and GREATER) must report N > 0 and keep every pixel that
 *              GL_RENDER finds visible;
 *   disabled   (the same occluder, passes behind it with gl_FragDepth,
 *              a discard and the alpha test after the shader, polygon
 *              stipple, 4x multisampling, NOTEQUAL and ALWAYS, and the
 *              depth test off) must report N = 0.
 * In both, on both drivers, every pass's NOHC must equal the samples an
 * occlusion query counts for the same draw in GL_RENDER and its PHC the
 * rectangle's area (analytic), so softpipe, which has no coarse test,
 * checks the same scenes' records.
 */
#include "coarse_util.h"

#define W 203
#define H 150
#define ARRAY_SIZE(a) (sizeof(a) / sizeof((a)[0]))

static PFNGLUSEPROGRAMPROC UseProgram;
static PFNGLGENQUERIESPROC GenQueries;
static PFNGLBEGINQUERYPROC BeginQuery;
static PFNGLENDQUERYPROC EndQuery;
static PFNGLGETQUERYOBJECTUIVPROC GetQueryObjectuiv;
static int g_argc;
static char **g_argv;

struct shape {
    bool rect;
    float x0, y0, x1, y1, z;   /* a rectangle at depth z, or a triangle's box and depths z .. z + 0.2 */
    bool right_angle;          /* else a triangle (x0, y0, z), (x1, y0, z1), (x0, y1, z) */
    float z1;
};

static void
draw_shape(const struct shape *s)
{
    if (s->rect) {
        ou_rect(s->x0, s->y0, s->x1, s->y1, s->z);
        return;
    }
    glBegin(GL_TRIANGLES);
    if (s->right_angle) {
        glVertex3f(s->x0, s->y0, s->z);
        glVertex3f(s->x1, s->y0, s->z1);
        glVertex3f(s->x0, s->y1, s->z);
    } else {
        glVertex3f(s->x0, s->y0, s->z);
        glVertex3f(s->x1, s->y0 + 7.3f, s->z + 0.2f);
        glVertex3f(s->x0 + 11.6f, s->y1, s->z + 0.1f);
    }
    glEnd();
}

/* The samples of `s` passing the current tests in GL_RENDER, nothing
 * written. */
static GLuint
samples_passed(const struct shape *s)
{
    GLuint query, samples = 0;
    GenQueries(1, &query);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    BeginQuery(GL_SAMPLES_PASSED, query);
    draw_shape(s);
    EndQuery(GL_SAMPLES_PASSED);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    GetQueryObjectuiv(query, GL_QUERY_RESULT, &samples);
    return samples;
}

/* One pass over `s` (the window as its tile), checked against GL_RENDER:
 * NOHC the samples passed (single-sampled), PHC the area of a rectangle,
 * a verbose list as long as NOHC. `covered` is the number of pixels the
 * shape covers before per-fragment operations, 0 when not known. */
static void
pass(const char *what, const struct shape *s, bool verbose, GLuint covered, bool multisampled)
{
    enum { PAIRS = W * H };
    static GLuint buffer[8 + 2 * PAIRS];
    GLuint *buffers[1] = {buffer};
    GLsizei sizes[1] = {verbose ? 8 + 2 * PAIRS : OU_BRIEF_SIZE};
    const GLint tile[4] = {0, 0, W, H};
    ou_fill(buffer, sizes[0]);
    OcclusionBuffersMESAX(1, sizes, buffers);
    ScissorsMESAX(1, tile);
    glRenderMode(verbose ? GL_VERBOSE_OCCLUSION_MESAX : GL_BRIEF_OCCLUSION_MESAX);
    draw_shape(s);
    glRenderMode(GL_RENDER);
    ScissorsMESAX(0, NULL);
    char name[256];
    snprintf(name, sizeof(name), "%s: GL error", what);
    const GLenum error = glGetError();
    coarse_check(error == GL_NO_ERROR, name, error, GL_NO_ERROR);
    if (multisampled) {
        /* Fragments, not samples: the shape lies behind the occluder. */
        snprintf(name, sizeof(name), "%s: NOHC", what);
        coarse_check(buffer[OU_NOHC] == 0, name, buffer[OU_NOHC], 0);
    } else {
        const GLuint expected = samples_passed(s);
        snprintf(name, sizeof(name), "%s: NOHC against GL_RENDER's samples passed", what);
        coarse_check(buffer[OU_NOHC] == expected, name, buffer[OU_NOHC], expected);
    }
    snprintf(name, sizeof(name), "%s: PHC", what);
    if (covered)
        coarse_check(buffer[OU_PHC] == covered, name, buffer[OU_PHC], covered);
    else
        coarse_check(buffer[OU_PHC] > 0, name, buffer[OU_PHC], 1);
    if (verbose) {
        snprintf(name, sizeof(name), "%s: verbose list length", what);
        coarse_check(buffer[0] == buffer[OU_NOHC], name, buffer[0], buffer[OU_NOHC]);
    }
}

static void
setup(const struct ou_fbo_functions *fbo, const struct coarse_format *format, int samples)
{
    coarse_make_fbo(fbo, W, H, format, samples);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    glClearDepth(1.0);
    glClearStencil(0);
    glClear(GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    /* The occluder, writing stencil 1 where it is. */
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, 1, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    ou_rect(0, 0, 150, H, 0.5f);
    glDisable(GL_STENCIL_TEST);
    glDepthMask(GL_FALSE);
}

static void
init(void)
{
    piglit_osmesa_init(g_argc, g_argv, W, H);
    ou_init();
    UseProgram = glUseProgram;
    GenQueries = glGenQueries;
    BeginQuery = glBeginQuery;
    EndQuery = glEndQuery;
    GetQueryObjectuiv = glGetQueryObjectuiv;
}

/* Scenes whose passes the coarse test can reject. */
static void
occluded(struct transcript *t)
{
    init();
    const GLuint early = coarse_build_program("  if (mod(floor(gl_FragCoord.x), 2.0) == 1.0) discard;\n", true);
    const struct ou_fbo_functions fbo = ou_fbo_functions();
    static const GLenum funcs[] = {GL_LESS, GL_LEQUAL, GL_GREATER, GL_GEQUAL, GL_EQUAL, GL_NEVER};
    static const char *func_names[] = {"LESS", "LEQUAL", "GREATER", "GEQUAL", "EQUAL", "NEVER"};
    /* Rectangles over the occluder (x < 150) and the cleared part. */
    static const float depths[] = {0.5f, 0.75f, 0.25f, 0.5000001f, 0.4999999f};
    for (unsigned f = 0; f < ARRAY_SIZE(coarse_formats); ++f) {
        setup(&fbo, &coarse_formats[f], 0);
        char what[128];
        for (unsigned k = 0; k < ARRAY_SIZE(funcs); ++k) {
            glDepthFunc(funcs[k]);
            for (unsigned d = 0; d < ARRAY_SIZE(depths); ++d) {
                const struct shape r = {true, 13, 9, 181, 141, depths[d], false, 0};
                snprintf(what, sizeof(what), "depth %s, %s, rectangle at z %.7f", coarse_formats[f].name,
                         func_names[k], depths[d]);
                pass(what, &r, d == 1, 168 * 132, false);
                const struct shape tri = {false, 5, 3, 140, 120, depths[d] - 0.1f, false, 0};
                snprintf(what, sizeof(what), "depth %s, %s, triangle from z %.7f", coarse_formats[f].name,
                         func_names[k], depths[d] - 0.1f);
                pass(what, &tri, false, 0, false);
            }
        }
        glDepthFunc(GL_LESS);

        /* Depth clamping: beyond far clamps to 1 (hidden everywhere),
         * beyond near to 0 (visible). */
        glEnable(GL_DEPTH_CLAMP);
        const struct shape far = {true, 0, 0, W, H, 1.25f, false, 0}, near = {true, 20, 20, 190, 130, -0.25f, false, 0};
        snprintf(what, sizeof(what), "depth %s, clamped beyond far", coarse_formats[f].name);
        pass(what, &far, false, W * H, false);
        snprintf(what, sizeof(what), "depth %s, clamped beyond near", coarse_formats[f].name);
        pass(what, &near, false, 170 * 110, false);
        glDisable(GL_DEPTH_CLAMP);

        /* Polygon offsets of at least 0.06 in depth (units at the
         * resolution of the finest format): a rectangle at 0.47 pushed
         * behind the occluder, one at 0.53 pulled in front of it. The
         * coarse test must add the offset to the plane. */
        glEnable(GL_POLYGON_OFFSET_FILL);
        const float units = 0.06f * 33554432.0f;
        glPolygonOffset(0, units);
        const struct shape pushed = {true, 10, 10, 140, 140, 0.47f, false, 0};
        snprintf(what, sizeof(what), "depth %s, offset behind the occluder", coarse_formats[f].name);
        pass(what, &pushed, false, 130 * 130, false);
        glPolygonOffset(0, -units);
        const struct shape pulled = {true, 10, 10, 140, 140, 0.53f, false, 0};
        snprintf(what, sizeof(what), "depth %s, offset in front of the occluder", coarse_formats[f].name);
        pass(what, &pulled, false, 130 * 130, false);
        const GLuint visible = samples_passed(&pulled);
        coarse_check(visible == 130 * 130, "the rectangle pulled in front is visible", visible, 130 * 130);
        glDisable(GL_POLYGON_OFFSET_FILL);

        /* A stencil test (where the occluder wrote 1), and early tests
         * with a discard after them: PHC is still the coverage. */
        glEnable(GL_STENCIL_TEST);
        glStencilFunc(GL_EQUAL, 1, 0xff);
        glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
        const struct shape behind = {true, 0, 0, W, H, 0.75f, false, 0};
        snprintf(what, sizeof(what), "depth %s, stencil test", coarse_formats[f].name);
        pass(what, &behind, false, W * H, false);
        glDisable(GL_STENCIL_TEST);
        UseProgram(early);
        snprintf(what, sizeof(what), "depth %s, early tests", coarse_formats[f].name);
        pass(what, &behind, true, W * H, false);
        UseProgram(0);
    }
    transcript_add(t, coarse_failures);
}

/* Blocks that one test per 16x16 block decides whole: the blocks cut by
 * the framebuffer's edges (W and H end inside a 16x16 block: its bounds
 * must hold every pixel the JIT reads there), and triangles inside one
 * 16x16 block (the plane must be bounded over all of its pixels, not over
 * one 4x4 block's). */
static void
edges(struct transcript *t)
{
    init();
    const struct ou_fbo_functions fbo = ou_fbo_functions();
    char what[128];
    for (unsigned f = 0; f < ARRAY_SIZE(coarse_formats); ++f) {
        coarse_make_fbo(&fbo, W, H, &coarse_formats[f], 0);
        glEnable(GL_DEPTH_TEST);
        glDepthMask(GL_TRUE);
        glDepthFunc(GL_LESS);
        glClearDepth(1.0);
        glClear(GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
        /* Columns 200-202 and rows 148-149 stay at 1.0. */
        ou_rect(0, 0, 200, 148, 0.5f);
        glDepthMask(GL_FALSE);

        /* At 0.75: visible in those columns, or rows, alone. */
        const struct shape right = {true, 184, 0, W, 140, 0.75f, false, 0};
        snprintf(what, sizeof(what), "depth %s, the right edge's blocks", coarse_formats[f].name);
        pass(what, &right, false, (W - 184) * 140, false);
        const struct shape top = {true, 0, 136, 190, H, 0.75f, false, 0};
        snprintf(what, sizeof(what), "depth %s, the top edge's blocks", coarse_formats[f].name);
        pass(what, &top, false, 190 * (H - 136), false);

        /* Inside the 16x16 blocks at (16, 16), (96, 64) and (176, 128),
         * over the occluder: depth from 0.6 down to 0.45 across 15 pixels
         * under LESS, from 0.4 up to 0.55 under GREATER, so that only the
         * block's right part passes. */
        static const float corners[][2] = {{16, 16}, {96, 64}, {176, 128}};
        for (unsigned k = 0; k < ARRAY_SIZE(corners); ++k) {
            const float x = corners[k][0], y = corners[k][1];
            const struct shape falling = {false, x + 0.5f, y + 0.5f, x + 15.5f, y + 15.5f, 0.6f, true, 0.45f};
            snprintf(what, sizeof(what), "depth %s, LESS, a triangle inside the block at (%g, %g)",
                     coarse_formats[f].name, x, y);
            pass(what, &falling, false, 0, false);
            glDepthFunc(GL_GREATER);
            const struct shape rising = {false, x + 0.5f, y + 0.5f, x + 15.5f, y + 15.5f, 0.4f, true, 0.55f};
            snprintf(what, sizeof(what), "depth %s, GREATER, a triangle inside the block at (%g, %g)",
                     coarse_formats[f].name, x, y);
            pass(what, &rising, false, 0, false);
            glDepthFunc(GL_LESS);
            const GLuint visible = samples_passed(&falling);
            snprintf(what, sizeof(what), "depth %s, the triangle at (%g, %g) is partly visible",
                     coarse_formats[f].name, x, y);
            coarse_check(visible > 0 && visible < 120, what, visible, 1);
        }
    }
    transcript_add(t, coarse_failures);
}

/* Scenes where the coarse test must not be used, or never rejects. */
static void
disabled(struct transcript *t)
{
    init();
    const bool llvmpipe = strstr((const char *)glGetString(GL_RENDERER), "llvmpipe") != NULL;
    const GLuint frag_depth = coarse_build_program("  gl_FragDepth = gl_FragCoord.z;\n", false);
    const GLuint discard = coarse_build_program("  if (mod(floor(gl_FragCoord.x), 2.0) == 1.0) discard;\n", false);
    const struct ou_fbo_functions fbo = ou_fbo_functions();
    const struct shape behind = {true, 0, 0, 150, H, 0.75f, false, 0};   /* all over the occluder */
    char what[128];
    for (unsigned f = 0; f < ARRAY_SIZE(coarse_formats); ++f) {
        setup(&fbo, &coarse_formats[f], 0);
        snprintf(what, sizeof(what), "depth %s, gl_FragDepth", coarse_formats[f].name);
        UseProgram(frag_depth);
        pass(what, &behind, false, 150 * H, false);
        snprintf(what, sizeof(what), "depth %s, discard after the shader", coarse_formats[f].name);
        UseProgram(discard);
        pass(what, &behind, false, 75 * H, false);
        UseProgram(0);

        snprintf(what, sizeof(what), "depth %s, alpha test", coarse_formats[f].name);
        glEnable(GL_ALPHA_TEST);
        glAlphaFunc(GL_GREATER, 0.5f);
        glColor4f(1, 1, 1, 0.25f);
        pass(what, &behind, false, 150 * H, false);   /* PHC: before the alpha test */
        glColor4f(1, 1, 1, 1);
        glDisable(GL_ALPHA_TEST);

        snprintf(what, sizeof(what), "depth %s, polygon stipple", coarse_formats[f].name);
        GLubyte pattern[128];
        for (int i = 0; i < 128; ++i)
            pattern[i] = 0x55;   /* every other column */
        glPolygonStipple(pattern);
        glEnable(GL_POLYGON_STIPPLE);
        pass(what, &behind, false, 75 * H, false);
        glDisable(GL_POLYGON_STIPPLE);

        static const GLenum funcs[] = {GL_NOTEQUAL, GL_ALWAYS};
        for (unsigned k = 0; k < 2; ++k) {
            glDepthFunc(funcs[k]);
            snprintf(what, sizeof(what), "depth %s, %s", coarse_formats[f].name, k ? "ALWAYS" : "NOTEQUAL");
            pass(what, &behind, false, 150 * H, false);
        }
        glDepthFunc(GL_LESS);
        glDisable(GL_DEPTH_TEST);
        snprintf(what, sizeof(what), "depth %s, depth test off", coarse_formats[f].name);
        pass(what, &behind, false, 150 * H, false);
        glEnable(GL_DEPTH_TEST);
    }
    /* Multisampling: softpipe has none. */
    if (llvmpipe) {
        setup(&fbo, &coarse_formats[2], 4);
        pass("4x multisampled", &behind, false, 0, true);   /* PHC: edge fragments by sample */
    }
    transcript_add(t, coarse_failures);
}

int
main(int argc, char **argv)
{
    /* No context here: a child's driver must start its own threads. */
    g_argc = argc;
    g_argv = argv;
    static char err[1 << 16];
    struct transcript t = {0};
    struct {
        const char *name;
        void (*run)(struct transcript *);
        bool rejects;
    } classes[] = {{"occluded", occluded, true}, {"edges", edges, true}, {"disabled", disabled, false}};

    for (unsigned c = 0; c < ARRAY_SIZE(classes); ++c) {
        char name[128];
        snprintf(name, sizeof(name), "softpipe-%s", classes[c].name);
        const bool ok = coarse_run_child("softpipe", NULL, classes[c].run, &t, err, sizeof(err), name) &&
                        t.n == 1 && t.words[0] == 0;
        if (!ok)
            printf("%s: the records differ from GL_RENDER:\n%s\n", name, err);
        subtest(ok, name);
    }

    const char *threads[] = {"0", "1", "2", "8"};
    for (unsigned i = 0; i < 4; ++i) {
        for (unsigned c = 0; c < ARRAY_SIZE(classes); ++c) {
            char name[128], thread_env[64];
            snprintf(thread_env, sizeof(thread_env), "LP_NUM_THREADS=%s", threads[i]);
            const char *env[] = {thread_env, "LP_PERF=ou_coarse_verify", NULL};
            snprintf(name, sizeof(name), "llvmpipe-threads-%s-%s", threads[i], classes[c].name);
            const bool completed = coarse_run_child("llvmpipe", env, classes[c].run, &t, err, sizeof(err), name);
            const bool records = completed && t.n == 1 && t.words[0] == 0;
            if (completed && !records)
                printf("%s: the records differ from GL_RENDER:\n%s\n", name, err);
            long long blocks = 0;
            const long long rejected = completed ? coarse_rejected(err, &blocks) : -1;
            if (completed)
                printf("%s: rejected %lld of %lld pass blocks\n", name, rejected, blocks);
            if (completed && rejected < 0)
                printf("%s: no report of LP_PERF=ou_coarse_verify in the child's stderr\n", name);
            const bool counts = rejected >= 0 && (classes[c].rejects ? rejected > 0 : rejected == 0);
            char sub[160];
            snprintf(sub, sizeof(sub), "%s-exits-0", name);
            subtest(completed, sub);
            snprintf(sub, sizeof(sub), "%s-records-equal-render", name);
            subtest(records, sub);
            snprintf(sub, sizeof(sub), "%s-%s", name, classes[c].rejects ? "rejects-blocks" : "rejects-none");
            subtest(counts, sub);
        }
    }
    piglit_report_result(result);
}
