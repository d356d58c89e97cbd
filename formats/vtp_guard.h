#pragma once
/// Checks a solution file (.vtp) before VTK's XML reader sees it. VTK 9.1's reader trusts what a
/// file says: an array without a `type` or of an unknown one, or an element of an unexpected
/// name, is dereferenced as null, and the counts and block sizes a file claims are allocated as
/// they are. Fuzzing found each of these (fuzz/regressions/fuzz_solution/). So the XML is parsed
/// first (by VTK's own parser, which reads no data), and its tree is held to the layout `solve`
/// writes (write_solution: appended raw data, optionally compressed) and to the limits of
/// scene/limits.h.
#include <filesystem>

namespace rad {

/// Throws InputError naming the file and the element when the .vtp file is not well-formed XML,
/// has elements or attributes outside the layout of a solution file, an array of unknown type or
/// without one, counts beyond limits::kSolutionElements, or an appended array whose header
/// claims more than the file holds or a solution may have. Cost: one pass over the XML.
void check_solution_structure(const std::filesystem::path& file);

}  // namespace rad
