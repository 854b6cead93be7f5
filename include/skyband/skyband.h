#pragma once
// skyband: exact sky visibility and spectral sun + sky lighting of building and city models.
// The umbrella header of the library (target skyband::skyband): the entry points of every layer.
// Each layer's headers are also reachable one by one as "<layer>/<subsystem>/<name>.h" with the
// layer's own target (skyband::geometry, skyband::lighting, skyband::render, skyband::io).
// Units: metres, x east, y north, z up; azimuths clockwise from north; radiance W·m⁻²·sr⁻¹.
// Errors in user input throw skyband::InputError (geometry/core/input_error.h).

// geometry: meshes, calculation points, the visible sky of a point.
#include "geometry/core/input_error.h"
#include "geometry/core/vec3.h"
#include "geometry/horizon/horizon_profile.h"
#include "geometry/mesh/mesh_defects.h"
#include "geometry/mesh/scene.h"
#include "geometry/mesh/triangle_soup.h"
#include "geometry/points/facade_points.h"
#include "geometry/points/ground_grid.h"
#include "geometry/visibility/sky_factors.h"
#include "geometry/visibility/sky_visibility.h"
#include "geometry/visibility/visible_sky.h"

// lighting: spectra, skies, the sun, BRDFs, integrals over the visible sky, weather periods.
#include "lighting/brdf/material.h"
#include "lighting/climate/climate_irradiation.h"
#include "lighting/climate/weather_hours.h"
#include "lighting/climate/weather_series.h"
#include "lighting/integrals/point_irradiance.h"
#include "lighting/sky/cie_sky.h"
#include "lighting/sky/perez_sky.h"
#include "lighting/sky/sky_model.h"
#include "lighting/spectrum/colour.h"
#include "lighting/spectrum/spectrum.h"
#include "lighting/sun/sun.h"
#include "lighting/sun/sun_position.h"

// render: images of a scene through a pinhole camera.
#include "render/renderer.h"

// io: meshes and city models in, points and weather in, CSV, EXR, PNG, GeoTIFF, PLY out.
#include "io/citygml_reader.h"
#include "io/cityjson_reader.h"
#include "io/epw_reader.h"
#include "io/exr_writer.h"
#include "io/geo_raster.h"
#include "io/mesh_reader.h"
#include "io/ply_writer.h"
#include "io/png_writer.h"
#include "io/points_csv.h"
#include "io/scene_file.h"
#include "io/tmy3_reader.h"
