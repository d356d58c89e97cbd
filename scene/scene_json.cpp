#include "scene/scene_json.h"

#include <string>

#include "scene/error.h"
#include "scene/limits.h"

namespace rad::scene_json {
namespace {

/// JSON has no NaN or Infinity, but Python's json.dump writes them; a user who generated a
/// scene that way deserves a message naming the element, not a parse error at a byte offset.
/// Outside strings, those bare literals become marker strings the readers below reject.
std::string quote_nonfinite_literals(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  bool in_string = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      out += c;
      if (c == '\\' && i + 1 < text.size()) {
        out += text[++i];
      } else if (c == '"') {
        in_string = false;
      }
      continue;
    }
    if (c == '"') {
      in_string = true;
      out += c;
      continue;
    }
    bool replaced = false;
    for (const char* literal : {"-Infinity", "Infinity", "NaN"}) {
      const size_t len = std::char_traits<char>::length(literal);
      if (text.compare(i, len, literal) == 0) {
        out += std::string("\"\\u0001nonfinite:") + literal + "\"";
        i += len - 1;
        replaced = true;
        break;
      }
    }
    if (!replaced) out += c;
  }
  return out;
}

std::string line_column(const std::string& text, size_t byte) {
  size_t line = 1, column = 1;
  for (size_t i = 0; i < byte && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line, column = 1;
    } else {
      ++column;
    }
  }
  return std::to_string(line) + ":" + std::to_string(column);
}

/// The deepest nesting of arrays and objects outside strings, with the byte where it first
/// exceeds `limit` (or npos). nlohmann's parser keeps its own stack, but what it builds is
/// destroyed recursively: a file of 100,000 nested brackets would overflow the stack.
size_t too_deep_at(const std::string& text, int limit) {
  int depth = 0;
  bool in_string = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') {
        ++i;
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > limit) return i;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return std::string::npos;
}

}  // namespace

Json parse_json(const std::string& json_text, const std::filesystem::path& file) {
  if (const size_t at = too_deep_at(json_text, limits::kJsonDepth); at != std::string::npos) {
    throw InputError(file.string() + ":" + line_column(json_text, at) +
                     ": invalid JSON: nested deeper than " + std::to_string(limits::kJsonDepth) +
                     " levels");
  }
  try {
    return Json::parse(quote_nonfinite_literals(json_text));
  } catch (const Json::parse_error& e) {
    // nlohmann's message starts with "[json.exception.parse_error.101] parse error at line..."
    std::string what = e.what();
    const size_t colon = what.find("parse error");
    what = colon == std::string::npos ? what : what.substr(colon);
    throw InputError(file.string() + ":" + line_column(json_text, e.byte) +
                     ": invalid JSON: " + what);
  } catch (const Json::exception& e) {
    // "[json.exception.out_of_range.406] number overflow parsing '1e400'": the words only.
    std::string what = e.what();
    if (what.rfind("[json.exception.", 0) == 0 && what.find("] ") != std::string::npos)
      what = what.substr(what.find("] ") + 2);
    throw InputError(file.string() + ": invalid JSON: " + what);
  }
}

}  // namespace rad::scene_json
