/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit: commands that produce no fragments for the
 * framebuffer (GenerateMipmap, CopyTexSubImage2D) execute in an occlusion
 * pass as in RENDER mode and add nothing to the tiles; the draws with which
 * an implementation carries them out, or copies the source of a pixel
 * rectangle, are not fragments of the pass (spec section 5.X, "Commands
 * that are not drawing commands"). A depth or stencil CopyPixels counts
 * the fragments of its rectangle once, at the destination, as an occlusion
 * query counts them in RENDER mode.
 *
 * The window: 64 x 32, colour cleared to green, depth 1.0 but for an
 * occluder at depth 0.25 over the left half, stencil 5. Each pass has one
 * tile, the window (the default tile); every subtest checks the record.
 *
 * Subtests:
 *   generate-mipmap-adds-nothing     GenerateMipmap of a 64 x 64 texture in a
 *                                    pass: NOHC 0, PHC 0, empty box
 *   generate-mipmap-generates        ... and levels 1 to 6 hold level 0's red
 *                                    (they held blue before)
 *   copy-tex-sub-image-adds-nothing  CopyTexSubImage2D 16 x 16 in a pass: 0/0
 *   copy-tex-sub-image-copies        ... and the texture holds the window's
 *                                    green
 *   copy-pixels-depth-counts-once    CopyPixels DEPTH 8 x 8 from the occluder
 *                                    (0.25) to (40, 8), over depth 1.0:
 *                                    NOHC 64, PHC 64, box 40..47 x 8..15, z 0.25,
 *                                    and GL_SAMPLES_PASSED of the same command
 *                                    in RENDER mode is 64
 *   copy-pixels-stencil-counts-once  CopyPixels STENCIL 8 x 8 to (40, 8):
 *                                    64/64, box 40..47 x 8..15
 */
#include "ou_util.h"

enum { W = 64, H = 32, T = 64 };

static PFNGLGENERATEMIPMAPPROC GenerateMipmap;
static PFNGLGENQUERIESPROC GenQueries;
static PFNGLBEGINQUERYPROC BeginQuery;
static PFNGLENDQUERYPROC EndQuery;
static PFNGLGETQUERYOBJECTUIVPROC GetQueryObjectuiv;

static GLuint texture;

static void
paint_scene(void)
{
    glClearColor(0, 1, 0, 1);
    glClearDepth(1.0);
    glClearStencil(5);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    ou_rect(0, 0, W / 2, H, 0.25f);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

/* Level 0 red, levels 1..6 blue. */
static void
make_mipmapped_texture(void)
{
    static GLubyte texels[T * T * 4];
    glBindTexture(GL_TEXTURE_2D, texture);
    for (int level = 0, size = T; size >= 1; ++level, size /= 2) {
        for (int i = 0; i < size * size; ++i) {
            texels[4 * i + 0] = level == 0 ? 255 : 0;
            texels[4 * i + 1] = 0;
            texels[4 * i + 2] = level == 0 ? 0 : 255;
            texels[4 * i + 3] = 255;
        }
        glTexImage2D(GL_TEXTURE_2D, level, GL_RGBA8, size, size, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels);
    }
}

/* True when every texel of the level is (r, g, b, 255). */
static bool
level_is(int level, int size, GLubyte r, GLubyte g, GLubyte b)
{
    static GLubyte texels[T * T * 4];
    glBindTexture(GL_TEXTURE_2D, texture);
    glGetTexImage(GL_TEXTURE_2D, level, GL_RGBA, GL_UNSIGNED_BYTE, texels);
    for (int i = 0; i < size * size; ++i) {
        const GLubyte *t = &texels[4 * i];
        if (t[0] != r || t[1] != g || t[2] != b || t[3] != 255) {
            printf("level %d texel %d is (%u, %u, %u, %u), expected (%u, %u, %u, 255)\n", level, i, t[0], t[1], t[2],
                   t[3], r, g, b);
            return false;
        }
    }
    return true;
}

static void generate_mipmap(void) { glBindTexture(GL_TEXTURE_2D, texture); GenerateMipmap(GL_TEXTURE_2D); }
static void copy_tex_sub_image(void) { glBindTexture(GL_TEXTURE_2D, texture); glCopyTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 8, 8, 16, 16); }
static void copy_pixels_depth(void) { glRasterPos3f(40, 8, 0.5f); glCopyPixels(0, 0, 8, 8, GL_DEPTH); }
static void copy_pixels_stencil(void) { glRasterPos3f(40, 8, 0.5f); glCopyPixels(0, 0, 8, 8, GL_STENCIL); }

static bool
pass_record_is(const char *what, void (*command)(void), const GLuint expected[OU_BRIEF_SIZE], GLuint z_tolerance)
{
    GLuint record[1][OU_BRIEF_SIZE];
    const GLint overflowed = ou_brief_pass(0, NULL, record, command);
    const bool ok = ou_check_record(what, record[0], expected, z_tolerance);
    return ok && overflowed == 0 && piglit_check_gl_error(GL_NO_ERROR);
}

static GLuint
samples_in_render_mode(void (*command)(void))
{
    GLuint query, samples = 0xdeadbeefu;
    GenQueries(1, &query);
    BeginQuery(GL_SAMPLES_PASSED, query);
    command();
    EndQuery(GL_SAMPLES_PASSED);
    GetQueryObjectuiv(query, GL_QUERY_RESULT, &samples);
    return samples;
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
    static const GLuint nothing[OU_BRIEF_SIZE] = {0, 0, OU_EMPTY_MIN, OU_EMPTY_MAX, OU_EMPTY_MIN, OU_EMPTY_MAX,
                                                  OU_EMPTY_MIN, OU_EMPTY_MAX};
    const GLuint z = ou_depth(0.25);
    const GLuint copied_depth[OU_BRIEF_SIZE] = {64, 64, 40, 47, 8, 15, z, z};
    const GLuint copied_stencil[OU_BRIEF_SIZE] = {64, 64, 40, 47, 8, 15, 0, 0}; /* z: not compared */

    ou_init();
    GenerateMipmap = glGenerateMipmap;
    GenQueries = glGenQueries;
    BeginQuery = glBeginQuery;
    EndQuery = glEndQuery;
    GetQueryObjectuiv = glGetQueryObjectuiv;
    glGenTextures(1, &texture);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);

    paint_scene();
    if (!GenerateMipmap) {
        ou_subtest_unsupported("generate-mipmap-adds-nothing", "glGenerateMipmap");
    } else {
        make_mipmapped_texture();
        subtest(pass_record_is("GenerateMipmap", generate_mipmap, nothing, 0), "generate-mipmap-adds-nothing");
        bool generated = true;
        for (int level = 1, size = T / 2; size >= 1; ++level, size /= 2)
            generated = level_is(level, size, 255, 0, 0) && generated;
        subtest(generated, "generate-mipmap-generates");
    }

    make_mipmapped_texture();
    subtest(pass_record_is("CopyTexSubImage2D", copy_tex_sub_image, nothing, 0), "copy-tex-sub-image-adds-nothing");
    {
        static GLubyte texels[T * T * 4];
        bool copied = true;
        glBindTexture(GL_TEXTURE_2D, texture);
        glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels);
        for (int y = 0; y < 16 && copied; ++y)
            for (int x = 0; x < 16 && copied; ++x) {
                const GLubyte *t = &texels[4 * (y * T + x)];
                if (t[0] != 0 || t[1] != 255 || t[2] != 0) {
                    printf("texel (%d, %d) is (%u, %u, %u), expected the window's green\n", x, y, t[0], t[1], t[2]);
                    copied = false;
                }
            }
        subtest(copied, "copy-tex-sub-image-copies");
    }

    {
        const bool in_pass = pass_record_is("CopyPixels DEPTH", copy_pixels_depth, copied_depth,
                                            OU_Z24_READBACK_TOLERANCE);
        const GLuint samples = samples_in_render_mode(copy_pixels_depth);
        if (samples != 64)
            printf("GL_SAMPLES_PASSED of the CopyPixels in RENDER mode is %u, expected 64\n", samples);
        paint_scene();   /* the RENDER-mode copy wrote depth 0.25 at (40, 8) */
        subtest(in_pass && samples == 64, "copy-pixels-depth-counts-once");
    }

    /* Stencil rectangles take no depth test: z is the raster position's,
     * but the spec leaves it out of the comparison here (0 tolerance on
     * counts and box only). */
    {
        GLuint record[1][OU_BRIEF_SIZE];
        const GLint overflowed = ou_brief_pass(0, NULL, record, copy_pixels_stencil);
        GLuint expected[OU_BRIEF_SIZE];
        memcpy(expected, copied_stencil, sizeof(expected));
        expected[OU_ZMIN] = record[0][OU_ZMIN];
        expected[OU_ZMAX] = record[0][OU_ZMAX];
        subtest(ou_check_record("CopyPixels STENCIL", record[0], expected, 0) && overflowed == 0 &&
                    piglit_check_gl_error(GL_NO_ERROR),
                "copy-pixels-stencil-counts-once");
    }

    piglit_report_result(result);
}
