#pragma once
// Scene files: a TOML description of what `skyband render` draws (toml++ is included only in
// scene_file.cpp). Every key, its unit and its default:
//
//   meshes = ["building.obj", "ground.obj"]   # required; paths relative to the scene file
//
//   [materials]
//   default = "diffuse-wall"                  # for usemtl names that are neither built-in nor assigned
//   [materials.assign]                        # OBJ usemtl name -> built-in skyband material
//   wall = "ceramic-tile"                     # (a usemtl name that IS a built-in name maps to itself)
//
//   [camera]
//   position = [x, y, z]     # metres (x east, y north, z up); required
//   look_at  = [x, y, z]     # metres; required
//   up       = [0, 0, 1]
//   fov_deg  = 45            # vertical field of view, degrees, (0, 180)
//
//   [sun]                    # EITHER altitude/azimuth ...
//   altitude_deg = 50        # apparent altitude, degrees [-90, 90]
//   azimuth_deg  = 180       # degrees clockwise from north
//                            # ... OR place and time (NREL SPA, sun_position.h):
//   latitude_deg, longitude_deg (east +), elevation_m = 0,
//   time = "2024-06-21T10:00:00+02:00"  (ISO 8601; a TOML date-time also works),
//   utc_offset_hours         # when the time carries no offset
//
//   [sky]
//   model = "multiple"       # single | multiple | cie-1 … cie-15 | cie-overcast
//   aod550 = 0.1             # aerosol optical depth at 550 nm
//   angstrom_alpha = 1.3
//   ozone_du = 300           # Dobson units
//   zenith_luminance_cd_m2   # CIE skies only (default: gensky-style formula)
//
//   [quality]
//   visibility = "auto"      # how each surface sample's visible sky is found: "auto" (exact:
//                            # the exact horizon where it applies, else the exact union of the
//                            # occluders; geometry/visibility/sky_visibility.h), "exact" (the exact union
//                            # everywhere) or "bands" (the band method's own geometry pass)
//   bands = 64               # N equal-weight bands (sample lines), [1, 4096]
//   tolerance = 0            # 0 = fixed N. Else, exact visibility: N is doubled per sample
//                            # until the lines' SVF and exposure are within tolerance/2 of the
//                            # exact values (geometry/bands/sample_lines.h); bands: the band method's
//                            # adaptive refinement target. Either way every point then has its
//                            # own band layout and therefore its own sky table: much slower
//                            # shading (see renderer.h).
//   epsilon = 1e-3           # truncation threshold of the specular sky march (seed §3), (0, 1)
//   samples = 1              # samples per pixel, [1, 256]
//   paper_scale = false      # Cook–Torrance 1982 ×4 scale instead of the microfacet form
//   reuse_block = 32         # image-space reuse of the specular sky term: largest block, pixels,
//                            # [1, 1024] (rounded down to 4·2^k; < 4 = off; specular_reuse.h)
//   reuse_tolerance = 0.01   # its relative check tolerance, [0, 0.5] (0 = every pixel marched)
//
//   [image]
//   width = 640, height = 480  # pixels
//   exposure                 # PNG exposure (> 0); default: automatic from the total layer
//
// Overrides: "key=value" strings with dotted keys (`sun.altitude_deg=17`, `image.width=320`,
// `materials.assign.wall=painted-wall`); the value is read as a TOML value, and as a plain string
// when it is not one (`sky.model=cie-12`). Unknown keys (in the file or an override) are errors.
// Errors throw InputError naming "file:line:column", the key and the value, or "--set key=value".
// Text: UTF-8, with non-ASCII characters in strings and comments only (quote a key that holds
// them: "façade" = ...), and no control characters in string values — toml++ 3.3.0 is only ever
// given ASCII (io/toml_ascii.h says why). A mesh path the system refuses (a component over 255
// bytes) is an InputError naming the key, like a missing file.
#include <filesystem>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/mesh/camera.h"
#include "geometry/mesh/triangle_soup.h"
#include "geometry/visibility/sky_factors.h"
#include "lighting/atmosphere/atmosphere.h"
#include "lighting/sky/sky_model.h"

namespace skyband {

struct SceneDescription {
  std::filesystem::path file;                 // the scene file (messages, provenance)
  std::vector<std::filesystem::path> meshes;  // resolved against the scene file's folder
  std::string default_material = "diffuse-wall";
  std::map<std::string, std::string> material_assignment;  // usemtl name -> built-in material
  CameraSpec camera;                                       // includes image width/height
  double sun_altitude_deg = 50, sun_azimuth_deg = 180;
  std::string sun_source = "given";  // "given" or the SPA inputs
  AtmosphereParams atmosphere;
  std::string sky_model = "multiple";
  SkyModelSpec sky_spec;
  SkyFactorsMethod visibility = SkyFactorsMethod::automatic;
  int bands = 64;
  double tolerance = 0;
  double epsilon = 1e-3;
  int samples = 1;
  bool paper_scale = false;
  int reuse_block = 32;
  double reuse_tolerance = 0.01;
  std::optional<double> exposure;
};

// Parses scene text; `name` is used in messages and to resolve mesh paths (its parent folder).
SceneDescription parse_scene(std::string_view text, const std::filesystem::path& name,
                             std::span<const std::string> overrides = {});
// Reads and parses a scene file (InputError if unreadable).
SceneDescription load_scene_file(const std::filesystem::path& file, std::span<const std::string> overrides = {});

// Reads every mesh and joins them into one soup whose material_names are built-in material
// names (usemtl name → assignment → itself if built-in → default). `report` (optional) gets one
// line per mesh. The meshes must share one CRS (io/scene_crs.h).
TriangleSoup load_scene_geometry(const SceneDescription& scene, std::vector<std::string>* report = nullptr);

}  // namespace skyband
