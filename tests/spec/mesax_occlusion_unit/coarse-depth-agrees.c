/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit on llvmpipe: rejecting a pass's 4x4 blocks
 * against the bin's coarse depth changes no record. Every word of every
 * record (brief records, and each verbose list's header, pair count and
 * pairs) must be equal with the coarse test and without it
 * (LP_PERF=no_ou_coarse), at LP_NUM_THREADS 0, 1, 2 and 8, over seeded
 * random scenes on a 203 x 150 framebuffer object (edge bins and a column
 * of 4x4 blocks cut by the framebuffer's edge): depth buffers of 16, 24,
 * 24 + 8 stencil and 32-bit float; occluders drawn in GL_RENDER between
 * passes, scissored depth clears; passes of whole-pixel rectangles or
 * random triangles, and a triangle over the whole framebuffer (bins
 * covered whole), under the 8 depth functions, with polygon offset, depth
 * clamping (geometry beyond near and far), gl_FragDepth, a discard, the
 * alpha test, a stencil test, polygon stipple, early fragment tests and
 * 4x multisampling, in brief and verbose mode, over tiles of 1x1 pixel,
 * straddling bins, overlapping, and the whole window.
 *
 * On softpipe, which has no coarse test, the rectangle scenes (whole
 * pixels at constant depth, where both drivers' rasterizers agree, as
 * engines-agree.c shows) must give the same records as on llvmpipe, so the
 * test asserts the same behaviour there; the triangle and multisampled
 * scenes are llvmpipe's alone. Under LP_PERF=ou_coarse_verify the scenes
 * must have blocks rejected (so the comparison is not trivial), none
 * wrongly, and the same records. The test ignores GALLIUM_DRIVER: it runs
 * every configuration itself in child processes.
 */
#include "coarse_util.h"

#include <math.h>

#define W 203
#define H 150
#define PASSES 6
#define LIST_PAIRS 120000
#define MAX_TILES 16

enum feature {
    F_PLAIN, F_OFFSET, F_CLAMP, F_FRAGDEPTH, F_DISCARD, F_ALPHA, F_STENCIL, F_STIPPLE, F_EARLY, F_SHADER,
    F_COUNT
};

static const GLenum funcs[8] = {GL_NEVER, GL_LESS, GL_EQUAL, GL_LEQUAL, GL_GREATER, GL_NOTEQUAL, GL_GEQUAL,
                                GL_ALWAYS};

static unsigned seed;
static float
rnd(void)
{
    seed = seed * 1103515245u + 12345u;
    return (float)((seed >> 8) & 0xffff) / 65535.0f;
}
static unsigned
rndi(unsigned n)
{
    return (unsigned)(rnd() * n * 0.99999f);
}

static PFNGLUSEPROGRAMPROC UseProgram;
static GLuint programs[F_COUNT];

static void
build_programs(void)
{
    UseProgram = glUseProgram;
    const char *discard = "  if (mod(floor(gl_FragCoord.x) + floor(gl_FragCoord.y), 3.0) == 0.0) discard;\n";
    programs[F_FRAGDEPTH] = coarse_build_program("  gl_FragDepth = gl_FragCoord.z * 0.5 + 0.25;\n", false);
    programs[F_DISCARD] = coarse_build_program(discard, false);
    programs[F_EARLY] = coarse_build_program(discard, true);
    programs[F_SHADER] = coarse_build_program("", false);
}

/* Tile sets: the window; 1x1 tiles on bin corners and the framebuffer's
 * far corner; overlapping tiles (one on bin boundaries); tiles of 37 x 29
 * straddling bins. */
static int
tiles_of(unsigned set, GLint *t)
{
    static const GLint window[] = {0, 0, W, H};
    static const GLint small[] = {63, 64, 1, 1, 0, 0, 1, 1, W - 1, H - 1, 1, 1, 50, 40, 30, 30, 64, 0, 1, 1};
    static const GLint overlapping[] = {10, 10, 100, 80, 60, 50, 100, 80, 0, 100, W, 50, 120, 0, 83, H,
                                        64, 64, 64, 64};
    switch (set % 4) {
    case 0:
        memcpy(t, window, sizeof(window));
        return 1;
    case 1:
        memcpy(t, small, sizeof(small));
        return 5;
    case 2:
        memcpy(t, overlapping, sizeof(overlapping));
        return 5;
    default:
        for (int i = 0; i < 12; ++i) {
            t[4 * i] = -5 + (i % 6) * 37;
            t[4 * i + 1] = -7 + (i / 6) * 29 * 3;
            t[4 * i + 2] = 37;
            t[4 * i + 3] = 29;
        }
        return 12;
    }
}

static void
draw_occluders(int n)
{
    glEnable(GL_STENCIL_TEST);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    for (int i = 0; i < n; ++i) {
        glStencilFunc(GL_ALWAYS, i & 3, 0xff);
        const float x = floorf(rnd() * W), y = floorf(rnd() * H), z = 0.2f + 0.3f * rnd();
        ou_rect(x - 40, y - 30, x + 40 + floorf(rnd() * 60), y + 30 + floorf(rnd() * 40), z);
    }
    glDisable(GL_STENCIL_TEST);
}

/* A pass's primitives: whole-pixel rectangles at constant depth, or
 * triangles with depth varying over them; with depth clamping some lie
 * beyond the near or the far plane. In half the passes, first one
 * triangle over the whole framebuffer at the end of that depth range the
 * pass's depth function `func` lets pass least (the far end for LESS),
 * behind most of what is stored: llvmpipe bins it as covering whole bins,
 * and the coarse test rejects it for a bin before its blocks where the
 * bin's stored depth allows. Constant depth in the rectangle scenes, where
 * it covers whole pixels as their rectangles do. */
static void
draw_primitives(bool rects, bool beyond, GLenum func)
{
    const float z0 = beyond ? -0.3f : 0.02f, z1 = beyond ? 1.3f : 0.98f;
    if (rnd() < 0.5f) {
        const float z = func == GL_GREATER || func == GL_GEQUAL ? z0 : z1;
        const float dz = rects ? 0.0f : 0.01f * (rnd() - 0.5f);
        glBegin(GL_TRIANGLES);
        glVertex3f(-W, -H, z);
        glVertex3f(3 * W, -H, z + dz);
        glVertex3f(-W, 3 * H, z - dz);
        glEnd();
    }
    if (rects) {
        for (int i = 0; i < 12; ++i) {
            glColor4f(1, 1, 1, rnd() < 0.5f ? 0.3f : 0.8f);
            const float x = floorf(rnd() * W), y = floorf(rnd() * H);
            ou_rect(x, y, x + floorf(1 + rnd() * 70), y + floorf(1 + rnd() * 50), z0 + (z1 - z0) * rnd());
        }
        return;
    }
    glBegin(GL_TRIANGLES);
    for (int i = 0; i < 16; ++i) {
        glColor4f(1, 1, 1, rnd() < 0.5f ? 0.3f : 0.8f);
        const float cx = rnd() * W, cy = rnd() * H, r = 4 + rnd() * 60;
        for (int v = 0; v < 3; ++v)
            glVertex3f(cx + (rnd() - 0.5f) * 2 * r, cy + (rnd() - 0.5f) * 2 * r, z0 + (z1 - z0) * rnd());
    }
    glEnd();
}

static void
set_feature(enum feature f, unsigned p)
{
    static const float offsets[] = {0, 1, -1, 4, -4, 50};
    switch (f) {
    case F_OFFSET:
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(offsets[rndi(6)], offsets[rndi(6)]);
        break;
    case F_CLAMP:
        glEnable(GL_DEPTH_CLAMP);
        break;
    case F_ALPHA:
        glEnable(GL_ALPHA_TEST);
        glAlphaFunc(GL_GREATER, 0.5f);
        break;
    case F_STENCIL: {
        static const GLenum sf[] = {GL_EQUAL, GL_NOTEQUAL, GL_LESS, GL_GEQUAL};
        glEnable(GL_STENCIL_TEST);
        glStencilFunc(sf[rndi(4)], 1 + rndi(3), 3);
        glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
        break;
    }
    case F_STIPPLE: {
        GLubyte pattern[128];
        for (int i = 0; i < 128; ++i)
            pattern[i] = (i / 4) % 2 ? 0xcc : 0x33;
        glPolygonStipple(pattern);
        glEnable(GL_POLYGON_STIPPLE);
        /* Every other stippled pass declares early fragment tests. */
        if (p % 2)
            UseProgram(programs[F_EARLY]);
        break;
    }
    case F_FRAGDEPTH:
    case F_DISCARD:
    case F_EARLY:
    case F_SHADER:
        UseProgram(programs[f]);
        break;
    default:
        break;
    }
}

static void
reset_feature(void)
{
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDisable(GL_DEPTH_CLAMP);
    glDisable(GL_ALPHA_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_POLYGON_STIPPLE);
    UseProgram(0);
}

static GLuint *list_buffers[MAX_TILES];

/* One pass with the records appended to the transcript. */
static void
pass(struct transcript *t, unsigned scene, unsigned p, bool rects, enum feature f, bool verbose)
{
    GLint tiles[4 * MAX_TILES];
    const int n = tiles_of(rndi(4), tiles);
    const int lists = verbose ? (n < 4 ? n : 4) : n;
    const GLsizei size = verbose ? 8 + 2 * LIST_PAIRS : OU_BRIEF_SIZE;
    GLsizei sizes[MAX_TILES];
    for (int i = 0; i < lists; ++i) {
        ou_fill(list_buffers[i], size);
        sizes[i] = size;
    }
    const GLenum func = funcs[rndi(8)];
    glDepthFunc(func);
    glDepthMask(GL_FALSE);
    set_feature(f, p);
    OcclusionBuffersMESAX(lists, sizes, list_buffers);
    ScissorsMESAX(lists, tiles);
    glRenderMode(verbose ? GL_VERBOSE_OCCLUSION_MESAX : GL_BRIEF_OCCLUSION_MESAX);
    draw_primitives(rects, f == F_CLAMP, func);
    const GLint r = glRenderMode(GL_RENDER);
    ScissorsMESAX(0, NULL);
    reset_feature();

    transcript_add(t, coarse_where(scene, p, 0xff));
    transcript_add(t, (GLuint)r);
    transcript_add(t, glGetError());
    for (int i = 0; i < lists; ++i) {
        GLuint *b = list_buffers[i];
        transcript_add(t, coarse_where(scene, p, i));
        for (int w = 0; w < OU_BRIEF_SIZE; ++w)
            transcript_add(t, b[w]);
        if (verbose) {
            size_t pairs = b[OU_NOHC] < LIST_PAIRS ? b[OU_NOHC] : LIST_PAIRS;
            while (pairs > 0 && b[8 + 2 * pairs - 2] == 0xffffffffu)
                --pairs;   /* an overflowed list's end marker */
            ou_sort_pairs(b + 8, pairs);
            const uint64_t h = coarse_hash(b + 8, 2 * pairs);
            transcript_add(t, (GLuint)pairs);
            transcript_add(t, (GLuint)h);
            transcript_add(t, (GLuint)(h >> 32));
        }
    }
}

/* Scenes: each depth format with rectangles and with triangles; with
 * `multisampled`, a 4x multisampled scene of triangles after them. */
static int g_argc;
static char **g_argv;

static void
scenes(struct transcript *t, bool rects_only, bool multisampled)
{
    piglit_osmesa_init(g_argc, g_argv, W, H);
    ou_init();
    for (int i = 0; i < MAX_TILES; ++i)
        list_buffers[i] = malloc((8 + 2 * LIST_PAIRS) * sizeof(GLuint));
    build_programs();
    const struct ou_fbo_functions fbo = ou_fbo_functions();
    unsigned scene = 0;
    for (unsigned kind = 0; kind < 3; ++kind) {
        const bool rects = kind == 0, msaa = kind == 2;
        if ((rects_only && !rects) || (msaa && !multisampled))
            continue;
        for (unsigned fi = 0; fi < (msaa ? 1u : 4u); ++fi, ++scene) {
            seed = 1000 + 77 * scene;
            coarse_make_fbo(&fbo, W, H, &coarse_formats[msaa ? 2 : fi], msaa ? 4 : 0);
            glEnable(GL_DEPTH_TEST);
            glClearDepth(0.6 + 0.4 * rnd());
            glClearStencil(0);
            /* Clear writes depth only where the depth write mask lets it
             * (GL 4.6 compatibility, section 17.4.3), and the last pass
             * of the scene before left it off: the new framebuffer's
             * depth would otherwise be whatever its storage held. */
            glDepthMask(GL_TRUE);
            glClear(GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
            draw_occluders(10);
            for (unsigned p = 0; p < PASSES; ++p) {
                enum feature f = (enum feature)((scene * PASSES + p) % F_COUNT);
                /* The rectangle scenes are compared with softpipe, whose
                 * polygon offset differs from llvmpipe's in the last bit. */
                if (rects && f == F_OFFSET)
                    f = F_PLAIN;
                pass(t, scene, p, rects, f, p % 3 == 2);
                if (rnd() < 0.5f) {
                    draw_occluders(3);
                } else if (rnd() < 0.5f) {
                    glEnable(GL_SCISSOR_TEST);
                    glScissor(rndi(W), rndi(H), 20 + rndi(100), 20 + rndi(100));
                    glClearDepth(rnd());
                    glDepthMask(GL_TRUE);   /* the pass left it off */
                    glClear(GL_DEPTH_BUFFER_BIT);
                    glDisable(GL_SCISSOR_TEST);
                }
            }
        }
    }
}

static void
all_scenes(struct transcript *t)
{
    scenes(t, false, true);
}

static void
rectangle_scenes(struct transcript *t)
{
    scenes(t, true, false);
}

/* The transcript's first words: those of the rectangle scenes. */
static struct transcript
prefix(const struct transcript *t, size_t n)
{
    struct transcript p = *t;
    p.n = n < t->n ? n : t->n;
    return p;
}

static bool
nontrivial(const struct transcript *t)
{
    /* Some tile saw fragments fail the depth test and some saw them pass. */
    bool occluded = false, visible = false;
    for (size_t i = 0; i + OU_BRIEF_SIZE < t->n; ++i) {
        if ((t->words[i] & 0xf0000000u) == COARSE_HEADER && (t->words[i] & 0xff) != 0xff) {
            const GLuint *r = t->words + i + 1;
            occluded |= r[OU_NOHC] < r[OU_PHC];
            visible |= r[OU_NOHC] > 0;
        }
    }
    return occluded && visible;
}

int
main(int argc, char **argv)
{
    /* No context here: a child's driver must start its own threads. */
    g_argc = argc;
    g_argv = argv;
    static char err[1 << 16];
    struct transcript softpipe = {0}, reference = {0}, got = {0};

    const bool sp = coarse_run_child("softpipe", NULL, rectangle_scenes, &softpipe, err, sizeof(err),
                                     "softpipe");
    subtest(sp, "softpipe-child-completes");
    subtest(sp && nontrivial(&softpipe), "scenes-are-nontrivial");

    /* The scenes take the coarse test: under LP_PERF=ou_coarse_verify,
     * which shades every rejected block anyway and aborts if one of its
     * fragments passes, the child completes, rejects blocks and records
     * what the exact path records. */
    const char *verify[] = {"LP_NUM_THREADS=0", "LP_PERF=ou_coarse_verify", NULL};
    const char *exact[] = {"LP_NUM_THREADS=0", "LP_PERF=no_ou_coarse", NULL};
    const bool verified = coarse_run_child("llvmpipe", verify, all_scenes, &got, err, sizeof(err), "verify");
    const long long rejected = verified ? coarse_rejected(err, NULL) : -1;
    printf("llvmpipe, LP_NUM_THREADS 0: the coarse test rejected %lld blocks\n", rejected);
    subtest(verified && rejected > 0, "llvmpipe-verify-rejects-blocks");
    if (verified && coarse_run_child("llvmpipe", exact, all_scenes, &reference, err, sizeof(err), "exact"))
        subtest(coarse_same(&reference, &got, "verify"), "llvmpipe-verify-equals-no-coarse");
    else
        subtest(false, "llvmpipe-verify-equals-no-coarse");

    const char *threads[] = {"0", "1", "2", "8"};
    for (int i = 0; i < 4; ++i) {
        char name[128], thread_env[64];
        snprintf(thread_env, sizeof(thread_env), "LP_NUM_THREADS=%s", threads[i]);
        const char *off[] = {thread_env, "LP_PERF=no_ou_coarse", NULL};
        const char *on[] = {thread_env, NULL};

        snprintf(name, sizeof(name), "llvmpipe-threads-%s-no-coarse", threads[i]);
        const bool ref = coarse_run_child("llvmpipe", off, all_scenes, &reference, err, sizeof(err), name);
        snprintf(name, sizeof(name), "llvmpipe-threads-%s-coarse", threads[i]);
        const bool cur = coarse_run_child("llvmpipe", on, all_scenes, &got, err, sizeof(err), name);
        snprintf(name, sizeof(name), "llvmpipe-threads-%s-children-complete", threads[i]);
        subtest(ref && cur, name);
        snprintf(name, sizeof(name), "llvmpipe-threads-%s-coarse-equals-no-coarse", threads[i]);
        if (ref && cur)
            subtest(coarse_same(&reference, &got, name), name);
        else
            piglit_report_subtest_result(PIGLIT_SKIP, "%s", name);
        snprintf(name, sizeof(name), "llvmpipe-threads-%s-rectangles-equal-softpipe", threads[i]);
        if (sp && cur) {
            const struct transcript mine = prefix(&got, softpipe.n);
            subtest(coarse_same(&softpipe, &mine, name), name);
        } else {
            piglit_report_subtest_result(PIGLIT_SKIP, "%s", name);
        }
    }
    piglit_report_result(result);
}
