/* SPDX-License-Identifier: MIT */
/*
 * OSMesaDestroyContext of the current context while immediate-mode
 * vertices are still queued (vbo keeps them until the next flush) destroys
 * it without touching freed state, and a context made afterwards renders.
 *
 * Each subtest runs in a child process, so that a crash in one fails it
 * alone: the child makes a 32 x 32 context current, queues a triangle,
 * destroys the context, then makes a new one, clears it to red and reads
 * a pixel back; it reports success by its exit status 0.
 *
 * Subtests:
 *   after-end      glBegin, three vertices, glEnd: the triangle is queued
 *   inside-begin   glBegin and three vertices, no glEnd
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <GL/osmesa.h>

#include "piglit-util-gl.h"

enum { S = 32 };

static const int attribs[] = {
    OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_STENCIL_BITS, 8,
    OSMESA_PROFILE, OSMESA_COMPAT_PROFILE, 0,
};

static int
destroy_then_render(bool end)
{
    static GLubyte first[S * S * 4], second[S * S * 4];
    OSMesaContext context = OSMesaCreateContextAttribs(attribs, NULL);
    if (!context || !OSMesaMakeCurrent(context, first, GL_UNSIGNED_BYTE, S, S))
        return 2;
    glBegin(GL_TRIANGLES);
    glVertex2f(-1, -1);
    glVertex2f(1, -1);
    glVertex2f(0, 1);
    if (end)
        glEnd();
    OSMesaDestroyContext(context);

    context = OSMesaCreateContextAttribs(attribs, NULL);
    if (!context || !OSMesaMakeCurrent(context, second, GL_UNSIGNED_BYTE, S, S))
        return 3;
    glClearColor(1, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    GLubyte pixel[4] = {0, 0, 0, 0};
    glReadPixels(S / 2, S / 2, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, pixel);
    const bool red = pixel[0] == 255 && pixel[1] == 0 && pixel[2] == 0 && glGetError() == GL_NO_ERROR;
    OSMesaMakeCurrent(NULL, NULL, 0, 0, 0);
    OSMesaDestroyContext(context);
    return red ? 0 : 4;
}

static bool
in_child(const char *name, bool end)
{
    fflush(stdout);
    const pid_t child = fork();
    if (child == 0)
        _exit(destroy_then_render(end));
    int status = 0;
    if (child < 0 || waitpid(child, &status, 0) != child) {
        printf("%s: could not run the child\n", name);
        return false;
    }
    if (WIFSIGNALED(status))
        printf("%s: the child died of signal %d\n", name, WTERMSIG(status));
    else if (WEXITSTATUS(status) != 0)
        printf("%s: the child exited with %d (2, 3: no context; 4: the new context did not clear)\n", name,
               WEXITSTATUS(status));
    return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

int
main(int argc, char **argv)
{
    for (int i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "-auto") && strcmp(argv[i], "-fbo")) {
            fprintf(stderr, "%s: unknown argument '%s' (accepted: -auto -fbo)\n", argv[0], argv[i]);
            piglit_report_result(PIGLIT_FAIL);
        }
    }
    const bool after_end = in_child("after-end", true);
    piglit_report_subtest_result(after_end ? PIGLIT_PASS : PIGLIT_FAIL, "after-end");
    const bool inside_begin = in_child("inside-begin", false);
    piglit_report_subtest_result(inside_begin ? PIGLIT_PASS : PIGLIT_FAIL, "inside-begin");
    piglit_report_result(after_end && inside_begin ? PIGLIT_PASS : PIGLIT_FAIL);
}
