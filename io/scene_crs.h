#pragma once
// One CRS for the models of one scene. Files given together (`--mesh a.gml --mesh b.json`) are
// appended into one soup as they are (TriangleSoup::append), so they must be in one CRS:
//  - a file that names a CRS different from the one of a file read before it is refused
//    (InputError naming both files and both CRSs): models in different CRSs would be placed in
//    one frame as if they were the same, kilometres or continents apart, silently;
//  - a file that names none (OBJ, OFF, PLY, STL, a city model without one) joins any;
//  - geographic city models projected to UTM (io/citygml_reprojection.h) share the zone of the
//    first one where they can, so tiles on both sides of a zone boundary join in one CRS.
// CRSs are compared by same_crs (io/geo_raster.h: the same horizontal CRS, and the same vertical
// one when both name one); where it cannot tell (a CRS GDAL does not know), the later file's
// report carries a warning.
#include <optional>
#include <string>

#include "io/mesh_reader.h"

namespace skyband {

class SceneCrs {
 public:
  // The read options for the next file: `options` with the scene's UTM zone, if it has one.
  MeshReadOptions next(MeshReadOptions options) const;
  // Takes the report of a file just read into the scene: InputError if its CRS is not the
  // scene's; a warning added to report.warnings if that cannot be told.
  void add(MeshReadReport& report);
  // The scene's CRS, as the first file that names one names it ("" = none does).
  const std::string& crs() const { return crs_; }

 private:
  std::string crs_, file_;  // the first file naming a CRS, and that CRS
  std::optional<UtmZone> zone_;
};

}  // namespace skyband
