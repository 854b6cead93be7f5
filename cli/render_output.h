#pragma once
// Writing a rendered image: the multi-layer EXR (sun_diffuse, sun_specular, sky_diffuse,
// sky_specular, total; linear sRGB, W·m⁻²·sr⁻¹ CMF-weighted, see render/renderer.h) with
// provenance attributes, and a tone-mapped PNG preview beside it (FILE.exr → FILE.png).
#include <filesystem>
#include <map>
#include <optional>
#include <string>

#include "render/renderer.h"

namespace skyband::cli {

// Attributes every render carries: version, command line, sun, sky, units, quality.
std::map<std::string, std::string> render_attributes(const SkyModel& sky, const RenderSettings& settings,
                                                     const std::string& extra_key = {}, const std::string& extra_value = {});

// Writes FILE.exr and FILE.png; the PNG uses `exposure` if given, else auto_exposure(total).
// Returns the exposure used.
double write_render(const std::filesystem::path& exr_path, const RenderLayers& layers,
                    std::map<std::string, std::string> attributes, std::optional<double> exposure);

}  // namespace skyband::cli
