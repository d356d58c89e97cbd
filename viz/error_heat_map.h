#pragma once
/// The error map of experiments/error_map.h as a picture: a PNG heat map with a colour bar.
#include <filesystem>
#include <string>

#include "experiments/error_map.h"

namespace rad {

/// Writes a heat map PNG of the relative error from 0 to `max_value` (<= 0: the map's own
/// maximum) with a colour bar; `title` heads it. Atomically. Throws Error.
void write_error_heat_map(const std::filesystem::path& png, const ErrorMap& map,
                          const std::string& title, double max_value = 0);

}  // namespace rad
