/*
 * GL_MESAX_occlusion_unit's state is per context, and
 * GL_MESAX_occlusion_unit_async's pass objects are not shared (spec
 * MESAX_occlusion_unit section 5.X and issue 23; MESAX_occlusion_unit_async
 * section 5.X.1 and issue 14). Context A is the test's; context B shares
 * A's objects (OSMesa share list) and renders into a buffer of the same
 * size. Depth tests are off: every fragment passes.
 *
 * Subtests:
 *   share-group-shares-textures     sanity: a texture made in A is a texture in B
 *   tiles-per-context               tiles and buffers set in A are not B's, nor B's A's
 *   render-mode-per-context         while A is in a pass, B is in RENDER mode
 *   other-context-renders           B draws a 32 x 32 white rectangle into its buffer
 *                                   during A's pass, and binds framebuffers freely
 *   pass-counts-own-context-only    A's record counts A's 8 x 8 rectangle only
 *                                   (NOHC 64), not B's draw
 *   pass-names-not-shared           a name generated in A is no pass object in B;
 *                                   B deleting it leaves A's object
 *   same-name-different-objects     B's own object of the same name is not A's:
 *                                   B's pass ended leaves A's object never begun
 *   async-pass-state-per-context    with a pass begun by BeginOcclusionPassMESAX in
 *                                   progress in A, B's RENDER_MODE is RENDER and
 *                                   B's rectangle is drawn
 *   async-pass-counts-own-context-only  that pass, ended in A, counts A's 8 x 8
 *                                   rectangle only: NOHC 64, PHC 64
 */
#include "ou_util.h"

#include <GL/osmesa.h>

enum { S = 32 };

static OSMesaContext a_context, b_context;
static GLubyte b_pixels[S * S * 4];
static void *a_buffer;

static bool
make_current(OSMesaContext context, void *buffer)
{
    if (!OSMesaMakeCurrent(context, buffer, GL_UNSIGNED_BYTE, S, S)) {
        printf("OSMesaMakeCurrent failed\n");
        return false;
    }
    OSMesaPixelStore(OSMESA_Y_UP, 1);
    return true;
}

static GLint
get_integer(GLenum pname)
{
    GLint v = -1;
    glGetIntegerv(pname, &v);
    return v;
}

int main(int argc, char **argv)
{
    const struct ou_async_functions as = ou_init_async(argc, argv, S, S);
    a_context = OSMesaGetCurrentContext();
    GLint width, height, format;
    if (!OSMesaGetColorBuffer(a_context, &width, &height, &format, &a_buffer)) {
        printf("OSMesaGetColorBuffer failed\n");
        piglit_report_result(PIGLIT_FAIL);
    }
    static const int attribs[] = {
        OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_STENCIL_BITS, 8,
        OSMESA_PROFILE, OSMESA_COMPAT_PROFILE, 0,
    };
    b_context = OSMesaCreateContextAttribs(attribs, a_context);
    if (!b_context || !make_current(b_context, b_pixels)) {
        printf("could not make a second context sharing the first\n");
        piglit_report_result(PIGLIT_FAIL);
    }
    glViewport(0, 0, S, S);
    glMatrixMode(GL_PROJECTION);
    glOrtho(0, S, 0, S, 0, -1);
    glMatrixMode(GL_MODELVIEW);
    glDisable(GL_DEPTH_TEST);
    const GLint b_tiles[4] = {0, 0, 4, 4};
    ScissorsMESAX(1, b_tiles);
    make_current(a_context, a_buffer);
    glDisable(GL_DEPTH_TEST);

    /* The share group is real: what the extension's state does not share,
     * a texture does. */
    GLuint texture;
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 4, 4, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    make_current(b_context, b_pixels);
    const bool shared_texture = glIsTexture(texture) == GL_TRUE;
    make_current(a_context, a_buffer);
    subtest(shared_texture && piglit_check_gl_error(GL_NO_ERROR), "share-group-shares-textures");

    /* A's tiles and buffers. */
    const GLint a_tiles[8] = {0, 0, S, S, 0, 0, 16, 16};
    GLuint records[2][OU_BRIEF_SIZE];
    GLuint *buffers[2] = {records[0], records[1]};
    GLsizei sizes[2] = {OU_BRIEF_SIZE, OU_BRIEF_SIZE};
    ScissorsMESAX(2, a_tiles);
    OcclusionBuffersMESAX(2, sizes, buffers);
    const bool a_state = get_integer(GL_OCCLUSION_TILE_COUNT_MESAX) == 2 &&
                         get_integer(GL_OCCLUSION_BUFFER_COUNT_MESAX) == 2;
    make_current(b_context, b_pixels);
    const bool b_state = get_integer(GL_OCCLUSION_TILE_COUNT_MESAX) == 1 &&
                         get_integer(GL_OCCLUSION_BUFFER_COUNT_MESAX) == 0;
    make_current(a_context, a_buffer);
    if (!a_state || !b_state)
        printf("tile and buffer counts: A's %s, B's %s\n", a_state ? "right" : "wrong", b_state ? "right" : "wrong");
    subtest(a_state && b_state && piglit_check_gl_error(GL_NO_ERROR), "tiles-per-context");

    /* A's pass, with B drawing in the middle of it. */
    ou_fill(records[0], OU_BRIEF_SIZE);
    ou_fill(records[1], OU_BRIEF_SIZE);
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    ou_rect(4, 4, 12, 12, 0.5f);
    glFlush();

    make_current(b_context, b_pixels);
    const GLint b_mode = get_integer(GL_RENDER_MODE);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glColor4f(1, 1, 1, 1);
    ou_rect(0, 0, S, S, 0.5f);
    const struct ou_fbo_functions f = ou_fbo_functions();
    GLuint rb[2];
    const GLuint fbo = ou_make_fbo(&f, S, S, 0, false, rb);
    f.BindFramebuffer(GL_FRAMEBUFFER, 0);
    const bool b_bound = piglit_check_gl_error(GL_NO_ERROR) && fbo != 0;
    static const unsigned char white[4] = {255, 255, 255, 255};
    const bool b_drew = piglit_probe_rect_rgba_ub(0, 0, S, S, white, 0);
    glFinish();

    make_current(a_context, a_buffer);
    const GLint a_mode = get_integer(GL_RENDER_MODE);
    glRenderMode(GL_RENDER);
    if (b_mode != GL_RENDER || a_mode != GL_BRIEF_OCCLUSION_MESAX)
        printf("RENDER_MODE during A's pass: 0x%x in B, 0x%x in A\n", b_mode, a_mode);
    subtest(b_mode == GL_RENDER && a_mode == GL_BRIEF_OCCLUSION_MESAX, "render-mode-per-context");
    subtest(b_drew && b_bound, "other-context-renders");
    if (records[0][OU_NOHC] != 64 || records[0][OU_PHC] != 64 || records[1][OU_NOHC] != 64)
        printf("A's records: NOHC %u PHC %u, tile 1 NOHC %u; expected 64, 64, 64\n", records[0][OU_NOHC],
               records[0][OU_PHC], records[1][OU_NOHC]);
    subtest(records[0][OU_NOHC] == 64 && records[0][OU_PHC] == 64 && records[1][OU_NOHC] == 64 &&
                piglit_check_gl_error(GL_NO_ERROR),
            "pass-counts-own-context-only");
    ScissorsMESAX(0, NULL);

    /* Pass objects. */
    GLuint name = 0;
    as.GenOcclusionPasses(1, &name);
    make_current(b_context, b_pixels);
    ScissorsMESAX(0, NULL);
    GLuint b_record[OU_BRIEF_SIZE];
    GLuint *b_buffers[1] = {b_record};
    OcclusionBuffersMESAX(1, sizes, b_buffers);
    const bool unknown_in_b = !as.IsOcclusionPass(name);
    as.BeginOcclusionPass(GL_BRIEF_OCCLUSION_MESAX, name);
    const bool begin_fails_in_b = piglit_check_gl_error(GL_INVALID_OPERATION);
    as.DeleteOcclusionPasses(1, &name);
    const bool delete_ignored_in_b = piglit_check_gl_error(GL_NO_ERROR);
    make_current(a_context, a_buffer);
    const bool still_in_a = as.IsOcclusionPass(name);
    if (!unknown_in_b || !begin_fails_in_b || !delete_ignored_in_b || !still_in_a)
        printf("pass %u: unknown in B %d, Begin fails in B %d, Delete ignored in B %d, still in A %d\n", name,
               unknown_in_b, begin_fails_in_b, delete_ignored_in_b, still_in_a);
    subtest(unknown_in_b && begin_fails_in_b && delete_ignored_in_b && still_in_a, "pass-names-not-shared");

    /* B makes objects of its own until one has A's name, begins and ends a
     * pass on it; A's object of that name was never begun. */
    make_current(b_context, b_pixels);
    GLuint b_names[64];
    as.GenOcclusionPasses(64, b_names);
    int same = -1;
    for (int i = 0; i < 64; ++i)
        if (b_names[i] == name)
            same = i;
    bool b_pass = false;
    if (same >= 0) {
        as.BeginOcclusionPass(GL_BRIEF_OCCLUSION_MESAX, name);
        ou_rect(0, 0, 4, 4, 0.5f);
        as.EndOcclusionPass();
        GLint overflowed = -1;
        as.GetOcclusionPassiv(name, GL_OCCLUSION_PASS_RESULT_MESAX, &overflowed);
        b_pass = piglit_check_gl_error(GL_NO_ERROR) && overflowed == 0 && b_record[OU_NOHC] == 16;
    }
    make_current(a_context, a_buffer);
    GLint available = 7;
    as.GetOcclusionPassiv(name, GL_OCCLUSION_PASS_RESULT_AVAILABLE_MESAX, &available);
    const bool a_never_begun = piglit_check_gl_error(GL_INVALID_OPERATION) && available == 7;
    if (same < 0 || !b_pass || !a_never_begun)
        printf("B's object %u: %s, its pass %s; A's object %s\n", name, same >= 0 ? "made" : "not among 64 names",
               b_pass ? "read" : "not read", a_never_begun ? "never begun" : "has a pass");
    subtest(same >= 0 && b_pass && a_never_begun, "same-name-different-objects");

    /* A pass of A begun by BeginOcclusionPassMESAX, with B drawing in the
     * middle of it. */
    GLuint a_pass;
    as.GenOcclusionPasses(1, &a_pass);
    ScissorsMESAX(0, NULL);
    OcclusionBuffersMESAX(1, sizes, buffers);
    ou_fill(records[0], OU_BRIEF_SIZE);
    as.BeginOcclusionPass(GL_BRIEF_OCCLUSION_MESAX, a_pass);
    ou_rect(0, 0, 8, 8, 0.5f);

    make_current(b_context, b_pixels);
    const GLint b_mode_async = get_integer(GL_RENDER_MODE);
    static const unsigned char red[4] = {255, 0, 0, 255};
    glClear(GL_COLOR_BUFFER_BIT);
    glColor4ub(255, 0, 0, 255);
    ou_rect(0, 0, S, S, 0.5f);
    const bool b_drew_red = piglit_probe_rect_rgba_ub(0, 0, S, S, red, 0);
    if (b_mode_async != GL_RENDER)
        printf("B's RENDER_MODE is 0x%x during A's BeginOcclusionPassMESAX pass\n", b_mode_async);
    subtest(b_mode_async == GL_RENDER && b_drew_red && piglit_check_gl_error(GL_NO_ERROR),
            "async-pass-state-per-context");
    glFinish();

    make_current(a_context, a_buffer);
    as.EndOcclusionPass();
    GLint a_overflowed = -1;
    as.GetOcclusionPassiv(a_pass, GL_OCCLUSION_PASS_RESULT_MESAX, &a_overflowed);
    if (records[0][OU_NOHC] != 64 || records[0][OU_PHC] != 64)
        printf("A's pass: NOHC %u PHC %u, expected 64 and 64\n", records[0][OU_NOHC], records[0][OU_PHC]);
    subtest(records[0][OU_NOHC] == 64 && records[0][OU_PHC] == 64 && a_overflowed == 0 &&
                piglit_check_gl_error(GL_NO_ERROR),
            "async-pass-counts-own-context-only");

    OSMesaDestroyContext(b_context);
    piglit_report_result(result);
}
