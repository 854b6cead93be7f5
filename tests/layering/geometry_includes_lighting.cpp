// A back-edge that must not compile: geometry sits below lighting (CMakeLists.txt, skyband_layer), so a
// geometry source does not see lighting's headers. Compiled only by the CTest layering.geometry_includes_lighting.
#include "lighting/spectrum/spectrum.h"
