/*
 * GL_MESAX_occlusion_unit: the GL may skip fragment shading in a pass only
 * when no output of the shader can change a fragment's coverage (section
 * 3.11, issue 14). A shader that writes gl_SampleMask, or whose alpha
 * feeds SAMPLE_ALPHA_TO_COVERAGE, must run. In a 4x framebuffer object,
 * one tile, (8, 8) to (24, 24), and a triangle over the whole window, the
 * shaders clear every sample left of x = 16 (mask 0, or alpha 0 with
 * alpha-to-coverage) and keep the others (mask ~0, alpha 1); fragments
 * count by covered samples (section 5.X), so each pass must count what a
 * shader that discards the fragments left of x = 16 counts (a shader the
 * GL must run), and less than a shader that keeps them all. The triangle
 * is clipped into several (issue 6: their shared edges' pixels have a
 * fragment of each), which is why the counts are compared, not computed.
 *
 * Subtests:
 *   sample-mask-output-counts          gl_SampleMask: the discarding shader's
 *                                      counts and box
 *   alpha-to-coverage-output-counts    alpha-to-coverage: the same
 *
 * softpipe has no multisampling (GL_MAX_SAMPLES below 4): there the test
 * skips, the one driver property it cannot have.
 */
#include "ou_util.h"

#define S 32

static PFNGLUSEPROGRAMPROC UseProgram;

static void
triangle_over_window(void)
{
    glBegin(GL_TRIANGLES);
    glVertex3f(-100, -100, 0.5f);
    glVertex3f(300, -100, 0.5f);
    glVertex3f(-100, 300, 0.5f);
    glEnd();
}

static const GLint tile[4] = {8, 8, 16, 16};

/* The record of a pass over the triangle with the shader `source`. */
static bool
pass_with(const char *source, bool alpha_to_coverage, GLuint record[OU_BRIEF_SIZE])
{
    const GLuint program = piglit_build_fragment_program(source);
    if (!program)
        return false;
    GLuint records[1][OU_BRIEF_SIZE];
    UseProgram(program);
    if (alpha_to_coverage)
        glEnable(GL_SAMPLE_ALPHA_TO_COVERAGE);
    ou_brief_pass(1, tile, records, triangle_over_window);
    glDisable(GL_SAMPLE_ALPHA_TO_COVERAGE);
    UseProgram(0);
    memcpy(record, records[0], sizeof(records[0]));
    return true;
}

static GLuint discarding[OU_BRIEF_SIZE], keeping[OU_BRIEF_SIZE];

static void
check(const char *name, const char *source, bool alpha_to_coverage)
{
    GLuint record[OU_BRIEF_SIZE];
    if (!pass_with(source, alpha_to_coverage, record)) {
        printf("%s: the shader did not build\n", name);
        subtest(false, name);
        return;
    }
    const bool ok = ou_check_record(name, record, discarding, 0) && record[OU_PHC] < keeping[OU_PHC];
    if (!ok)
        printf("%s: PHC %u; the discarding shader's %u, the keeping shader's %u\n", name, record[OU_PHC],
               discarding[OU_PHC], keeping[OU_PHC]);
    subtest(ok && piglit_check_gl_error(GL_NO_ERROR), name);
}

int
main(int argc, char **argv)
{
    ou_init(argc, argv, S, S);
    GLint max_samples = 0;
    glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
    if (max_samples < 4) {
        printf("%s has no 4x multisampling (GL_MAX_SAMPLES %d)\n", (const char *)glGetString(GL_RENDERER),
               max_samples);
        piglit_report_result(PIGLIT_SKIP);
    }
    UseProgram = (PFNGLUSEPROGRAMPROC)piglit_get_proc_address("glUseProgram");
    struct ou_fbo_functions f = ou_fbo_functions();
    GLuint renderbuffers[2];
    ou_make_fbo(&f, S, S, 4, true, renderbuffers);
    glDisable(GL_DEPTH_TEST);
    if (!pass_with("#version 150 compatibility\n"
                   "out vec4 colour;\n"
                   "void main() {\n"
                   "  if (gl_FragCoord.x < 16.0) discard;\n"
                   "  colour = vec4(1.0);\n"
                   "}\n",
                   false, discarding) ||
        !pass_with("#version 150 compatibility\n"
                   "out vec4 colour;\n"
                   "void main() { colour = vec4(1.0); }\n",
                   false, keeping)) {
        printf("the reference shaders did not build\n");
        piglit_report_result(PIGLIT_FAIL);
    }
    if (discarding[OU_XMIN] != 16 || discarding[OU_NOHC] == 0 || discarding[OU_PHC] >= keeping[OU_PHC]) {
        printf("the discarding shader counts %u (x from %u), the keeping one %u\n", discarding[OU_PHC],
               discarding[OU_XMIN], keeping[OU_PHC]);
        piglit_report_result(PIGLIT_FAIL);
    }

    check("sample-mask-output-counts",
          "#version 150 compatibility\n"
          "#extension GL_ARB_sample_shading : require\n"
          "out vec4 colour;\n"
          "void main() {\n"
          "  gl_SampleMask[0] = gl_FragCoord.x < 16.0 ? 0 : -1;\n"
          "  colour = vec4(1.0);\n"
          "}\n",
          false);
    check("alpha-to-coverage-output-counts",
          "#version 150 compatibility\n"
          "out vec4 colour;\n"
          "void main() {\n"
          "  colour = vec4(1.0, 1.0, 1.0, gl_FragCoord.x < 16.0 ? 0.0 : 1.0);\n"
          "}\n",
          true);
    piglit_report_result(result);
}
