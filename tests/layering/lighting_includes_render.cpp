// A back-edge that must not compile: lighting sits below render (CMakeLists.txt, skyband_layer), so a
// lighting source does not see render's headers. Compiled only by the CTest layering.lighting_includes_render.
#include "render/renderer.h"
