/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit: a fragment whose depth is not a number (a shader
 * writing NaN to gl_FragDepth) is recorded with depth 0 (section 5.X: NaN
 * records as 0, the nearest depth, so that a record's zmin never claims a
 * visible fragment is farther than it may be), and the record stays well
 * formed: zmin <= zmax whenever NOHC > 0.
 *
 * The depth test is on with ALWAYS, so that every fragment passes and the
 * shader's depth is the depth the test uses; depth writes are off.
 *
 * Subtests:
 *   all-nan-records-zero          a 16 x 16 quad, every fragment NaN:
 *                                 NOHC 256, zmin = zmax = 0
 *   nan-beside-finite             left half NaN, right half 0.75: zmin 0,
 *                                 zmax the record value of 0.75
 *   finite-only-unchanged         every fragment 0.75: zmin = zmax = 0.75
 *
 * and, with the 24-bit (normalized) depth buffer of the window, the depth
 * test itself takes NaN as 0 on both drivers (issue 18), as it does for
 * GL_SAMPLES_PASSED in RENDER mode:
 *   nan-passes-less-than-one      LESS against a buffer of 1.0: NOHC 256,
 *                                 and SAMPLES_PASSED in RENDER mode 256
 *   nan-fails-greater-than-half   GREATER against 0.5: NOHC 0, SAMPLES_PASSED 0
 *
 * and the same with a DEPTH_COMPONENT32F buffer (framebuffer object), where
 * both drivers' tests take NaN as 0 too (issue 18; "Dependencies on
 * ARB_depth_buffer_float and OpenGL 3.0"):
 *   float-buffer-nan-passes-less-than-one, float-buffer-nan-fails-greater-than-half
 *
 * An interpolated depth is not a number when the vertices' z is not one.
 * Depth clipping discards such a primitive; under depth clamping
 * (ARB_depth_clamp) it is drawn, and its depth is taken as 0 as a shader's
 * is, in both buffers:
 *   clamped-vertex-nan-passes-less-than-one, clamped-vertex-nan-fails-greater-than-half,
 *   float-buffer-clamped-vertex-nan-passes-less-than-one,
 *   float-buffer-clamped-vertex-nan-fails-greater-than-half
 */
#include "ou_util.h"

#define S 16

static GLuint
program_for(const char *depth_expression)
{
    char source[512];
    snprintf(source, sizeof(source),
             "#version 110\n"
             "uniform float zero;\n"
             "void main() {\n"
             "  float nan = zero / zero;\n"
             "  gl_FragDepth = %s;\n"
             "  gl_FragColor = vec4(1.0);\n"
             "}\n",
             depth_expression);
    return piglit_build_simple_program(NULL, source);
}

static bool
check(const char *name, const char *depth_expression, GLuint zmin, GLuint zmax)
{
    const GLuint program = program_for(depth_expression);
    if (!program) {
        printf("%s: the GLSL 1.10 shader did not build\n", name);
        subtest(false, name);
        return false;
    }
    PFNGLUSEPROGRAMPROC UseProgram = glUseProgram;
    PFNGLGETUNIFORMLOCATIONPROC GetUniformLocation =
        glGetUniformLocation;
    PFNGLUNIFORM1FPROC Uniform1f = glUniform1f;
    UseProgram(program);
    Uniform1f(GetUniformLocation(program, "zero"), 0.0f);

    GLuint record[8];
    GLuint *buffers[1] = {record};
    GLsizei sizes[1] = {8};
    OcclusionBuffersMESAX(1, sizes, buffers);
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    ou_rect(0, 0, S, S, 0.5f);
    glRenderMode(GL_RENDER);
    UseProgram(0);
    const bool ok = record[OU_NOHC] == S * S && record[OU_ZMIN] == zmin && record[OU_ZMAX] == zmax &&
                    record[OU_ZMIN] <= record[OU_ZMAX];
    if (!ok)
        printf("%s: NOHC %u zmin 0x%08x zmax 0x%08x, expected %u 0x%08x 0x%08x\n", name, record[OU_NOHC],
               record[OU_ZMIN], record[OU_ZMAX], S * S, zmin, zmax);
    subtest(ok && piglit_check_gl_error(GL_NO_ERROR), name);
    return ok;
}

/* A vertex shader giving every vertex a clip-space z that is not a number
 * (a NaN object-space z would poison x and y too, through the matrices). */
static GLuint
vertex_nan_program(void)
{
    return piglit_build_simple_program("#version 110\n"
                                       "uniform float zero;\n"
                                       "void main() {\n"
                                       "  vec4 p = ftransform();\n"
                                       "  gl_Position = vec4(p.xy, zero / zero, p.w);\n"
                                       "}\n",
                                       NULL);
}

/* A NaN-depth quad against a buffer cleared to `clear` under `func`: the
 * pass's NOHC and, in RENDER mode, GL_SAMPLES_PASSED must both be
 * `expected`. The NaN is the fragment shader's, or with `from_vertices`
 * the vertices' z, under depth clamping. */
static void
check_test(const char *name, GLenum func, double clear, GLuint expected, bool from_vertices)
{
    const GLuint program = from_vertices ? vertex_nan_program() : program_for("nan");
    PFNGLUSEPROGRAMPROC UseProgram = glUseProgram;
    PFNGLGETUNIFORMLOCATIONPROC GetUniformLocation =
        glGetUniformLocation;
    PFNGLUNIFORM1FPROC Uniform1f = glUniform1f;
    PFNGLGENQUERIESPROC GenQueries = glGenQueries;
    PFNGLBEGINQUERYPROC BeginQuery = glBeginQuery;
    PFNGLENDQUERYPROC EndQuery = glEndQuery;
    PFNGLGETQUERYOBJECTUIVPROC GetQueryObjectuiv =
        glGetQueryObjectuiv;
    if (!program) {
        printf("%s: the GLSL 1.10 shader did not build\n", name);
        subtest(false, name);
        return;
    }
    if (from_vertices)
        glEnable(GL_DEPTH_CLAMP);
    glClearDepth(clear);
    glDepthMask(GL_TRUE);
    glClear(GL_DEPTH_BUFFER_BIT);
    glDepthMask(GL_FALSE);
    glDepthFunc(func);
    UseProgram(program);
    Uniform1f(GetUniformLocation(program, "zero"), 0.0f);

    GLuint query, samples = 0xdeadbeefu;
    GenQueries(1, &query);
    BeginQuery(GL_SAMPLES_PASSED, query);
    ou_rect(0, 0, S, S, 0.5f);
    EndQuery(GL_SAMPLES_PASSED);
    GetQueryObjectuiv(query, GL_QUERY_RESULT, &samples);

    GLuint record[8];
    GLuint *buffers[1] = {record};
    GLsizei sizes[1] = {8};
    OcclusionBuffersMESAX(1, sizes, buffers);
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    ou_rect(0, 0, S, S, 0.5f);
    glRenderMode(GL_RENDER);
    UseProgram(0);
    glDisable(GL_DEPTH_CLAMP);
    const bool ok = record[OU_NOHC] == expected && samples == expected;
    if (!ok)
        printf("%s: NOHC %u, SAMPLES_PASSED %u, expected %u\n", name, record[OU_NOHC], samples, expected);
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
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_ALWAYS);
    glDepthMask(GL_FALSE);
    check("all-nan-records-zero", "nan", 0, 0);
    check("nan-beside-finite", "gl_FragCoord.x < 8.0 ? nan : 0.75", 0, ou_depth(0.75));
    check("finite-only-unchanged", "0.75", ou_depth(0.75), ou_depth(0.75));
    check_test("nan-passes-less-than-one", GL_LESS, 1.0, S * S, false);
    check_test("nan-fails-greater-than-half", GL_GREATER, 0.5, 0, false);
    check_test("clamped-vertex-nan-passes-less-than-one", GL_LESS, 1.0, S * S, true);
    check_test("clamped-vertex-nan-fails-greater-than-half", GL_GREATER, 0.5, 0, true);

    struct ou_fbo_functions f = ou_fbo_functions();
    GLuint fbo, renderbuffers[2];
    f.GenFramebuffers(1, &fbo);
    f.GenRenderbuffers(2, renderbuffers);
    f.BindRenderbuffer(GL_RENDERBUFFER, renderbuffers[0]);
    f.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, S, S);
    f.BindRenderbuffer(GL_RENDERBUFFER, renderbuffers[1]);
    f.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, S, S);
    f.BindFramebuffer(GL_FRAMEBUFFER, fbo);
    f.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, renderbuffers[0]);
    f.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, renderbuffers[1]);
    if (f.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        printf("a framebuffer object with a DEPTH_COMPONENT32F buffer is incomplete\n");
        subtest(false, "float-buffer-nan-passes-less-than-one");
        subtest(false, "float-buffer-nan-fails-greater-than-half");
        subtest(false, "float-buffer-clamped-vertex-nan-passes-less-than-one");
        subtest(false, "float-buffer-clamped-vertex-nan-fails-greater-than-half");
        piglit_report_result(result);
    }
    check_test("float-buffer-nan-passes-less-than-one", GL_LESS, 1.0, S * S, false);
    check_test("float-buffer-nan-fails-greater-than-half", GL_GREATER, 0.5, 0, false);
    check_test("float-buffer-clamped-vertex-nan-passes-less-than-one", GL_LESS, 1.0, S * S, true);
    check_test("float-buffer-clamped-vertex-nan-fails-greater-than-half", GL_GREATER, 0.5, 0, true);
    piglit_report_result(result);
}
