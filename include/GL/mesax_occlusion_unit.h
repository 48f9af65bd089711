/*
 * GL_MESAX_occlusion_unit: tokens and entry-point types, as
 * spec/MESAX_occlusion_unit.txt defines them. Include after <GL/gl.h>;
 * fetch the entry points with the platform's GetProcAddress.
 */
#ifndef GL_MESAX_occlusion_unit
#define GL_MESAX_occlusion_unit 1

#define GL_BRIEF_OCCLUSION_MESAX           0x9791
#define GL_VERBOSE_OCCLUSION_MESAX         0x9792
#define GL_MAX_OCCLUSION_TILES_MESAX       0x9793
#define GL_OCCLUSION_TILE_COUNT_MESAX      0x9794
#define GL_OCCLUSION_TILE_MESAX            0x9795
#define GL_OCCLUSION_BUFFER_COUNT_MESAX    0x9796
#define GL_OCCLUSION_BUFFER_SIZE_MESAX     0x9797
#define GL_OCCLUSION_BUFFER_POINTER_MESAX  0x9798

typedef void (APIENTRYP PFNGLSCISSORSMESAXPROC)(GLsizei count, const GLint *tiles);
typedef void (APIENTRYP PFNGLOCCLUSIONBUFFERSMESAXPROC)(GLsizei count, const GLsizei *sizes,
                                                        GLuint *const *buffers);

#endif
