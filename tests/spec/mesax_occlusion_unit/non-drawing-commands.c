/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit: commands that are not drawing commands execute
 * in an occlusion pass as in RENDER mode and add nothing to the tiles,
 * however the GL carries them out (spec section 5.X and issue 22); Accum,
 * which writes the framebuffer, has no effect. (GenerateMipmap,
 * CopyTexSubImage2D and CopyPixels are internal-blits-not-counted's.)
 *
 * The window: 32 x 32 with an accumulation buffer, colour cleared to green,
 * depth test off; each pass has the default tile, the window, and draws
 * nothing but the command; every "-not-counted" subtest checks the record
 * (NOHC 0, PHC 0, empty box) and the command's effect.
 *
 * Subtests:
 *   read-pixels-into-pack-buffer-not-counted    the pack buffer holds the green
 *   tex-sub-image-from-unpack-buffer-not-counted  the texture holds the buffer's red
 *   copy-image-sub-data-not-counted             the destination texture holds the
 *                                               source's blue
 *   accum-has-no-effect                         Accum(RETURN) in a pass leaves the
 *                                               red colour buffer red, Accum(LOAD)
 *                                               leaves the accumulation buffer's
 *                                               green; both count nothing
 */
#include "ou_util.h"

#include <GL/osmesa.h>

enum { S = 32, T = 16 };

static PFNGLGENBUFFERSPROC GenBuffers;
static PFNGLBINDBUFFERPROC BindBuffer;
static PFNGLBUFFERDATAPROC BufferData;
static PFNGLGETBUFFERSUBDATAPROC GetBufferSubData;

static const GLuint nothing[OU_BRIEF_SIZE] = {0, 0, OU_EMPTY_MIN, OU_EMPTY_MAX, OU_EMPTY_MIN, OU_EMPTY_MAX,
                                              OU_EMPTY_MIN, OU_EMPTY_MAX};

/* Runs `command` alone in a brief pass; true when it counted nothing. */
static bool
counts_nothing(const char *name, void (*command)(void))
{
    GLuint rec[1][OU_BRIEF_SIZE];
    ou_brief_pass(0, NULL, rec, command);
    return ou_check_record(name, rec[0], nothing, 0) && piglit_check_gl_error(GL_NO_ERROR);
}

static bool
all_texels(const char *name, GLuint texture, const GLubyte expected[4])
{
    static GLubyte texels[T * T * 4];
    glBindTexture(GL_TEXTURE_2D, texture);
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels);
    for (int i = 0; i < T * T; ++i)
        if (memcmp(texels + 4 * i, expected, 4)) {
            printf("%s: texel %d is %u %u %u %u\n", name, i, texels[4 * i], texels[4 * i + 1], texels[4 * i + 2],
                   texels[4 * i + 3]);
            return false;
        }
    return true;
}

static GLuint
texture_of(const GLubyte colour[4])
{
    static GLubyte texels[T * T * 4];
    for (int i = 0; i < T * T; ++i)
        memcpy(texels + 4 * i, colour, 4);
    GLuint texture;
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, T, T, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels);
    return texture;
}

static GLuint pack_buffer, unpack_buffer, texture, source, destination;

static void
read_pixels(void)
{
    BindBuffer(GL_PIXEL_PACK_BUFFER, pack_buffer);
    glReadPixels(0, 0, S, S, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
}

static void
tex_sub_image(void)
{
    BindBuffer(GL_PIXEL_UNPACK_BUFFER, unpack_buffer);
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, T, T, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    BindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
}

static void
copy_image(void)
{
    PFNGLCOPYIMAGESUBDATAPROC CopyImageSubData =
        glCopyImageSubData;
    CopyImageSubData(source, GL_TEXTURE_2D, 0, 0, 0, 0, destination, GL_TEXTURE_2D, 0, 0, 0, 0, T, T, 1);
}

static void
accum(void)
{
    glAccum(GL_RETURN, 1.0f);
    glAccum(GL_LOAD, 0.0f);
}

PIGLIT_GL_TEST_CONFIG_BEGIN

    config.supports_gl_compat_version = 10;
    config.window_width = S;
    config.window_height = S;
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
    /* A context with an accumulation buffer, which piglit_osmesa_init's
     * has not. */
    static const int attribs[] = {
        OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_STENCIL_BITS, 8, OSMESA_ACCUM_BITS, 16,
        OSMESA_PROFILE, OSMESA_COMPAT_PROFILE, 0,
    };
    static GLubyte pixels[S * S * 4];
    OSMesaContext first = OSMesaGetCurrentContext();
    GLint first_width, first_height, first_format;
    void *first_buffer = NULL;
    OSMesaGetColorBuffer(first, &first_width, &first_height, &first_format, &first_buffer);
    OSMesaContext context = OSMesaCreateContextAttribs(attribs, NULL);
    if (!context || !OSMesaMakeCurrent(context, pixels, GL_UNSIGNED_BYTE, S, S)) {
        printf("could not make an OSMesa context with an accumulation buffer\n");
        piglit_report_result(PIGLIT_FAIL);
    }
    OSMesaPixelStore(OSMESA_Y_UP, 1);
    glViewport(0, 0, S, S);
    glMatrixMode(GL_PROJECTION);
    glOrtho(0, S, 0, S, 0, -1);
    glMatrixMode(GL_MODELVIEW);
    glDisable(GL_DEPTH_TEST);
    GenBuffers = glGenBuffers;
    BindBuffer = glBindBuffer;
    BufferData = glBufferData;
    GetBufferSubData = glGetBufferSubData;

    static const GLubyte green[4] = {0, 255, 0, 255}, red[4] = {255, 0, 0, 255}, blue[4] = {0, 0, 255, 255},
                         black[4] = {0, 0, 0, 255};
    glClearColor(0, 1, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);

    /* ReadPixels into a pixel pack buffer. */
    static GLubyte packed[S * S * 4];
    GenBuffers(1, &pack_buffer);
    BindBuffer(GL_PIXEL_PACK_BUFFER, pack_buffer);
    BufferData(GL_PIXEL_PACK_BUFFER, sizeof(packed), NULL, GL_STREAM_READ);
    BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    bool ok = counts_nothing("read-pixels-into-pack-buffer-not-counted", read_pixels);
    BindBuffer(GL_PIXEL_PACK_BUFFER, pack_buffer);
    GetBufferSubData(GL_PIXEL_PACK_BUFFER, 0, sizeof(packed), packed);
    BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    for (int i = 0; i < S * S && ok; ++i)
        if (memcmp(packed + 4 * i, green, 4)) {
            printf("read-pixels-into-pack-buffer-not-counted: pixel %d is %u %u %u %u\n", i, packed[4 * i],
                   packed[4 * i + 1], packed[4 * i + 2], packed[4 * i + 3]);
            ok = false;
        }
    subtest(ok, "read-pixels-into-pack-buffer-not-counted");

    /* TexSubImage2D from a pixel unpack buffer. */
    static GLubyte reds[T * T * 4];
    for (int i = 0; i < T * T; ++i)
        memcpy(reds + 4 * i, red, 4);
    texture = texture_of(black);
    GenBuffers(1, &unpack_buffer);
    BindBuffer(GL_PIXEL_UNPACK_BUFFER, unpack_buffer);
    BufferData(GL_PIXEL_UNPACK_BUFFER, sizeof(reds), reds, GL_STREAM_DRAW);
    BindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    ok = counts_nothing("tex-sub-image-from-unpack-buffer-not-counted", tex_sub_image);
    subtest(ok && all_texels("tex-sub-image-from-unpack-buffer-not-counted", texture, red),
            "tex-sub-image-from-unpack-buffer-not-counted");

    /* CopyImageSubData. */
    if (!piglit_is_extension_supported("GL_ARB_copy_image")) {
        ou_subtest_unsupported("copy-image-sub-data-not-counted", "GL_ARB_copy_image");
    } else {
        source = texture_of(blue);
        destination = texture_of(black);
        ok = counts_nothing("copy-image-sub-data-not-counted", copy_image);
        subtest(ok && all_texels("copy-image-sub-data-not-counted", destination, blue),
                "copy-image-sub-data-not-counted");
    }

    /* Accum: the accumulation buffer holds green, the colour buffer red. */
    glAccum(GL_LOAD, 1.0f);
    glClearColor(1, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    ok = counts_nothing("accum-has-no-effect", accum);
    const bool colour_kept = ou_probe_rect_rgba_ub(0, 0, S, S, red, 0);
    glAccum(GL_RETURN, 1.0f);
    const bool accum_kept = ou_probe_rect_rgba_ub(0, 0, S, S, green, 1);
    if (!colour_kept || !accum_kept)
        printf("accum-has-no-effect: the colour buffer %s, the accumulation buffer %s\n",
               colour_kept ? "kept" : "changed", accum_kept ? "kept" : "changed");
    subtest(ok && colour_kept && accum_kept && piglit_check_gl_error(GL_NO_ERROR), "accum-has-no-effect");

    OSMesaMakeCurrent(first, first_buffer, GL_UNSIGNED_BYTE, S, S);
    OSMesaDestroyContext(context);
    piglit_report_result(result);
}
