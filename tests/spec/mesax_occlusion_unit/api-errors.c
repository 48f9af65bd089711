/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit: every error of the spec's Errors section, and
 * that a command that generates one has no other effect.
 *
 * The valid state is two tiles, A and B, with one buffer each, sized for
 * exactly the verbose record of a full-window draw. Every failing call
 * passes arrays of its own whose valid entries differ from that state, so
 * that a call which copied part of its arguments before finding the error
 * would leave a visible change. The spec has a query for the tile count
 * only; the tiles and buffers are read back through a verbose pass after
 * each failing call: its records must land in A's and B's buffers with A's
 * and B's contents, with no overflow (a buffer made smaller would
 * overflow), and the failing calls' buffers must stay untouched.
 */
#include "ou_util.h"

#define W 32
#define H 32

static const GLint valid_tiles[8] = {1, 2, 3, 4, 8, 9, 5, 6};   /* A: 3 x 4, B: 5 x 6 */
#define NOHC_A 12
#define NOHC_B 30
#define SIZE_A (8 + 2 * NOHC_A)
#define SIZE_B (8 + 2 * NOHC_B)
#define GUARD 16   /* words past each buffer that no record may reach */
#define OTHER 64   /* size of the failing calls' buffers */

static GLuint a[SIZE_A + GUARD], b[SIZE_B + GUARD];
static GLuint c[OTHER], d[OTHER];
static GLuint *valid_buffers[2] = {a, b};
static const GLsizei valid_sizes[2] = {SIZE_A, SIZE_B};

static GLint
get(GLenum pname)
{
    GLint v = -12345;
    glGetIntegerv(pname, &v);
    return v;
}

static void draw_all(void) { ou_rect(0, 0, W, H, 0.5f); }

static void
fill_all(void)
{
    ou_fill(a, SIZE_A + GUARD);
    ou_fill(b, SIZE_B + GUARD);
    ou_fill(c, OTHER);
    ou_fill(d, OTHER);
}

static bool
untouched(const char *name, const GLuint *buffer, int from, int to)
{
    for (int i = from; i < to; ++i) {
        if (buffer[i] != OU_SENTINEL) {
            printf("%s: word %d written (0x%08x)\n", name, i, buffer[i]);
            return false;
        }
    }
    return true;
}

/* The verbose record of tile `t` (x, y, w, h) of a full-window draw:
 * header and the complete list, as a set. */
static bool
record_is_tile(const char *name, GLuint *record, const GLint *t)
{
    const GLuint n = (GLuint)(t[2] * t[3]);
    const GLuint z = ou_depth(0.5);
    const GLuint expected[OU_BRIEF_SIZE] = {n, n, (GLuint)t[0], (GLuint)(t[0] + t[2] - 1),
                                            (GLuint)t[1], (GLuint)(t[1] + t[3] - 1), z, z};
    if (!ou_check_record(name, record, expected, 0))
        return false;
    ou_sort_pairs(record + 8, n);
    GLuint k = 0;
    for (GLint y = t[1]; y < t[1] + t[3]; ++y) {
        for (GLint x = t[0]; x < t[0] + t[2]; ++x, ++k) {
            if (record[8 + 2 * k] != (GLuint)x || record[8 + 2 * k + 1] != (GLuint)y) {
                printf("%s: pair %u is (%u, %u), expected (%d, %d)\n", name, k, record[8 + 2 * k],
                       record[8 + 2 * k + 1], x, y);
                return false;
            }
        }
    }
    return true;
}

/* Reads the state back: tile count 2, RENDER mode, and a verbose pass that
 * writes A's and B's records, exactly fitting, into a and b only. */
static bool
state_is_valid(void)
{
    const GLint count = get(GL_OCCLUSION_TILE_COUNT_MESAX), mode = get(GL_RENDER_MODE);
    if (count != 2 || mode != GL_RENDER) {
        printf("tile count %d (expected 2), render mode 0x%x\n", count, mode);
        return false;
    }
    fill_all();
    glRenderMode(GL_VERBOSE_OCCLUSION_MESAX);
    draw_all();
    const GLint overflowed = glRenderMode(GL_RENDER);
    if (!piglit_check_gl_error(GL_NO_ERROR))
        return false;
    if (overflowed != 0) {
        printf("%d tiles overflowed: a buffer size changed\n", overflowed);
        return false;
    }
    return record_is_tile("tile A", a, &valid_tiles[0]) && record_is_tile("tile B", b, &valid_tiles[4]) &&
           untouched("past A's buffer", a, SIZE_A, SIZE_A + GUARD) &&
           untouched("past B's buffer", b, SIZE_B, SIZE_B + GUARD) && untouched("buffer c", c, 0, OTHER) &&
           untouched("buffer d", d, 0, OTHER);
}

/* The error `expected`, then the valid state unchanged. */
static void
check_error_keeps_state(GLenum expected, const char *name)
{
    const bool error = piglit_check_gl_error(expected);
    subtest(error && state_is_valid(), name);
}

static void
test_rendermode_without_buffers(void)
{
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    subtest(piglit_check_gl_error(GL_INVALID_OPERATION) && get(GL_RENDER_MODE) == GL_RENDER,
            "rendermode-brief-without-buffers");
    glRenderMode(GL_VERBOSE_OCCLUSION_MESAX);
    subtest(piglit_check_gl_error(GL_INVALID_OPERATION) && get(GL_RENDER_MODE) == GL_RENDER,
            "rendermode-verbose-without-buffers");

    /* From SELECT: the error leaves SELECT current and its hits pending,
     * so the name loaded after it makes a second hit record. */
    GLuint select_buffer[64];
    glSelectBuffer(64, select_buffer);
    glRenderMode(GL_SELECT);
    glInitNames();
    glPushName(5);
    draw_all();
    GLint r = glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    bool ok = piglit_check_gl_error(GL_INVALID_OPERATION) && r == 0 && get(GL_RENDER_MODE) == GL_SELECT;
    glLoadName(6);
    draw_all();
    const GLint hits = glRenderMode(GL_RENDER);
    if (hits != 2 || select_buffer[3] != 5 || select_buffer[7] != 6) {
        printf("after the failed RenderMode, SELECT returned %d hits (expected 2, names 5 and 6)\n", hits);
        ok = false;
    }
    subtest(ok, "rendermode-select-to-occlusion-without-buffers");

    /* From FEEDBACK: FEEDBACK stays current and the values of both draws
     * are returned, twice the count of one draw. */
    GLfloat feedback[256];
    glFeedbackBuffer(256, GL_2D, feedback);
    glRenderMode(GL_FEEDBACK);
    draw_all();
    const GLint one_draw = glRenderMode(GL_RENDER);
    glRenderMode(GL_FEEDBACK);
    draw_all();
    r = glRenderMode(GL_VERBOSE_OCCLUSION_MESAX);
    ok = piglit_check_gl_error(GL_INVALID_OPERATION) && r == 0 && get(GL_RENDER_MODE) == GL_FEEDBACK;
    draw_all();
    const GLint values = glRenderMode(GL_RENDER);
    if (one_draw <= 0 || values != 2 * one_draw) {
        printf("after the failed RenderMode, FEEDBACK returned %d values (one draw: %d)\n", values, one_draw);
        ok = false;
    }
    subtest(ok, "rendermode-feedback-to-occlusion-without-buffers");
}

static void
test_scissors_errors(GLint max_tiles)
{
    GLint *many = malloc(sizeof(GLint) * 4 * (size_t)(max_tiles + 1));
    for (int i = 0; i <= max_tiles; ++i) {
        many[4 * i] = 16;
        many[4 * i + 1] = 16;
        many[4 * i + 2] = 2;
        many[4 * i + 3] = 2;
    }
    const GLint negative_count[8] = {20, 20, 2, 2, 0, 0, 1, 1};
    const GLint bad_second_width[8] = {16, 16, 4, 4, 0, 0, -1, 4};
    const GLint bad_second_height[8] = {24, 0, 4, 4, 0, 0, 4, -2};

    ScissorsMESAX(-1, negative_count);
    check_error_keeps_state(GL_INVALID_VALUE, "scissors-negative-count");
    ScissorsMESAX(max_tiles + 1, many);
    check_error_keeps_state(GL_INVALID_VALUE, "scissors-count-above-max");
    ScissorsMESAX(1, NULL);
    check_error_keeps_state(GL_INVALID_VALUE, "scissors-null-tiles");
    ScissorsMESAX(2, bad_second_width);
    check_error_keeps_state(GL_INVALID_VALUE, "scissors-negative-width");
    ScissorsMESAX(2, bad_second_height);
    check_error_keeps_state(GL_INVALID_VALUE, "scissors-negative-height");
    free(many);
}

static void
test_buffers_errors(GLint max_tiles)
{
    GLuint **many = malloc(sizeof(GLuint *) * (size_t)(max_tiles + 1));
    GLsizei *many_sizes = malloc(sizeof(GLsizei) * (size_t)(max_tiles + 1));
    for (int i = 0; i <= max_tiles; ++i) {
        many[i] = c;
        many_sizes[i] = 8;
    }
    GLuint *other[2] = {c, d};
    GLuint *second_null[2] = {c, NULL};
    const GLsizei small[2] = {8, 8}, second_below_8[2] = {8, 7};

    OcclusionBuffersMESAX(-1, small, other);
    check_error_keeps_state(GL_INVALID_VALUE, "buffers-negative-count");
    OcclusionBuffersMESAX(max_tiles + 1, many_sizes, many);
    check_error_keeps_state(GL_INVALID_VALUE, "buffers-count-above-max");
    OcclusionBuffersMESAX(2, second_below_8, other);
    check_error_keeps_state(GL_INVALID_VALUE, "buffers-size-below-8");
    OcclusionBuffersMESAX(2, small, second_null);
    check_error_keeps_state(GL_INVALID_VALUE, "buffers-null-buffer");
    OcclusionBuffersMESAX(2, NULL, other);
    check_error_keeps_state(GL_INVALID_VALUE, "buffers-null-sizes");
    OcclusionBuffersMESAX(2, small, NULL);
    check_error_keeps_state(GL_INVALID_VALUE, "buffers-null-buffers");
    free(many);
    free(many_sizes);
}

/* Errors inside a pass: the pass goes on with its tiles and buffers. */
static void
test_errors_inside_pass(void)
{
    const GLint other_tile[4] = {16, 16, 2, 2};
    GLuint *other[2] = {c, d};
    const GLsizei small[2] = {8, 8};

    fill_all();
    glRenderMode(GL_VERBOSE_OCCLUSION_MESAX);
    subtest(piglit_check_gl_error(GL_NO_ERROR) && get(GL_RENDER_MODE) == GL_VERBOSE_OCCLUSION_MESAX,
            "rendermode-verbose-enters");

    ScissorsMESAX(1, other_tile);
    subtest(piglit_check_gl_error(GL_INVALID_OPERATION) && get(GL_OCCLUSION_TILE_COUNT_MESAX) == 2,
            "scissors-inside-occlusion-mode");
    OcclusionBuffersMESAX(2, small, other);
    subtest(piglit_check_gl_error(GL_INVALID_OPERATION), "buffers-inside-occlusion-mode");

    glRenderMode(GL_TEXTURE_2D);
    subtest(piglit_check_gl_error(GL_INVALID_ENUM) && get(GL_RENDER_MODE) == GL_VERBOSE_OCCLUSION_MESAX &&
                a[OU_NOHC] == OU_SENTINEL,
            "rendermode-invalid-enum-keeps-pass");

    glBegin(GL_TRIANGLES);
    const GLint r = glRenderMode(GL_RENDER);
    glEnd();
    subtest(piglit_check_gl_error(GL_INVALID_OPERATION) && r == 0 &&
                get(GL_RENDER_MODE) == GL_VERBOSE_OCCLUSION_MESAX && a[OU_NOHC] == OU_SENTINEL,
            "rendermode-inside-begin-end-keeps-pass");

    draw_all();
    const GLint overflowed = glRenderMode(GL_RENDER);
    subtest(piglit_check_gl_error(GL_NO_ERROR) && overflowed == 0 && record_is_tile("tile A", a, &valid_tiles[0]) &&
                record_is_tile("tile B", b, &valid_tiles[4]) && untouched("buffer c", c, 0, OTHER) &&
                untouched("buffer d", d, 0, OTHER),
            "errors-inside-pass-keep-its-tiles-and-buffers");
    subtest(state_is_valid(), "errors-inside-pass-keep-state");
}

static void
test_begin_end_errors(void)
{
    const GLint other_tile[4] = {16, 16, 2, 2};
    GLuint *other[2] = {c, d};
    const GLsizei small[2] = {8, 8};

    glBegin(GL_TRIANGLES);
    ScissorsMESAX(1, other_tile);
    glEnd();
    check_error_keeps_state(GL_INVALID_OPERATION, "scissors-inside-begin-end");

    glBegin(GL_TRIANGLES);
    OcclusionBuffersMESAX(2, small, other);
    glEnd();
    check_error_keeps_state(GL_INVALID_OPERATION, "buffers-inside-begin-end");

    /* No pass begins: no record is written before the state is read back. */
    fill_all();
    glBegin(GL_TRIANGLES);
    const GLint r = glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    glEnd();
    const bool error = piglit_check_gl_error(GL_INVALID_OPERATION) && r == 0 &&
                       get(GL_RENDER_MODE) == GL_RENDER && untouched("buffer a", a, 0, SIZE_A + GUARD);
    subtest(error && state_is_valid(), "rendermode-inside-begin-end");
}

PIGLIT_GL_TEST_CONFIG_BEGIN

    config.supports_gl_compat_version = 10;
    config.window_width = W;
    config.window_height = H;
    config.window_visual = PIGLIT_GL_VISUAL_RGBA | PIGLIT_GL_VISUAL_DEPTH | PIGLIT_GL_VISUAL_STENCIL;
    config.khr_no_error_support = PIGLIT_HAS_ERRORS;

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
    glDisable(GL_DEPTH_TEST);
    const GLint max_tiles = get(GL_MAX_OCCLUSION_TILES_MESAX);

    /* Initially no buffers are set. */
    test_rendermode_without_buffers();

    ScissorsMESAX(2, valid_tiles);
    subtest(piglit_check_gl_error(GL_NO_ERROR) && get(GL_OCCLUSION_TILE_COUNT_MESAX) == 2, "scissors-valid-sets-count");
    OcclusionBuffersMESAX(2, valid_sizes, valid_buffers);
    check_error_keeps_state(GL_NO_ERROR, "buffers-valid");

    test_scissors_errors(max_tiles);
    test_buffers_errors(max_tiles);

    /* Three tiles, two buffers: RenderMode fails and begins no pass. */
    const GLint three_tiles[12] = {1, 2, 3, 4, 8, 9, 5, 6, 0, 0, 1, 1};
    ScissorsMESAX(3, three_tiles);
    fill_all();
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    subtest(piglit_check_gl_error(GL_INVALID_OPERATION) && get(GL_RENDER_MODE) == GL_RENDER &&
                untouched("buffer a", a, 0, SIZE_A + GUARD) && untouched("buffer b", b, 0, SIZE_B + GUARD),
            "rendermode-fewer-buffers-than-tiles");
    ScissorsMESAX(2, valid_tiles);

    test_errors_inside_pass();
    test_begin_end_errors();

    /* Valid extremes of ScissorsMESAX and OcclusionBuffersMESAX. */
    GLint *many = calloc(4 * (size_t)max_tiles, sizeof(GLint));
    ScissorsMESAX(max_tiles, many);
    subtest(piglit_check_gl_error(GL_NO_ERROR) && get(GL_OCCLUSION_TILE_COUNT_MESAX) == max_tiles,
            "scissors-max-count-accepted");
    free(many);
    ScissorsMESAX(0, NULL);
    subtest(piglit_check_gl_error(GL_NO_ERROR) && get(GL_OCCLUSION_TILE_COUNT_MESAX) == 0,
            "scissors-zero-count-null-accepted");
    /* Zero buffers: the default tile has none, so no pass can begin. */
    OcclusionBuffersMESAX(0, NULL, NULL);
    const bool accepted = piglit_check_gl_error(GL_NO_ERROR);
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    subtest(accepted && piglit_check_gl_error(GL_INVALID_OPERATION) && get(GL_RENDER_MODE) == GL_RENDER,
            "buffers-zero-count-null-unsets-buffers");

    piglit_report_result(result);
}
