#include "io/scene_crs.h"

#include "geometry/core/input_error.h"
#include "io/geo_raster.h"
#include "io/utf8_text.h"

namespace skyband {

MeshReadOptions SceneCrs::next(MeshReadOptions options) const {
  if (zone_) options.utm_zone = zone_;
  return options;
}

void SceneCrs::add(MeshReadReport& report) {
  if (!zone_ && report.utm_zone) zone_ = report.utm_zone;
  if (report.crs.empty()) return;
  if (crs_.empty()) {
    crs_ = report.crs;
    file_ = report.file;
    return;
  }
  const std::optional<bool> same = same_crs(crs_, report.crs);
  if (same == false)
    throw InputError(
        report.file + " is in the CRS " + printable_text(report.crs) + ", " + file_ + " (read before it) in " +
        printable_text(crs_) +
        ": models in different CRSs cannot be combined in one scene; reproject one of them to the other's CRS first");
  if (!same)
    report.warnings.push_back(report.file + " is in the CRS " + printable_text(report.crs) + ", " + file_ + " in " +
                              printable_text(crs_) +
                              ": GDAL does not know one of them, so whether they are the same is not "
                              "checked; the models are combined as they are");
}

}  // namespace skyband
