// Placed first on the include path of the engine library only.
#error "src/engine must not include <GL/glew.h>: the engine is plain C++ (Eigen + OpenMP). GL belongs in src/render."
