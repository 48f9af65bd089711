/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit: results do not depend on how the work is split.
 * The same scenes are measured in child processes on softpipe and on
 * llvmpipe with LP_NUM_THREADS = 0, 1, 2, 4 and 8 (the driver is chosen
 * once per process), by 63 tiles of 37 x 29 pixels starting at (-5, -7),
 * which straddle llvmpipe's 64 x 64 bins and so its threads, one 1x1 tile
 * on a bin corner (63, 64), and verbose lists of four tiles (compared as
 * sorted sets); and by four tiles on bin boundaries (the whole window
 * among them), which llvmpipe sums per bin instead of per 4x4 block, so
 * the whole-window record must also equal the same tile's record from a
 * pass where a 1x1 tile sends one bin back to the per-block path; and, with
 * -tiles-4096, by 4096 tiles of 5 x 5 pixels at a stride of 4 from (-2, -3),
 * overlapping 1 to 4 deep, about 289 over each 64 x 64 bin (llvmpipe's
 * per-bin tile lists, in chunks of 64):
 *   rectangles  200 overlapping axis-aligned rectangles on whole pixels,
 *               each at its own depth: every configuration, softpipe
 *               included, must give identical records (no tolerance).
 *   triangles   300 random triangles of varying depth: llvmpipe's thread
 *               counts must agree exactly. (softpipe is not compared here:
 *               its rasterizer covers other edge pixels than llvmpipe's in
 *               GL_RENDER too (hundreds of pixels in a scene like this), and its
 *               z plane rounds differently; verbose-list and
 *               extents-vs-readpixels check each driver against its own
 *               GL_RENDER.)
 * Both scenes are depth tested against an occluder drawn in GL_RENDER.
 * The test ignores GALLIUM_DRIVER: it runs every configuration itself. A
 * child that crashes, exits with an error or sees a GL error fails the test
 * (subtest llvmpipe-threads-N-child-completes; softpipe's fails it outright).
 */
#define _DEFAULT_SOURCE 1   /* setenv, strsignal */
#include <math.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include "ou_util.h"

#define SIZE 256
#define TILES 64
#define LIST_TILES 4
#define ALIGNED_TILES 4
#define MANY_TILES 4096
#define LIST_WORDS (8 + 2 * 300000)   /* fragments, not pixels: triangles overlap */

struct records {
    GLuint brief[TILES][OU_BRIEF_SIZE];
    GLuint verbose[LIST_TILES][LIST_WORDS];
    GLuint aligned[ALIGNED_TILES][OU_BRIEF_SIZE];   /* tiles on bin boundaries */
    GLuint mixed[2][OU_BRIEF_SIZE];                 /* the window and a 1x1 tile */
    GLuint many[MANY_TILES][OU_BRIEF_SIZE];         /* 64 x 64 overlapping tiles */
};

struct results {
    int ok;
    struct records scene[2];   /* rectangles, triangles */
};

static unsigned seed = 12345;
static float rnd(void) { seed = seed * 1103515245u + 12345u; return (float)((seed >> 8) & 0xffff) / 65535.0f; }

static void
draw_triangles(void)
{
    seed = 12345;
    glBegin(GL_TRIANGLES);
    for (int i = 0; i < 300; ++i) {
        const float cx = rnd() * SIZE, cy = rnd() * SIZE, r = 4 + rnd() * 40;
        for (int v = 0; v < 3; ++v)
            glVertex3f(cx + (rnd() - 0.5f) * 2 * r, cy + (rnd() - 0.5f) * 2 * r, 0.1f + 0.8f * rnd());
    }
    glEnd();
}

static void
draw_rectangles(void)
{
    seed = 777;
    for (int i = 0; i < 200; ++i) {
        const float x = floorf(rnd() * SIZE), y = floorf(rnd() * SIZE);
        const float w = floorf(1 + rnd() * 60), h = floorf(1 + rnd() * 60);
        ou_rect(x, y, x + w, y + h, 0.1f + 0.8f * rnd());
    }
}

static bool tiles_4096;   /* -tiles-4096: the MANY_TILES pass too */

/* A brief pass over MANY_TILES overlapping tiles; false on a GL error. */
static bool
many_tiles_pass(GLuint (*records)[OU_BRIEF_SIZE], void (*draw)(void))
{
    static GLint tiles[4 * MANY_TILES];
    static GLuint *buffers[MANY_TILES];
    static GLsizei sizes[MANY_TILES];
    for (int k = 0; k < MANY_TILES; ++k) {
        tiles[4 * k] = -2 + 4 * (k % 64);
        tiles[4 * k + 1] = -3 + 4 * (k / 64);
        tiles[4 * k + 2] = 5;
        tiles[4 * k + 3] = 5;
        ou_fill(records[k], OU_BRIEF_SIZE);
        buffers[k] = records[k];
        sizes[k] = OU_BRIEF_SIZE;
    }
    OcclusionBuffersMESAX(MANY_TILES, sizes, buffers);
    ScissorsMESAX(MANY_TILES, tiles);
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    draw();
    const GLint overflowed = glRenderMode(GL_RENDER);
    ScissorsMESAX(0, NULL);
    return overflowed == 0 && piglit_check_gl_error(GL_NO_ERROR);
}

static bool
measure_scene(struct records *out, void (*draw)(void))
{
    static GLint tiles[4 * TILES];
    for (int i = 0; i < 63; ++i) {
        tiles[4 * i] = -5 + (i % 8) * 37;
        tiles[4 * i + 1] = -7 + (i / 8) * 29 * 9 / 8;
        tiles[4 * i + 2] = 37;
        tiles[4 * i + 3] = 29;
    }
    tiles[4 * 63] = 63; tiles[4 * 63 + 1] = 64; tiles[4 * 63 + 2] = 1; tiles[4 * 63 + 3] = 1;

    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glClear(GL_DEPTH_BUFFER_BIT);
    ou_rect(60, 40, 200, 180, 0.45f);   /* the occluder, in GL_RENDER */

    ou_brief_pass(TILES, tiles, out->brief, draw);
    const GLint aligned[4 * ALIGNED_TILES] = {0, 0, SIZE, SIZE, 64, 0, 128, SIZE, 0, 64, SIZE, 64, 128, 128, 128, 128};
    ou_brief_pass(ALIGNED_TILES, aligned, out->aligned, draw);
    const GLint mixed[4 * 2] = {0, 0, SIZE, SIZE, 63, 64, 1, 1};
    ou_brief_pass(2, mixed, out->mixed, draw);
    const bool many = !tiles_4096 || many_tiles_pass(out->many, draw);

    GLuint *buffers[LIST_TILES];
    GLsizei sizes[LIST_TILES];
    for (int i = 0; i < LIST_TILES; ++i) {
        ou_fill(out->verbose[i], LIST_WORDS);
        buffers[i] = out->verbose[i];
        sizes[i] = LIST_WORDS;
    }
    const GLint list_tiles[4 * LIST_TILES] = {60, 60, 10, 10, 0, 0, 128, 128, 50, 50, 30, 30, 120, 120, 30, 30};
    OcclusionBuffersMESAX(LIST_TILES, sizes, buffers);
    ScissorsMESAX(LIST_TILES, list_tiles);
    glRenderMode(GL_VERBOSE_OCCLUSION_MESAX);
    draw();
    GLint overflowed = glRenderMode(GL_RENDER);
    ScissorsMESAX(0, NULL);
    for (int i = 0; i < LIST_TILES; ++i)
        ou_sort_pairs(out->verbose[i] + 8, out->verbose[i][0]);
    return many && overflowed == 0 && glGetError() == GL_NO_ERROR;
}

static void
measure(struct results *out)
{
    out->ok = measure_scene(&out->scene[0], draw_rectangles) && measure_scene(&out->scene[1], draw_triangles);
}

/* Runs measure() in a child on `driver` with `threads` (NULL: unset).
 * False, with the reason printed, when the child crashed, exited with an
 * error, reported less than its results or saw a GL error. */
static bool
run_child(const char *driver, const char *threads, struct results *out, int argc, char **argv)
{
    int fd[2];
    if (pipe(fd) != 0) {
        perror("pipe");
        return false;
    }
    fflush(stdout);
    pid_t pid = fork();
    if (pid < 0) {
        perror("fork");
        return false;
    }
    if (pid == 0) {
        close(fd[0]);
        setenv("GALLIUM_DRIVER", driver, 1);
        if (threads)
            setenv("LP_NUM_THREADS", threads, 1);
        /* The child reports through the pipe, not with piglit lines. */
        piglit_osmesa_init(argc, argv, SIZE, SIZE);
        ou_init();
        static struct results r;
        measure(&r);
        _exit(ou_write_all(fd[1], &r, sizeof(r)) ? 0 : 1);
    }
    close(fd[1]);
    char *p = (char *)out;
    size_t got = 0;
    for (ssize_t n; got < sizeof(*out) && (n = read(fd[0], p + got, sizeof(*out) - got)) > 0;)
        got += (size_t)n;
    close(fd[0]);
    int status = 0;
    waitpid(pid, &status, 0);

    const char *what = threads ? threads : "unset";
    if (WIFSIGNALED(status)) {
        printf("%s child (LP_NUM_THREADS %s) died of signal %d (%s)\n", driver, what, WTERMSIG(status),
               strsignal(WTERMSIG(status)));
        return false;
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        printf("%s child (LP_NUM_THREADS %s) exited with status %d\n", driver, what,
               WIFEXITED(status) ? WEXITSTATUS(status) : -1);
        return false;
    }
    if (got != sizeof(*out)) {
        printf("%s child (LP_NUM_THREADS %s) reported %zu of %zu bytes\n", driver, what, got, sizeof(*out));
        return false;
    }
    if (!out->ok) {
        printf("%s child (LP_NUM_THREADS %s): a pass overflowed or raised a GL error\n", driver, what);
        return false;
    }
    return true;
}

static bool
same(const struct records *a, const struct records *b, const char *name)
{
    for (int t = 0; t < TILES; ++t) {
        char what[96];
        snprintf(what, sizeof(what), "%s tile %d", name, t);
        if (!ou_check_record(what, b->brief[t], a->brief[t], 0))
            return false;
    }
    for (int t = 0; t < ALIGNED_TILES; ++t) {
        char what[96];
        snprintf(what, sizeof(what), "%s bin-aligned tile %d", name, t);
        if (!ou_check_record(what, b->aligned[t], a->aligned[t], 0))
            return false;
    }
    for (int t = 0; t < (tiles_4096 ? MANY_TILES : 0); ++t) {
        char what[96];
        snprintf(what, sizeof(what), "%s tile %d of %d", name, t, MANY_TILES);
        if (!ou_check_record(what, b->many[t], a->many[t], 0))
            return false;
    }
    for (int t = 0; t < LIST_TILES; ++t) {
        const GLuint n = a->verbose[t][0];
        if (b->verbose[t][0] != n || memcmp(a->verbose[t] + 8, b->verbose[t] + 8, 2 * n * sizeof(GLuint))) {
            printf("%s: verbose list of tile %d differs\n", name, t);
            return false;
        }
    }
    return true;
}

static bool
nontrivial(const struct records *r)
{
    bool visible = false, occluded = false;
    for (int t = 0; t < 63; ++t) {
        visible |= r->brief[t][OU_NOHC] > 0;
        occluded |= r->brief[t][OU_NOHC] < r->brief[t][OU_PHC];
    }
    return visible && occluded && r->verbose[1][0] > 100;
}

int main(int argc, char **argv)
{
    static struct results softpipe, first, other;
    tiles_4096 = ou_take_flag(&argc, argv, "-tiles-4096");
    if (!run_child("softpipe", NULL, &softpipe, argc, argv))
        piglit_report_result(PIGLIT_FAIL);
    subtest(nontrivial(&softpipe.scene[0]) && nontrivial(&softpipe.scene[1]), "scenes-are-nontrivial");

    const char *threads[] = {"0", "1", "2", "4", "8"};
    bool have_first = false;   /* threads 0, the triangles' reference */
    for (int i = 0; i < 5; ++i) {
        char name[64];
        snprintf(name, sizeof(name), "llvmpipe-threads-%s", threads[i]);
        struct results *r = i == 0 ? &first : &other;
        /* A child that crashes or fails fails the test; what it would
         * have measured is then not compared. */
        char what[96];
        const bool completed = run_child("llvmpipe", threads[i], r, argc, argv);
        snprintf(what, sizeof(what), "%s-child-completes", name);
        subtest(completed, what);
        if (!completed) {
            piglit_report_subtest_result(PIGLIT_SKIP, "%s-rectangles-equal-softpipe", name);
            piglit_report_subtest_result(PIGLIT_SKIP, "%s-per-bin-equals-per-block", name);
            if (i > 0)
                piglit_report_subtest_result(PIGLIT_SKIP, "%s-triangles-equal-threads-0", name);
            continue;
        }
        have_first |= i == 0;
        snprintf(what, sizeof(what), "%s-rectangles-equal-softpipe", name);
        subtest(same(&softpipe.scene[0], &r->scene[0], what), what);
        snprintf(what, sizeof(what), "%s-per-bin-equals-per-block", name);
        subtest(ou_check_record("rectangles window", r->scene[0].mixed[0], r->scene[0].aligned[0], 0) &&
                    ou_check_record("triangles window", r->scene[1].mixed[0], r->scene[1].aligned[0], 0),
                what);
        if (i > 0 && have_first) {
            snprintf(what, sizeof(what), "%s-triangles-equal-threads-0", name);
            subtest(same(&first.scene[1], &r->scene[1], what), what);
        } else if (i > 0) {
            piglit_report_subtest_result(PIGLIT_SKIP, "%s-triangles-equal-threads-0", name);
        }
    }
    piglit_report_result(result);
}
