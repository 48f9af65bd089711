/*
 * OSMesaMakeCurrent of the current context on a buffer of another size
 * leaves in the old buffer's memory what was drawn into it before the call,
 * an immediate-mode primitive still queued at the call (vbo keeps
 * glBegin/glEnd vertices until the next flush) included: the old buffer is
 * the client's memory, OSMesa renders into a texture of its own and copies
 * it there at glFlush and glFinish, and on a change of size it destroys the
 * texture, so the copy must come first.
 *
 * The scenario runs in a child process, so that a crash fails the subtest
 * without ending the program: the child makes a context current on a 32 x 32
 * RGBA buffer filled with a sentinel, clears it to black and calls glFinish
 * (the black reaches the buffer), queues a white quad over the pixels
 * (4..11, 4..11) between glBegin and glEnd, and makes the context current
 * on a 64 x 64 buffer. It then reads the old buffer's memory (OSMESA_Y_UP,
 * the default: row 0 is the bottom row).
 *
 * Expected, from the quad's corners: white exactly over the pixels whose
 * centres lie inside the quad, black elsewhere (tolerance 0: the edges lie
 * on pixel boundaries, white and black are exact in RGBA8).
 *
 * Subtest:
 *   queued-quad-in-old-buffer-memory
 * (make-current-resized-with-queued-vertices checks that the quad is drawn
 * once and not into the new buffer.)
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <GL/osmesa.h>

#include "piglit-util-gl.h"

enum { OLD = 32, NEW = 64, X0 = 4, Y0 = 4, X1 = 12, Y1 = 12, SENTINEL = 0x5a };

static const int attribs[] = {
    OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_STENCIL_BITS, 8,
    OSMESA_PROFILE, OSMESA_COMPAT_PROFILE, 0,
};

static bool
inside_quad(int x, int y)
{
    return x + 0.5f > X0 && x + 0.5f < X1 && y + 0.5f > Y0 && y + 0.5f < Y1;
}

/* 0 when the old buffer holds the quad over the clear; 1 when it does not;
 * 2, 3 when a context could not be made current. */
static int
make_current_resized(void)
{
    static GLubyte old_buffer[OLD][OLD][4], new_buffer[NEW][NEW][4];
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
    glColor4f(1, 1, 1, 1);
    glBegin(GL_QUADS);
    glVertex2f(X0, Y0);
    glVertex2f(X1, Y0);
    glVertex2f(X1, Y1);
    glVertex2f(X0, Y1);
    glEnd();
    if (!OSMesaMakeCurrent(context, new_buffer, GL_UNSIGNED_BYTE, NEW, NEW))
        return 3;

    unsigned wrong = 0, quad_pixels = 0;
    for (int y = 0; y < OLD; ++y) {
        for (int x = 0; x < OLD; ++x) {
            const GLubyte *p = old_buffer[y][x];
            const GLubyte expected = inside_quad(x, y) ? 255 : 0;
            quad_pixels += inside_quad(x, y);
            if ((p[0] != expected || p[1] != expected || p[2] != expected || p[3] != expected) && wrong++ == 0)
                printf("old buffer: pixel (%d, %d) is %d %d %d %d, expected %s\n", x, y, p[0], p[1], p[2], p[3],
                       expected ? "white (the queued quad)" : "black (the clear)");
        }
    }
    if (wrong)
        printf("old buffer: %u of %d pixels wrong (the quad covers %u)\n", wrong, OLD * OLD, quad_pixels);
    fflush(stdout);
    OSMesaMakeCurrent(NULL, NULL, 0, 0, 0);
    OSMesaDestroyContext(context);
    return wrong == 0 ? 0 : 1;
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
    int status = 0;
    const bool waited = child > 0 && waitpid(child, &status, 0) == child;
    if (!waited)
        printf("could not run the child\n");
    else if (WIFSIGNALED(status))
        printf("the child died of signal %d\n", WTERMSIG(status));
    else if (WEXITSTATUS(status) > 1)
        printf("the child exited with %d (no context)\n", WEXITSTATUS(status));
    const bool ok = waited && WIFEXITED(status) && WEXITSTATUS(status) == 0;
    piglit_report_subtest_result(ok ? PIGLIT_PASS : PIGLIT_FAIL, "queued-quad-in-old-buffer-memory");
    piglit_report_result(ok ? PIGLIT_PASS : PIGLIT_FAIL);
}
