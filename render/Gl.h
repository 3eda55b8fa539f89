#pragma once
// The OpenGL 4.5 core API. glvnd's libOpenGL exports every core entry point, so the prototypes are
// linked directly and no loader is needed; the context must come from HeadlessGlContext.
#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>
