#include "viz/offscreen_display.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkRenderWindow.h>
#include <vtkWindowToImageFilter.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>

#include "formats/atomic_file.h"
#include "scene/error.h"

namespace rad {
namespace {

/// True when `display` (":N" or ":N.S", a local server) has a listening socket. Remote displays
/// ("host:N") are trusted as given.
bool display_answers(const std::string& display) {
  if (display.empty()) return false;
  if (display[0] != ':') return true;
  const std::string number = display.substr(1, display.find('.') - 1);
  const std::string path = "/tmp/.X11-unix/X" + number;
  const int fd = socket(AF_UNIX, SOCK_STREAM, 0);
  if (fd < 0) return false;
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  std::strncpy(address.sun_path, path.c_str(), sizeof(address.sun_path) - 1);
  const bool ok = connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) == 0;
  close(fd);
  return ok;
}

/// The Xvfb child, stopped when the process exits normally.
pid_t xvfb_pid = -1;

void stop_xvfb() {
  if (xvfb_pid > 0) {
    kill(xvfb_pid, SIGTERM);
    waitpid(xvfb_pid, nullptr, 0);
    xvfb_pid = -1;
  }
}

/// Starts Xvfb on a free display and returns ":N" once it accepts connections. Throws Error.
std::string start_xvfb() {
  int pipe_fds[2];
  if (pipe(pipe_fds) != 0)
    throw Error(std::string("cannot start Xvfb: pipe: ") + std::strerror(errno));
  // Xvfb writes the display number it chose to this descriptor once it accepts connections.
  // Built before fork: the child of a threaded process must not allocate.
  const std::string fd = std::to_string(pipe_fds[1]);
  const pid_t pid = fork();
  if (pid < 0) throw Error(std::string("cannot start Xvfb: fork: ") + std::strerror(errno));
  if (pid == 0) {
    close(pipe_fds[0]);
    prctl(PR_SET_PDEATHSIG, SIGTERM);  // never outlive us, even when we are killed
    const int null = open("/dev/null", O_WRONLY);
    if (null >= 0) {
      dup2(null, STDOUT_FILENO);
      dup2(null, STDERR_FILENO);
    }
    // -noreset: by default an X server resets when its last client leaves, and a connection
    // made during the reset fails; VTK then crashed in XSync (seen under ctest -j2, where the
    // chart's window and its interactor open and close connections on a loaded machine).
    execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", "1920x1200x24", "-nolisten",
           "tcp", "-noreset", static_cast<char*>(nullptr));
    _exit(127);
  }
  close(pipe_fds[1]);
  std::string number;
  pollfd wait_for{pipe_fds[0], POLLIN, 0};
  // Up to 20 s: Xvfb usually answers in well under a second.
  while (poll(&wait_for, 1, 20000) > 0) {
    char c;
    if (read(pipe_fds[0], &c, 1) != 1 || c == '\n') break;
    number += c;
  }
  close(pipe_fds[0]);
  if (number.empty()) {
    int status = 0;
    kill(pid, SIGTERM);
    waitpid(pid, &status, 0);
    const bool missing = WIFEXITED(status) && WEXITSTATUS(status) == 127;
    throw Error(std::string("drawing needs an X display: none answers at $DISPLAY and ") +
                (missing
                     ? "Xvfb is not installed (apt-get install xvfb, or scripts/install-deps.sh)"
                     : "Xvfb did not start"));
  }
  xvfb_pid = pid;
  std::atexit(stop_xvfb);
  // -displayfd reports the number once the server listens; wait until it answers (up to 20 s).
  for (int i = 0; i < 2000 && !display_answers(":" + number); ++i) usleep(10000);
  return ":" + number;
}

}  // namespace

void ensure_display() {
  static std::mutex mutex;
  static std::string own;  // our Xvfb's display, once started
  const std::lock_guard<std::mutex> lock(mutex);
  const char* display = std::getenv("DISPLAY");
  if (display && display_answers(display)) return;
  if (own.empty()) own = start_xvfb();
  setenv("DISPLAY", own.c_str(), 1);
}

void write_window_png(const std::filesystem::path& file, vtkRenderWindow* window) {
  window->SetOffScreenRendering(1);
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->Update();
  AtomicFile out(file);
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(out.temp_path().c_str());
  writer->SetInputConnection(grab->GetOutputPort());
  writer->Write();
  if (writer->GetErrorCode() != 0) throw Error(file.string() + ": cannot write PNG");
  out.commit();
}

}  // namespace rad
