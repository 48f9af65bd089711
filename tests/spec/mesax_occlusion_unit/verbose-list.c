/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit, VERBOSE_OCCLUSION_MESAX: the list of a tile is
 * exactly the set of pixels whose depth a GL_RENDER draw of the same
 * geometry changes; NOHC is its size; the record's first 8 words are those
 * of section 5.X (PHC the pixels the triangle covers, the extents and the
 * depth range those of the listed pixels) whether or not the list fits;
 * overflowed lists keep only listed pixels, end in 0xFFFFFFFF after as many
 * whole pairs as fit, and glRenderMode returns the number of overflowed
 * tiles.
 *
 * Tolerances: counts, coordinates and sets exact; zmin and zmax within
 * OU_Z24_READBACK_TOLERANCE of the depth read back from the 24-bit depth
 * buffer (ou_util.h derives it).
 */
#include <stdlib.h>

#include "ou_util.h"

#define W 64
#define H 48

/* A tilted triangle in front of part of the occluder and behind another part. */
static void
draw_target(void)
{
    glBegin(GL_TRIANGLES);
    glVertex3f(3.3f, 2.7f, 0.2f);
    glVertex3f(60.1f, 11.4f, 0.6f);
    glVertex3f(21.8f, 45.2f, 0.45f);
    glEnd();
}

static void
clear_depth(void)
{
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glClearDepth(1.0);
    glClear(GL_DEPTH_BUFFER_BIT);
}

static void
setup_scene(void)
{
    clear_depth();
    ou_rect(20, 0, 44, 48, 0.4f);   /* occludes the triangle where it is deeper than 0.4 */
}

/* What GL_RENDER says the record must hold. */
static GLuint *expected_pairs;   /* the changed pixels, sorted by y, then x */
static size_t expected_count;
static GLuint expected_header[OU_BRIEF_SIZE];

static void
measure_render(void)
{
    const size_t n = (size_t)W * H;
    GLuint *before = malloc(n * 4), *after = malloc(n * 4);

    /* PHC: every pixel the triangle covers changes an empty depth buffer. */
    clear_depth();
    glReadPixels(0, 0, W, H, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, before);
    draw_target();
    glReadPixels(0, 0, W, H, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, after);
    GLuint covered = 0;
    for (size_t i = 0; i < n; ++i)
        covered += before[i] != after[i];

    /* The list, the extents and the depth range: the pixels it changes in the scene. */
    setup_scene();
    glReadPixels(0, 0, W, H, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, before);
    draw_target();
    glReadPixels(0, 0, W, H, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, after);
    expected_pairs = malloc(n * 2 * 4);
    GLuint xmin = OU_EMPTY_MIN, xmax = 0, ymin = OU_EMPTY_MIN, ymax = 0, zmin = OU_EMPTY_MIN, zmax = 0;
    for (int y = 0; y < H; ++y) {
        for (int x = 0; x < W; ++x) {
            const GLuint z = after[y * W + x];
            if (before[y * W + x] == z)
                continue;
            expected_pairs[2 * expected_count] = x;
            expected_pairs[2 * expected_count + 1] = y;
            ++expected_count;
            xmin = (GLuint)x < xmin ? (GLuint)x : xmin;
            xmax = (GLuint)x > xmax ? (GLuint)x : xmax;
            ymin = (GLuint)y < ymin ? (GLuint)y : ymin;
            ymax = (GLuint)y > ymax ? (GLuint)y : ymax;
            zmin = z < zmin ? z : zmin;
            zmax = z > zmax ? z : zmax;
        }
    }
    const GLuint header[OU_BRIEF_SIZE] = {(GLuint)expected_count, covered, xmin, xmax, ymin, ymax, zmin, zmax};
    memcpy(expected_header, header, sizeof(header));
    free(before);
    free(after);
}

static bool
header_ok(const char *name, const GLuint *record)
{
    return ou_check_record(name, record, expected_header, OU_Z24_READBACK_TOLERANCE);
}

static bool
is_expected_pair(GLuint x, GLuint y)
{
    const GLuint key[2] = {x, y};
    return bsearch(key, expected_pairs, expected_count, 2 * sizeof(GLuint), ou_compare_pairs) != NULL;
}

/* The k pairs of an overflowed list are distinct listed pixels: a pixel
 * covered once by the triangle is non-occluded at most once. */
static bool
pairs_are_subset(const char *name, GLuint *pairs, size_t k)
{
    ou_sort_pairs(pairs, k);
    for (size_t i = 0; i < k; ++i) {
        if (!is_expected_pair(pairs[2 * i], pairs[2 * i + 1])) {
            printf("%s: kept pair (%u, %u) is not a non-occluded pixel\n", name, pairs[2 * i], pairs[2 * i + 1]);
            return false;
        }
        if (i > 0 && pairs[2 * i] == pairs[2 * i - 2] && pairs[2 * i + 1] == pairs[2 * i - 1]) {
            printf("%s: kept pair (%u, %u) appears twice\n", name, pairs[2 * i], pairs[2 * i + 1]);
            return false;
        }
    }
    return true;
}

PIGLIT_GL_TEST_CONFIG_BEGIN

    config.supports_gl_compat_version = 10;
    config.window_width = W;
    config.window_height = H;
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
    ou_init();
    const size_t n = (size_t)W * H;
    GLuint *buffer = malloc((8 + 2 * n + 16) * 4);

    measure_render();
    const size_t count = expected_count;

    /* The same in a verbose pass, with room for everything. */
    setup_scene();
    GLsizei size = (GLsizei)(8 + 2 * n);
    GLuint *buffers[1] = {buffer};
    ou_fill(buffer, (int)(8 + 2 * n + 16));
    OcclusionBuffersMESAX(1, &size, buffers);
    glRenderMode(GL_VERBOSE_OCCLUSION_MESAX);
    draw_target();
    GLint overflowed = glRenderMode(GL_RENDER);
    GLuint nohc = buffer[OU_NOHC];
    bool ok = overflowed == 0 && nohc == count && count > 50 && piglit_check_gl_error(GL_NO_ERROR);
    if (!ok)
        printf("NOHC %u, pixels changed in GL_RENDER %zu, overflow %d\n", nohc, count, overflowed);
    subtest(ok, "nohc-equals-changed-pixels");
    subtest(header_ok("fitting record", buffer), "record-phc-extents-depth-match-render");

    bool same = nohc == count;
    if (same) {
        ou_sort_pairs(buffer + 8, nohc);
        same = memcmp(buffer + 8, expected_pairs, count * 2 * sizeof(GLuint)) == 0;
        if (!same)
            printf("the verbose list differs from the set of changed pixels\n");
    }
    subtest(same && buffer[8 + 2 * nohc] == OU_SENTINEL, "list-equals-changed-pixels");

    /* Exact fit: no terminator, the word after the buffer untouched. */
    setup_scene();
    size = (GLsizei)(8 + 2 * count);
    ou_fill(buffer, (int)(8 + 2 * n + 16));
    OcclusionBuffersMESAX(1, &size, buffers);
    glRenderMode(GL_VERBOSE_OCCLUSION_MESAX);
    draw_target();
    overflowed = glRenderMode(GL_RENDER);
    subtest(overflowed == 0 && header_ok("exact fit", buffer) && buffer[size] == OU_SENTINEL &&
                buffer[size - 1] != 0xffffffffu,
            "exact-fit-no-overflow");

    /* Three tiles, two of them overflowing: one word short, and only 10 words. */
    GLuint *b1 = malloc((8 + 2 * n + 16) * 4), *b2 = malloc(64 * 4);
    GLuint *three[3] = {buffer, b1, b2};
    GLsizei sizes[3] = {(GLsizei)(8 + 2 * n), (GLsizei)(8 + 2 * count - 1), 10};
    const GLint tiles[12] = {0, 0, W, H, 0, 0, W, H, 0, 0, W, H};
    setup_scene();
    ou_fill(buffer, (int)(8 + 2 * n + 16));
    ou_fill(b1, (int)(8 + 2 * n + 16));
    ou_fill(b2, 64);
    OcclusionBuffersMESAX(3, sizes, three);
    ScissorsMESAX(3, tiles);
    glRenderMode(GL_VERBOSE_OCCLUSION_MESAX);
    draw_target();
    overflowed = glRenderMode(GL_RENDER);
    ScissorsMESAX(0, NULL);
    const size_t k1 = (size_t)(sizes[1] - 9) / 2;   /* whole pairs before the terminator */
    subtest(overflowed == 2, "rendermode-returns-overflowed-tiles");
    subtest(b1[8 + 2 * k1] == 0xffffffffu && b1[8 + 2 * k1 - 1] != OU_SENTINEL && b1[8 + 2 * k1 + 1] == OU_SENTINEL,
            "overflow-one-word-short-terminated");
    subtest(header_ok("one word short", b1), "overflow-one-word-short-keeps-header");
    subtest(pairs_are_subset("one word short", b1 + 8, k1), "overflow-one-word-short-pairs-are-non-occluded-pixels");
    subtest(b2[8] == 0xffffffffu && b2[9] == OU_SENTINEL, "overflow-10-words-terminated");
    subtest(header_ok("10 words", b2), "overflow-10-words-keeps-header");
    subtest(buffer[8 + 2 * count] == OU_SENTINEL && header_ok("fitting tile", buffer), "fitting-tile-not-terminated");

    /* A buffer of 8 words in verbose mode: the brief record, counted as overflowed. */
    setup_scene();
    GLsizei eight = 8;
    ou_fill(b2, 64);
    GLuint *only[1] = {b2};
    OcclusionBuffersMESAX(1, &eight, only);
    glRenderMode(GL_VERBOSE_OCCLUSION_MESAX);
    draw_target();
    overflowed = glRenderMode(GL_RENDER);
    subtest(overflowed == 1 && header_ok("8 words", b2) && b2[8] == OU_SENTINEL, "overflow-8-words-no-terminator");

    free(expected_pairs); free(buffer); free(b1); free(b2);
    piglit_report_result(result);
}
