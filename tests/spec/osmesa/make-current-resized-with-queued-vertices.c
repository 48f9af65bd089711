/* SPDX-License-Identifier: MIT */
/*
 * OSMesaMakeCurrent of the current context on a buffer of another size,
 * while an immediate-mode primitive is still queued (vbo keeps glBegin/glEnd
 * vertices until the next flush), draws the queued primitive once, into the
 * buffer it was issued for, and not into the new one: the GL executes
 * commands in the order they were issued, and a command issued while a
 * buffer is current renders into that buffer. OSMesa destroys the old
 * buffer when the size changes; drawing the queue afterwards used the freed
 * buffer (softpipe crashed; llvmpipe drew into the new buffer). The old
 * buffer is the client's memory: OSMesa renders into a texture of its own
 * and copies it there at glFlush and glFinish, so the quad must reach that
 * memory before the texture goes.
 *
 * The scenario runs in a child process, so that a crash fails the subtests
 * without ending the program: the child makes a context current on a 32 x 32
 * RGBA buffer filled with a sentinel, clears it to black and calls glFinish
 * (the black reaches the buffer), begins a GL_SAMPLES_PASSED query, queues a
 * white quad over the pixels (4..11, 4..11) between glBegin and glEnd, makes
 * the context current on a 64 x 64 buffer, ends the query, reads the new
 * buffer's framebuffer with glReadPixels, and reads the old buffer's memory
 * (OSMESA_Y_UP, the default: row 0 is the bottom row). (The viewport set for
 * the old buffer stays, so the quad drawn into the new buffer would cover
 * the same pixels there.)
 *
 * Expected, from the quad's corners: the query counts the pixels whose
 * centres lie inside the quad (tolerance 0: its edges lie on pixel
 * boundaries, and the buffer is single-sampled), and the quad's pixels of
 * the new buffer are not all white. The new buffer's contents are undefined
 * until drawn (softpipe does not clear a new texture, which may reuse the
 * old one's memory), so only the whole white footprint a draw leaves counts
 * as the quad drawn there. The old buffer's memory holds white exactly over
 * the quad's pixels and black elsewhere (exact in RGBA8).
 *
 * Subtests:
 *   queued-quad-drawn-once               GL_SAMPLES_PASSED is the quad's pixels
 *   queued-quad-not-drawn-in-new-buffer  the quad's footprint in the new buffer
 *                                        is not all white
 *   queued-quad-in-old-buffer-memory     the old buffer's memory holds the
 *                                        clear and the quad
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <GL/osmesa.h>

#include "piglit-util-gl.h"

enum { OLD = 32, NEW = 64, X0 = 4, Y0 = 4, X1 = 12, Y1 = 12, SENTINEL = 0x5a };

/* The child's exit status when the scenario ran: RAN and the bits of the
 * subtests that passed. */
enum { RAN = 64, DRAWN_ONCE = 1, NOT_IN_NEW = 2, IN_OLD = 4 };

static const int attribs[] = {
    OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_STENCIL_BITS, 8,
    OSMESA_PROFILE, OSMESA_COMPAT_PROFILE, 0,
};

static bool
inside_quad(int x, int y)
{
    return x + 0.5f > X0 && x + 0.5f < X1 && y + 0.5f > Y0 && y + 0.5f < Y1;
}

static int
make_current_resized(void)
{
    static GLubyte old_buffer[OLD][OLD][4], new_buffer[NEW][NEW][4], read[NEW][NEW][4];
    memset(old_buffer, SENTINEL, sizeof(old_buffer));
    OSMesaContext context = OSMesaCreateContextAttribs(attribs, NULL);
    if (!context || !OSMesaMakeCurrent(context, old_buffer, GL_UNSIGNED_BYTE, OLD, OLD))
        return 2;
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glOrtho(0, OLD, 0, OLD, -1, 1);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glDisable(GL_DEPTH_TEST);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT);
    glFinish();
    GLuint query, samples = 0xdeadbeefu;
    glGenQueries(1, &query);
    glBeginQuery(GL_SAMPLES_PASSED, query);
    glColor4f(1, 1, 1, 1);
    glBegin(GL_QUADS);
    glVertex2f(X0, Y0);
    glVertex2f(X1, Y0);
    glVertex2f(X1, Y1);
    glVertex2f(X0, Y1);
    glEnd();
    if (!OSMesaMakeCurrent(context, new_buffer, GL_UNSIGNED_BYTE, NEW, NEW))
        return 3;
    glEndQuery(GL_SAMPLES_PASSED);
    glGetQueryObjectuiv(query, GL_QUERY_RESULT, &samples);
    glReadPixels(0, 0, NEW, NEW, GL_RGBA, GL_UNSIGNED_BYTE, read);
    const GLenum error = glGetError();

    unsigned quad_pixels = 0, white = 0;
    for (int y = 0; y < NEW; ++y) {
        for (int x = 0; x < NEW; ++x) {
            if (inside_quad(x, y)) {
                ++quad_pixels;
                white += read[y][x][0] == 255 && read[y][x][1] == 255 && read[y][x][2] == 255 && read[y][x][3] == 255;
            }
        }
    }
    if (samples != quad_pixels)
        printf("GL_SAMPLES_PASSED %u, expected %u (the quad's pixels)\n", samples, quad_pixels);
    if (white == quad_pixels)
        printf("new buffer: every one of the quad's %u pixels is white: the quad was drawn there\n", quad_pixels);
    if (error != GL_NO_ERROR)
        printf("GL error 0x%x after the MakeCurrent\n", error);
    unsigned wrong_in_old = 0;
    for (int y = 0; y < OLD; ++y) {
        for (int x = 0; x < OLD; ++x) {
            const GLubyte *p = old_buffer[y][x];
            const GLubyte expected = inside_quad(x, y) ? 255 : 0;
            if ((p[0] != expected || p[1] != expected || p[2] != expected || p[3] != expected) &&
                wrong_in_old++ == 0)
                printf("old buffer: pixel (%d, %d) is %d %d %d %d, expected %s\n", x, y, p[0], p[1], p[2], p[3],
                       expected ? "white (the queued quad)" : "black (the clear)");
        }
    }
    if (wrong_in_old)
        printf("old buffer: %u of %d pixels wrong (the quad covers %u)\n", wrong_in_old, OLD * OLD, quad_pixels);
    fflush(stdout);
    OSMesaMakeCurrent(NULL, NULL, 0, 0, 0);
    OSMesaDestroyContext(context);
    return RAN | (samples == quad_pixels && error == GL_NO_ERROR ? DRAWN_ONCE : 0) |
           (white < quad_pixels && error == GL_NO_ERROR ? NOT_IN_NEW : 0) | (wrong_in_old == 0 ? IN_OLD : 0);
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
    fflush(stdout);
    const pid_t child = fork();
    if (child == 0)
        _exit(make_current_resized());
    int status = 0, code = 0;
    if (child < 0 || waitpid(child, &status, 0) != child)
        printf("could not run the child\n");
    else if (WIFSIGNALED(status))
        printf("the child died of signal %d\n", WTERMSIG(status));
    else if ((code = WEXITSTATUS(status)) < RAN)
        printf("the child exited with %d (2, 3: no context)\n", code);
    const bool drawn_once = (code & RAN) && (code & DRAWN_ONCE), not_in_new = (code & RAN) && (code & NOT_IN_NEW);
    const bool in_old = (code & RAN) && (code & IN_OLD);
    piglit_report_subtest_result(drawn_once ? PIGLIT_PASS : PIGLIT_FAIL, "queued-quad-drawn-once");
    piglit_report_subtest_result(not_in_new ? PIGLIT_PASS : PIGLIT_FAIL, "queued-quad-not-drawn-in-new-buffer");
    piglit_report_subtest_result(in_old ? PIGLIT_PASS : PIGLIT_FAIL, "queued-quad-in-old-buffer-memory");
    piglit_report_result(drawn_once && not_in_new && in_old ? PIGLIT_PASS : PIGLIT_FAIL);
}
