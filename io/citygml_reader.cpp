#include "io/citygml_reader.h"

#include <citygml/citygml.h>
#include <citygml/citygmllogger.h>
#include <citygml/citymodel.h>
#include <citygml/cityobject.h>
#include <citygml/geometry.h>
#include <citygml/implictgeometry.h>
#include <citygml/polygon.h>

#include <xercesc/framework/MemBufInputSource.hpp>
#include <xercesc/sax/SAXParseException.hpp>
#include <xercesc/sax2/DefaultHandler.hpp>
#include <xercesc/sax2/SAX2XMLReader.hpp>
#include <xercesc/sax2/XMLReaderFactory.hpp>
#include <xercesc/util/PlatformUtils.hpp>
#include <xercesc/util/XMLString.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <mutex>
#include <set>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include "geometry/core/input_error.h"
#include "geometry/mesh/polygon_with_holes_triangulation.h"
#include "io/citygml_reprojection.h"
#include "io/mesh_reader.h"
#include "io/utf8_text.h"

namespace skyband {
namespace {

using citygml::CityObject;
using Type = CityObject::CityObjectsType;
constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
// libcitygml 2.4 keeps only the last piece of a text node Xerces delivers in pieces: measured,
// a 1,038,788-byte posList is read whole, a 1,050,038-byte one loses its start (1 MiB chunks).
constexpr std::size_t kMaxTextBytes = 1000000;

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::size_t line_of(const std::string& bytes, std::size_t offset) {
  return 1 + static_cast<std::size_t>(std::count(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(offset), '\n'));
}

std::string read_bytes(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw InputError("mesh file '" + file.string() + "' does not exist");
  if (std::filesystem::is_directory(file, ec)) throw InputError("mesh file '" + file.string() + "' is a directory, not a file");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string() + ": cannot open: " + std::strerror(errno));
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(file.string() + ": read error");
  return bytes;
}

// ---- The byte scan before libcitygml -------------------------------------------------------

struct FileScan {
  std::string version;                 // "1.0" / "2.0"
  std::vector<std::string> srs_names;  // distinct srsName values, in order of appearance
};

// The root element's start tag (after a BOM, the XML declaration, comments and processing
// instructions). DOCTYPEs are refused: CityGML uses none, and a DTD could make Xerces fetch
// external files or expand entities without bound.
std::string_view root_start_tag(const std::string& name, const std::string& bytes) {
  refuse_wide_text(name, bytes, "CityGML");
  std::size_t i = bytes.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
  while (true) {
    while (i < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[i]))) ++i;
    if (i >= bytes.size() || bytes[i] != '<')
      throw InputError(name + ":" + std::to_string(line_of(bytes, std::min(i, bytes.size()))) + ": not XML (no root element)");
    if (bytes.compare(i, 4, "<!--") == 0) {
      const std::size_t end = bytes.find("-->", i + 4);
      if (end == std::string::npos)
        throw InputError(name + ":" + std::to_string(line_of(bytes, i)) + ": malformed XML: unterminated comment");
      i = end + 3;
    } else if (bytes.compare(i, 2, "<?") == 0) {
      const std::size_t end = bytes.find("?>", i + 2);
      if (end == std::string::npos)
        throw InputError(name + ":" + std::to_string(line_of(bytes, i)) + ": malformed XML: unterminated <?...?>");
      i = end + 2;
    } else if (bytes.compare(i, 2, "<!") == 0) {
      throw InputError(name + ":" + std::to_string(line_of(bytes, i)) +
                       ": a DOCTYPE declaration: CityGML files have none (refused: a DTD could load external files)");
    } else {
      const std::size_t end = bytes.find('>', i);
      if (end == std::string::npos)
        throw InputError(name + ":" + std::to_string(line_of(bytes, i)) + ": malformed XML: unterminated root element");
      return std::string_view(bytes).substr(i, end + 1 - i);
    }
  }
}

// Every text run (between '>' and the next '<') must be shorter than kMaxTextBytes.
void check_text_lengths(const std::string& name, const std::string& bytes) {
  std::size_t i = bytes.find('>');
  while (i != std::string::npos) {
    const std::size_t next = bytes.find('<', i + 1);
    const std::size_t end = next == std::string::npos ? bytes.size() : next;
    if (end - i - 1 > kMaxTextBytes)
      throw InputError(name + ":" + std::to_string(line_of(bytes, i)) + ": a text of " + std::to_string(end - i - 1) +
                       " bytes (a gml:posList?): libcitygml 2.4 cuts texts over 1 MiB silently, so the file is not read; "
                       "split the ring or convert the file to CityJSON (citygml-tools to-cityjson)");
    if (next == std::string::npos) return;
    i = bytes.find('>', next);
  }
}

// Line numbers of increasing offsets into the file, counted once over the bytes.
class LineCounter {
 public:
  explicit LineCounter(const std::string& bytes) : bytes_(bytes) {}
  std::size_t at(std::size_t offset) {
    line_ += static_cast<std::size_t>(std::count(bytes_.begin() + static_cast<std::ptrdiff_t>(pos_),
                                                 bytes_.begin() + static_cast<std::ptrdiff_t>(offset), '\n'));
    pos_ = offset;
    return line_;
  }

 private:
  const std::string& bytes_;
  std::size_t pos_ = 0, line_ = 1;
};

// The coordinate texts libcitygml reads: gml:posList (a ring, a curve: x y z triples), gml:pos
// (one position: a ring's vertex, an implicit geometry's reference point) and
// core:transformationMatrix (16 numbers). Each must be plain text up to its end tag: libcitygml
// keeps only the piece of a text after its last interruption, so a comment, CDATA section,
// character reference or child element inside it would silently cut the ring (measured).
// Every number must be a finite double, parsed as the mesh readers parse theirs
// (mesh_io::parse_coordinate): libcitygml reads a gml:pos with `stream >> x >> y >> z` and no
// check, so 1e400 would become 1.8e308, "NaN" a NaN and an empty or garbled pos a vertex at
// (0, 0, 0), and a matrix stops at its first bad number, silently (measured). The counts are
// checked too: libcitygml drops a posList's trailing 1 or 2 numbers and reads only the first three
// of a longer pos. GML 2's gml:coordinates and gml:coord it does not read at all (the ring is
// dropped): refused.
void check_coordinate_lists(const std::string& name, const std::string& bytes) {
  LineCounter lines(bytes);
  for (std::size_t lt = bytes.find('<'); lt != std::string::npos; lt = bytes.find('<', lt + 1)) {
    std::size_t n = lt + 1;
    while (n < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[n])) && bytes[n] != '>' && bytes[n] != '/') ++n;
    const std::string_view qname(bytes.data() + lt + 1, n - lt - 1);
    const std::size_t colon = qname.rfind(':');
    const std::string_view local = colon == std::string_view::npos ? qname : qname.substr(colon + 1);
    const bool pos_list = local == "posList", pos = local == "pos", matrix = local == "transformationMatrix";
    const bool gml2 = local == "coordinates" || local == "coord";
    if (!pos_list && !pos && !matrix && !gml2) continue;
    const std::size_t tag_end = bytes.find('>', n);
    if (tag_end == std::string::npos) return;  // malformed: Xerces says where
    const std::string element = "<" + printable_text(qname) + ">";
    const std::size_t line = lines.at(lt);
    auto fail = [&](const std::string& what) {
      throw InputError(name + ":" + std::to_string(line) + ": " + element + " " + what);
    };
    if (gml2) fail("(GML 2 coordinates) is not read by libcitygml 2.4, which would drop its ring: write it as a gml:posList");
    const std::string expected = pos ? "x y z" : matrix ? "16 numbers (a 4 x 4 matrix)" : "x y z triples";
    if (bytes[tag_end - 1] == '/') fail("is empty: " + expected + " expected");
    const std::size_t text_end = bytes.find('<', tag_end + 1);
    const std::string end_tag = "</" + std::string(qname);
    if (text_end == std::string::npos || bytes.compare(text_end, end_tag.size(), end_tag) != 0)
      fail("holds a comment, CDATA section or element: only plain numbers are read (libcitygml would drop the part before it)");
    const std::string_view text(bytes.data() + tag_end + 1, text_end - tag_end - 1);
    if (text.find('&') != std::string_view::npos)
      fail("holds a character or entity reference: only plain numbers are read (libcitygml would drop the part before it)");
    std::size_t numbers = 0;
    const std::string what = "coordinate in " + element;
    for (std::size_t i = 0; i < text.size();) {
      while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
      const std::size_t start = i;
      while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i]))) ++i;
      if (i == start) break;
      ++numbers;
      const std::size_t offset = static_cast<std::size_t>(text.data() - bytes.data()) + start;
      double value = 0;
      const auto [end, ec] = std::from_chars(text.data() + start, text.data() + i, value);
      // The shared parser throws the error naming the value (and reads a leading '+', valid in xs:double).
      if (ec != std::errc() || end != text.data() + i || !std::isfinite(value))
        mesh_io::parse_coordinate(text.substr(start, i - start), name, lines.at(offset), what.c_str());
    }
    if (numbers == 0) fail("is empty: " + expected + " expected");
    if (pos && numbers != 3) fail("holds " + std::to_string(numbers) + " numbers, not x y z");
    if (pos_list && numbers % 3 != 0) fail("holds " + std::to_string(numbers) + " numbers, not x y z triples");
    if (matrix && numbers != 16) fail("holds " + std::to_string(numbers) + " numbers, not 16 (a 4 x 4 matrix)");
    lt = text_end;
  }
}

std::vector<std::string> srs_names(const std::string& bytes) {
  std::vector<std::string> out;
  for (std::size_t i = bytes.find("srsName="); i != std::string::npos; i = bytes.find("srsName=", i + 8)) {
    const std::size_t q = i + 8;
    if (q >= bytes.size() || (bytes[q] != '"' && bytes[q] != '\'')) continue;
    const std::size_t end = bytes.find(bytes[q], q + 1);
    if (end == std::string::npos) break;
    std::string value = bytes.substr(q + 1, end - q - 1);
    if (std::find(out.begin(), out.end(), value) == out.end()) out.push_back(std::move(value));
    if (out.size() > 16) break;  // enough to tell mixed CRSs
  }
  return out;
}

FileScan scan_bytes(const std::string& name, const std::string& bytes) {
  FileScan scan;
  const std::string_view root = root_start_tag(name, bytes);
  for (const char quote : {'"', '\''}) {
    const std::string ns = std::string("http://www.opengis.net/citygml/3.0") + quote;
    if (const std::size_t at = bytes.find(ns); at != std::string::npos)
      throw InputError(name + ":" + std::to_string(line_of(bytes, at)) +
                       ": CityGML 3.0 is not supported (the reader reads CityGML 1.0 and 2.0); convert the file to CityGML 2.0 "
                       "or CityJSON first, e.g. with citygml-tools (citygml-tools to-cityjson " +
                       std::filesystem::path(name).filename().string() + ")");
  }
  if (root.find("http://www.opengis.net/citygml/2.0") != std::string_view::npos)
    scan.version = "2.0";
  else if (root.find("http://www.opengis.net/citygml/1.0") != std::string_view::npos)
    scan.version = "1.0";
  else {
    std::string tag(root.substr(0, std::min<std::size_t>(root.find_first_of(" \t\r\n>"), 60)));
    throw InputError(name + ": not CityGML 1.0 or 2.0: the root element " + printable_text(tag) +
                     "> declares neither http://www.opengis.net/citygml/2.0 nor http://www.opengis.net/citygml/1.0");
  }
  check_text_lengths(name, bytes);
  return scan;
}

// ---- Application Domain Extensions ---------------------------------------------------------

// Namespaces of CityGML 1.0/2.0 itself (core and every module), GML and xAL; elements of any
// other namespace belong to an Application Domain Extension.
bool is_citygml_namespace(std::string_view uri) {
  return uri.starts_with("http://www.opengis.net/citygml/") || uri.starts_with("http://www.opengis.net/gml") ||
         uri == "urn:oasis:names:tc:ciq:xsdschema:xAL:2.0";
}

// The ADE elements blanked out of the file (the outermost ones), by namespace.
struct AdeNamespace {
  std::string uri;
  std::map<std::string, std::size_t> elements;  // qname → count
  // "2 x <test:A>, 1 x <test:B>" (at most `kinds` element names, then "...").
  std::string list(std::size_t kinds) const {
    std::string out;
    std::size_t k = 0;
    for (const auto& [qname, n] : elements) {
      if (k++ == kinds) return out + ", ...";
      out += (out.empty() ? "" : ", ") + std::to_string(n) + " x <" + printable_text(qname) + ">";
    }
    return out;
  }
};
using AdeElements = std::vector<AdeNamespace>;  // in order of appearance

// Blanks out (every byte but line ends replaced by a space, so lines and columns stay) each
// outermost element of an ADE namespace, with its content, and then each element left with no
// content by that (no child element, no text, no attribute: the property, such as a
// core:cityObjectMember or bldg:boundedBy, that held an ADE feature). libcitygml 2.4 reads
// elements by their local name whatever their namespace, skips the ones it does not know, and
// fails on the property then left without an object ("endElement called on unbound
// CityGMLElementParser"); an ADE element whose local name it knows (an ADE's own lod2Solid or
// boundedBy) it would read as CityGML. Runs on well-formed XML (after first_xml_error).
AdeElements blank_ade_elements(std::string& bytes) {
  struct Open {
    std::size_t start = 0, bindings = 0, kept_children = 0, removed_children = 0;
    bool ade = false, inside_ade = false, attributes = false, text = false;
  };
  std::vector<Open> open;
  std::vector<std::pair<std::string, std::string>> bindings;  // (prefix, URI), innermost last
  std::vector<std::pair<std::size_t, std::size_t>> removed;   // [begin, end) byte ranges, in order
  AdeElements found;
  auto is_space = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  // Just past the next `what` from `from` (the end of the file if there is none).
  auto past = [&](std::string_view what, std::size_t from) {
    const std::size_t at = bytes.find(what, from);
    return at == std::string::npos ? bytes.size() : at + what.size();
  };
  auto remove = [&](std::size_t begin, std::size_t end) {
    while (!removed.empty() && removed.back().first >= begin) removed.pop_back();  // inside it
    removed.emplace_back(begin, end);
  };
  // The end of an element (its end tag, or its empty-element tag, ends at `end`).
  auto close = [&](std::size_t end) {
    const Open e = open.back();
    open.pop_back();
    bindings.resize(e.bindings);
    if (e.inside_ade) return;
    bool gone = e.ade;
    if (!gone && !open.empty() && e.removed_children > 0 && e.kept_children == 0 && !e.text && !e.attributes) gone = true;
    if (gone) remove(e.start, end);
    if (!open.empty()) ++(gone ? open.back().removed_children : open.back().kept_children);
  };
  std::size_t i = 0;
  while (true) {
    const std::size_t lt = bytes.find('<', i);
    if (!open.empty() && !open.back().text)
      for (std::size_t k = i; k < std::min(lt, bytes.size()); ++k)
        if (!is_space(bytes[k])) {
          open.back().text = true;
          break;
        }
    if (lt == std::string::npos) break;
    if (bytes.compare(lt, 4, "<!--") == 0) {
      i = past("-->", lt + 4);
    } else if (bytes.compare(lt, 9, "<![CDATA[") == 0) {
      if (!open.empty()) open.back().text = true;
      i = past("]]>", lt + 9);
    } else if (bytes.compare(lt, 2, "<?") == 0) {
      i = past("?>", lt + 2);
    } else if (bytes.compare(lt, 2, "<!") == 0) {
      i = past(">", lt + 2);
    } else if (bytes.compare(lt, 2, "</") == 0) {
      i = past(">", lt + 2);
      if (!open.empty()) close(i);
    } else {
      std::size_t k = lt + 1;
      while (k < bytes.size() && !is_space(bytes[k]) && bytes[k] != '>' && bytes[k] != '/') ++k;
      const std::string qname = bytes.substr(lt + 1, k - lt - 1);
      Open e;
      e.start = lt;
      e.bindings = bindings.size();
      e.inside_ade = !open.empty() && (open.back().ade || open.back().inside_ade);
      // Attributes up to the tag's end ('>' may appear inside quoted values).
      while (true) {
        while (k < bytes.size() && is_space(bytes[k])) ++k;
        if (k >= bytes.size() || bytes[k] == '>' || bytes[k] == '/') break;
        const std::size_t eq = bytes.find('=', k);
        if (eq == std::string::npos) break;
        std::size_t name_end = eq;
        while (name_end > k && is_space(bytes[name_end - 1])) --name_end;
        const std::string attribute = bytes.substr(k, name_end - k);
        std::size_t q = eq + 1;
        while (q < bytes.size() && is_space(bytes[q])) ++q;
        if (q >= bytes.size() || (bytes[q] != '"' && bytes[q] != '\'')) break;
        const std::size_t value_end = bytes.find(bytes[q], q + 1);
        if (value_end == std::string::npos) break;
        const std::string value = bytes.substr(q + 1, value_end - q - 1);
        if (attribute == "xmlns")
          bindings.emplace_back("", value);
        else if (attribute.starts_with("xmlns:"))
          bindings.emplace_back(attribute.substr(6), value);
        else
          e.attributes = true;
        k = value_end + 1;
      }
      const bool empty_element = k < bytes.size() && bytes[k] == '/';
      i = past(">", k);
      const std::size_t colon = qname.find(':');
      const std::string prefix = colon == std::string::npos ? "" : qname.substr(0, colon);
      const auto binding = std::find_if(bindings.rbegin(), bindings.rend(), [&](const auto& b) { return b.first == prefix; });
      const std::string_view local = std::string_view(qname).substr(colon == std::string::npos ? 0 : colon + 1);
      if (!e.inside_ade && local == "externalReference" && binding != bindings.rend() &&
          (binding->second == "http://www.opengis.net/citygml/2.0" || binding->second == "http://www.opengis.net/citygml/1.0")) {
        // core:externalReference (a link to another data set, no geometry; every building of the
        // Bavarian and other cadastral LoD2 files has one): libcitygml 2.4 fails on its
        // core:informationSystem ("Expected start tag <core:externalreference>"), so it goes too.
        e.ade = true;
      } else if (!e.inside_ade && binding != bindings.rend() && !binding->second.empty() &&
                 !is_citygml_namespace(binding->second)) {
        e.ade = true;
        auto ns = std::find_if(found.begin(), found.end(), [&](const AdeNamespace& a) { return a.uri == binding->second; });
        if (ns == found.end()) ns = found.insert(found.end(), {binding->second, {}});
        if (ns->elements.size() < 64 || ns->elements.count(qname)) ++ns->elements[qname];
      }
      open.push_back(e);
      if (empty_element) close(i);
    }
  }
  for (const auto& [begin, end] : removed)
    for (std::size_t k = begin; k < end; ++k)
      if (bytes[k] != '\n' && bytes[k] != '\r') bytes[k] = ' ';
  return found;
}

// ---- Xerces: where malformed XML breaks ----------------------------------------------------

std::string transcode(const XMLCh* text) {
  if (!text) return "";
  char* s = xercesc::XMLString::transcode(text);
  std::string out = s ? s : "";
  xercesc::XMLString::release(&s);
  return out;
}

void init_xerces() {
  static std::once_flag once;
  std::call_once(once, [] { xercesc::XMLPlatformUtils::Initialize(); });
}

// A well-formedness pass of Xerces alone, before libcitygml: returns "line:column: message" of
// the first fatal error, or "" if Xerces finds none. libcitygml 2.4 on malformed XML loses the
// line (it logs Xerces' message alone) and leaks the objects it had built (measured with
// LeakSanitizer: ~130 kB for a file cut after its first building), so it only sees well-formed
// XML. Costs a SAX pass without handlers, a fraction of libcitygml's own.
std::string first_xml_error(const std::string& bytes) {
  init_xerces();
  struct Handler : xercesc::DefaultHandler {};
  Handler handler;
  std::unique_ptr<xercesc::SAX2XMLReader> parser(xercesc::XMLReaderFactory::createXMLReader());
  parser->setFeature(xercesc::XMLUni::fgSAX2CoreNameSpaces, false);
  parser->setFeature(xercesc::XMLUni::fgXercesLoadExternalDTD, false);
  parser->setContentHandler(&handler);
  parser->setErrorHandler(&handler);
  xercesc::MemBufInputSource source(reinterpret_cast<const XMLByte*>(bytes.data()), bytes.size(), "citygml");
  try {
    parser->parse(source);
  } catch (const xercesc::SAXParseException& e) {
    return std::to_string(e.getLineNumber()) + ":" + std::to_string(e.getColumnNumber()) + ": " + transcode(e.getMessage());
  } catch (const xercesc::XMLException& e) {
    return transcode(e.getMessage());
  } catch (...) {
    return "";
  }
  return "";
}

// ---- libcitygml's messages -----------------------------------------------------------------

// Collects what libcitygml logs: errors, and the warnings that mean lost or misread data.
class Logger : public citygml::CityGMLLogger {
 public:
  Logger() : CityGMLLogger(LOGLEVEL::LL_WARNING) {}
  void log(LOGLEVEL level, const std::string& message, const char*, int) const override {
    if (level == LOGLEVEL::LL_ERROR) {
      if (error.empty()) error = message;
    } else if (level == LOGLEVEL::LL_WARNING) {
      warning(message);
    }
  }
  mutable std::string error;            // the first error
  mutable std::string bad_coordinates;  // the first "Mismatch type" (a posList that is not numbers)
  mutable std::string bad_dimension;    // the first srsDimension ≠ 3
  mutable std::map<std::string, std::size_t> unknown_elements;
  mutable std::size_t missing_xlinks = 0, short_rings = 0, duplicate_exteriors = 0;
  mutable std::string first_missing_xlink;

 private:
  void warning(const std::string& m) const {
    if (m.find("Mismatch type") != std::string::npos) {
      if (bad_coordinates.empty()) bad_coordinates = m;
    } else if (m.find("srsDimension") != std::string::npos) {
      if (bad_dimension.empty()) bad_dimension = m;
    } else if (m.rfind("Found start tag of unknown node <", 0) == 0) {
      const std::size_t b = 33, e = m.find('>', b);
      if (e != std::string::npos && (unknown_elements.size() < 64 || unknown_elements.count(m.substr(b, e - b))))
        ++unknown_elements[m.substr(b, e - b)];
    } else if (m.find("requests Polygon with id") != std::string::npos) {
      if (missing_xlinks++ == 0) first_missing_xlink = m;
    } else if (m.find("contains less than 4 vertices") != std::string::npos) {
      ++short_rings;
    } else if (m.find("Duplicate definition of exterior") != std::string::npos) {
      ++duplicate_exteriors;
    }
  }
};

// "line 12, column 5" out of a libcitygml message ("... at  line 12, column 5 in file x"), as "12:5".
std::string location_of(const std::string& message) {
  const std::size_t at = message.find("line ");
  if (at == std::string::npos) return "";
  long line = 0, column = 0;
  if (std::sscanf(message.c_str() + at, "line %ld, column %ld", &line, &column) != 2) return "";
  return std::to_string(line) + ":" + std::to_string(column);
}

// "file:12:5" with the location of a libcitygml message, "file" when it gives none.
std::string file_at(const std::string& name, const std::string& message) {
  const std::string at = location_of(message);
  return at.empty() ? name : name + ":" + at;
}

std::string without_file(std::string message) {
  if (const std::size_t p = message.find(" in file "); p != std::string::npos) message.erase(p);
  return message;
}

// ---- LoD -----------------------------------------------------------------------------------

// A requested LoD "2" / "2.0" / "2.0.0" → 2; nullopt for what no CityGML LoD equals ("2.2").
std::optional<unsigned> parse_requested_lod(const std::string& name, const std::string& text) {
  std::vector<long long> parts;
  std::size_t i = 0;
  while (true) {
    long long v = 0;
    const auto [end, ec] = std::from_chars(text.data() + i, text.data() + text.size(), v);
    if (ec != std::errc() || v < 0)
      throw InputError(name + ": requested LoD '" + printable_text(text) + "' is not a LoD such as \"2\"");
    parts.push_back(v);
    i = static_cast<std::size_t>(end - text.data());
    if (i == text.size()) break;
    if (text[i] != '.' || i + 1 == text.size())
      throw InputError(name + ": requested LoD '" + printable_text(text) + "' is not a LoD such as \"2\"");
    ++i;
  }
  for (std::size_t k = 1; k < parts.size(); ++k)
    if (parts[k] != 0) return std::nullopt;  // CityGML has integer LoDs 0–4
  if (parts[0] > 4) return std::nullopt;
  return static_cast<unsigned>(parts[0]);
}

// ---- The model walk ------------------------------------------------------------------------

bool is_opening_or_boundary(Type t) {
  switch (t) {
    case Type::COT_WallSurface:
    case Type::COT_RoofSurface:
    case Type::COT_GroundSurface:
    case Type::COT_ClosureSurface:
    case Type::COT_FloorSurface:
    case Type::COT_InteriorWallSurface:
    case Type::COT_CeilingSurface:
    case Type::COT_OuterCeilingSurface:
    case Type::COT_OuterFloorSurface:
    case Type::COT_Door:
    case Type::COT_Window:
      return true;
    default:
      return false;
  }
}

bool is_transportation(Type t) {
  return t == Type::COT_Road || t == Type::COT_Track || t == Type::COT_Railway || t == Type::COT_Square ||
         t == Type::COT_TransportationObject;
}

// A thematic surface: a semantic surface of the object above it, not an object of its own.
bool is_thematic_surface(Type t, Type parent) {
  if (is_opening_or_boundary(t)) return true;
  if (t == Type::COT_TransportationObject && is_transportation(parent)) return true;  // (Auxiliary)TrafficArea
  if (t == Type::COT_WaterBody && parent == Type::COT_WaterBody) return true;         // WaterSurface, WaterGroundSurface, ...
  return false;
}

std::string surface_type_name(const CityObject& s) {
  if (s.getType() == Type::COT_TransportationObject) return "TrafficArea";
  return s.getTypeAsString();
}

std::string object_type_name(const CityObject& o) {
  switch (o.getType()) {
    // libcitygml maps TransportationComplex (and its areas) to one type; at object level it is a complex.
    case Type::COT_TransportationObject:
      return "TransportationComplex";
    // Types libcitygml 2.4 parses but names "Unknown" (cityObjectsTypeToString has no case for
    // them): the relief components (a TINRelief is the terrain of PLATEAU's dem files) and groups.
    case Type::COT_ReliefComponent:
      return "ReliefComponent";
    case Type::COT_TINRelief:
      return "TINRelief";
    case Type::COT_MassPointRelief:
      return "MassPointRelief";
    case Type::COT_BreaklineRelief:
      return "BreaklineRelief";
    case Type::COT_RasterRelief:
      return "RasterRelief";
    case Type::COT_CityObjectGroup:
      return "CityObjectGroup";
    default:
      return o.getTypeAsString();
  }
}

struct ObjectEntry {
  const CityObject* object = nullptr;
  std::vector<const CityObject*> surfaces;  // thematic surfaces (openings of them included)
  std::vector<std::uint32_t> children;      // child objects (BuildingPart, BuildingInstallation, ...)
  std::set<unsigned> lods;                  // LoDs with at least one polygon
  std::optional<unsigned> chosen;
  bool implicit = false;         // has implicit geometries
  bool implicit_unread = false;  // ... that are not read (geographic CRS)
};

bool has_polygons(const citygml::Geometry& g) {
  if (g.getPolygonsCount() > 0) return true;
  for (unsigned i = 0; i < g.getGeometriesCount(); ++i)
    if (has_polygons(g.getGeometry(i))) return true;
  return false;
}

bool has_curves(const citygml::Geometry& g) {
  if (g.getLineStringCount() > 0) return true;
  for (unsigned i = 0; i < g.getGeometriesCount(); ++i)
    if (has_curves(g.getGeometry(i))) return true;
  return false;
}

void add_lods(const CityObject& o, std::set<unsigned>& lods) {
  for (unsigned g = 0; g < o.getGeometriesCount(); ++g)
    if (has_polygons(o.getGeometry(g))) lods.insert(o.getGeometry(g).getLOD());
}

// A hashable exact position (bit patterns), for sharing bit-identical vertices.
struct PositionKey {
  std::array<std::uint64_t, 3> bits;
  bool operator==(const PositionKey&) const = default;
};
struct PositionHash {
  std::size_t operator()(const PositionKey& k) const {
    std::uint64_t h = 1469598103934665603ull;
    for (const std::uint64_t b : k.bits) h = (h ^ b) * 1099511628211ull ^ (b >> 29);
    return static_cast<std::size_t>(h);
  }
};

// What a read counts, then hands to the report.
struct Counts {
  std::size_t objects = 0, objects_with_geometry = 0, skipped_objects = 0, thematic_surfaces = 0, surfaces = 0,
              surfaces_with_holes = 0, implicit_instances = 0;
  std::map<std::string, std::size_t> lods_used;
};

// Notes aggregated by reason: "<count> x <reason> (first: <where>)".
class Notes {
 public:
  void add(const std::string& reason, const std::string& example) {
    auto [it, inserted] = counts_.try_emplace(reason, std::pair<std::size_t, std::string>{0, example});
    if (inserted) order_.push_back(reason);
    ++it->second.first;
  }
  void emit(std::vector<std::string>& out) const {
    for (const std::string& reason : order_) {
      const auto& [count, example] = counts_.at(reason);
      out.push_back(std::to_string(count) + " x " + reason +
                    (example.empty() ? "" : " (first: " + printable_text(example) + ")"));
    }
  }

 private:
  std::map<std::string, std::pair<std::size_t, std::string>> counts_;
  std::vector<std::string> order_;
};

// The model's polygons as rings of raw coordinates (file CRS), gathered before any
// reprojection so that every vertex can be projected in one pass.
struct RawSurfaces {
  std::vector<Vec3> coordinates;          // all rings' vertices, file order
  std::vector<std::uint32_t> ring_start;  // ring r = coordinates[ring_start[r], ring_start[r + 1])
  struct Surface {
    std::uint32_t object, material, first_ring, rings;
  };
  std::vector<Surface> surfaces;
};

// An implicit geometry's placement (CityGML 2.0 §10.3.6): a template vertex x goes to
// M·(x, 1) + reference point, M the row-major 4×4 transformationMatrix (its top three rows).
struct Placement {
  const double* m;  // 16 values, row-major
  Vec3 reference;
  Vec3 apply(const Vec3& x) const {
    return Vec3(m[0] * x.x() + m[1] * x.y() + m[2] * x.z() + m[3], m[4] * x.x() + m[5] * x.y() + m[6] * x.z() + m[7],
                m[8] * x.x() + m[9] * x.y() + m[10] * x.z() + m[11]) +
           reference;
  }
};

class ModelWalk {
 public:
  // read_implicit: place implicit geometries (not in geographic CRSs, where a template in metres
  // cannot be added to a reference point in degrees before the projection).
  ModelWalk(const std::string& file, std::optional<unsigned> requested, bool lod_set, bool read_implicit, TriangleSoup& soup,
            RawSurfaces& raw, Counts& counts, Notes& notes)
      : file_(file),
        requested_(requested),
        lod_set_(lod_set),
        read_implicit_(read_implicit),
        soup_(soup),
        raw_(raw),
        counts_(counts),
        notes_(notes) {
    raw_.ring_start.assign(1, 0);
  }

  void read(const citygml::CityModel& model) {
    for (unsigned i = 0; i < model.getNumRootCityObjects(); ++i) collect(model.getRootCityObject(i), kNone);
    for (ObjectEntry& e : entries_) e.chosen = choose(e);
    for (ObjectEntry& e : entries_) read_object(e);
  }

 private:
  // Flattens the object tree into entries (objects), thematic surfaces attached to their object.
  void collect(const CityObject& o, std::uint32_t parent) {
    const auto index = static_cast<std::uint32_t>(entries_.size());
    entries_.push_back({});
    entries_[index].object = &o;
    if (parent != kNone) entries_[parent].children.push_back(index);
    add_lods(o, entries_[index].lods);
    add_implicit_lods(o, entries_[index]);
    for (unsigned c = 0; c < o.getChildCityObjectsCount(); ++c) {
      const CityObject& child = o.getChildCityObject(c);
      if (is_thematic_surface(child.getType(), o.getType()))
        attach_surface(child, index);
      else
        collect(child, index);
    }
  }

  void attach_surface(const CityObject& s, std::uint32_t owner) {
    entries_[owner].surfaces.push_back(&s);
    add_lods(s, entries_[owner].lods);
    add_implicit_lods(s, entries_[owner]);
    for (unsigned c = 0; c < s.getChildCityObjectsCount(); ++c) attach_surface(s.getChildCityObject(c), owner);  // openings
  }

  void add_implicit_lods(const CityObject& o, ObjectEntry& e) const {
    if (o.getImplicitGeometryCount() == 0) return;
    e.implicit = true;
    if (!read_implicit_) {
      e.implicit_unread = true;
      return;
    }
    for (unsigned i = 0; i < o.getImplicitGeometryCount(); ++i) {
      const citygml::ImplicitGeometry& ig = o.getImplicitGeometry(i);
      for (unsigned g = 0; g < ig.getGeometriesCount(); ++g)
        if (has_polygons(ig.getGeometry(g))) e.lods.insert(ig.getGeometry(g).getLOD());
    }
  }

  // An object's implicit geometries of LoD `lod`, each instance placed (templates shared by
  // several instances are read once per instance).
  void read_implicit(const CityObject& o, unsigned lod, const std::string& material) {
    for (unsigned i = 0; i < o.getImplicitGeometryCount(); ++i) {
      const citygml::ImplicitGeometry& ig = o.getImplicitGeometry(i);
      const TVec3d r = ig.getReferencePoint();
      const Placement place{ig.getTransformMatrix().getMatrix(), Vec3(r.x, r.y, r.z)};
      const std::size_t before = counts_.surfaces;
      for (unsigned g = 0; g < ig.getGeometriesCount(); ++g) read_geometry(ig.getGeometry(g), lod, material, &place);
      if (counts_.surfaces > before) ++counts_.implicit_instances;
    }
  }

  std::optional<unsigned> choose(const ObjectEntry& e) const {
    if (e.lods.empty()) return std::nullopt;
    if (lod_set_) {
      if (requested_ && e.lods.count(*requested_)) return requested_;
      return std::nullopt;
    }
    return *e.lods.rbegin();
  }

  void read_object(const ObjectEntry& e) {
    ++counts_.objects;
    const CityObject& o = *e.object;
    if (e.implicit_unread)
      notes_.add(
          "objects with implicit geometries (templates): not read in a geographic CRS (a template in metres on a "
          "reference point in degrees)",
          o.getId());
    if (e.lods.empty()) {
      if (e.implicit_unread) ++counts_.skipped_objects;
      return;  // no geometry of its own: fine (a parent whose children carry it)
    }
    if (!e.chosen) {
      ++counts_.skipped_objects;
      notes_.add("objects skipped: no geometry of the requested LoD", o.getId());
      return;
    }
    if (!lod_set_) {
      std::optional<unsigned> best_child;
      for (const std::uint32_t c : e.children)
        if (entries_[c].chosen && (!best_child || *entries_[c].chosen > *best_child)) best_child = entries_[c].chosen;
      if (best_child && *e.chosen < *best_child) {
        ++counts_.skipped_objects;
        notes_.add("parent objects skipped: their highest LoD is below their children's (LoD " + std::to_string(*e.chosen) +
                       " parent, LoD " + std::to_string(*best_child) + " children)",
                   o.getId());
        return;
      }
    }
    object_name_ = &o.getId();
    object_index_ = kNone;
    const std::size_t before = counts_.surfaces;
    // Thematic surfaces first: a polygon that the object's solid references again is read with
    // its surface type.
    for (const CityObject* s : e.surfaces) {
      const std::size_t s_before = counts_.surfaces;
      for (unsigned g = 0; g < s->getGeometriesCount(); ++g) read_geometry(s->getGeometry(g), *e.chosen, surface_type_name(*s));
      if (read_implicit_) read_implicit(*s, *e.chosen, surface_type_name(*s));
      if (counts_.surfaces > s_before) ++counts_.thematic_surfaces;
    }
    for (unsigned g = 0; g < o.getGeometriesCount(); ++g) read_geometry(o.getGeometry(g), *e.chosen, object_type_name(o));
    if (read_implicit_) read_implicit(o, *e.chosen, object_type_name(o));
    if (counts_.surfaces > before) {
      ++counts_.objects_with_geometry;
      ++counts_.lods_used[std::to_string(*e.chosen)];
    } else {
      ++counts_.skipped_objects;
      notes_.add("objects skipped: no readable polygon at their LoD", o.getId());
    }
  }

  void read_geometry(const citygml::Geometry& g, unsigned lod, const std::string& material, const Placement* place = nullptr) {
    if (g.getLOD() != lod) return;
    if (g.getLineStringCount() > 0) notes_.add("curve geometries (lines) not read: no area", *object_name_);
    for (unsigned p = 0; p < g.getPolygonsCount(); ++p) read_polygon(*g.getPolygon(p), material, place);
    for (unsigned c = 0; c < g.getGeometriesCount(); ++c) read_geometry(g.getGeometry(c), lod, material, place);
  }

  // One ring into raw_.coordinates, cleaned: closing vertex and consecutive repeats removed.
  // Returns false (and adds nothing) for fewer than 3 distinct positions.
  bool add_ring(const std::vector<TVec3d>& ring, const std::string& where, const Placement* place) {
    const std::size_t start = raw_.coordinates.size();
    for (const auto& v : ring) {
      const Vec3 p = place ? place->apply(Vec3(v.x, v.y, v.z)) : Vec3(v.x, v.y, v.z);
      if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z()))
        throw InputError(file_ + ": polygon " + printable_text(where) + " of object " + printable_text(*object_name_) +
                         ": non-finite coordinate");
      if (raw_.coordinates.size() > start && raw_.coordinates.back() == p) {
        if (ring.size() > 1 && &v != &ring.back()) notes_.add("repeated consecutive vertices removed", where);
        continue;
      }
      raw_.coordinates.push_back(p);
    }
    if (raw_.coordinates.size() - start > 1 && raw_.coordinates.back() == raw_.coordinates[start]) raw_.coordinates.pop_back();
    distinct_.assign(raw_.coordinates.begin() + static_cast<std::ptrdiff_t>(start), raw_.coordinates.end());  // reused buffer
    std::sort(distinct_.begin(), distinct_.end(),
              [](const Vec3& a, const Vec3& b) { return std::tie(a.x(), a.y(), a.z()) < std::tie(b.x(), b.y(), b.z()); });
    if (std::unique(distinct_.begin(), distinct_.end()) - distinct_.begin() < 3) {
      raw_.coordinates.resize(start);
      return false;
    }
    raw_.ring_start.push_back(static_cast<std::uint32_t>(raw_.coordinates.size()));
    return true;
  }

  void read_polygon(const citygml::Polygon& polygon, const std::string& material, const Placement* place) {
    if (!place && !read_polygons_.insert(&polygon).second) {
      notes_.add("polygons referenced twice (xlink:href): read once", polygon.getId());
      return;
    }
    const auto outer = polygon.exteriorRing();
    if (!outer) {
      notes_.add("polygons skipped: no exterior ring", polygon.getId());
      return;
    }
    const auto first_ring = static_cast<std::uint32_t>(raw_.ring_start.size() - 1);
    if (!add_ring(outer->getVertices(), polygon.getId(), place)) {
      notes_.add("surfaces skipped: outer ring with fewer than 3 distinct vertices", polygon.getId());
      return;
    }
    for (const auto& inner : polygon.interiorRings())
      if (!add_ring(inner->getVertices(), polygon.getId(), place))
        notes_.add("inner rings (holes) skipped: fewer than 3 distinct vertices", polygon.getId());
    if (object_index_ == kNone) {
      object_index_ = static_cast<std::uint32_t>(soup_.object_names.size());
      soup_.object_names.push_back(*object_name_);
    }
    const auto rings = static_cast<std::uint32_t>(raw_.ring_start.size() - 1) - first_ring;
    raw_.surfaces.push_back({object_index_, material_index(material), first_ring, rings});
    ++counts_.surfaces;
  }

  std::uint32_t material_index(const std::string& name) {
    const auto [it, inserted] = materials_.try_emplace(name, static_cast<std::uint32_t>(soup_.material_names.size()));
    if (inserted) soup_.material_names.push_back(name);
    return it->second;
  }

  const std::string& file_;
  std::optional<unsigned> requested_;
  bool lod_set_;
  bool read_implicit_;
  TriangleSoup& soup_;
  RawSurfaces& raw_;
  Counts& counts_;
  Notes& notes_;
  std::vector<ObjectEntry> entries_;
  std::unordered_set<const citygml::Polygon*> read_polygons_;
  std::unordered_map<std::string, std::uint32_t> materials_;
  std::vector<Vec3> distinct_;  // add_ring's scratch
  const std::string* object_name_ = nullptr;
  std::uint32_t object_index_ = kNone;
};

// Shares bit-identical positions and triangulates every surface into the soup.
void triangulate_surfaces(const RawSurfaces& raw, TriangleSoup& soup, Counts& counts, Notes& notes) {
  std::unordered_map<PositionKey, std::uint32_t, PositionHash> index;
  index.reserve(raw.coordinates.size());
  std::vector<std::uint32_t> vertex_of(raw.coordinates.size());
  for (std::size_t i = 0; i < raw.coordinates.size(); ++i) {
    const Vec3& p = raw.coordinates[i];
    const PositionKey key{
        {std::bit_cast<std::uint64_t>(p.x()), std::bit_cast<std::uint64_t>(p.y()), std::bit_cast<std::uint64_t>(p.z())}};
    const auto [it, inserted] = index.try_emplace(key, static_cast<std::uint32_t>(soup.vertices.size()));
    if (inserted) soup.vertices.push_back(p);
    vertex_of[i] = it->second;
  }
  std::vector<std::vector<std::uint32_t>> rings;
  for (const RawSurfaces::Surface& s : raw.surfaces) {
    rings.resize(s.rings);
    for (std::uint32_t r = 0; r < s.rings; ++r) {
      const std::uint32_t b = raw.ring_start[s.first_ring + r], e = raw.ring_start[s.first_ring + r + 1];
      rings[r].assign(vertex_of.begin() + b, vertex_of.begin() + e);
    }
    const PolygonWithHolesTriangulation t = triangulate_polygon_with_holes(soup.vertices, rings);
    if (t.holes_dropped) notes.add("surfaces with crossing rings: holes not cut out (surface filled)", "");
    if (t.method == PolygonTriangulationMethod::kFanZeroArea) notes.add("zero-area surfaces (fan-triangulated)", "");
    if (t.method == PolygonTriangulationMethod::kFanSelfIntersecting) notes.add("self-crossing surfaces (fan-triangulated)", "");
    for (const auto& tri : t.triangles) {
      soup.triangles.push_back(tri);
      soup.triangle_material.push_back(s.material);
      soup.triangle_object.push_back(s.object);
    }
    if (s.rings > 1 && !t.holes_dropped) ++counts.surfaces_with_holes;
  }
}

// libcitygml on the file's bytes; every way it can fail becomes an InputError.
std::shared_ptr<const citygml::CityModel> load_model(const std::string& name, const std::string& bytes, const Logger& logger,
                                                     std::shared_ptr<Logger> shared_logger) {
  citygml::ParserParams params;
  params.tesselate = false;  // rings as written: we triangulate (holes included) ourselves
  params.optimize = false;   // no merging of polygons, no vertex removal
  params.keepVertices = true;
  std::shared_ptr<const citygml::CityModel> model;
  std::string thrown;
  try {
    std::istringstream stream(bytes);
    model = citygml::load(stream, params, shared_logger);
  } catch (const xercesc::SAXParseException& e) {
    thrown = std::to_string(e.getLineNumber()) + ":" + std::to_string(e.getColumnNumber()) + ": " + transcode(e.getMessage());
  } catch (const xercesc::XMLException& e) {
    thrown = transcode(e.getMessage());
  } catch (const std::exception& e) {
    thrown = e.what();
  } catch (...) {
    thrown = "unknown exception";
  }
  if (logger.error.find("called on unbound") != std::string::npos) {
    // A property element (core:cityObjectMember, bldg:boundedBy, ...) whose object libcitygml
    // does not know: it skips the object, then cannot end the property.
    const std::size_t b = logger.error.find("for element <"), e = logger.error.find('>', b);
    const std::string element = b == std::string::npos || e == std::string::npos ? "" : logger.error.substr(b + 12, e - b - 11);
    throw InputError(file_at(name, logger.error) + ": libcitygml 2.4 cannot read the content of " +
                     printable_text(element.empty() ? "an element" : element) +
                     " ending here (an object of a kind it does not know, or none)");
  }
  if (!thrown.empty() || !logger.error.empty() || !model) {
    const std::string what = !thrown.empty()         ? thrown
                             : !logger.error.empty() ? without_file(logger.error)
                                                     : "no CityModel in the file";
    const std::string at = location_of(logger.error);
    throw InputError(name + (at.empty() ? "" : ":" + at) + ": libcitygml: " + printable_text(what).substr(0, 300));
  }
  if (!logger.bad_coordinates.empty())
    throw InputError(file_at(name, logger.bad_coordinates) +
                     ": a coordinate list (gml:posList / gml:pos) holds something that is not a finite number");
  if (!logger.bad_dimension.empty())
    throw InputError(file_at(name, logger.bad_dimension) + ": srsDimension is not 3 (only 3D coordinates are read)");
  return model;
}

// The CRS: one set of EPSG codes in all srsNames; geocentric refused.
CrsInfo check_crs(const std::string& name, const FileScan& scan, CityGmlReport& report) {
  if (scan.srs_names.empty()) {
    report.notes.push_back("no srsName: coordinates taken as metres in an unknown projected CRS");
    return {};
  }
  const std::string& srs = scan.srs_names.front();
  for (const std::string& other : scan.srs_names)
    if (crs_epsg_codes(other) != crs_epsg_codes(srs))
      throw InputError(name + ": mixed CRSs: srsName '" + printable_text(srs) + "' and '" + printable_text(other) + "'");
  report.crs_in_file = srs;
  report.crs = srs;
  const CrsInfo info = classify_crs(srs);
  if (info.kind == CrsKind::geocentric)
    throw InputError(name + ": srsName '" + printable_text(srs) +
                     "' is a geocentric CRS (z is not up); reproject to a projected CRS first");
  if (info.kind == CrsKind::unknown)
    report.notes.push_back("srsName '" + printable_text(srs) + "' is not a CRS PROJ knows: coordinates taken as metres");
  if (info.kind == CrsKind::geographic && (info.epsg == 0 || info.name.empty()))
    throw InputError(name + ": srsName '" + printable_text(srs) +
                     "' is geographic (degrees) and PROJ does not know it: cannot reproject");
  return info;
}

// Geographic coordinates → the UTM zone of the model's centre (io/citygml_reprojection.h).
void project_if_geographic(const std::string& name, const CrsInfo& info, std::optional<UtmZone> shared, RawSurfaces& raw,
                           CityGmlReport& report) {
  if (info.kind != CrsKind::geographic || raw.coordinates.empty()) return;
  const Reprojection r = reproject_geographic_to_utm(name, info, raw.coordinates, shared);
  report.crs = r.target_crs;
  report.reprojection = r.description;
  report.utm_zone = r.zone;
}

TriangleSoup read_unguarded(const std::filesystem::path& file, const CityGmlReadOptions& options, CityGmlReport* report) {
  const std::string name = file.string();
  std::optional<unsigned> requested;
  if (options.lod) requested = parse_requested_lod(name, *options.lod);
  std::string bytes = read_bytes(file);
  FileScan scan = scan_bytes(name, bytes);

  if (const std::string xml = first_xml_error(bytes); !xml.empty()) {
    // A file cut short (an interrupted download or copy) ends before the root's end tag.
    const std::size_t last = bytes.find_last_not_of(" \t\r\n");
    const bool cut = last == std::string::npos || last < 10 || bytes.compare(last - 9, 10, "CityModel>") != 0;
    throw InputError(name + ":" + printable_text(xml).substr(0, 300) + " (malformed XML" +
                     (cut ? "; the file ends before </core:CityModel>: cut short?)" : ")"));
  }
  const AdeElements ade = blank_ade_elements(bytes);
  check_coordinate_lists(name, bytes);
  scan.srs_names = srs_names(bytes);
  auto logger = std::make_shared<Logger>();
  const auto model = load_model(name, bytes, *logger, logger);

  CityGmlReport r;
  r.file = name;
  r.format = "CityGML " + scan.version;
  TriangleSoup soup;
  RawSurfaces raw;
  Counts counts;
  Notes notes;
  const CrsInfo crs = check_crs(name, scan, r);
  ModelWalk(name, requested, options.lod.has_value(), crs.kind != CrsKind::geographic, soup, raw, counts, notes).read(*model);
  project_if_geographic(name, crs, options.utm_zone, raw, r);
  triangulate_surfaces(raw, soup, counts, notes);

  r.objects = counts.objects;
  r.objects_with_geometry = counts.objects_with_geometry;
  r.skipped_objects = counts.skipped_objects;
  r.thematic_surfaces = counts.thematic_surfaces;
  r.surfaces = counts.surfaces;
  r.surfaces_with_holes = counts.surfaces_with_holes;
  r.triangles = soup.triangles.size();
  r.vertices = soup.vertices.size();
  r.lods_used = counts.lods_used;
  if (!r.reprojection.empty()) r.notes.push_back(r.reprojection);
  if (counts.implicit_instances)
    r.notes.push_back(std::to_string(counts.implicit_instances) +
                      " implicit geometries placed (template x -> M x + reference point)");
  notes.emit(r.notes);
  for (const auto& [element, n] : logger->unknown_elements)
    r.notes.push_back(std::to_string(n) + " x <" + printable_text(element) +
                      "> not read by libcitygml (skipped with its content)");
  if (logger->missing_xlinks)
    r.notes.push_back(std::to_string(logger->missing_xlinks) + " xlink:href to polygons that do not exist (first: " +
                      printable_text(without_file(logger->first_missing_xlink)).substr(0, 200) + ")");
  if (logger->short_rings)
    r.notes.push_back(std::to_string(logger->short_rings) + " rings with fewer than 4 positions in the file");
  if (logger->duplicate_exteriors)
    r.notes.push_back(std::to_string(logger->duplicate_exteriors) + " polygons with a second exterior ring: the first one kept");
  for (const AdeNamespace& a : ade)
    r.notes.push_back("not read: the elements of the Application Domain Extension " + printable_text(a.uri) +
                      " (ADEs are not supported), with their content: " + a.list(8));
  if (r.triangles == 0) {
    std::string uses;
    for (std::size_t k = 0; k < ade.size() && k < 3; ++k)
      uses += (k ? "; " : "") + printable_text(ade[k].uri) + " (" + ade[k].list(3) + ")";
    if (ade.size() > 3) uses += "; ...";
    throw InputError(
        name + ": no triangles (" + std::to_string(r.objects) + " city objects, " + std::to_string(r.skipped_objects) +
        " skipped" + (options.lod ? ", requested LoD " + printable_text(*options.lod) : std::string()) + ")" +
        (ade.empty() ? std::string()
                     : std::string("; not read, as Application Domain Extensions are not supported: the elements of ") + uses));
  }
  if (report) *report = std::move(r);
  return soup;
}

}  // namespace

bool is_citygml_path(const std::filesystem::path& file) {
  const std::string ext = lower(file.extension().string());
  return ext == ".gml" || ext == ".xml" || ext == ".citygml";
}

std::string CityGmlReport::summary() const {
  std::ostringstream os;
  os << file << ": " << format << (crs.empty() ? ", no CRS" : ", CRS " + crs) << "\n";
  os << "  " << objects << " objects, " << objects_with_geometry << " read, " << skipped_objects << " skipped; "
     << thematic_surfaces << " thematic surfaces; " << surfaces << " polygons (" << surfaces_with_holes << " with holes) -> "
     << triangles << " triangles, " << vertices << " vertices\n";
  os << "  LoDs:";
  for (const auto& [lod, n] : lods_used) os << " " << lod << " (" << n << " objects)";
  os << "\n";
  for (const std::string& n : notes) os << "  note: " << n << "\n";
  return os.str();
}

TriangleSoup read_citygml(const std::filesystem::path& file, const CityGmlReadOptions& options, CityGmlReport* report) {
  try {
    return read_unguarded(file, options, report);
  } catch (const InputError&) {
    throw;
  } catch (const std::invalid_argument& e) {
    // triangulate_polygon_with_holes rejects what the walk above never hands it; a safety net.
    throw InputError(file.string() + ": malformed CityGML (" + printable_text(e.what()) + ")");
  }
}

}  // namespace skyband
