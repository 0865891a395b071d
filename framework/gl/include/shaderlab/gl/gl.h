// The one way framework code reaches OpenGL: the glad-generated 4.5 core loader.
#pragma once

#include <glad/gl.h>
