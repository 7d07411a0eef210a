// Compiled with the engine's include path by the engine_rejects_gl_include test, which expects
// the build to fail: the engine may not include GL.
#include <GL/gl.h>
int probe() { return 0; }
