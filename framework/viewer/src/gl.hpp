#pragma once
// The OpenGL the viewer draws with, chosen at compile time: OpenGL 3.3 core through GLEW on
// the desktop, OpenGL ES 3.0 in the browser (SPRINGLAB_GLES3: Emscripten's WebGL2, which
// needs no function loader). Every file of the viewer that calls OpenGL includes this.
#ifdef SPRINGLAB_GLES3
#include <GLES3/gl3.h>
#else
#include <GL/glew.h>
#endif

namespace springlab::viewer {

// The first line of every shader: the GLSL of the context, with the default float precision
// GLSL ES asks for in fragment shaders.
#ifdef SPRINGLAB_GLES3
inline constexpr const char* kGlslVersion = "#version 300 es\nprecision highp float;\n";
#else
inline constexpr const char* kGlslVersion = "#version 330 core\n";
#endif

}  // namespace springlab::viewer
