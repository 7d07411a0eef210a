#pragma once
// The one place GL headers come in: GLEW first (it defines the GL API), then what the render
// code needs besides.
#include <GL/glew.h>
