/* SPDX-License-Identifier: MIT */
/*
 * With DEPTH_CLAMP disabled, a fragment shader's depth is not clamped to the
 * depth range (OpenGL 4.6, section 13.7: clamping to [min(n, f), max(n, f)]
 * applies only while depth clamping is enabled), whatever the primitive:
 * also for those a driver draws as triangles of its own (wide, smooth and
 * polygon-mode lines, smooth points, point sprites).
 *
 * A 64 x 64 window, depth cleared to 0.3, depth range [0.4, 0.6], the
 * depth test LESS, a shader writing gl_FragDepth = 0.2 and white. A
 * primitive passes where its depth, 0.2, is below 0.3, so it must write the
 * same pixels as with the depth test off (counted from glReadPixels,
 * tolerance 0), and at least one.
 *
 * Subtests: triangle, wide-line, smooth-line, polygon-mode-line,
 * smooth-point, point-sprite.
 */
#include <stdio.h>

#include "piglit-util-gl.h"

enum { S = 64 };

static unsigned
drawn(void (*draw)(void), GLenum depth_func)
{
    static GLubyte pixels[S][S][4];
    unsigned n = 0;

    glClearColor(0, 0, 0, 0);
    glClearDepth(0.3);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glDepthFunc(depth_func);
    draw();
    glReadPixels(0, 0, S, S, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
    for (int y = 0; y < S; ++y)
        for (int x = 0; x < S; ++x)
            n += pixels[y][x][0] != 0;
    return n;
}

static void
triangle(void)
{
    glBegin(GL_TRIANGLES);
    glVertex2f(8, 8);
    glVertex2f(56, 12);
    glVertex2f(30, 54);
    glEnd();
}

static void
line(void)
{
    glBegin(GL_LINES);
    glVertex2f(6.3f, 9.1f);
    glVertex2f(57.2f, 50.4f);
    glEnd();
}

static void
wide_line(void)
{
    glLineWidth(5);
    line();
    glLineWidth(1);
}

static void
smooth_line(void)
{
    glEnable(GL_LINE_SMOOTH);
    line();
    glDisable(GL_LINE_SMOOTH);
}

static void
polygon_mode_line(void)
{
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glLineWidth(3);
    triangle();
    glLineWidth(1);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
}

static void
point(void)
{
    glPointSize(9);
    glBegin(GL_POINTS);
    glVertex2f(32.5f, 32.5f);
    glEnd();
    glPointSize(1);
}

static void
smooth_point(void)
{
    glEnable(GL_POINT_SMOOTH);
    point();
    glDisable(GL_POINT_SMOOTH);
}

static void
point_sprite(void)
{
    glEnable(GL_POINT_SPRITE);
    point();
    glDisable(GL_POINT_SPRITE);
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
    static const struct {
        const char *name;
        void (*draw)(void);
    } primitives[] = {
        {"triangle", triangle},         {"wide-line", wide_line},       {"smooth-line", smooth_line},
        {"polygon-mode-line", polygon_mode_line}, {"smooth-point", smooth_point}, {"point-sprite", point_sprite},
    };
    enum piglit_result result = PIGLIT_PASS;

    const GLuint program = piglit_build_simple_program(NULL,
        "#version 110\n"
        "void main() { gl_FragDepth = 0.2; gl_FragColor = vec4(1.0); }\n");
    if (!program) {
        printf("the shader did not build\n");
        piglit_report_result(PIGLIT_FAIL);
    }
    PFNGLUSEPROGRAMPROC UseProgram = glUseProgram;
    UseProgram(program);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glOrtho(0, S, 0, S, -1, 1);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glDisable(GL_DEPTH_CLAMP);
    glDepthRange(0.4, 0.6);
    glEnable(GL_DEPTH_TEST);

    for (unsigned i = 0; i < sizeof(primitives) / sizeof(primitives[0]); ++i) {
        const unsigned all = drawn(primitives[i].draw, GL_ALWAYS);
        const unsigned passing = drawn(primitives[i].draw, GL_LESS);
        const bool ok = all > 0 && passing == all && piglit_check_gl_error(GL_NO_ERROR);
        if (!ok)
            printf("%s: %u pixels pass LESS, %u drawn with the test off\n", primitives[i].name, passing, all);
        piglit_report_subtest_result(ok ? PIGLIT_PASS : PIGLIT_FAIL, "%s", primitives[i].name);
        if (!ok)
            result = PIGLIT_FAIL;
    }
    piglit_report_result(result);
}
