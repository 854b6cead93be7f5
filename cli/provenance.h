#pragma once
// How an output file was made, recorded beside it: `<output>.provenance.json` holds the skyband
// version, the command line as typed, the working folder, the time it was written (UTC,
// ISO 8601) and each input file's flag, path, size in bytes and modification time — enough to
// tell later which model, points and weather a CSV came from and to run it again. Written
// atomically (io/atomic_file.h) after the output itself. EXR and NetCDF outputs carry the same
// facts in their own headers.
#include <string>
#include <utility>
#include <vector>

namespace skyband::cli {

// `inputs`: (flag, path) pairs, e.g. {"--mesh", "city.json"}; empty paths are left out.
void write_provenance(const std::string& output, const std::vector<std::pair<std::string, std::string>>& inputs);

}  // namespace skyband::cli
