#include "formats/vtp_guard.h"

#include <vtkNew.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkZLibDataCompressor.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "formats/vtk_messages.h"
#include "scene/error.h"
#include "scene/limits.h"

namespace rad {
namespace {

/// The elements of a solution file and those each may hold (VTK's XML PolyData layout). Arrays
/// may repeat; every other element appears at most once in its parent.
const std::map<std::string, std::set<std::string>>& layout() {
  static const std::map<std::string, std::set<std::string>> children{
      {"VTKFile", {"PolyData", "AppendedData"}},
      {"PolyData", {"FieldData", "Piece"}},
      {"FieldData", {"Array", "DataArray"}},
      {"Piece", {"PointData", "CellData", "Points", "Verts", "Lines", "Strips", "Polys"}},
      {"PointData", {"Array", "DataArray"}},
      {"CellData", {"Array", "DataArray"}},
      {"Points", {"DataArray"}},
      {"Verts", {"DataArray"}},
      {"Lines", {"DataArray"}},
      {"Strips", {"DataArray"}},
      {"Polys", {"DataArray"}},
      {"Array", {}},
      {"DataArray", {}},
      {"AppendedData", {}},
  };
  return children;
}

bool is_array(const std::string& name) { return name == "Array" || name == "DataArray"; }

/// The attributes each element may have: those VTK writes for a solution. VTK ignores others,
/// so a misspelled one ("NumberOfCompon") silently drops the value it was meant to give.
const std::set<std::string>& attributes_of(const std::string& element) {
  static const std::map<std::string, std::set<std::string>> allowed{
      {"VTKFile", {"type", "version", "byte_order", "header_type", "compressor"}},
      {"Piece",
       {"NumberOfPoints", "NumberOfVerts", "NumberOfLines", "NumberOfStrips", "NumberOfPolys"}},
      {"PointData", {"Scalars", "Vectors", "Normals", "Tensors", "TCoords"}},
      {"CellData", {"Scalars", "Vectors", "Normals", "Tensors", "TCoords"}},
      {"Array",
       {"type", "Name", "NumberOfComponents", "NumberOfTuples", "format", "offset", "RangeMin",
        "RangeMax"}},
      {"DataArray",
       {"type", "Name", "NumberOfComponents", "NumberOfTuples", "format", "offset", "RangeMin",
        "RangeMax"}},
      {"AppendedData", {"encoding"}},
  };
  static const std::set<std::string> none;
  const auto it = allowed.find(element);
  return it == allowed.end() ? none : it->second;
}

/// An appended array, with what its XML says its data must hold: VTK reads as many bytes as the
/// XML implies from what the binary header says is there, and dereferences null where the two
/// disagree (a header of 0 blocks for an array that has values, found by the fuzzer).
struct AppendedArray {
  std::string path;
  long long offset = 0;
  long double exact_bytes = -1;  ///< the bytes it must hold, or -1 when the XML does not say
  long double least_bytes = 0;   ///< at least these (a string's terminators)
  int empty = -1;                ///< 1: must hold nothing, 0: must hold something, -1: unknown
  /// A string array's strings: VTK 9.1 stores every 0-terminated string of the data, past the
  /// array's end when there are more than the XML says (a heap overflow the fuzzer found), so
  /// the data must hold exactly this many; -1 for other arrays.
  long double strings = -1;
};

/// What the walk of the tree collects for the check of the appended data.
struct AppendedArrays {
  std::vector<AppendedArray> arrays;
  bool compressed = false;
  bool big_endian = false;
  size_t header_word = 4;  ///< bytes of each number in an array's header (header_type)
};

class Guard {
 public:
  explicit Guard(const std::filesystem::path& file) : file_(file.string()) {}

  [[noreturn]] void fail(const std::string& path, const std::string& detail) const {
    throw InputError(file_ + ": " + path + ": " + detail +
                     " (not a solution file of `radiosity solve`, or a damaged one)");
  }

  void walk(vtkXMLDataElement* element, const std::string& path, const std::string& parent,
            AppendedArrays& appended) {
    const std::string name = element->GetName() ? element->GetName() : "";
    const auto& allowed = layout().at(name);
    for (int a = 0; a < element->GetNumberOfAttributes(); ++a) {
      const char* attribute = element->GetAttributeName(a);
      if (!attribute || !attributes_of(name).count(attribute)) {
        fail(path, "unexpected attribute \"" +
                       std::string(attribute ? attribute : "").substr(0, 40) + "\"");
      }
    }
    if (name == "VTKFile") check_root(element, path, appended);
    if (name == "Piece") check_piece(element, path);
    if (is_array(name)) check_array(element, path, parent, appended);
    if (name == "AppendedData") {
      const char* encoding = element->GetAttribute("encoding");
      if (!encoding || std::strcmp(encoding, "raw") != 0) fail(path, "appended data not raw");
    }
    std::map<std::string, int> seen;
    for (int i = 0; i < element->GetNumberOfNestedElements(); ++i) {
      vtkXMLDataElement* child = element->GetNestedElement(i);
      const std::string child_name = child && child->GetName() ? child->GetName() : "";
      std::string child_path = path;
      child_path.append("/").append(child_name.substr(0, 40));
      if (is_array(child_name)) {
        child_path.append("[").append(std::to_string(seen[child_name])).append("]");
        if (const char* array_name = child->GetAttribute("Name")) {
          child_path.append(" \"").append(std::string(array_name).substr(0, 40)).append("\"");
        }
      }
      if (!allowed.count(child_name)) {
        fail(child_path, "unexpected element <" + child_name.substr(0, 40) + "> in <" + name + ">");
      }
      if (++seen[child_name] > 1 && !is_array(child_name)) {
        fail(child_path, "a second <" + child_name + "> in <" + name + ">");
      }
      walk(child, child_path, name, appended);
    }
    if (name == "VTKFile" && seen["PolyData"] != 1) fail(path, "no <PolyData>");
    if (name == "PolyData" && seen["Piece"] != 1) fail(path, "not exactly one <Piece>");
  }

 private:
  /// A non-negative decimal count of at most `limit`, or fail.
  long long count(vtkXMLDataElement* element, const std::string& path, const char* attribute,
                  long double limit, bool required) const {
    const char* text = element->GetAttribute(attribute);
    if (!text) {
      if (required) fail(path, std::string("no ") + attribute);
      return 0;
    }
    long double value = 0;
    const size_t length = std::strlen(text);
    if (length == 0) fail(path, std::string(attribute) + " is empty");
    for (size_t i = 0; i < length; ++i) {
      if (text[i] < '0' || text[i] > '9') {
        fail(path, std::string(attribute) + "=\"" + std::string(text).substr(0, 40) +
                       "\" is not a count");
      }
      value = 10 * value + (text[i] - '0');
    }
    if (value > limit) {
      fail(path, std::string(attribute) + " claims more than " +
                     std::to_string(static_cast<long long>(limit)) +
                     ", beyond the limit of a solution file (" +
                     std::to_string(limits::kSolutionElements) + " elements)");
    }
    return static_cast<long long>(value);
  }

  void check_root(vtkXMLDataElement* root, const std::string& path, AppendedArrays& appended) {
    const auto attribute = [&](const char* key) {
      const char* value = root->GetAttribute(key);
      return std::string(value ? value : "");
    };
    if (attribute("type") != "PolyData") fail(path, "type is not \"PolyData\"");
    const std::string order = attribute("byte_order");
    if (order != "LittleEndian" && order != "BigEndian") fail(path, "no byte_order");
    appended.big_endian = order == "BigEndian";
    const std::string header = attribute("header_type");
    if (header != "" && header != "UInt32" && header != "UInt64") {
      fail(path, "header_type \"" + header.substr(0, 40) + "\"");
    }
    appended.header_word = header == "UInt64" ? 8 : 4;
    const std::string compressor = attribute("compressor");
    if (compressor != "" && compressor != "vtkZLibDataCompressor") {
      fail(path, "unknown compressor \"" + compressor.substr(0, 40) + "\" (solve writes zlib)");
    }
    appended.compressed = compressor != "";
  }

  void check_piece(vtkXMLDataElement* piece, const std::string& path) {
    // Cells and points: one or a few per element.
    const long double most = 4.0L * limits::kSolutionElements;
    for (const char* key :
         {"NumberOfPoints", "NumberOfVerts", "NumberOfLines", "NumberOfStrips", "NumberOfPolys"}) {
      piece_[key] = count(piece, path, key, most, /*required=*/false);
    }
  }

  /// The values an array in `parent` must have, from its own NumberOfTuples or its piece's
  /// counts, or -1 when the XML does not say (a field array without NumberOfTuples, a cell
  /// connectivity).
  long double tuples(vtkXMLDataElement* array, const std::string& path,
                     const std::string& parent) const {
    if (array->GetAttribute("NumberOfTuples")) {
      return count(array, path, "NumberOfTuples", 8.0L * limits::kSolutionElements, true);
    }
    const auto counted = [&](const char* key) {
      const auto it = piece_.find(key);
      return static_cast<long double>(it == piece_.end() ? 0 : it->second);
    };
    // A field array has no piece to count it: `solve` always writes its NumberOfTuples.
    if (parent == "FieldData") fail(path, "a field array without NumberOfTuples");
    if (parent == "PointData" || parent == "Points") return counted("NumberOfPoints");
    if (parent == "CellData") {
      return counted("NumberOfVerts") + counted("NumberOfLines") + counted("NumberOfStrips") +
             counted("NumberOfPolys");
    }
    const char* name = array->GetAttribute("Name");
    if (name && std::strcmp(name, "offsets") == 0 && layout().at("Piece").count(parent)) {
      return counted(("NumberOf" + parent).c_str());
    }
    return -1;
  }

  void check_array(vtkXMLDataElement* array, const std::string& path, const std::string& parent,
                   AppendedArrays& appended) const {
    // With no type or an unknown one, VTK 9.1 creates no array and dereferences it. Only the
    // types `solve` writes pass: every other one is a reading path of VTK's left untried.
    static const std::set<std::string> known{"Int32", "Int64", "Float64", "String"};
    const char* type = array->GetAttribute("type");
    if (!type || !known.count(type)) {
      fail(path, type ? "an array of unknown type \"" + std::string(type).substr(0, 40) + "\""
                      : std::string("an array without a type"));
    }
    const char* format = array->GetAttribute("format");
    if (!format || std::strcmp(format, "appended") != 0) fail(path, "an array not appended");
    long long components = 1;
    if (array->GetAttribute("NumberOfComponents")) {
      components = count(array, path, "NumberOfComponents", 64, true);
      if (components == 0) fail(path, "NumberOfComponents is 0");
    }
    AppendedArray a{path, count(array, path, "offset", 1e18L, /*required=*/true)};
    // Arrays hold up to 8 corners per element (checked in tuples()).
    const long double values = tuples(array, path, parent);
    const std::string kind = type;
    if (values >= 0) {
      const long double n = values * static_cast<long double>(components);
      if (kind == "String") {
        a.least_bytes = n;  // each string ends with a 0
        a.strings = n;
      } else {
        a.exact_bytes = n * static_cast<long double>(value_bytes(kind));
      }
    } else {
      // A connectivity: values exactly when its piece has cells of its kind.
      const auto it = piece_.find("NumberOf" + parent);
      a.empty = it == piece_.end() || it->second == 0 ? 1 : 0;
    }
    appended.arrays.push_back(std::move(a));
  }

  /// Bytes of one value of a known numeric array type.
  static int value_bytes(const std::string& type) { return type == "Int32" ? 4 : 8; }

  std::string file_;
  std::map<std::string, long long> piece_;  ///< the counts of the piece being walked
};

/// The most a string array may hold: a solution's strings are a path, a fingerprint, and the
/// settings and statistics as JSON.
constexpr long double kMostStringBytes = 16 << 20;

/// `count` bytes of the file from `at` (whose bounds the caller checked).
std::string bytes_at(std::ifstream& in, long double at, long double count) {
  std::string out(static_cast<size_t>(count), '\0');
  in.clear();
  in.seekg(static_cast<std::streamoff>(at));
  in.read(out.data(), static_cast<std::streamsize>(out.size()));
  return out;
}

/// A zlib-compressed array's data, block by block (`blocks`: the first compressed byte, the
/// block size, the last block's size; sizes already checked against the file and the limits).
std::string uncompressed(const Guard& guard, std::ifstream& in, const std::string& path,
                         const std::array<long double, 3>& blocks,
                         const std::vector<long double>& compressed_sizes) {
  vtkNew<vtkZLibDataCompressor> zlib;
  std::string out;
  long double at = blocks[0];
  for (size_t b = 0; b < compressed_sizes.size(); ++b) {
    const std::string packed = bytes_at(in, at, compressed_sizes[b]);
    at += compressed_sizes[b];
    const bool last = b + 1 == compressed_sizes.size();
    std::string block(static_cast<size_t>(last && blocks[2] != 0 ? blocks[2] : blocks[1]), '\0');
    const size_t got =
        zlib->Uncompress(reinterpret_cast<const unsigned char*>(packed.data()), packed.size(),
                         reinterpret_cast<unsigned char*>(block.data()), block.size());
    if (got != block.size()) guard.fail(path, "its compressed data is damaged");
    out += block;
  }
  return out;
}

/// The binary headers of the appended arrays (at the data's start + each array's offset): with a
/// compressor, [blocks, block size, last block size, each block's compressed size]; without, the
/// byte count. VTK sizes its buffers from them, so a hostile file could claim gigabytes there:
/// each header and the compressed blocks must fit in the file, and what it claims uncompressed
/// must stay within what limits::kSolutionElements allows (8 corners of 3 doubles per element).
void check_appended_headers(const Guard& guard, const std::filesystem::path& file,
                            const AppendedArrays& appended, long double data_start) {
  std::error_code error;
  const auto bytes = static_cast<long double>(std::filesystem::file_size(file, error));
  if (error) guard.fail("AppendedData", "cannot read the file's size");
  const size_t word = appended.header_word;
  const long double most = 8.0L * 3 * 8 * static_cast<long double>(limits::kSolutionElements);
  std::ifstream in(file, std::ios::binary);
  // The word at `at`, or at the stream's position when `at` is negative (no seek: the table of
  // block sizes is read in one sweep); -1 past the end of the file.
  const auto read_word = [&](long double at) -> long double {
    if (at >= 0) {
      if (at + word > bytes) return -1;
      in.seekg(static_cast<std::streamoff>(at));
    }
    unsigned char b[8] = {};
    if (!in.read(reinterpret_cast<char*>(b), static_cast<std::streamsize>(word))) return -1;
    long double v = 0;
    for (size_t i = 0; i < word; ++i) {
      v = 256 * v + b[appended.big_endian ? i : word - 1 - i];
    }
    return v;
  };
  for (const AppendedArray& array : appended.arrays) {
    std::vector<long double> block_sizes;  // compressed, of a string array's blocks
    std::array<long double, 3> blocks{};   // first compressed byte, block size, last block size
    const long double start = data_start + static_cast<long double>(array.offset);
    const long double first = read_word(start);
    bool bad = first < 0;
    long double holds = first;  // uncompressed bytes
    if (!bad && appended.compressed) {
      const long double block = read_word(start + word);
      const long double last = read_word(start + 2 * word);
      const long double data = start + (3 + first) * word;  // the first compressed block
      bad = block < 0 || last < 0 || last > block || data > bytes || first * block > most;
      holds = first == 0 ? 0 : (first - 1) * block + (last == 0 ? block : last);
      // Each block's compressed size, which VTK allocates as it reads the block.
      long double compressed = 0;
      if (!bad) in.seekg(static_cast<std::streamoff>(start + 3 * word));
      for (long double b = 0; !bad && b < first; ++b) {
        const long double size = read_word(-1);
        compressed += size;
        bad = size < 0 || data + compressed > bytes;
        if (array.strings >= 0) block_sizes.push_back(size);
      }
      blocks = {data, block, last};
    } else if (!bad) {
      bad = start + word + first > bytes || first > most;
    }
    if (bad) {
      guard.fail(array.path, "its appended header (offset " + std::to_string(array.offset) +
                                 ") claims more data than the file holds or a solution may have");
    }
    if ((array.exact_bytes >= 0 && holds != array.exact_bytes) || holds < array.least_bytes ||
        (array.empty >= 0 && (holds == 0) != (array.empty == 1))) {
      guard.fail(array.path, "its appended header (offset " + std::to_string(array.offset) +
                                 ") says " + std::to_string(static_cast<long long>(holds)) +
                                 " bytes, not what its XML implies");
    }
    if (array.strings >= 0) {
      if (holds > kMostStringBytes) guard.fail(array.path, "a string array of more than 16 MiB");
      const std::string text = appended.compressed
                                   ? uncompressed(guard, in, array.path, blocks, block_sizes)
                                   : bytes_at(in, start + word, holds);
      const auto zeros = static_cast<long double>(std::count(text.begin(), text.end(), '\0'));
      if (zeros != array.strings || (!text.empty() && text.back() != '\0')) {
        guard.fail(array.path, "its data holds " + std::to_string(static_cast<long long>(zeros)) +
                                   " strings, not the " +
                                   std::to_string(static_cast<long long>(array.strings)) +
                                   " its XML says");
      }
    }
  }
}

}  // namespace

void check_solution_structure(const std::filesystem::path& file) {
  Guard guard(file);
  std::ifstream stream(file, std::ios::binary);
  capture_vtk_messages();
  vtkNew<vtkXMLDataParser> parser;
  parser->SetStream(&stream);
  if (!parser->Parse() || !parser->GetRootElement()) {
    const std::string why = vtk_message();
    guard.fail("XML", "cannot parse the XML" + (why.empty() ? "" : " (" + why + ")"));
  }
  vtkXMLDataElement* root = parser->GetRootElement();
  if (!root->GetName() || std::strcmp(root->GetName(), "VTKFile") != 0) {
    guard.fail("XML", "the root element is not <VTKFile>");
  }
  AppendedArrays appended;
  guard.walk(root, "VTKFile", "", appended);
  if (appended.arrays.empty()) return;
  if (parser->GetAppendedDataPosition() <= 0) guard.fail("VTKFile", "no appended data");
  check_appended_headers(guard, file, appended,
                         static_cast<long double>(parser->GetAppendedDataPosition()));
}

}  // namespace rad
