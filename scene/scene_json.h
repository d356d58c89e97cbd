#pragma once
/// Reading a scene file's JSON with the element's path in every message: the parse (nesting
/// limit, NaN and Infinity literals named where they are, line and column of a syntax error)
/// and the Reader of typed values. Used by scene_loader.cpp only.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "geometry/vec.h"
#include "scene/error.h"

namespace rad::scene_json {

using Json = nlohmann::json;

/// The JSON document of a scene file, or an InputError naming the file with the line and
/// column: nested deeper than limits::kJsonDepth, or not JSON.
Json parse_json(const std::string& json_text, const std::filesystem::path& file);

/// Text markers for the non-standard literals NaN, Infinity and -Infinity: they survive
/// parsing as strings so the element can be named.
inline constexpr const char* kNonFinitePrefix = "\x01nonfinite:";

/// Reading JSON values with the element's path in every message.
class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw InputError(file_ + ": " + where + ": " + what);
  }
  std::string at(const std::string& where) const { return file_ + ": " + where; }

  void require_object(const Json& j, const std::string& where,
                      const std::set<std::string>& allowed) const {
    if (!j.is_object()) fail(where, "expected an object, got " + type_name(j));
    for (const auto& [key, value] : j.items()) {
      if (!allowed.count(key)) {
        std::string list;
        for (const auto& k : allowed) list += (list.empty() ? "" : ", ") + k;
        fail(where, "unknown key \"" + key + "\" (allowed: " + list + ")");
      }
    }
  }

  double number(const Json& j, const std::string& where) const {
    if (j.is_string()) {
      const std::string s = j.get<std::string>();
      if (s.rfind(kNonFinitePrefix, 0) == 0) {
        fail(where,
             "is not a finite number (" + s.substr(std::string(kNonFinitePrefix).size()) + ")");
      }
    }
    if (!j.is_number()) fail(where, "expected a number, got " + type_name(j));
    const double value = j.get<double>();
    if (!std::isfinite(value)) fail(where, "is not a finite number");
    return value;
  }

  int positive_int(const Json& j, const std::string& where) const {
    if (!j.is_number_integer() || j.get<long long>() <= 0 || j.get<long long>() > 1 << 20) {
      fail(where, "expected a positive integer (at most 1048576), got " + j.dump());
    }
    return j.get<int>();
  }

  std::string string(const Json& j, const std::string& where) const {
    if (!j.is_string() || j.get<std::string>().rfind(kNonFinitePrefix, 0) == 0) {
      fail(where, "expected a string, got " + type_name(j));
    }
    return j.get<std::string>();
  }

  Vec3 vec3(const Json& j, const std::string& where) const {
    if (!j.is_array() || j.size() != 3) fail(where, "expected [x, y, z], got " + abbreviated(j));
    return {number(j[0], where + "[0]"), number(j[1], where + "[1]"), number(j[2], where + "[2]")};
  }

  /// An RGB triple, or one number for a grey.
  Rgb rgb(const Json& j, const std::string& where) const {
    if (j.is_number()) {
      const double v = number(j, where);
      return {v, v, v};
    }
    if (!j.is_array() || j.size() != 3) fail(where, "expected [r, g, b], got " + abbreviated(j));
    return {number(j[0], where + "[0]"), number(j[1], where + "[1]"), number(j[2], where + "[2]")};
  }

 private:
  static std::string type_name(const Json& j) {
    if (j.is_string() && j.get<std::string>().rfind(kNonFinitePrefix, 0) == 0) {
      return "a non-finite number";
    }
    return std::string(j.type_name()) + " " + abbreviated(j);
  }
  static std::string abbreviated(const Json& j) {
    std::string text = j.dump();
    return text.size() > 40 ? text.substr(0, 37) + "..." : text;
  }

  std::string file_;
};

}  // namespace rad::scene_json
