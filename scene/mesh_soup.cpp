#include <algorithm>
#include <charconv>
#include <cstdlib>

#include "scene/error.h"
#include "scene/limits.h"
#include "scene/mesh_formats.h"

namespace rad::mesh_formats {

void MeshSource::fail(const std::string& detail) const {
  throw InputError(where + ": cannot read mesh file '" + file + "' (" + detail + ")");
}

void MeshSource::check_claim(long long count, const char* what, long long limit,
                             std::uintmax_t min_bytes, std::uintmax_t available) const {
  const std::string claims = where + ": mesh file '" + file + "' claims ";
  if (count < 0) {
    throw InputError(claims + "a negative count (" + std::to_string(count) + ") of " + what);
  }
  if (count > limit) {
    throw InputError(claims + std::to_string(count) + " " + what + ", more than the limit of " +
                     std::to_string(limit));
  }
  // count <= limit < 2^31 and min_bytes is a few bytes, so the product cannot overflow.
  if (static_cast<std::uintmax_t>(count) * min_bytes > available) {
    throw InputError(claims + std::to_string(count) + " " + what + ", more than its " +
                     std::to_string(available) + " bytes hold");
  }
}

SoupBuilder::SoupBuilder(const MeshSource& source, long long first_index)
    : source_(source), first_index_(first_index) {}

void SoupBuilder::reserve(long long vertices, long long faces) {
  vertices_.reserve(static_cast<size_t>(std::max(0LL, vertices)));
  face_ends_.reserve(static_cast<size_t>(std::max(0LL, faces)));
}

void SoupBuilder::add_vertex(const Vec3& p) {
  if (vertex_count() >= limits::kMeshVertices) {
    source_.fail("more than the limit of " + std::to_string(limits::kMeshVertices) + " vertices");
  }
  vertices_.push_back(p);
}

void SoupBuilder::add_index(long long index) {
  const size_t start = face_ends_.empty() ? 0 : face_ends_.back();
  if (static_cast<long long>(indices_.size() - start) >= limits::kPolygonVertices) {
    source_.fail("face " + std::to_string(face_count()) + " has more than " +
                 std::to_string(limits::kPolygonVertices) + " vertices");
  }
  indices_.push_back(index);
}

void SoupBuilder::end_face() {
  if (face_count() >= limits::kPolygons) {
    source_.fail("more than the limit of " + std::to_string(limits::kPolygons) + " faces");
  }
  face_ends_.push_back(indices_.size());
}

Faces SoupBuilder::take() {
  Faces faces(face_ends_.size());
  const long long n = vertex_count();
  size_t start = 0;
  for (size_t f = 0; f < face_ends_.size(); ++f) {
    faces[f].reserve(face_ends_[f] - start);
    for (size_t i = start; i < face_ends_[f]; ++i) {
      if (indices_[i] < 0 || indices_[i] >= n) {
        source_.fail(
            "face " + std::to_string(f) + ": vertex index " +
            std::to_string(indices_[i] + first_index_) + " is out of range " +
            (n == 0 ? std::string("(the file has no vertices)")
                    : std::to_string(first_index_) + ".." + std::to_string(n - 1 + first_index_)));
      }
      faces[f].push_back(vertices_[static_cast<size_t>(indices_[i])]);
    }
    start = face_ends_[f];
  }
  return faces;
}

bool Lines::next(std::string_view& line) {
  if (at_ >= text_.size()) return false;
  size_t end = text_.find('\n', at_);
  if (end == std::string_view::npos) end = text_.size();
  line = text_.substr(at_, end - at_);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  at_ = std::min(end + 1, text_.size());
  ++number_;
  return true;
}

namespace {
bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }
}  // namespace

bool Words::next(std::string_view& word) {
  size_t begin = 0;
  while (begin < line_.size() && is_blank(line_[begin])) ++begin;
  if (begin == line_.size()) return false;
  size_t end = begin;
  while (end < line_.size() && !is_blank(line_[end])) ++end;
  word = line_.substr(begin, end - begin);
  line_.remove_prefix(end);
  return true;
}

std::string_view Words::rest() const {
  std::string_view rest = line_;
  while (!rest.empty() && is_blank(rest.front())) rest.remove_prefix(1);
  while (!rest.empty() && is_blank(rest.back())) rest.remove_suffix(1);
  return rest;
}

std::optional<double> parse_real(std::string_view word) {
  if (!word.empty() && word.front() == '+') word.remove_prefix(1);
  double value = 0;
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  // Out of double's range (1e999 or 1e-999) is an error of from_chars; strtod (in the C
  // locale every program starts in) gives what a reader expects there: +-inf, which validation
  // names, or a value rounded to zero.
  if (error == std::errc::result_out_of_range && end == word.data() + word.size()) {
    return std::strtod(std::string(word).c_str(), nullptr);
  }
  if (error != std::errc() || end != word.data() + word.size() || word.empty()) return {};
  return value;
}

std::optional<long long> parse_integer(std::string_view word) {
  if (!word.empty() && word.front() == '+') word.remove_prefix(1);
  long long value = 0;
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  if (error != std::errc() || end != word.data() + word.size() || word.empty()) return {};
  return value;
}

}  // namespace rad::mesh_formats
