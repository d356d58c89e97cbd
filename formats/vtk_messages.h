#pragma once
/// VTK's own messages (errors and warnings of its readers and writers, its logger's coloured
/// lines) are captured instead of printed: a user sees one line of ours naming the file, never
/// VTK's log with escape codes, timestamps and C++ file names (issue 16).
#include <string>

namespace rad {

/// Installs the capture (once per process; later calls do nothing) and clears this thread's
/// messages. Call before a VTK read or write.
void capture_vtk_messages();

/// The first error or warning VTK reported on this thread since capture_vtk_messages(), reduced
/// to its message (no source path, object address or line breaks); empty when none.
std::string vtk_message();

}  // namespace rad
