#include "io/crs_codes.h"

#include <cctype>

namespace skyband {

std::vector<int> crs_epsg_codes(const std::string& crs) {
  std::string l = crs;
  for (char& c : l) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  std::vector<int> codes;
  std::size_t pos = l.find("epsg");
  while (pos != std::string::npos) {
    const std::size_t next = l.find("epsg", pos + 4);
    const std::string part = l.substr(pos + 4, next == std::string::npos ? std::string::npos : next - pos - 4);
    std::size_t end = part.size();
    while (end > 0 && !std::isdigit(static_cast<unsigned char>(part[end - 1]))) --end;
    std::size_t begin = end;
    while (begin > 0 && std::isdigit(static_cast<unsigned char>(part[begin - 1]))) --begin;
    if (begin < end && end - begin <= 9) codes.push_back(std::stoi(part.substr(begin, end - begin)));
    pos = next;
  }
  return codes;
}

}  // namespace skyband
