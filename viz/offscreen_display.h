#pragma once
/// An X display for VTK's OpenGL rendering (charts, heat maps, the patch-mesh picture).
///
/// Debian's VTK 9.1 renders through GLX only: with no X server it aborts the process. So before
/// the first render we make sure there is one: the user's ($DISPLAY, when its socket answers),
/// or else a private Xvfb started for this process (Xvfb picks a free display number itself,
/// -displayfd) and stopped at exit. Users and CI then need no xvfb-run wrapper.
#include <filesystem>

class vtkRenderWindow;

namespace rad {

/// Makes $DISPLAY name a usable X server, starting Xvfb if needed (at most once per process;
/// later calls point $DISPLAY back at it if it was changed). Call before any VTK render window
/// is created. Throws Error when there is no display and Xvfb cannot be started (not
/// installed: scripts/install-deps.sh).
void ensure_display();

/// Renders `window` (offscreen) and writes its frame as an RGB PNG, atomically. Throws Error.
void write_window_png(const std::filesystem::path& file, vtkRenderWindow* window);

}  // namespace rad
