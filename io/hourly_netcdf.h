#pragma once
// Hourly results as NetCDF-4 with CF conventions (CF-1.8), which xarray opens in one line
// (`xarray.open_dataset("hourly.nc")`) and numpy/netCDF4 read directly:
//
//   dimensions  point (the rows of the points file, in order), time (the weather's intervals)
//   time(time)            double, "hours since 1970-01-01 00:00:00" UTC, the middle of each interval
//   time_bounds(time, 2)  double, the interval's ends (CF cell bounds)
//   point(point)          int, 0-based row of the points file; point_id(point) string when the
//                         points file has an `id` column
//   x, y, z, nx, ny, nz (point)        double, metres and the unit normal, as read
//   sky_W_m2, sun_W_m2, ground_W_m2, global_W_m2 (point, time)   float, mean irradiance over the
//                         interval on the point's face, broadband shortwave (W m-2)
//   global_lx (point, time)  float, mean illuminance over the interval on the point's face (lx)
//   global attributes: title, source (the weather file and its site), history (the command),
//                      Conventions = "CF-1.8"
//
// Written as the points are computed: memory O(points), not O(points × hours); chunks of one
// point's whole series, deflate level 1 with shuffle (night hours compress to nothing). The file
// is written under a temporary name beside the target and renamed when complete: an interrupted
// run leaves no half-written file.
#include <filesystem>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include "geometry/bands/band_visibility.h"
#include "io/interrupted_output.h"

namespace skyband {

struct HourlyNetcdfSpec {
  std::filesystem::path file;
  std::vector<double> time_begin_h, time_end_h;  // per interval, hours since 1970-01-01 UTC
  std::vector<QueryPoint> points;
  std::vector<std::string> point_ids;  // empty, or one per point
  std::string title, source, history;
};

class HourlyNetcdfWriter {
 public:
  // Creates the temporary file with every dimension, coordinate and attribute. Throws InputError
  // naming the file when it cannot be created.
  explicit HourlyNetcdfWriter(const HourlyNetcdfSpec& spec);
  ~HourlyNetcdfWriter();  // an uncommitted file is removed
  HourlyNetcdfWriter(const HourlyNetcdfWriter&) = delete;
  HourlyNetcdfWriter& operator=(const HourlyNetcdfWriter&) = delete;

  // One point's series (one value per interval each: irradiances in W m-2, the global illuminance
  // in lx); thread-safe.
  void write(std::size_t point, std::span<const float> sky, std::span<const float> sun, std::span<const float> ground,
             std::span<const float> global_lx);
  // Closes the file and renames it into place.
  void commit();

 private:
  void check(int status, const char* what) const;
  std::filesystem::path file_, temp_;
  std::unique_ptr<TemporaryOutput> removed_on_interrupt_;  // temp_, while it is not committed
  std::size_t times_ = 0;
  int ncid_ = -1;
  int var_[5] = {-1, -1, -1, -1, -1};
  bool open_ = false;
  std::mutex mutex_;
  std::vector<float> global_;
};

}  // namespace skyband
