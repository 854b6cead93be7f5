#define BOOST_TEST_MODULE scene_crs
#include <boost/test/unit_test.hpp>

// SceneCrs (io/scene_crs.h): files of one scene share a CRS; the first file naming one sets it,
// a file naming another is refused naming both, one naming none joins, one that cannot be
// compared joins with a warning; the UTM zone of the first geographic model is handed on.

#include <string>

#include "geometry/core/input_error.h"
#include "input_error_of.h"
#include "io/scene_crs.h"

using namespace skyband;

namespace {

MeshReadReport report(const std::string& file, const std::string& crs, std::optional<UtmZone> zone = std::nullopt) {
  MeshReadReport r;
  r.file = file;
  r.crs = crs;
  r.utm_zone = zone;
  return r;
}

using skyband::test::error_of;

}  // namespace

BOOST_AUTO_TEST_CASE(files_in_one_crs_join_and_others_are_refused_naming_both) {
  SceneCrs scene;
  MeshReadReport obj = report("trees.obj", ""), a = report("a.gml", "EPSG:28992"), b = report("b.json", "EPSG:7415"),
                 c = report("c.gml", "urn:ogc:def:crs:EPSG::25833");
  scene.add(obj);
  BOOST_TEST(scene.crs().empty());
  scene.add(a);
  scene.add(b);    // RD New + NAP height: the same horizontal CRS
  scene.add(obj);  // no CRS: joins
  BOOST_TEST(scene.crs() == "EPSG:28992");
  BOOST_TEST(a.warnings.empty());
  BOOST_TEST(b.warnings.empty());
  const std::string e = error_of([&] { scene.add(c); });
  BOOST_TEST(e.find("c.gml is in the CRS urn:ogc:def:crs:EPSG::25833, a.gml (read before it) in EPSG:28992") == 0u, e);
  BOOST_TEST(e.find("cannot be combined") != std::string::npos, e);
  BOOST_TEST(e.find('\n') == std::string::npos);
}

BOOST_AUTO_TEST_CASE(a_crs_that_cannot_be_compared_joins_with_a_warning) {
  SceneCrs scene;
  MeshReadReport a = report("a.gml", "EPSG:25833"), b = report("b.gml", "urn:adv:crs:ETRS89_UTM33*DE_DHHN92_NH");
  scene.add(a);
  scene.add(b);
  BOOST_TEST_REQUIRE(b.warnings.size() == 1u);
  BOOST_TEST(b.warnings[0].find("b.gml is in the CRS urn:adv:crs:ETRS89_UTM33*DE_DHHN92_NH, a.gml in EPSG:25833") == 0u,
             b.warnings[0]);
}

BOOST_AUTO_TEST_CASE(the_first_geographic_models_utm_zone_is_handed_on) {
  SceneCrs scene;
  MeshReadOptions options;
  options.lod = "2";
  BOOST_TEST(!scene.next(options).utm_zone.has_value());
  MeshReadReport projected = report("rd.gml", "EPSG:6690"), tokyo = report("tokyo.gml", "EPSG:6690", UtmZone{53, true});
  scene.add(projected);
  BOOST_TEST(!scene.next(options).utm_zone.has_value());
  scene.add(tokyo);
  const MeshReadOptions next = scene.next(options);
  BOOST_TEST((next.utm_zone == UtmZone{53, true}));
  BOOST_TEST(*next.lod == "2");
  MeshReadReport other = report("osaka.gml", "EPSG:6690", UtmZone{54, true});  // a later zone does not replace it
  scene.add(other);
  BOOST_TEST((scene.next(options).utm_zone == UtmZone{53, true}));
}
