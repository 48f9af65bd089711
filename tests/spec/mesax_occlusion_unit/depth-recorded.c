/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit: the depth a record holds is the depth the depth
 * test uses or would use (section 5.X): the fragment shader's gl_FragDepth
 * where it writes one, clamped to the depth range under depth clamping,
 * whether the depth test is on or off.
 *
 * Window z = object z here (ou_init's projection), DepthRange(0, 1) unless
 * a subtest says otherwise. Records are compared exactly: these depths pass
 * through the transforms unrounded.
 *
 * Subtests:
 *   shader-depth-test-off      gl_FragDepth = 0.25 over a quad at z 0.5,
 *                              depth test off: zmin = zmax = 0.25
 *   shader-depth-test-always   the same with the test on (ALWAYS)
 *   clamp-range-test-off       DEPTH_CLAMP, DepthRange(0.25, 0.75), a quad
 *                              beyond the far plane (clip z > w): recorded
 *                              0.75, the depth range's far end
 *   clamp-range-test-always    the same with the test on (ALWAYS)
 */
#include "ou_util.h"

#define S 16

static GLuint
nohc_zmin_zmax(GLuint out[3], void (*draw)(void))
{
    GLuint record[8];
    GLuint *buffers[1] = {record};
    GLsizei sizes[1] = {8};
    OcclusionBuffersMESAX(1, sizes, buffers);
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    draw();
    glRenderMode(GL_RENDER);
    out[0] = record[OU_NOHC];
    out[1] = record[OU_ZMIN];
    out[2] = record[OU_ZMAX];
    return out[0];
}

static void
quad_at_half(void)
{
    ou_rect(0, 0, S, S, 0.5f);
}

/* Object z 1.5: window z 1.5 before clamping, outside [0, 1] and the
 * range [0.25, 0.75]. ou_init's glOrtho maps object z to window z; with
 * depth clamping the far plane does not clip it. */
static void
quad_beyond_far(void)
{
    ou_rect(0, 0, S, S, 1.5f);
}

static void
check(const char *name, void (*draw)(void), double expected_z)
{
    GLuint r[3];
    nohc_zmin_zmax(r, draw);
    const bool ok = r[0] == S * S && r[1] == ou_depth(expected_z) && r[2] == ou_depth(expected_z);
    if (!ok)
        printf("%s: NOHC %u zmin 0x%08x zmax 0x%08x, expected %u and 0x%08x\n", name, r[0], r[1], r[2], S * S,
               ou_depth(expected_z));
    subtest(ok && piglit_check_gl_error(GL_NO_ERROR), name);
}

PIGLIT_GL_TEST_CONFIG_BEGIN

    config.supports_gl_compat_version = 20;
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
    glDepthMask(GL_FALSE);
    const GLuint program = piglit_build_simple_program(NULL, "#version 110\n"
                                                          "void main() {\n"
                                                          "  gl_FragDepth = 0.25;\n"
                                                          "  gl_FragColor = vec4(1.0);\n"
                                                          "}\n");
    PFNGLUSEPROGRAMPROC UseProgram = glUseProgram;
    if (!program) {
        printf("the GLSL 1.10 shader did not build\n");
        subtest(false, "shader-depth-test-off");
        subtest(false, "shader-depth-test-always");
    } else {
        UseProgram(program);
        glDisable(GL_DEPTH_TEST);
        check("shader-depth-test-off", quad_at_half, 0.25);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_ALWAYS);
        check("shader-depth-test-always", quad_at_half, 0.25);
        UseProgram(0);
    }

    glEnable(GL_DEPTH_CLAMP);
    glDepthRange(0.25, 0.75);
    glDisable(GL_DEPTH_TEST);
    check("clamp-range-test-off", quad_beyond_far, 0.75);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_ALWAYS);
    check("clamp-range-test-always", quad_beyond_far, 0.75);
    piglit_report_result(result);
}
