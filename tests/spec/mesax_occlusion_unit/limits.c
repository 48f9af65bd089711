/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit: the extension string, the entry points, the
 * limits and the initial state of New State / New Implementation Dependent
 * State, through every Get command the spec names.
 *
 * Subtests:
 *   entry-points                   glScissorsMESAX and glOcclusionBuffersMESAX
 *                                  resolve and act: a tile count set by one is
 *                                  read back, a pass entered with a buffer set
 *                                  by the other writes its record
 *   max-tiles-at-least-64          MAX_OCCLUSION_TILES_MESAX >= 64
 *   max-tiles-4096-on-occu-drivers with -tiles-4096: llvmpipe and softpipe
 *                                  report at least 4096 (their limit, not the
 *                                  spec's: llvmpipe's per-bin tile lists keep
 *                                  its cost per fragment independent of the
 *                                  tile count)
 *   tile-count-initially-0         OCCLUSION_TILE_COUNT_MESAX == 0
 *   render-mode-initially-render
 *   max-tiles-get{boolean,float,double}v
 *                                  the other Get commands return the limit
 *                                  GetIntegerv returns, converted as section
 *                                  6.1.2 of OpenGL 2.1 converts integers
 *                                  (a non-zero integer is TRUE)
 *   tile-count-0-get{boolean,float,double}v
 *   tile-count-3-get{boolean,float,double}v
 *                                  the same for the tile count at 0 and at 3,
 *                                  so that both boolean values are seen
 */
#include "ou_util.h"

static GLint
get_integer(GLenum pname)
{
    GLint v = -12345;
    glGetIntegerv(pname, &v);
    return v;
}

/* GetBooleanv, GetFloatv and GetDoublev of `pname` against GetIntegerv's
 * `expected`; one subtest per command. */
static void
check_other_gets(GLenum pname, const char *name, GLint expected)
{
    char subtest_name[64];
    GLboolean b = 0x7f;   /* neither GL_FALSE nor GL_TRUE */
    GLfloat f = -12345.0f;
    GLdouble d = -12345.0;

    glGetBooleanv(pname, &b);
    bool ok = piglit_check_gl_error(GL_NO_ERROR) && b == (expected ? GL_TRUE : GL_FALSE);
    if (!ok)
        printf("GetBooleanv(%s) is %d, GetIntegerv %d\n", name, b, expected);
    snprintf(subtest_name, sizeof(subtest_name), "%s-getbooleanv", name);
    subtest(ok, subtest_name);

    glGetFloatv(pname, &f);
    ok = piglit_check_gl_error(GL_NO_ERROR) && f == (GLfloat)expected;
    if (!ok)
        printf("GetFloatv(%s) is %g, GetIntegerv %d\n", name, f, expected);
    snprintf(subtest_name, sizeof(subtest_name), "%s-getfloatv", name);
    subtest(ok, subtest_name);

    glGetDoublev(pname, &d);
    ok = piglit_check_gl_error(GL_NO_ERROR) && d == (GLdouble)expected;
    if (!ok)
        printf("GetDoublev(%s) is %g, GetIntegerv %d\n", name, d, expected);
    snprintf(subtest_name, sizeof(subtest_name), "%s-getdoublev", name);
    subtest(ok, subtest_name);
}

/* The entry points act on the GL: a dispatch stub that exists for any name
 * would resolve too, so resolving alone proves nothing. */
static bool
entry_points_work(void)
{
    if (!ou_resolve_entry_points()) {
        printf("glScissorsMESAX %p, glOcclusionBuffersMESAX %p\n", (void *)ScissorsMESAX,
               (void *)OcclusionBuffersMESAX);
        return false;
    }
    const GLint tile[4] = {0, 0, 2, 2};
    ScissorsMESAX(1, tile);
    const GLint count = get_integer(GL_OCCLUSION_TILE_COUNT_MESAX);

    GLuint record[OU_BRIEF_SIZE];
    GLuint *buffers[1] = {record};
    const GLsizei size = OU_BRIEF_SIZE;
    ou_fill(record, OU_BRIEF_SIZE);
    OcclusionBuffersMESAX(1, &size, buffers);
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    const GLint mode = get_integer(GL_RENDER_MODE);
    glRenderMode(GL_RENDER);
    ScissorsMESAX(0, NULL);
    OcclusionBuffersMESAX(0, NULL, NULL);

    /* Nothing was drawn: NOHC and PHC are 0 in a written record. */
    const bool ok = piglit_check_gl_error(GL_NO_ERROR) && count == 1 && mode == GL_BRIEF_OCCLUSION_MESAX &&
                    record[OU_NOHC] == 0 && record[OU_PHC] == 0;
    if (!ok)
        printf("tile count %d (expected 1), render mode 0x%x, record NOHC 0x%08x PHC 0x%08x\n", count, mode,
               record[OU_NOHC], record[OU_PHC]);
    return ok;
}

PIGLIT_GL_TEST_CONFIG_BEGIN

    config.supports_gl_compat_version = 10;
    config.window_width = 16;
    config.window_height = 16;
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
    const bool tiles_4096 = ou_take_flag(&argc, argv, "-tiles-4096");
    ou_init_context();

    /* The initial state first: entry-points changes and restores it. */
    const GLint max_tiles = get_integer(GL_MAX_OCCLUSION_TILES_MESAX);
    bool ok = piglit_check_gl_error(GL_NO_ERROR) && max_tiles >= 64;
    if (!ok)
        printf("MAX_OCCLUSION_TILES_MESAX is %d\n", max_tiles);
    subtest(ok, "max-tiles-at-least-64");

    if (tiles_4096 && ou_driver_is_patched()) {
        ok = max_tiles >= 4096;
        if (!ok)
            printf("%s reports MAX_OCCLUSION_TILES_MESAX %d, expected at least 4096\n",
                   (const char *)glGetString(GL_RENDERER), max_tiles);
        subtest(ok, "max-tiles-4096-on-occu-drivers");
    }

    const GLint count = get_integer(GL_OCCLUSION_TILE_COUNT_MESAX);
    ok = piglit_check_gl_error(GL_NO_ERROR) && count == 0;
    if (!ok)
        printf("OCCLUSION_TILE_COUNT_MESAX is %d\n", count);
    subtest(ok, "tile-count-initially-0");

    subtest(get_integer(GL_RENDER_MODE) == GL_RENDER, "render-mode-initially-render");

    check_other_gets(GL_MAX_OCCLUSION_TILES_MESAX, "max-tiles", max_tiles);

    /* Tile count 0 (FALSE), then 3 (TRUE) read by every command. */
    bool entered = entry_points_work();
    subtest(entered, "entry-points");
    if (entered) {
        check_other_gets(GL_OCCLUSION_TILE_COUNT_MESAX, "tile-count-0", 0);
        const GLint three[12] = {0, 0, 1, 1, 1, 1, 1, 1, 2, 2, 1, 1};
        ScissorsMESAX(3, three);
        check_other_gets(GL_OCCLUSION_TILE_COUNT_MESAX, "tile-count-3", 3);
        ScissorsMESAX(0, NULL);
    }

    piglit_report_result(result);
}
