// A back-edge that must not compile: io sits below render (CMakeLists.txt, skyband_layer), so a
// io source does not see render's headers. Compiled only by the CTest layering.io_includes_render.
#include "render/renderer.h"
