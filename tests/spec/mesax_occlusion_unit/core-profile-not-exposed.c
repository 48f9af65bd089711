/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit is exposed in compatibility contexts only
 * (section "Dependencies on the compatibility profile"): in a core context
 * its enums are unknown, so the Gets of its state raise INVALID_ENUM and
 * leave the caller's memory alone, and the extension is not listed.
 *
 * The test's context is a 3.2 core one; limits.c shows the extension
 * and MAX_OCCLUSION_TILES_MESAX >= 64 in a compatibility context of the same
 * driver.
 *
 * Subtests:
 *   core-extension-not-listed          not among GL_EXTENSIONS (GetStringi)
 *   core-get-max-tiles-invalid-enum    GetIntegerv(MAX_OCCLUSION_TILES_MESAX)
 *   core-get-tile-count-invalid-enum   GetIntegerv(OCCLUSION_TILE_COUNT_MESAX)
 *   core-getfloat-invalid-enum         GetFloatv of both
 *   core-get-buffer-count-invalid-enum GetIntegerv(OCCLUSION_BUFFER_COUNT_MESAX)
 *   core-get-tile-invalid-enum         GetIntegerv and GetIntegeri_v(.., 0) of
 *                                      OCCLUSION_TILE_MESAX
 *   core-get-buffer-size-invalid-enum  the same for OCCLUSION_BUFFER_SIZE_MESAX
 *   core-get-buffer-pointer-invalid-enum
 *                                      GetPointerv(OCCLUSION_BUFFER_POINTER_MESAX)
 */
#include "ou_util.h"

static bool
get_is_invalid_enum(GLenum pname, bool as_float)
{
    GLint i = -12345;
    GLfloat f = -12345.0f;
    while (glGetError() != GL_NO_ERROR)
        ;
    if (as_float)
        glGetFloatv(pname, &f);
    else
        glGetIntegerv(pname, &i);
    const GLenum error = glGetError();
    const bool untouched = as_float ? f == -12345.0f : i == -12345;
    if (error != GL_INVALID_ENUM || !untouched)
        printf("Get 0x%x: error 0x%x, value %s\n", pname, error, untouched ? "untouched" : "written");
    return error == GL_INVALID_ENUM && untouched;
}

static bool
get_indexed_is_invalid_enum(PFNGLGETINTEGERI_VPROC GetIntegeri_v, GLenum pname)
{
    GLint v[4] = {-12345, -12345, -12345, -12345};
    while (glGetError() != GL_NO_ERROR)
        ;
    GetIntegeri_v(pname, 0, v);
    const GLenum error = glGetError();
    const bool untouched = v[0] == -12345 && v[1] == -12345;
    if (error != GL_INVALID_ENUM || !untouched)
        printf("GetIntegeri_v 0x%x: error 0x%x, value %s\n", pname, error, untouched ? "untouched" : "written");
    return error == GL_INVALID_ENUM && untouched;
}

static bool
get_pointer_is_invalid_enum(GLenum pname)
{
    void *p = (void *)&p;
    while (glGetError() != GL_NO_ERROR)
        ;
    glGetPointerv(pname, &p);
    const GLenum error = glGetError();
    const bool untouched = p == (void *)&p;
    if (error != GL_INVALID_ENUM || !untouched)
        printf("GetPointerv 0x%x: error 0x%x, value %s\n", pname, error, untouched ? "untouched" : "written");
    return error == GL_INVALID_ENUM && untouched;
}

PIGLIT_GL_TEST_CONFIG_BEGIN

    config.supports_gl_core_version = 32;
    config.window_width = 8;
    config.window_height = 8;
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
    /* softpipe and llvmpipe both make 3.2 core contexts: the framework
     * fails the test where it cannot. */
    printf("%s, %s\n", (const char *)glGetString(GL_VERSION), (const char *)glGetString(GL_RENDERER));
    PFNGLGETSTRINGIPROC GetStringi = glGetStringi;
    GLint count = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &count);
    bool listed = false;
    for (GLint k = 0; k < count; ++k)
        listed = listed || strcmp((const char *)GetStringi(GL_EXTENSIONS, (GLuint)k), "GL_MESAX_occlusion_unit") == 0;
    subtest(count > 0 && !listed, "core-extension-not-listed");
    subtest(get_is_invalid_enum(GL_MAX_OCCLUSION_TILES_MESAX, false), "core-get-max-tiles-invalid-enum");
    subtest(get_is_invalid_enum(GL_OCCLUSION_TILE_COUNT_MESAX, false), "core-get-tile-count-invalid-enum");
    subtest(get_is_invalid_enum(GL_MAX_OCCLUSION_TILES_MESAX, true) &&
                get_is_invalid_enum(GL_OCCLUSION_TILE_COUNT_MESAX, true),
            "core-getfloat-invalid-enum");
    subtest(get_is_invalid_enum(GL_OCCLUSION_BUFFER_COUNT_MESAX, false), "core-get-buffer-count-invalid-enum");
    PFNGLGETINTEGERI_VPROC GetIntegeri_v = glGetIntegeri_v;
    subtest(get_is_invalid_enum(GL_OCCLUSION_TILE_MESAX, false) &&
                get_indexed_is_invalid_enum(GetIntegeri_v, GL_OCCLUSION_TILE_MESAX),
            "core-get-tile-invalid-enum");
    subtest(get_is_invalid_enum(GL_OCCLUSION_BUFFER_SIZE_MESAX, false) &&
                get_indexed_is_invalid_enum(GetIntegeri_v, GL_OCCLUSION_BUFFER_SIZE_MESAX),
            "core-get-buffer-size-invalid-enum");
    subtest(get_pointer_is_invalid_enum(GL_OCCLUSION_BUFFER_POINTER_MESAX), "core-get-buffer-pointer-invalid-enum");
    piglit_report_result(result);
}
