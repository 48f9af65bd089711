/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit: the state queries of the tiles and buffers set
 * (spec, New State and "Additions to Chapter 6"): OCCLUSION_TILE_MESAX and
 * OCCLUSION_BUFFER_SIZE_MESAX through the indexed Gets (and index 0
 * through the plain ones), OCCLUSION_BUFFER_COUNT_MESAX through the plain
 * Gets, OCCLUSION_BUFFER_POINTER_MESAX through GetPointerv (buffer 0) and
 * GetPointerIndexedvEXT / GetPointeri_vEXT (issue 19).
 *
 * Every array set has distinct entries (no two tiles, sizes or pointers
 * alike, components of a tile distinct), so a query that read the wrong
 * index, or a call that copied part of its arguments before failing, shows.
 *
 * Subtests:
 *   initial-buffer-count-0       OCCLUSION_BUFFER_COUNT_MESAX is 0
 *   initial-tiles-zero           every tile index reads (0, 0, 0, 0)
 *   initial-sizes-zero           every size index reads 0
 *   initial-pointers-null        GetPointerv and every indexed pointer: NULL
 *   tiles-read-back              ScissorsMESAX(5, ...): each tile, the count,
 *                                GetIntegerv of the tile name = tile 0
 *   tiles-past-count-zero        a later ScissorsMESAX(2, ...) zeroes 2..max-1
 *   tiles-cleared-by-count-0     ScissorsMESAX(0, NULL) zeroes all
 *   buffers-read-back-sizes      OcclusionBuffersMESAX(5, ...): count, sizes
 *   buffers-read-back-pointers   each pointer through both indexed names,
 *                                GetPointerv = buffer 0
 *   buffers-past-count-zero      a later OcclusionBuffersMESAX(2, ...) zeroes
 *                                sizes and pointers 2..max-1
 *   buffers-cleared-by-count-0   OcclusionBuffersMESAX(0, NULL, NULL) zeroes all
 *   failing-scissors-keep-tiles  each INVALID_VALUE of ScissorsMESAX leaves
 *                                count and every tile as they were
 *   failing-buffers-keep-buffers each INVALID_VALUE of OcclusionBuffersMESAX
 *                                leaves count, sizes and pointers
 *   state-during-{brief,verbose}-pass
 *                                the queries work in a pass and return the
 *                                state set; ScissorsMESAX and
 *                                OcclusionBuffersMESAX fail there with
 *                                INVALID_OPERATION and change nothing; the
 *                                state is the same after the pass
 *   default-tile-not-reported    in a pass with no tiles set, the default tile
 *                                (scissor box) is not the tile state: count 0,
 *                                tile 0 reads (0, 0, 0, 0)
 *   index-range-{tile,size,pointer}
 *                                index max - 1 works even past the count;
 *                                max and 0xFFFFFFFF give INVALID_VALUE and
 *                                write nothing
 *   wrong-type-queries           INVALID_ENUM, nothing written: the pointer
 *                                through GetIntegerv/GetIntegeri_v, the tile
 *                                and size through GetPointerv and
 *                                GetPointerIndexedvEXT, the counts through
 *                                GetIntegeri_v
 *   {tile-0,tile-3,size-3,size-5}-get{booleani,integer64i,floati,doublei}_v
 *                                the other indexed Gets convert as the
 *                                non-indexed ones do: tile 0 has a negative
 *                                x and a zero width, tile 3 a zero width,
 *                                size 3 is 2^31 - 1, size 5 (past the count)
 *                                is 0
 *   buffer-count-get{boolean,integer64,float,double}v
 *                                at 0 and at 5
 */
#include <limits.h>

#include "ou_util.h"

#define N 5

static GLint max_tiles;

static PFNGLGETINTEGERI_VPROC GetIntegeri_v;
static PFNGLGETBOOLEANI_VPROC GetBooleani_v;
static PFNGLGETINTEGER64I_VPROC GetInteger64i_v;
static PFNGLGETFLOATI_VPROC GetFloati_v;
static PFNGLGETDOUBLEI_VPROC GetDoublei_v;
static PFNGLGETINTEGER64VPROC GetInteger64v;
static PFNGLGETPOINTERINDEXEDVEXTPROC GetPointerIndexedvEXT;
static PFNGLGETPOINTERI_VEXTPROC GetPointeri_vEXT;

/* Tiles: components distinct within and across tiles; x negative, width
 * and height zero occur (all are valid). */
static const GLint tiles_a[4 * N] = {
    -5, 7, 0, 9,
    1, 2, 3, 4,
    10, 11, 12, 13,
    1000, 2000, 0, 30,
    40, 50, 60, 70,
};
static const GLint tiles_b[4 * 2] = {21, 22, 23, 24, 31, 32, 33, 34};

/* Sizes: distinct, the least (8) among them; each buffer has the words its
 * size says (the pool's rows have 32). sizes_big, set only outside passes
 * (when the GL writes no buffer), holds the largest a sizei holds. */
static const GLsizei sizes_a[N] = {9, 8, 30, 32, 17};
static const GLsizei sizes_b[2] = {12, 13};
static const GLsizei sizes_big[N] = {31, 10, 11, INT_MAX, 8};
static GLuint pool[N + 2][32];
static GLuint *buffers_a[N] = {pool[0], pool[1], pool[2], pool[3], pool[4]};
static GLuint *buffers_b[2] = {pool[5], pool[6]};

static GLint
get(GLenum pname)
{
    GLint v = -12345;
    glGetIntegerv(pname, &v);
    return v;
}

static int
gl_version(void)
{
    const char *v = (const char *)glGetString(GL_VERSION);
    int major = 0, minor = 0;
    if (v)
        sscanf(v, "%d.%d", &major, &minor);
    return 10 * major + minor;
}

/* Tile i as GetIntegeri_v reads it. */
static bool
tile_is(GLuint i, const GLint *expected)
{
    GLint v[4] = {-12345, -12345, -12345, -12345};
    GetIntegeri_v(GL_OCCLUSION_TILE_MESAX, i, v);
    if (!piglit_check_gl_error(GL_NO_ERROR))
        return false;
    if (memcmp(v, expected, sizeof(v)) != 0) {
        printf("tile %u is (%d, %d, %d, %d), expected (%d, %d, %d, %d)\n", i, v[0], v[1], v[2], v[3],
               expected[0], expected[1], expected[2], expected[3]);
        return false;
    }
    return true;
}

static bool
size_is(GLuint i, GLint expected)
{
    GLint v = -12345;
    GetIntegeri_v(GL_OCCLUSION_BUFFER_SIZE_MESAX, i, &v);
    if (!piglit_check_gl_error(GL_NO_ERROR))
        return false;
    if (v != expected) {
        printf("size %u is %d, expected %d\n", i, v, expected);
        return false;
    }
    return true;
}

/* Pointer i through GetPointerIndexedvEXT and its alias GetPointeri_vEXT. */
static bool
pointer_is(GLuint i, const void *expected)
{
    void *p = (void *)&p, *q = (void *)&q;
    GetPointerIndexedvEXT(GL_OCCLUSION_BUFFER_POINTER_MESAX, i, &p);
    GetPointeri_vEXT(GL_OCCLUSION_BUFFER_POINTER_MESAX, i, &q);
    if (!piglit_check_gl_error(GL_NO_ERROR))
        return false;
    if (p != expected || q != expected) {
        printf("pointer %u is %p (GetPointerIndexedvEXT), %p (GetPointeri_vEXT), expected %p\n", i, p, q,
               expected);
        return false;
    }
    return true;
}

static bool
pointer0_is(const void *expected)
{
    void *p = (void *)&p;
    glGetPointerv(GL_OCCLUSION_BUFFER_POINTER_MESAX, &p);
    if (!piglit_check_gl_error(GL_NO_ERROR))
        return false;
    if (p != expected) {
        printf("GetPointerv(OCCLUSION_BUFFER_POINTER_MESAX) is %p, expected %p\n", p, expected);
        return false;
    }
    return true;
}

/* The tile state: count, tiles[0..count-1], zero past them, and the plain
 * GetIntegerv of the tile name reading tile 0. */
static bool
tiles_are(GLint count, const GLint *tiles)
{
    static const GLint zero[4] = {0, 0, 0, 0};
    bool ok = true;
    const GLint c = get(GL_OCCLUSION_TILE_COUNT_MESAX);
    if (!piglit_check_gl_error(GL_NO_ERROR) || c != count) {
        printf("OCCLUSION_TILE_COUNT_MESAX is %d, expected %d\n", c, count);
        ok = false;
    }
    for (GLint i = 0; i < max_tiles && ok; ++i)
        ok = tile_is((GLuint)i, i < count ? &tiles[4 * i] : zero);

    GLint v[4] = {-12345, -12345, -12345, -12345};
    glGetIntegerv(GL_OCCLUSION_TILE_MESAX, v);
    const GLint *t0 = count > 0 ? tiles : zero;
    if (!piglit_check_gl_error(GL_NO_ERROR) || memcmp(v, t0, sizeof(v)) != 0) {
        printf("GetIntegerv(OCCLUSION_TILE_MESAX) is (%d, %d, %d, %d), expected tile 0 (%d, %d, %d, %d)\n", v[0],
               v[1], v[2], v[3], t0[0], t0[1], t0[2], t0[3]);
        ok = false;
    }
    return ok;
}

static bool
sizes_are(GLint count, const GLsizei *sizes)
{
    bool ok = true;
    const GLint c = get(GL_OCCLUSION_BUFFER_COUNT_MESAX);
    if (!piglit_check_gl_error(GL_NO_ERROR) || c != count) {
        printf("OCCLUSION_BUFFER_COUNT_MESAX is %d, expected %d\n", c, count);
        ok = false;
    }
    for (GLint i = 0; i < max_tiles && ok; ++i)
        ok = size_is((GLuint)i, i < count ? sizes[i] : 0);
    const GLint s0 = get(GL_OCCLUSION_BUFFER_SIZE_MESAX);
    if (!piglit_check_gl_error(GL_NO_ERROR) || s0 != (count > 0 ? sizes[0] : 0)) {
        printf("GetIntegerv(OCCLUSION_BUFFER_SIZE_MESAX) is %d, expected size 0 (%d)\n", s0,
               count > 0 ? sizes[0] : 0);
        ok = false;
    }
    return ok;
}

static bool
pointers_are(GLint count, GLuint *const *buffers)
{
    bool ok = pointer0_is(count > 0 ? buffers[0] : NULL);
    for (GLint i = 0; i < max_tiles && ok; ++i)
        ok = pointer_is((GLuint)i, i < count ? buffers[i] : NULL);
    return ok;
}

static bool
buffers_are(GLint count, const GLsizei *sizes, GLuint *const *buffers)
{
    return sizes_are(count, sizes) && pointers_are(count, buffers);
}

static void
test_initial(void)
{
    const GLint count = get(GL_OCCLUSION_BUFFER_COUNT_MESAX);
    bool ok = piglit_check_gl_error(GL_NO_ERROR) && count == 0;
    if (!ok)
        printf("OCCLUSION_BUFFER_COUNT_MESAX is %d\n", count);
    subtest(ok, "initial-buffer-count-0");
    subtest(tiles_are(0, NULL), "initial-tiles-zero");
    subtest(sizes_are(0, NULL), "initial-sizes-zero");
    subtest(pointers_are(0, NULL), "initial-pointers-null");
}

static void
test_tiles(void)
{
    ScissorsMESAX(N, tiles_a);
    subtest(piglit_check_gl_error(GL_NO_ERROR) && tiles_are(N, tiles_a), "tiles-read-back");
    ScissorsMESAX(2, tiles_b);
    subtest(piglit_check_gl_error(GL_NO_ERROR) && tiles_are(2, tiles_b), "tiles-past-count-zero");
    ScissorsMESAX(0, NULL);
    subtest(piglit_check_gl_error(GL_NO_ERROR) && tiles_are(0, NULL), "tiles-cleared-by-count-0");
}

static void
test_buffers(void)
{
    OcclusionBuffersMESAX(N, sizes_a, buffers_a);
    const bool set = piglit_check_gl_error(GL_NO_ERROR);
    subtest(set && sizes_are(N, sizes_a), "buffers-read-back-sizes");
    subtest(set && pointers_are(N, buffers_a), "buffers-read-back-pointers");
    OcclusionBuffersMESAX(2, sizes_b, buffers_b);
    subtest(piglit_check_gl_error(GL_NO_ERROR) && buffers_are(2, sizes_b, buffers_b), "buffers-past-count-zero");
    OcclusionBuffersMESAX(0, NULL, NULL);
    subtest(piglit_check_gl_error(GL_NO_ERROR) && buffers_are(0, NULL, NULL), "buffers-cleared-by-count-0");
}

/* Each failing call has arguments whose valid entries differ from the state
 * set, and fails on its last entry, after the valid ones. */
static void
test_failing_calls(void)
{
    ScissorsMESAX(N, tiles_a);
    OcclusionBuffersMESAX(N, sizes_a, buffers_a);

    GLint *many = malloc(sizeof(GLint) * 4 * (size_t)(max_tiles + 1));
    for (int i = 0; i < 4 * (max_tiles + 1); ++i)
        many[i] = 100 + i;
    static const GLint bad_height[4 * 3] = {91, 92, 93, 94, 95, 96, 97, 98, 99, 100, 101, -1};
    static const GLint bad_width[4 * 3] = {81, 82, 83, 84, 85, 86, 87, 88, 89, 90, -2, 91};

    bool ok = true;
    ScissorsMESAX(max_tiles + 1, many);
    ok = piglit_check_gl_error(GL_INVALID_VALUE) && tiles_are(N, tiles_a) && ok;
    ScissorsMESAX(-1, many);
    ok = piglit_check_gl_error(GL_INVALID_VALUE) && tiles_are(N, tiles_a) && ok;
    ScissorsMESAX(3, bad_height);
    ok = piglit_check_gl_error(GL_INVALID_VALUE) && tiles_are(N, tiles_a) && ok;
    ScissorsMESAX(3, bad_width);
    ok = piglit_check_gl_error(GL_INVALID_VALUE) && tiles_are(N, tiles_a) && ok;
    ScissorsMESAX(2, NULL);
    ok = piglit_check_gl_error(GL_INVALID_VALUE) && tiles_are(N, tiles_a) && ok;
    subtest(ok, "failing-scissors-keep-tiles");

    GLsizei *many_sizes = malloc(sizeof(GLsizei) * (size_t)(max_tiles + 1));
    GLuint **many_buffers = malloc(sizeof(GLuint *) * (size_t)(max_tiles + 1));
    for (int i = 0; i <= max_tiles; ++i) {
        many_sizes[i] = 10 + i % 20;
        many_buffers[i] = pool[5 + i % 2];
    }
    const GLsizei small_last[3] = {18, 19, 7};
    GLuint *const null_last[3] = {pool[6], pool[5], NULL};
    const GLsizei sizes_c[3] = {20, 21, 22};
    GLuint *const buffers_c[3] = {pool[6], pool[5], pool[6]};

    ok = true;
    OcclusionBuffersMESAX(max_tiles + 1, many_sizes, many_buffers);
    ok = piglit_check_gl_error(GL_INVALID_VALUE) && buffers_are(N, sizes_a, buffers_a) && ok;
    OcclusionBuffersMESAX(-1, many_sizes, many_buffers);
    ok = piglit_check_gl_error(GL_INVALID_VALUE) && buffers_are(N, sizes_a, buffers_a) && ok;
    OcclusionBuffersMESAX(3, small_last, buffers_c);
    ok = piglit_check_gl_error(GL_INVALID_VALUE) && buffers_are(N, sizes_a, buffers_a) && ok;
    OcclusionBuffersMESAX(3, sizes_c, null_last);
    ok = piglit_check_gl_error(GL_INVALID_VALUE) && buffers_are(N, sizes_a, buffers_a) && ok;
    OcclusionBuffersMESAX(3, NULL, buffers_c);
    ok = piglit_check_gl_error(GL_INVALID_VALUE) && buffers_are(N, sizes_a, buffers_a) && ok;
    OcclusionBuffersMESAX(3, sizes_c, NULL);
    ok = piglit_check_gl_error(GL_INVALID_VALUE) && buffers_are(N, sizes_a, buffers_a) && ok;
    subtest(ok, "failing-buffers-keep-buffers");

    free(many);
    free(many_sizes);
    free(many_buffers);
    ScissorsMESAX(0, NULL);
    OcclusionBuffersMESAX(0, NULL, NULL);
}

static void
test_during_pass(GLenum mode, const char *name)
{
    ScissorsMESAX(N, tiles_a);
    OcclusionBuffersMESAX(N, sizes_a, buffers_a);
    glRenderMode(mode);
    bool ok = piglit_check_gl_error(GL_NO_ERROR) && get(GL_RENDER_MODE) == (GLint)mode;
    ok = ok && tiles_are(N, tiles_a) && buffers_are(N, sizes_a, buffers_a);
    ScissorsMESAX(2, tiles_b);
    ok = piglit_check_gl_error(GL_INVALID_OPERATION) && ok;
    OcclusionBuffersMESAX(2, sizes_b, buffers_b);
    ok = piglit_check_gl_error(GL_INVALID_OPERATION) && ok;
    ScissorsMESAX(0, NULL);
    ok = piglit_check_gl_error(GL_INVALID_OPERATION) && ok;
    ok = ok && tiles_are(N, tiles_a) && buffers_are(N, sizes_a, buffers_a);
    glRenderMode(GL_RENDER);
    ok = piglit_check_gl_error(GL_NO_ERROR) && ok;
    ok = ok && tiles_are(N, tiles_a) && buffers_are(N, sizes_a, buffers_a);
    subtest(ok, name);
    ScissorsMESAX(0, NULL);
    OcclusionBuffersMESAX(0, NULL, NULL);
}

static void
test_default_tile(void)
{
    OcclusionBuffersMESAX(1, sizes_b, buffers_b);
    glScissor(1, 2, 3, 4);
    glEnable(GL_SCISSOR_TEST);
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    bool ok = piglit_check_gl_error(GL_NO_ERROR) && tiles_are(0, NULL);
    glRenderMode(GL_RENDER);
    glDisable(GL_SCISSOR_TEST);
    glScissor(0, 0, piglit_width, piglit_height);
    ok = piglit_check_gl_error(GL_NO_ERROR) && ok;
    subtest(ok, "default-tile-not-reported");
    OcclusionBuffersMESAX(0, NULL, NULL);
}

/* An index out of range: INVALID_VALUE, nothing written. */
static bool
index_invalid(GLenum pname, GLuint index)
{
    if (pname == GL_OCCLUSION_BUFFER_POINTER_MESAX) {
        void *p = (void *)&p, *q = (void *)&q;
        GetPointerIndexedvEXT(pname, index, &p);
        bool ok = piglit_check_gl_error(GL_INVALID_VALUE);
        GetPointeri_vEXT(pname, index, &q);
        ok = piglit_check_gl_error(GL_INVALID_VALUE) && ok;
        if (p != (void *)&p || q != (void *)&q) {
            printf("pointer of index %u written: %p, %p\n", index, p, q);
            ok = false;
        }
        return ok;
    }
    GLint v[4] = {-12345, -12345, -12345, -12345};
    GLint64 v64[4] = {-12345, -12345, -12345, -12345};
    GetIntegeri_v(pname, index, v);
    bool ok = piglit_check_gl_error(GL_INVALID_VALUE);
    GetInteger64i_v(pname, index, v64);
    ok = piglit_check_gl_error(GL_INVALID_VALUE) && ok;
    for (int k = 0; k < 4; ++k) {
        if (v[k] != -12345 || v64[k] != -12345) {
            printf("0x%x of index %u written\n", pname, index);
            ok = false;
        }
    }
    return ok;
}

static void
test_index_range(void)
{
    static const GLint zero[4] = {0, 0, 0, 0};
    ScissorsMESAX(N, tiles_a);
    OcclusionBuffersMESAX(N, sizes_a, buffers_a);
    const GLuint last = (GLuint)max_tiles - 1;

    subtest(tile_is(last, zero) && index_invalid(GL_OCCLUSION_TILE_MESAX, (GLuint)max_tiles) &&
                index_invalid(GL_OCCLUSION_TILE_MESAX, 0xffffffffu),
            "index-range-tile");
    subtest(size_is(last, 0) && index_invalid(GL_OCCLUSION_BUFFER_SIZE_MESAX, (GLuint)max_tiles) &&
                index_invalid(GL_OCCLUSION_BUFFER_SIZE_MESAX, 0xffffffffu),
            "index-range-size");
    subtest(pointer_is(last, NULL) && index_invalid(GL_OCCLUSION_BUFFER_POINTER_MESAX, (GLuint)max_tiles) &&
                index_invalid(GL_OCCLUSION_BUFFER_POINTER_MESAX, 0xffffffffu),
            "index-range-pointer");
    ScissorsMESAX(0, NULL);
    OcclusionBuffersMESAX(0, NULL, NULL);
}

static bool
int_get_invalid_enum(GLenum pname, bool indexed)
{
    GLint v[4] = {-12345, -12345, -12345, -12345};
    if (indexed)
        GetIntegeri_v(pname, 0, v);
    else
        glGetIntegerv(pname, v);
    const bool ok = piglit_check_gl_error(GL_INVALID_ENUM) && v[0] == -12345 && v[1] == -12345;
    if (!ok)
        printf("GetInteger%sv(0x%x%s): value %s\n", indexed ? "i_" : "", pname, indexed ? ", 0" : "",
               v[0] == -12345 ? "untouched" : "written");
    return ok;
}

static bool
pointer_get_invalid_enum(GLenum pname)
{
    void *p = (void *)&p, *q = (void *)&q;
    glGetPointerv(pname, &p);
    bool ok = piglit_check_gl_error(GL_INVALID_ENUM);
    GetPointerIndexedvEXT(pname, 0, &q);
    ok = piglit_check_gl_error(GL_INVALID_ENUM) && ok;
    if (p != (void *)&p || q != (void *)&q) {
        printf("GetPointerv / GetPointerIndexedvEXT(0x%x) wrote a pointer\n", pname);
        ok = false;
    }
    return ok;
}

static void
test_wrong_types(void)
{
    ScissorsMESAX(N, tiles_a);
    OcclusionBuffersMESAX(N, sizes_a, buffers_a);
    bool ok = int_get_invalid_enum(GL_OCCLUSION_BUFFER_POINTER_MESAX, false);
    ok = int_get_invalid_enum(GL_OCCLUSION_BUFFER_POINTER_MESAX, true) && ok;
    ok = int_get_invalid_enum(GL_OCCLUSION_BUFFER_COUNT_MESAX, true) && ok;
    ok = int_get_invalid_enum(GL_OCCLUSION_TILE_COUNT_MESAX, true) && ok;
    ok = int_get_invalid_enum(GL_MAX_OCCLUSION_TILES_MESAX, true) && ok;
    ok = pointer_get_invalid_enum(GL_OCCLUSION_TILE_MESAX) && ok;
    ok = pointer_get_invalid_enum(GL_OCCLUSION_BUFFER_SIZE_MESAX) && ok;
    ok = pointer_get_invalid_enum(GL_OCCLUSION_BUFFER_COUNT_MESAX) && ok;
    subtest(ok, "wrong-type-queries");
    ScissorsMESAX(0, NULL);
    OcclusionBuffersMESAX(0, NULL, NULL);
}

/* GetBooleani_v, GetInteger64i_v, GetFloati_v and GetDoublei_v of `count`
 * components of `pname` at `index`, against `expected`. */
static void
check_indexed_forms(GLenum pname, const char *name, int count, GLuint index, const GLint *expected)
{
    char subtest_name[64];
    GLboolean b[4];
    GLint64 i64[4];
    GLfloat f[4];
    GLdouble d[4];
    bool ok;

    memset(b, 0x7f, sizeof(b));   /* neither GL_FALSE nor GL_TRUE */
    GetBooleani_v(pname, index, b);
    ok = piglit_check_gl_error(GL_NO_ERROR);
    for (int k = 0; k < count; ++k) {
        if (b[k] != (expected[k] ? GL_TRUE : GL_FALSE)) {
            printf("GetBooleani_v(%s, %u)[%d] is %d, expected from %d\n", name, index, k, b[k], expected[k]);
            ok = false;
        }
    }
    snprintf(subtest_name, sizeof(subtest_name), "%s-getbooleani_v", name);
    subtest(ok, subtest_name);

    snprintf(subtest_name, sizeof(subtest_name), "%s-getinteger64i_v", name);
    if (!GetInteger64i_v) {
        ou_subtest_unsupported(subtest_name, "OpenGL 3.2 (GetInteger64i_v)");
    } else {
        for (int k = 0; k < 4; ++k)
            i64[k] = -12345;
        GetInteger64i_v(pname, index, i64);
        ok = piglit_check_gl_error(GL_NO_ERROR);
        for (int k = 0; k < count; ++k) {
            if (i64[k] != expected[k]) {
                printf("GetInteger64i_v(%s, %u)[%d] is %lld, expected %d\n", name, index, k, (long long)i64[k],
                       expected[k]);
                ok = false;
            }
        }
        subtest(ok, subtest_name);
    }

    snprintf(subtest_name, sizeof(subtest_name), "%s-getfloati_v", name);
    if (!GetFloati_v) {
        ou_subtest_unsupported(subtest_name, "ARB_viewport_array (GetFloati_v)");
    } else {
        for (int k = 0; k < 4; ++k)
            f[k] = -12345.0f;
        GetFloati_v(pname, index, f);
        ok = piglit_check_gl_error(GL_NO_ERROR);
        for (int k = 0; k < count; ++k) {
            if (f[k] != (GLfloat)expected[k]) {
                printf("GetFloati_v(%s, %u)[%d] is %.9g, expected %d\n", name, index, k, f[k], expected[k]);
                ok = false;
            }
        }
        subtest(ok, subtest_name);
    }

    snprintf(subtest_name, sizeof(subtest_name), "%s-getdoublei_v", name);
    if (!GetDoublei_v) {
        ou_subtest_unsupported(subtest_name, "ARB_viewport_array (GetDoublei_v)");
    } else {
        for (int k = 0; k < 4; ++k)
            d[k] = -12345.0;
        GetDoublei_v(pname, index, d);
        ok = piglit_check_gl_error(GL_NO_ERROR);
        for (int k = 0; k < count; ++k) {
            if (d[k] != (GLdouble)expected[k]) {
                printf("GetDoublei_v(%s, %u)[%d] is %.17g, expected %d\n", name, index, k, d[k], expected[k]);
                ok = false;
            }
        }
        subtest(ok, subtest_name);
    }
}

/* The plain Gets of OCCLUSION_BUFFER_COUNT_MESAX against `expected`. */
static bool
buffer_count_forms(GLint expected, int form)
{
    GLboolean b = 0x7f;
    GLint64 i64 = -12345;
    GLfloat f = -12345.0f;
    GLdouble d = -12345.0;
    bool ok;
    switch (form) {
    case 0:
        glGetBooleanv(GL_OCCLUSION_BUFFER_COUNT_MESAX, &b);
        ok = b == (expected ? GL_TRUE : GL_FALSE);
        break;
    case 1:
        GetInteger64v(GL_OCCLUSION_BUFFER_COUNT_MESAX, &i64);
        ok = i64 == expected;
        break;
    case 2:
        glGetFloatv(GL_OCCLUSION_BUFFER_COUNT_MESAX, &f);
        ok = f == (GLfloat)expected;
        break;
    default:
        glGetDoublev(GL_OCCLUSION_BUFFER_COUNT_MESAX, &d);
        ok = d == (GLdouble)expected;
        break;
    }
    ok = piglit_check_gl_error(GL_NO_ERROR) && ok;
    if (!ok)
        printf("form %d of OCCLUSION_BUFFER_COUNT_MESAX: boolean %d, int64 %lld, float %g, double %g; expected %d\n",
               form, b, (long long)i64, f, d, expected);
    return ok;
}

static void
test_get_forms(void)
{
    ScissorsMESAX(N, tiles_a);
    OcclusionBuffersMESAX(N, sizes_a, buffers_a);
    check_indexed_forms(GL_OCCLUSION_TILE_MESAX, "tile-0", 4, 0, &tiles_a[0]);
    check_indexed_forms(GL_OCCLUSION_TILE_MESAX, "tile-3", 4, 3, &tiles_a[12]);
    OcclusionBuffersMESAX(N, sizes_big, buffers_a);
    check_indexed_forms(GL_OCCLUSION_BUFFER_SIZE_MESAX, "size-3", 1, 3, &sizes_big[3]);
    static const GLint zero = 0;
    check_indexed_forms(GL_OCCLUSION_BUFFER_SIZE_MESAX, "size-5", 1, 5, &zero);

    static const char *forms[] = {"getbooleanv", "getinteger64v", "getfloatv", "getdoublev"};
    char subtest_name[64];
    for (int form = 0; form < 4; ++form) {
        snprintf(subtest_name, sizeof(subtest_name), "buffer-count-%s", forms[form]);
        if (form == 1 && !GetInteger64v) {
            ou_subtest_unsupported(subtest_name, "OpenGL 3.2 (GetInteger64v)");
            continue;
        }
        bool ok = buffer_count_forms(N, form);
        OcclusionBuffersMESAX(0, NULL, NULL);
        ok = buffer_count_forms(0, form) && ok;
        OcclusionBuffersMESAX(N, sizes_a, buffers_a);
        subtest(ok, subtest_name);
    }
    ScissorsMESAX(0, NULL);
    OcclusionBuffersMESAX(0, NULL, NULL);
}

PIGLIT_GL_TEST_CONFIG_BEGIN

    config.supports_gl_compat_version = 10;
    config.window_width = 16;
    config.window_height = 16;
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

    const int version = gl_version();
    if (version < 30) {
        ou_subtest_unsupported("state-queries", "OpenGL 3.0 (GetIntegeri_v, GetBooleani_v)");
        piglit_report_result(result);
    }
    if (!piglit_is_extension_supported("GL_EXT_direct_state_access")) {
        /* Without it the pointers past the first have no query (issue 19). */
        ou_subtest_unsupported("state-queries", "EXT_direct_state_access (GetPointerIndexedvEXT)");
        piglit_report_result(result);
    }
    GetIntegeri_v = glGetIntegeri_v;
    GetBooleani_v = glGetBooleani_v;
    GetPointerIndexedvEXT = glGetPointerIndexedvEXT;
    GetPointeri_vEXT = glGetPointeri_vEXT;
    if (version >= 32) {
        GetInteger64i_v = glGetInteger64i_v;
        GetInteger64v = glGetInteger64v;
    }
    if (version >= 41 || piglit_is_extension_supported("GL_ARB_viewport_array")) {
        GetFloati_v = glGetFloati_v;
        GetDoublei_v = glGetDoublei_v;
    }
    if (!GetIntegeri_v || !GetBooleani_v || !GetPointerIndexedvEXT || !GetPointeri_vEXT) {
        printf("an entry point of OpenGL 3.0 or EXT_direct_state_access is missing\n");
        piglit_report_result(PIGLIT_FAIL);
    }

    max_tiles = get(GL_MAX_OCCLUSION_TILES_MESAX);
    if (!piglit_check_gl_error(GL_NO_ERROR) || max_tiles < 64) {
        printf("MAX_OCCLUSION_TILES_MESAX is %d\n", max_tiles);
        piglit_report_result(PIGLIT_FAIL);
    }

    test_initial();
    test_tiles();
    test_buffers();
    test_failing_calls();
    test_during_pass(GL_BRIEF_OCCLUSION_MESAX, "state-during-brief-pass");
    test_during_pass(GL_VERBOSE_OCCLUSION_MESAX, "state-during-verbose-pass");
    test_default_tile();
    test_index_range();
    test_wrong_types();
    test_get_forms();

    piglit_report_result(result);
}
