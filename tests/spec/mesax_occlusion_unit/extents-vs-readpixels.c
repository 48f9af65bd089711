/*
 * GL_MESAX_occlusion_unit: the bounding box and depth range of a tile equal
 * those of the pixels whose depth a GL_RENDER draw of the same geometry
 * changes, read back with glReadPixels. The geometry is a tilted triangle,
 * partly behind an occluder, so z varies over it.
 *
 * Tolerances: the box exactly; zmin/zmax within 1024 record units (2^-22
 * of the depth range): the record holds the fragment's z before the
 * 24-bit depth buffer quantizes it (spec issue 3), 256 units per step.
 */
#include <float.h>

#include "ou_util.h"

#define W 64
#define H 48

static void
draw_target(void)
{
    glBegin(GL_TRIANGLES);
    glVertex3f(4.4f, 3.1f, 0.1f);
    glVertex3f(59.7f, 9.3f, 0.9f);
    glVertex3f(30.2f, 44.6f, 0.55f);
    glEnd();
}

static void
setup_scene(void)
{
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glClearDepth(1.0);
    glClear(GL_DEPTH_BUFFER_BIT);
    ou_rect(30, 0, 64, 48, 0.5f);
}

int main(int argc, char **argv)
{
    ou_init(argc, argv, W, H);
    static GLuint before[W * H], after[W * H];
    static GLfloat depth[W * H];

    setup_scene();
    glReadPixels(0, 0, W, H, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, before);
    draw_target();
    glReadPixels(0, 0, W, H, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, after);
    glReadPixels(0, 0, W, H, GL_DEPTH_COMPONENT, GL_FLOAT, depth);
    GLuint n = 0, xmin = ~0u, xmax = 0, ymin = ~0u, ymax = 0;
    float zmin = FLT_MAX, zmax = -FLT_MAX;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            if (before[y * W + x] != after[y * W + x]) {
                ++n;
                xmin = (GLuint)x < xmin ? (GLuint)x : xmin;
                xmax = (GLuint)x > xmax ? (GLuint)x : xmax;
                ymin = (GLuint)y < ymin ? (GLuint)y : ymin;
                ymax = (GLuint)y > ymax ? (GLuint)y : ymax;
                zmin = depth[y * W + x] < zmin ? depth[y * W + x] : zmin;
                zmax = depth[y * W + x] > zmax ? depth[y * W + x] : zmax;
            }

    GLuint rec[1][OU_BRIEF_SIZE];
    setup_scene();
    ou_brief_pass(0, NULL, rec, draw_target);
    const GLuint expected[OU_BRIEF_SIZE] = {n, rec[0][OU_PHC], xmin, xmax, ymin, ymax, ou_depth(zmin), ou_depth(zmax)};
    bool ok = n > 100 && rec[0][OU_PHC] > n && ou_check_record("tilted triangle", rec[0], expected, 1024) &&
              piglit_check_gl_error(GL_NO_ERROR);
    piglit_report_subtest_result(ok ? PIGLIT_PASS : PIGLIT_FAIL, "tilted-triangle-partly-occluded");
    piglit_report_result(ok ? PIGLIT_PASS : PIGLIT_FAIL);
}
