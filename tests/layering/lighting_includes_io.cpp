// A back-edge that must not compile: lighting sits below io (CMakeLists.txt, skyband_layer), so a
// lighting source does not see io's headers. Compiled only by the CTest layering.lighting_includes_io.
#include "io/mesh_reader.h"
