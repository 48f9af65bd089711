/*
 * GL_MESAX_occlusion_unit_async: pass objects and the state of a pass are
 * per context (spec MESAX_occlusion_unit_async, issue 14). A second OSMesa
 * context shares the first one's objects (a texture made in the first is a
 * texture in the second), but not its pass objects, and a pass in progress
 * in the first neither puts the second in an occlusion mode nor counts the
 * second's fragments.
 *
 * Subtests:
 *   share-group-shares-textures      sanity: glIsTexture of the first's
 *                                    texture is TRUE in the second
 *   pass-names-not-shared            IsOcclusionPassMESAX of the first's pass
 *                                    object is FALSE in the second
 *   pass-state-per-context           with a pass in progress in the first,
 *                                    the second's RENDER_MODE is RENDER and
 *                                    its quad is drawn
 *   pass-counts-own-context-only     the pass, ended in the first, counts the
 *                                    first's 8 x 8 quad only: NOHC 64
 */
#include "ou_util.h"

#include <GL/osmesa.h>

enum { W = 32, H = 32 };

int
main(int argc, char **argv)
{
    struct ou_async_functions a = ou_init_async(argc, argv, W, H);
    OSMesaContext first = OSMesaGetCurrentContext();
    static const int attribs[] = {
        OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_STENCIL_BITS, 8,
        OSMESA_PROFILE, OSMESA_COMPAT_PROFILE, 0,
    };
    static unsigned char first_buffer[W * H * 4], second_buffer[W * H * 4];
    OSMesaContext second = OSMesaCreateContextAttribs(attribs, first);
    if (!first || !second) {
        printf("could not make a second OSMesa context sharing the first's objects\n");
        piglit_report_result(PIGLIT_FAIL);
    }
    GLuint texture, pass, record[OU_BRIEF_SIZE];
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 4, 4, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    a.GenOcclusionPasses(1, &pass);
    GLuint *buffers[1] = {record};
    GLsizei sizes[1] = {OU_BRIEF_SIZE};
    OcclusionBuffersMESAX(1, sizes, buffers);
    ou_fill(record, OU_BRIEF_SIZE);
    glDisable(GL_DEPTH_TEST);
    a.BeginOcclusionPass(GL_BRIEF_OCCLUSION_MESAX, pass);
    ou_rect(0, 0, 8, 8, 0.5f);

    if (!OSMesaMakeCurrent(second, second_buffer, GL_UNSIGNED_BYTE, W, H)) {
        printf("could not make the second context current\n");
        piglit_report_result(PIGLIT_FAIL);
    }
    OSMesaPixelStore(OSMESA_Y_UP, 1);
    /* Entry points are per process with OSMesa; the projection is this
     * context's own state. */
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glOrtho(0, W, 0, H, 0, -1);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    subtest(glIsTexture(texture) == GL_TRUE, "share-group-shares-textures");
    subtest(a.IsOcclusionPass(pass) == GL_FALSE && piglit_check_gl_error(GL_NO_ERROR), "pass-names-not-shared");
    {
        GLint mode = 0;
        static const unsigned char red[4] = {255, 0, 0, 255};
        glGetIntegerv(GL_RENDER_MODE, &mode);
        glClearColor(0, 0, 0, 1);
        glClear(GL_COLOR_BUFFER_BIT);
        glDisable(GL_DEPTH_TEST);
        glColor4ub(255, 0, 0, 255);
        ou_rect(0, 0, W, H, 0.5f);
        if (mode != GL_RENDER)
            printf("the second context's RENDER_MODE is 0x%x during the first's pass\n", mode);
        subtest(mode == GL_RENDER && piglit_probe_rect_rgba_ub(0, 0, W, H, red, 0) &&
                    piglit_check_gl_error(GL_NO_ERROR),
                "pass-state-per-context");
    }

    /* Back to the first context, on a buffer of the same size. */
    if (!OSMesaMakeCurrent(first, first_buffer, GL_UNSIGNED_BYTE, W, H)) {
        printf("could not make the first context current again\n");
        piglit_report_result(PIGLIT_FAIL);
    }
    a.EndOcclusionPass();
    GLint overflowed = -1;
    a.GetOcclusionPassiv(pass, GL_OCCLUSION_PASS_RESULT_MESAX, &overflowed);
    if (record[OU_NOHC] != 64 || record[OU_PHC] != 64)
        printf("the first context's pass: NOHC %u PHC %u, expected 64 and 64\n", record[OU_NOHC], record[OU_PHC]);
    subtest(record[OU_NOHC] == 64 && record[OU_PHC] == 64 && overflowed == 0 && piglit_check_gl_error(GL_NO_ERROR),
            "pass-counts-own-context-only");

    OSMesaDestroyContext(second);
    piglit_report_result(result);
}
