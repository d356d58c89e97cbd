// The module graph of DESIGN.md §2 is a rule: this test reads every source file and every
// module's CMakeLists.txt and fails when a module includes or links a module, or a third-party
// library, it may not use.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kModules{"geometry",    "scene",      "specular", "reference",
                                        "distributed", "hemisphere", "vertex",   "radiosity",
                                        "octree",      "localpass",  "formats",  "render",
                                        "experiments", "viz",        "cli"};

/// Modules each module may include (itself included): the graph of docs/architecture.md.
/// tests/ and bench/ may use everything.
const std::map<std::string, std::set<std::string>> kAllowedModules{
    {"geometry", {"geometry"}},
    {"scene", {"scene", "geometry"}},
    {"specular", {"specular", "scene", "geometry"}},
    {"reference", {"reference", "scene", "geometry"}},
    {"distributed", {"distributed", "scene", "geometry"}},
    {"hemisphere", {"hemisphere", "geometry"}},
    {"vertex", {"vertex", "scene", "geometry"}},
    {"radiosity", {"radiosity", "scene", "geometry"}},
    {"octree", {"octree", "geometry"}},
    {"localpass",
     {"localpass", "specular", "octree", "hemisphere", "vertex", "radiosity", "scene", "geometry"}},
    {"formats", {"formats", "radiosity", "scene", "geometry"}},
    {"render",
     {"render", "localpass", "specular", "reference", "octree", "radiosity", "scene", "geometry",
      "formats", "distributed"}},
    {"experiments",
     {"experiments", "render", "localpass", "specular", "reference", "octree", "radiosity", "scene",
      "geometry", "formats", "distributed"}},
    {"viz",
     {"viz", "experiments", "render", "localpass", "specular", "reference", "octree", "radiosity",
      "scene", "geometry", "formats", "distributed"}},
    {"cli",
     {"cli", "viz", "experiments", "render", "formats", "distributed", "localpass", "specular",
      "reference", "octree", "hemisphere", "vertex", "radiosity", "scene", "geometry"}},
};

/// Third-party headers, by include prefix, and the modules that may include them. Eigen and the
/// standard library are open to all. Embree may appear only in scene's .cpp files (never in a
/// header), VTK only in formats (its file I/O), viz and cli, OpenEXR only in formats, Boost
/// (small_vector) only in hemisphere, MPI only in distributed's .cpp files.
struct ThirdParty {
  std::regex include;
  std::set<std::string> modules;
  bool sources_only;
};
const std::vector<std::pair<std::string, ThirdParty>>& third_party() {
  static const std::vector<std::pair<std::string, ThirdParty>> rules{
      {"Embree", {std::regex(R"(^embree\d?/)"), {"scene"}, true}},
      {"VTK", {std::regex(R"(^vtk\w*\.h$)"), {"formats", "viz", "cli"}, false}},
      {"OpenEXR", {std::regex(R"(^(Imf|Imath|Iex|OpenEXR/|Imath/))"), {"formats"}, false}},
      {"OpenMesh", {std::regex(R"(^OpenMesh/)"), {"radiosity"}, false}},
      {"TBB",
       {std::regex(R"(^(tbb|oneapi)/)"),
        {"radiosity", "localpass", "render", "experiments", "cli"},
        false}},
      {"nlohmann-json", {std::regex(R"(^nlohmann/)"), {"scene", "formats", "cli"}, false}},
      {"CLI11", {std::regex(R"(^CLI/)"), {"cli"}, false}},
      {"Boost", {std::regex(R"(^boost/)"), {"hemisphere"}, false}},
      {"MPI", {std::regex(R"(^mpi\.h$)"), {"distributed"}, true}},
  };
  return rules;
}

/// Violations in one file's text. `module` is the folder the file lives in.
std::vector<std::string> include_violations(const std::string& module, const std::string& file,
                                            const std::string& text) {
  std::vector<std::string> out;
  static const std::regex include_line(R"(^\s*#\s*include\s*[<"]([^">]+)[">])");
  const bool is_header = file.size() > 2 && (file.ends_with(".h") || file.ends_with(".hpp"));
  std::istringstream lines(text);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    std::smatch m;
    if (!std::regex_search(line, m, include_line)) continue;
    const std::string header = m[1];
    const std::string where = file + ":" + std::to_string(number) + ": ";
    const std::string first = header.substr(0, header.find('/'));
    const bool is_module = header.find('/') != std::string::npos &&
                           std::find(kModules.begin(), kModules.end(), first) != kModules.end();
    if (is_module && !kAllowedModules.at(module).count(first)) {
      out.push_back(where + module + " may not include " + header);
    }
    for (const auto& [name, rule] : third_party()) {
      if (!std::regex_search(header, rule.include)) continue;
      if (!rule.modules.count(module))
        out.push_back(where + module + " may not use " + name + " (" + header + ")");
      if (rule.sources_only && is_header)
        out.push_back(where + name + " must not appear in a header");
    }
  }
  return out;
}

/// Violations in a module's CMakeLists.txt: rad_* targets it links that it may not use.
std::vector<std::string> link_violations(const std::string& module, const std::string& text) {
  std::vector<std::string> out;
  static const std::regex target(R"(\brad_(\w+))");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), target);
       it != std::sregex_iterator(); ++it) {
    const std::string name = (*it)[1];
    if (name == "warnings" || name == "module_includes") continue;
    if (std::find(kModules.begin(), kModules.end(), name) == kModules.end()) continue;
    if (!kAllowedModules.at(module).count(name)) {
      out.push_back(module + "/CMakeLists.txt links rad_" + name + ", which " + module +
                    " may not use");
    }
  }
  return out;
}

std::string read(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string join(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  return out;
}

TEST(ModuleGraph, CheckerCatchesForbiddenIncludes) {
  // The checker itself must be able to fail.
  EXPECT_EQ(include_violations("scene", "scene/a.cpp", "#include \"formats/image_io.h\"\n").size(),
            1u);
  EXPECT_EQ(
      include_violations("hemisphere", "hemisphere/a.cpp", "#include \"scene/scene.h\"\n").size(),
      1u);
  EXPECT_EQ(include_violations("geometry", "geometry/a.h", "#include \"scene/polygon.h\"\n").size(),
            1u);
  EXPECT_EQ(
      include_violations("vertex", "vertex/a.cpp", "#include \"hemisphere/visible_surface.h\"\n")
          .size(),
      1u);
  EXPECT_EQ(include_violations("render", "render/a.cpp", "#include \"viz/charts.h\"\n").size(), 1u);
  EXPECT_EQ(include_violations("experiments", "experiments/a.cpp", "#include <vtkNew.h>\n").size(),
            1u);
  EXPECT_EQ(include_violations("formats", "formats/a.cpp", "#include \"localpass/local_pass.h\"\n")
                .size(),
            1u);
  EXPECT_EQ(include_violations("scene", "scene/a.h", "#include <embree3/rtcore.h>\n").size(), 1u);
  EXPECT_EQ(include_violations("localpass", "localpass/a.cpp", "  #  include <vtkNew.h>\n").size(),
            1u);
  EXPECT_EQ(include_violations("octree", "octree/a.cpp", "#include <ImfHeader.h>\n").size(), 1u);
  EXPECT_TRUE(
      include_violations("viz", "viz/a.cpp", "#include \"scene/scene.h\"\n#include <vtkNew.h>\n")
          .empty());
  EXPECT_TRUE(include_violations("scene", "scene/a.cpp", "#include <embree3/rtcore.h>\n").empty());
  EXPECT_EQ(
      link_violations("radiosity", "target_link_libraries(rad_radiosity PUBLIC rad_octree)").size(),
      1u);
  // octree includes only geometry, so it links only geometry (issue 38)
  EXPECT_EQ(
      link_violations(
          "octree", "target_link_libraries(rad_octree PUBLIC rad_radiosity rad_scene rad_warnings)")
          .size(),
      2u);
  EXPECT_TRUE(
      link_violations("octree", "target_link_libraries(rad_octree PUBLIC rad_geometry)").empty());
  // the references know nothing of the local pass, nor the unfolding of the gatherers
  EXPECT_EQ(
      include_violations("reference", "reference/a.cpp", "#include \"localpass/local_pass.h\"\n")
          .size(),
      1u);
  EXPECT_EQ(include_violations("specular", "specular/a.h", "#include \"octree/octree.h\"\n").size(),
            1u);
}

TEST(ModuleGraph, SourcesIncludeOnlyAllowedModulesAndLibraries) {
  const fs::path root = RAD_SOURCE_DIR;
  std::vector<std::string> violations;
  int files = 0;
  for (const std::string& module : kModules) {
    ASSERT_TRUE(fs::is_directory(root / module)) << "missing module folder " << module;
    for (const auto& entry : fs::recursive_directory_iterator(root / module)) {
      const std::string ext = entry.path().extension().string();
      if (ext != ".h" && ext != ".cpp" && ext != ".hpp") continue;
      ++files;
      const std::string relative = fs::relative(entry.path(), root).string();
      for (auto& v : include_violations(module, relative, read(entry.path())))
        violations.push_back(v);
    }
  }
  EXPECT_GT(files, 10);
  EXPECT_TRUE(violations.empty()) << join(violations);
}

TEST(ModuleGraph, TargetsLinkOnlyAllowedModules) {
  const fs::path root = RAD_SOURCE_DIR;
  std::vector<std::string> violations;
  for (const std::string& module : kModules) {
    const fs::path cmake = root / module / "CMakeLists.txt";
    ASSERT_TRUE(fs::exists(cmake)) << "every module has its own target: " << cmake;
    for (auto& v : link_violations(module, read(cmake))) violations.push_back(v);
  }
  EXPECT_TRUE(violations.empty()) << join(violations);
}

TEST(ModuleGraph, EveryModuleHasAHeaderStatingItsRole) {
  const fs::path root = RAD_SOURCE_DIR;
  for (const std::string& module : kModules) {
    if (module == "cli") continue;  // the executable: cli/main.cpp says what it is
    const std::string text = read(root / module / (std::string(module) + ".h"));
    EXPECT_NE(text.find("Module `" + std::string(module) + "`"), std::string::npos) << module;
    EXPECT_NE(text.find("May use"), std::string::npos) << module;
  }
}

}  // namespace
