#include "formats/vtk_messages.h"

#include <vtkLogger.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkSmartPointer.h>

#include <mutex>

namespace rad {
namespace {

thread_local std::string first_message;

/// "ERROR: In /path/file.cxx, line 12\nvtkXMLDataParser (0x55d): Error parsing XML ...\n\n":
/// the text after the object's name and address, on one line.
std::string reduce(const std::string& text) {
  std::string line;
  size_t start = 0;
  while (start < text.size()) {  // the last non-empty line holds the message
    const size_t end = text.find('\n', start);
    const std::string piece = text.substr(start, end == std::string::npos ? end : end - start);
    if (piece.find_first_not_of(" \t\r") != std::string::npos) line = piece;
    if (end == std::string::npos) break;
    start = end + 1;
  }
  const size_t address = line.find("): ");
  if (address != std::string::npos && line.find(" (0x") != std::string::npos)
    line = line.substr(address + 3);
  while (!line.empty() && (line.back() == ' ' || line.back() == '\r')) line.pop_back();
  return line;
}

class CapturingWindow : public vtkOutputWindow {
 public:
  static CapturingWindow* New();
  vtkTypeMacro(CapturingWindow, vtkOutputWindow) void DisplayText(const char* text) override {
    keep(text);
  }
  void DisplayErrorText(const char* text) override { keep(text); }
  void DisplayWarningText(const char* text) override { keep(text); }
  void DisplayGenericWarningText(const char* text) override { keep(text); }
  void DisplayDebugText(const char*) override {}

 private:
  static void keep(const char* text) {
    if (first_message.empty() && text != nullptr) first_message = reduce(text);
  }
};
vtkStandardNewMacro(CapturingWindow);

}  // namespace

void capture_vtk_messages() {
  static std::once_flag installed;
  std::call_once(installed, [] {
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
    vtkOutputWindow::SetInstance(vtkSmartPointer<CapturingWindow>::New());
  });
  first_message.clear();
}

std::string vtk_message() { return first_message; }

}  // namespace rad
