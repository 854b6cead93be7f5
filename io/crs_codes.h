#pragma once
// EPSG codes in the CRS names city models carry (CityJSON referenceSystem, CityGML srsName).
#include <string>
#include <vector>

namespace skyband {

// The EPSG codes named in a CRS string: for each "EPSG" the last run of digits before the next
// "EPSG" ("urn:ogc:def:crs:EPSG::6697", "http://www.opengis.net/def/crs/EPSG/0/6697",
// "EPSG:6697", compound "urn:ogc:def:crs,crs:EPSG::6668,crs:EPSG::6695").
std::vector<int> crs_epsg_codes(const std::string& crs);

}  // namespace skyband
