/*
 * GL_MESAX_occlusion_unit, paying only for what is used (spec issue 14): an
 * occlusion pass runs no fragment shader when the shader can neither
 * discard nor write depth and the alpha test is off, and it does run one
 * that discards (whose discards change the counts). Measured with
 * ARB_pipeline_statistics_query's FRAGMENT_SHADER_INVOCATIONS; skipped where
 * that query is missing. GL_RENDER shades the same draw, so the test can fail.
 */
#include "ou_util.h"

#define W 32
#define H 32
#ifndef GL_FRAGMENT_SHADER_INVOCATIONS_ARB
#define GL_FRAGMENT_SHADER_INVOCATIONS_ARB 0x82F4
#endif

static PFNGLBEGINQUERYPROC BeginQuery;
static PFNGLENDQUERYPROC EndQuery;
static PFNGLGETQUERYOBJECTUIVPROC GetQueryObjectuiv;
static PFNGLUSEPROGRAMPROC UseProgram;
static GLuint query;

/* Fragment shader invocations of one full-window rectangle in `mode`. */
static GLuint
invocations(GLenum mode)
{
    GLuint record[8], n = 0;
    GLuint *buffers[1] = {record};
    GLsizei size = 8;
    OcclusionBuffersMESAX(1, &size, buffers);
    BeginQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB, query);
    if (mode != GL_RENDER)
        glRenderMode(mode);
    ou_rect(0, 0, W, H, 0.5f);
    if (mode != GL_RENDER)
        glRenderMode(GL_RENDER);
    EndQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB);
    GetQueryObjectuiv(query, GL_QUERY_RESULT, &n);
    return n;
}

static void
check_invocations(bool ok, const char *name, GLuint n)
{
    if (!ok)
        printf("%s: %u fragment shader invocations\n", name, n);
    piglit_report_subtest_result(ok ? PIGLIT_PASS : PIGLIT_FAIL, "%s", name);
    if (!ok)
        result = PIGLIT_FAIL;
}

int main(int argc, char **argv)
{
    ou_init(argc, argv, W, H);
    piglit_require_extension("GL_ARB_pipeline_statistics_query");
    PFNGLGENQUERIESPROC GenQueries = (PFNGLGENQUERIESPROC)piglit_get_proc_address("glGenQueries");
    BeginQuery = (PFNGLBEGINQUERYPROC)piglit_get_proc_address("glBeginQuery");
    EndQuery = (PFNGLENDQUERYPROC)piglit_get_proc_address("glEndQuery");
    GetQueryObjectuiv = (PFNGLGETQUERYOBJECTUIVPROC)piglit_get_proc_address("glGetQueryObjectuiv");
    UseProgram = (PFNGLUSEPROGRAMPROC)piglit_get_proc_address("glUseProgram");
    GenQueries(1, &query);
    glDisable(GL_DEPTH_TEST);

    const GLuint plain = piglit_build_fragment_program("#version 110\nvoid main() { gl_FragColor = vec4(gl_FragCoord.x / 32.0); }\n");
    const GLuint discards = piglit_build_fragment_program("#version 110\n"
                                    "void main() { if (gl_FragCoord.x < 16.0) discard; gl_FragColor = vec4(1.0); }\n");
    UseProgram(plain);
    GLuint n = invocations(GL_RENDER);
    check_invocations(n >= W * H, "render-mode-shades", n);
    n = invocations(GL_BRIEF_OCCLUSION_MESAX);
    check_invocations(n == 0, "brief-pass-skips-plain-shader", n);
    n = invocations(GL_VERBOSE_OCCLUSION_MESAX);
    check_invocations(n == 0, "verbose-pass-skips-plain-shader", n);
    glEnable(GL_ALPHA_TEST);
    glAlphaFunc(GL_GREATER, 0.5f);
    n = invocations(GL_BRIEF_OCCLUSION_MESAX);
    check_invocations(n >= W * H, "alpha-test-needs-shading", n);
    glDisable(GL_ALPHA_TEST);
    UseProgram(discards);
    n = invocations(GL_BRIEF_OCCLUSION_MESAX);
    check_invocations(n >= W * H, "discarding-shader-runs", n);
    UseProgram(0);

    piglit_report_result(result);
}
