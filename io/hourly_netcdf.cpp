#include "io/hourly_netcdf.h"

#include <netcdf.h>

#include <cstring>
#include <system_error>

#include "geometry/core/input_error.h"

namespace skyband {

void HourlyNetcdfWriter::check(int status, const char* what) const {
  if (status != NC_NOERR) throw InputError(file_.string() + ": cannot write NetCDF (" + what + "): " + nc_strerror(status));
}

HourlyNetcdfWriter::HourlyNetcdfWriter(const HourlyNetcdfSpec& spec) : file_(spec.file), times_(spec.time_begin_h.size()) {
  temp_ = file_;
  temp_ += ".partial";
  removed_on_interrupt_ = std::make_unique<TemporaryOutput>(temp_);
  check(nc_create(temp_.c_str(), NC_CLOBBER | NC_NETCDF4, &ncid_), "create");
  open_ = true;
  int dim_point, dim_time, dim_nv;
  const std::size_t n = spec.points.size();
  check(nc_def_dim(ncid_, "point", n, &dim_point), "point dimension");
  check(nc_def_dim(ncid_, "time", times_, &dim_time), "time dimension");
  check(nc_def_dim(ncid_, "nv", 2, &dim_nv), "bounds dimension");
  const auto text = [&](int var, const char* name, const std::string& value) {
    check(nc_put_att_text(ncid_, var, name, value.size(), value.c_str()), name);
  };
  int v_time, v_bounds, v_point, v_id = -1, v_xyz[6];
  check(nc_def_var(ncid_, "time", NC_DOUBLE, 1, &dim_time, &v_time), "time");
  text(v_time, "units", "hours since 1970-01-01 00:00:00");
  text(v_time, "standard_name", "time");
  text(v_time, "calendar", "standard");
  text(v_time, "bounds", "time_bounds");
  text(v_time, "long_name", "middle of the interval (UTC)");
  const int bdims[2] = {dim_time, dim_nv};
  check(nc_def_var(ncid_, "time_bounds", NC_DOUBLE, 2, bdims, &v_bounds), "time_bounds");
  check(nc_def_var(ncid_, "point", NC_INT, 1, &dim_point, &v_point), "point");
  text(v_point, "long_name", "0-based row of the points file");
  if (!spec.point_ids.empty()) {
    check(nc_def_var(ncid_, "point_id", NC_STRING, 1, &dim_point, &v_id), "point_id");
    text(v_id, "long_name", "the points file's id column");
  }
  const char* names[6] = {"x", "y", "z", "nx", "ny", "nz"};
  const char* longs[6] = {"x (east)", "y (north)", "z (up)", "normal x", "normal y", "normal z"};
  for (int k = 0; k < 6; ++k) {
    check(nc_def_var(ncid_, names[k], NC_DOUBLE, 1, &dim_point, &v_xyz[k]), names[k]);
    text(v_xyz[k], "units", k < 3 ? "m" : "1");
    text(v_xyz[k], "long_name", longs[k]);
  }
  const int dims[2] = {dim_point, dim_time};
  const char* vars[5] = {"sky_W_m2", "sun_W_m2", "ground_W_m2", "global_W_m2", "global_lx"};
  const char* what[5] = {"diffuse sky irradiance on the face (Perez all-weather sky)", "direct sun irradiance on the face",
                         "ground-reflected irradiance on the face", "global irradiance on the face (sky + sun + ground)",
                         "global illuminance on the face (sky + sun + ground)"};
  const std::size_t chunk[2] = {1, times_ > 0 ? times_ : 1};
  for (int k = 0; k < 5; ++k) {
    check(nc_def_var(ncid_, vars[k], NC_FLOAT, 2, dims, &var_[k]), vars[k]);
    if (n > 0 && times_ > 0) {
      check(nc_def_var_chunking(ncid_, var_[k], NC_CHUNKED, chunk), "chunking");
      check(nc_def_var_deflate(ncid_, var_[k], 1, 1, 1), "deflate");
    }
    text(var_[k], "units", k < 4 ? "W m-2" : "lx");
    text(var_[k], "long_name",
         std::string(what[k]) + (k < 4 ? ", mean over the interval, broadband shortwave" : ", mean over the interval"));
    text(var_[k], "cell_methods", "time: mean");
  }
  text(NC_GLOBAL, "Conventions", "CF-1.8");
  text(NC_GLOBAL, "title", spec.title);
  text(NC_GLOBAL, "source", spec.source);
  text(NC_GLOBAL, "history", spec.history);
  check(nc_enddef(ncid_), "enddef");
  if (times_ > 0) {
    std::vector<double> mid(times_), bounds(2 * times_);
    for (std::size_t t = 0; t < times_; ++t) {
      mid[t] = 0.5 * (spec.time_begin_h[t] + spec.time_end_h[t]);
      bounds[2 * t] = spec.time_begin_h[t];
      bounds[2 * t + 1] = spec.time_end_h[t];
    }
    check(nc_put_var_double(ncid_, v_time, mid.data()), "time values");
    check(nc_put_var_double(ncid_, v_bounds, bounds.data()), "time_bounds values");
  }
  if (n > 0) {
    std::vector<int> rows(n);
    for (std::size_t i = 0; i < n; ++i) rows[i] = static_cast<int>(i);
    check(nc_put_var_int(ncid_, v_point, rows.data()), "point values");
    std::vector<double> c(n);
    for (int k = 0; k < 6; ++k) {
      for (std::size_t i = 0; i < n; ++i) c[i] = k < 3 ? spec.points[i].position[k] : spec.points[i].normal[k - 3];
      check(nc_put_var_double(ncid_, v_xyz[k], c.data()), names[k]);
    }
    if (v_id >= 0) {
      std::vector<const char*> ids(n);
      for (std::size_t i = 0; i < n; ++i) ids[i] = spec.point_ids[i].c_str();
      check(nc_put_var_string(ncid_, v_id, ids.data()), "point_id values");
    }
  }
}

HourlyNetcdfWriter::~HourlyNetcdfWriter() {
  if (open_) {
    nc_close(ncid_);
    std::error_code ec;
    std::filesystem::remove(temp_, ec);
  }
}

void HourlyNetcdfWriter::write(std::size_t point, std::span<const float> sky, std::span<const float> sun,
                               std::span<const float> ground, std::span<const float> global_lx) {
  const std::lock_guard lock(mutex_);
  const std::size_t start[2] = {point, 0}, count[2] = {1, times_};
  global_.resize(times_);
  for (std::size_t t = 0; t < times_; ++t) global_[t] = sky[t] + sun[t] + ground[t];
  check(nc_put_vara_float(ncid_, var_[0], start, count, sky.data()), "sky_W_m2");
  check(nc_put_vara_float(ncid_, var_[1], start, count, sun.data()), "sun_W_m2");
  check(nc_put_vara_float(ncid_, var_[2], start, count, ground.data()), "ground_W_m2");
  check(nc_put_vara_float(ncid_, var_[3], start, count, global_.data()), "global_W_m2");
  check(nc_put_vara_float(ncid_, var_[4], start, count, global_lx.data()), "global_lx");
}

void HourlyNetcdfWriter::commit() {
  check(nc_close(ncid_), "close");
  open_ = false;
  std::error_code ec;
  std::filesystem::rename(temp_, file_, ec);
  removed_on_interrupt_.reset();
  if (ec) {
    std::filesystem::remove(temp_, ec);
    throw InputError(file_.string() + ": cannot write (" + ec.message() + ")");
  }
}

}  // namespace skyband
