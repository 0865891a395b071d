/* See include/glad/gl.h: glad 2's gladLoadGL over glad 1's gladLoadGLLoader. */
#include <glad/gl.h>

int shaderlab_glad1_load(GLADloadfunc load) {
    /* Both types are "a function that takes a name and returns an address": glad 1 spells the
     * address void*, glad 2 a function pointer. The platforms Mesa runs on pass them alike. */
    if (!gladLoadGLLoader((GLADloadproc)(void*)load)) return 0;
    return GLVersion.major * 10000 + GLVersion.minor;
}
