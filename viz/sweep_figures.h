#pragma once
/// The pictures of the accuracy-versus-tolerance experiment (experiments/sweep.h): the error
/// maps as heat maps on one colour scale, and three charts with log axes.
#include <filesystem>
#include <vector>

#include "experiments/sweep.h"

namespace rad {

/// Writes error_maps/<slug>.png for every row (on sweep.error_scale) and the charts, into
/// `folder`. Throws Error.
void write_sweep_figures(const std::filesystem::path& folder, const SweepResult& sweep);

/// The charts error_vs_tolerance.png, time_vs_tolerance.png and error_vs_time.png in `folder`.
void write_sweep_charts(const std::filesystem::path& folder, const std::vector<SweepRow>& rows);

}  // namespace rad
