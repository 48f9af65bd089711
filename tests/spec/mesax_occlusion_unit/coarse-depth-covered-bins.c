/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit on llvmpipe: an exact pass's primitive that
 * covers whole 64x64 bins, where its depth cannot pass the depth test
 * anywhere in a bin, is rejected for the bin before its blocks are
 * visited, and every tile over the bin still counts its coverage in PHC.
 *
 * A 203 x 150 framebuffer object (bins cut by its right and top edges, a
 * column of 4x4 blocks cut at x = 200) of each depth format: cleared to
 * 1.0, an occluder at z = 0.5 over x < 150. Passes, brief and verbose, of
 * one triangle over the whole framebuffer (llvmpipe bins it as covering
 * whole bins), over five tiles: the window, tiles inside bins, across bin
 * edges and the occluder's edge, the framebuffer's corner, and exactly one
 * bin:
 *   at z = 0.75 under LESS: hidden over the occluder (whole bins there are
 *     rejected), visible beyond it;
 *   at z = 0.25 under GREATER and at z = 0.75 under EQUAL: hidden
 *     everywhere.
 * Each tile's record must be the analytic one: PHC its area, NOHC its
 * pixels at x >= 150 where the triangle is visible (0 elsewhere), a
 * verbose list as long as NOHC. softpipe (no coarse test) checks the same
 * records; llvmpipe at LP_NUM_THREADS 0, 1, 2 and 8, and under
 * LP_PERF=ou_coarse_verify (which walks the rejected bins' blocks anyway
 * and aborts if the JIT finds a fragment passing in one or a coverage
 * other than the one credited), where its report must count primitives
 * rejected for a whole bin.
 */
#include "coarse_util.h"

#define W 203
#define H 150
#define OCCLUDER_X1 150
#define ARRAY_SIZE(a) (sizeof(a) / sizeof((a)[0]))
#define TILES 5

static int g_argc;
static char **g_argv;

static const GLint tiles[TILES][4] = {
    {0, 0, W, H},        /* the window */
    {10, 10, 40, 40},    /* inside the bin at (0, 0) */
    {130, 20, 60, 100},  /* across bin edges and the occluder's edge */
    {196, 140, 7, 10},   /* the framebuffer's corner, in an edge bin */
    {64, 64, 64, 64},    /* exactly the bin at (64, 64) */
};

static unsigned
overlap(GLint a0, GLint a1, GLint b0, GLint b1)
{
    const GLint lo = a0 > b0 ? a0 : b0, hi = a1 < b1 ? a1 : b1;
    return hi > lo ? (unsigned)(hi - lo) : 0;
}

static void
pass(const char *what, float z, bool visible_beyond_occluder, bool verbose)
{
    enum { PAIRS = W * H };
    static GLuint storage[TILES][8 + 2 * PAIRS];
    GLuint *buffers[TILES];
    GLsizei sizes[TILES];
    for (int i = 0; i < TILES; ++i) {
        buffers[i] = storage[i];
        sizes[i] = verbose ? 8 + 2 * PAIRS : OU_BRIEF_SIZE;
        ou_fill(buffers[i], sizes[i]);
    }
    OcclusionBuffersMESAX(TILES, sizes, buffers);
    ScissorsMESAX(TILES, &tiles[0][0]);
    glRenderMode(verbose ? GL_VERBOSE_OCCLUSION_MESAX : GL_BRIEF_OCCLUSION_MESAX);
    glBegin(GL_TRIANGLES);
    glVertex3f(-W, -H, z);
    glVertex3f(3 * W, -H, z);
    glVertex3f(-W, 3 * H, z);
    glEnd();
    glRenderMode(GL_RENDER);
    ScissorsMESAX(0, NULL);

    char name[256];
    snprintf(name, sizeof(name), "%s: GL error", what);
    const GLenum error = glGetError();
    coarse_check(error == GL_NO_ERROR, name, error, GL_NO_ERROR);
    for (int i = 0; i < TILES; ++i) {
        const GLint *t = tiles[i];
        const unsigned width = overlap(t[0], t[0] + t[2], 0, W), height = overlap(t[1], t[1] + t[3], 0, H);
        const unsigned visible = visible_beyond_occluder ? overlap(t[0], t[0] + t[2], OCCLUDER_X1, W) * height : 0;
        snprintf(name, sizeof(name), "%s, tile %d: PHC", what, i);
        coarse_check(buffers[i][OU_PHC] == width * height, name, buffers[i][OU_PHC], width * height);
        snprintf(name, sizeof(name), "%s, tile %d: NOHC", what, i);
        coarse_check(buffers[i][OU_NOHC] == visible, name, buffers[i][OU_NOHC], visible);
        if (verbose) {
            snprintf(name, sizeof(name), "%s, tile %d: verbose list length", what, i);
            coarse_check(buffers[i][0] == visible, name, buffers[i][0], visible);
        }
    }
}

static void
scenes(struct transcript *t)
{
    piglit_osmesa_init(g_argc, g_argv, W, H);
    ou_init();
    const struct ou_fbo_functions fbo = ou_fbo_functions();
    char what[160];
    for (unsigned f = 0; f < ARRAY_SIZE(coarse_formats); ++f) {
        coarse_make_fbo(&fbo, W, H, &coarse_formats[f], 0);
        glEnable(GL_DEPTH_TEST);
        glDepthMask(GL_TRUE);
        glDepthFunc(GL_LESS);
        glClearDepth(1.0);
        glClear(GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
        ou_rect(0, 0, OCCLUDER_X1, H, 0.5f);
        glDepthMask(GL_FALSE);
        for (int verbose = 0; verbose < 2; ++verbose) {
            const char *mode = verbose ? "verbose" : "brief";
            glDepthFunc(GL_LESS);
            snprintf(what, sizeof(what), "depth %s, %s, LESS at 0.75", coarse_formats[f].name, mode);
            pass(what, 0.75f, true, verbose);
            glDepthFunc(GL_GREATER);
            snprintf(what, sizeof(what), "depth %s, %s, GREATER at 0.25", coarse_formats[f].name, mode);
            pass(what, 0.25f, false, verbose);
            glDepthFunc(GL_EQUAL);
            snprintf(what, sizeof(what), "depth %s, %s, EQUAL at 0.75", coarse_formats[f].name, mode);
            pass(what, 0.75f, false, verbose);
        }
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

    bool ok = coarse_run_child("softpipe", NULL, scenes, &t, err, sizeof(err), "softpipe") && t.n == 1 &&
              t.words[0] == 0;
    if (!ok)
        printf("softpipe: the records are not the analytic ones:\n%s\n", err);
    subtest(ok, "softpipe-records-analytic");

    const char *threads[] = {"0", "1", "2", "8"};
    for (unsigned i = 0; i < ARRAY_SIZE(threads); ++i) {
        char name[128], thread_env[64];
        snprintf(thread_env, sizeof(thread_env), "LP_NUM_THREADS=%s", threads[i]);
        const char *env[] = {thread_env, NULL};
        snprintf(name, sizeof(name), "llvmpipe-threads-%s-records-analytic", threads[i]);
        ok = coarse_run_child("llvmpipe", env, scenes, &t, err, sizeof(err), name) && t.n == 1 &&
             t.words[0] == 0;
        if (!ok)
            printf("%s: the records are not the analytic ones:\n%s\n", name, err);
        subtest(ok, name);
    }

    const char *verify[] = {"LP_NUM_THREADS=0", "LP_PERF=ou_coarse_verify", NULL};
    const bool completed = coarse_run_child("llvmpipe", verify, scenes, &t, err, sizeof(err), "verify");
    subtest(completed && t.n == 1 && t.words[0] == 0, "llvmpipe-verify-records-analytic");
    const char *line = completed ? strstr(err, "exact passes rejected ") : NULL;
    long long covered = -1;
    if (!line || sscanf(line, "exact passes rejected %lld", &covered) != 1)
        covered = -1;
    printf("llvmpipe, LP_PERF=ou_coarse_verify: %lld primitives covering a whole bin rejected there\n",
           covered);
    subtest(covered > 0, "llvmpipe-verify-rejects-covered-bins");
    piglit_report_result(result);
}
