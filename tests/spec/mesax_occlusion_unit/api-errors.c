/*
 * GL_MESAX_occlusion_unit: every error of the spec's Errors section, and
 * that a command that generates one changes nothing.
 */
#include "ou_util.h"



static GLint
get(GLenum pname)
{
    GLint v = -12345;
    glGetIntegerv(pname, &v);
    return v;
}


int main(int argc, char **argv)
{
    ou_init(argc, argv, 32, 32);
    GLint max_tiles = get(GL_MAX_OCCLUSION_TILES_MESAX);
    const GLint two_tiles[8] = {0, 0, 4, 4, 8, 8, 4, 4};
    const GLint bad_second[8] = {0, 0, 4, 4, 8, 8, -1, 4};
    const GLint bad_height[4] = {0, 0, 4, -2};
    GLint many[4 * 65];
    memset(many, 0, sizeof(many));

    /* ScissorsMESAX, INVALID_VALUE; the tile count stays as it was. */
    ScissorsMESAX(2, two_tiles);
    subtest(piglit_check_gl_error(GL_NO_ERROR) && get(GL_OCCLUSION_TILE_COUNT_MESAX) == 2, "scissors-valid-sets-count");
    ScissorsMESAX(-1, two_tiles);
    subtest(piglit_check_gl_error(GL_INVALID_VALUE) && get(GL_OCCLUSION_TILE_COUNT_MESAX) == 2, "scissors-negative-count");
    ScissorsMESAX(max_tiles + 1, many);
    subtest(piglit_check_gl_error(GL_INVALID_VALUE) && get(GL_OCCLUSION_TILE_COUNT_MESAX) == 2, "scissors-count-above-max");
    ScissorsMESAX(1, NULL);
    subtest(piglit_check_gl_error(GL_INVALID_VALUE) && get(GL_OCCLUSION_TILE_COUNT_MESAX) == 2, "scissors-null-tiles");
    ScissorsMESAX(2, bad_second);
    subtest(piglit_check_gl_error(GL_INVALID_VALUE) && get(GL_OCCLUSION_TILE_COUNT_MESAX) == 2, "scissors-negative-width");
    ScissorsMESAX(1, bad_height);
    subtest(piglit_check_gl_error(GL_INVALID_VALUE) && get(GL_OCCLUSION_TILE_COUNT_MESAX) == 2, "scissors-negative-height");
    ScissorsMESAX(max_tiles, many);
    subtest(piglit_check_gl_error(GL_NO_ERROR) && get(GL_OCCLUSION_TILE_COUNT_MESAX) == max_tiles, "scissors-max-count-accepted");
    ScissorsMESAX(0, NULL);
    subtest(piglit_check_gl_error(GL_NO_ERROR) && get(GL_OCCLUSION_TILE_COUNT_MESAX) == 0, "scissors-zero-count-null-accepted");

    /* RenderMode without buffers: INVALID_OPERATION, mode stays RENDER. */
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    subtest(piglit_check_gl_error(GL_INVALID_OPERATION) && get(GL_RENDER_MODE) == GL_RENDER, "rendermode-without-buffers");
    glRenderMode(GL_VERBOSE_OCCLUSION_MESAX);
    subtest(piglit_check_gl_error(GL_INVALID_OPERATION) && get(GL_RENDER_MODE) == GL_RENDER, "rendermode-verbose-without-buffers");

    /* OcclusionBuffersMESAX: a valid call, then failing ones that must leave it in place. */
    GLuint a[8], b[8];
    GLuint *one[1] = {a};
    GLuint *two[2] = {a, b};
    GLuint *with_null[2] = {a, NULL};
    const GLsizei size8[2] = {8, 8}, size7[2] = {8, 7};
    OcclusionBuffersMESAX(1, size8, one);
    subtest(piglit_check_gl_error(GL_NO_ERROR), "buffers-valid");
    OcclusionBuffersMESAX(-1, size8, two);
    subtest(piglit_check_gl_error(GL_INVALID_VALUE), "buffers-negative-count");
    OcclusionBuffersMESAX(max_tiles + 1, size8, two);
    subtest(piglit_check_gl_error(GL_INVALID_VALUE), "buffers-count-above-max");
    OcclusionBuffersMESAX(2, size7, two);
    subtest(piglit_check_gl_error(GL_INVALID_VALUE), "buffers-size-below-8");
    OcclusionBuffersMESAX(2, size8, with_null);
    subtest(piglit_check_gl_error(GL_INVALID_VALUE), "buffers-null-buffer");
    OcclusionBuffersMESAX(2, NULL, two);
    subtest(piglit_check_gl_error(GL_INVALID_VALUE), "buffers-null-sizes");
    OcclusionBuffersMESAX(2, size8, NULL);
    subtest(piglit_check_gl_error(GL_INVALID_VALUE), "buffers-null-buffers");

    /* Still one buffer: two tiles need two, so RenderMode fails and changes nothing... */
    ScissorsMESAX(2, two_tiles);
    ou_fill(a, 8);
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    subtest(piglit_check_gl_error(GL_INVALID_OPERATION) && get(GL_RENDER_MODE) == GL_RENDER && a[0] == OU_SENTINEL,
            "rendermode-fewer-buffers-than-tiles");
    /* ...and with one tile the failed calls above left buffer `a` in place. */
    ScissorsMESAX(0, NULL);
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    bool entered = piglit_check_gl_error(GL_NO_ERROR) && get(GL_RENDER_MODE) == GL_BRIEF_OCCLUSION_MESAX;
    subtest(entered, "rendermode-brief-enters");

    /* Inside an occlusion mode: INVALID_OPERATION, nothing changes. */
    ScissorsMESAX(2, two_tiles);
    subtest(piglit_check_gl_error(GL_INVALID_OPERATION) && get(GL_OCCLUSION_TILE_COUNT_MESAX) == 0,
            "scissors-inside-occlusion-mode");
    OcclusionBuffersMESAX(2, size8, two);
    subtest(piglit_check_gl_error(GL_INVALID_OPERATION), "buffers-inside-occlusion-mode");
    /* An invalid mode: INVALID_ENUM, the pass goes on, no record is written. */
    glRenderMode(GL_TEXTURE_2D);
    subtest(piglit_check_gl_error(GL_INVALID_ENUM) && get(GL_RENDER_MODE) == GL_BRIEF_OCCLUSION_MESAX &&
                a[0] == OU_SENTINEL,
            "rendermode-invalid-enum-keeps-pass");
    ou_rect(0, 0, 2, 2, 0.5f);
    GLint overflow = glRenderMode(GL_RENDER);
    subtest(piglit_check_gl_error(GL_NO_ERROR) && overflow == 0 && a[OU_NOHC] == 4 && a[OU_PHC] == 4,
            "rendermode-render-writes-record");

    /* Between Begin and End. */
    glBegin(GL_TRIANGLES);
    ScissorsMESAX(0, NULL);
    glEnd();
    subtest(piglit_check_gl_error(GL_INVALID_OPERATION), "scissors-inside-begin-end");
    glBegin(GL_TRIANGLES);
    OcclusionBuffersMESAX(1, size8, one);
    glEnd();
    subtest(piglit_check_gl_error(GL_INVALID_OPERATION), "buffers-inside-begin-end");

    piglit_report_result(result);
}
