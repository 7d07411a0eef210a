// Placed first on the include path of the engine library only.
#error "src/engine must not include <GLFW/glfw3.h>: the engine is plain C++ (Eigen + OpenMP). GL belongs in src/render."
