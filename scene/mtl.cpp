#include "scene/mtl.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <sstream>

#include "scene/error.h"
#include "scene/mesh_formats.h"

namespace rad {
namespace {

using mesh_formats::Lines;
using mesh_formats::parse_real;
using mesh_formats::Words;

/// The statements of one `newmtl` that a scene material uses, as the file wrote them.
struct MtlStatements {
  std::string name;
  long long line = 0;  ///< of its newmtl
  std::optional<Rgb> kd, ks, ke, tf;
  std::optional<double> d, tr, ns, ni;
  int illum = 2;  ///< the MTL default (a Phong highlight; no reflection, no glass)
};

/// Phong exponents from this one up are a mirror: Blender writes Ns = 1000 (1 - roughness)^2,
/// 1000 for a smooth surface.
constexpr double kMirrorExponent = 1000;
/// The largest reflectance a translated material keeps (below 1: a surface reflecting all it
/// receives makes the progressive solution never converge; the JSON scene refuses 1).
constexpr double kMaxReflectance = 0.99;

/// `illum` models that turn on ray-traced reflection (3: reflection; 4, 6, 7, 9: glass; 5, 8:
/// Fresnel or unraytraced reflection). 0 to 2 are colour, ambient and a Phong highlight: Ks is
/// then the colour of a highlight, which a diffuse solution has no part for.
bool reflects(int illum) { return illum >= 3 && illum <= 9; }
/// `illum` models of glass (4: glass, 6: refraction, 7: Fresnel refraction, 9: glass unraytraced).
bool is_glass(int illum) { return illum == 4 || illum == 6 || illum == 7 || illum == 9; }

/// 'word', built by appending (GCC 12 warns falsely of "'" + std::string(...) under -O2).
std::string quote(std::string_view word) {
  std::string quoted = "'";
  quoted.append(word);
  quoted += '\'';
  return quoted;
}

class MtlParser {
 public:
  MtlParser(std::string_view text, const std::string& file, std::vector<std::string>& warnings)
      : lines_(text), file_(file), warnings_(warnings) {}

  std::vector<MtlStatements> parse() {
    for (std::string_view line; lines_.next(line);) {
      if (const size_t hash = line.find('#'); hash != std::string_view::npos)
        line = line.substr(0, hash);
      Words words(line);
      std::string_view keyword;
      if (!words.next(keyword)) continue;
      statement(keyword, words);
    }
    return std::move(materials_);
  }

 private:
  [[noreturn]] void fail(const std::string& detail) const {
    throw InputError(file_ + " line " + std::to_string(lines_.number()) + ": " + detail);
  }

  double number(Words& words, std::string_view keyword) const {
    std::string_view word;
    if (!words.next(word)) fail(quote(keyword) + " needs a number");
    const auto value = parse_real(word);
    if (!value || !std::isfinite(*value)) {
      fail("cannot parse " + quote(keyword) + " value " + quote(word) + " (a finite number)");
    }
    return *value;
  }

  /// "Kd r g b", or "Kd r" for a grey (MTL: g and b default to r).
  Rgb colour(Words& words, std::string_view keyword) const {
    std::array<double, 3> c{};
    int count = 0;
    for (std::string_view word; words.next(word);) {
      if (count == 0 && (word == "spectral" || word == "xyz")) {
        fail(quote(std::string(keyword) + " " + std::string(word)) +
             " colours are not supported (give r g b)");
      }
      const auto value = parse_real(word);
      if (count == 3 || !value || !std::isfinite(*value)) {
        fail("cannot parse " + quote(keyword) + ": expected 1 or 3 finite numbers");
      }
      c[count++] = *value;
    }
    if (count == 1) c[1] = c[2] = c[0];
    if (count != 1 && count != 3)
      fail(quote(keyword) + " needs 1 or 3 numbers, has " + std::to_string(count));
    const Rgb rgb(c[0], c[1], c[2]);
    if ((rgb.array() < 0).any()) fail(quote(keyword) + " is negative");
    return rgb;
  }

  MtlStatements& current(std::string_view keyword) {
    if (materials_.empty()) fail(quote(keyword) + " before the first 'newmtl'");
    return materials_.back();
  }

  void statement(std::string_view keyword, Words& words) {
    if (keyword == "newmtl") {
      MtlStatements statements;
      statements.name = words.rest();
      statements.line = lines_.number();
      materials_.push_back(std::move(statements));
    } else if (keyword == "Kd") {
      current(keyword).kd = colour(words, keyword);
    } else if (keyword == "Ks") {
      current(keyword).ks = colour(words, keyword);
    } else if (keyword == "Ke") {
      current(keyword).ke = colour(words, keyword);
    } else if (keyword == "Tf") {
      current(keyword).tf = colour(words, keyword);
    } else if (keyword == "d" || keyword == "Tr") {
      std::string_view word;
      Words peek = words;
      if (peek.next(word) && word == "-halo") words.next(word);  // a halo is still a dissolve
      const double value = number(words, keyword);
      if (!(value >= 0 && value <= 1)) fail(quote(keyword) + " is outside [0, 1]");
      (keyword == "d" ? current(keyword).d : current(keyword).tr) = value;
    } else if (keyword == "Ns") {
      const double value = number(words, keyword);
      if (value < 0) fail("'Ns' is negative");
      current(keyword).ns = value;
    } else if (keyword == "Ni") {
      current(keyword).ni = number(words, keyword);
    } else if (keyword == "illum") {
      const double value = number(words, keyword);
      if (!(value >= 0 && value <= 10 && value == std::floor(value)))
        fail("'illum' is not an illumination model from 0 to 10");
      current(keyword).illum = static_cast<int>(value);
    } else if (keyword.starts_with("map_") || keyword == "bump" || keyword == "disp" ||
               keyword == "decal" || keyword == "refl") {
      if (!textures_warned_) {
        textures_warned_ = true;
        warnings_.push_back(file_ + " line " + std::to_string(lines_.number()) + ": " +
                            quote(keyword) +
                            " texture maps are not used: a face takes its material's colours");
      }
    }
    // Ka (ambient), Pr/Pm (PBR extensions) and the rest shade a rasteriser's pixels: skipped.
  }

  Lines lines_;
  const std::string& file_;
  std::vector<std::string>& warnings_;
  std::vector<MtlStatements> materials_;
  bool textures_warned_ = false;
};

/// The scene material of one MTL material (the table in docs/formats.md), scaled into what a
/// surface can send on (reflectance < 1; reflectance + transmittance + specular <= 1 per
/// channel) with a warning when the file asked for more.
Material translate(const MtlStatements& s, const std::string& file,
                   std::vector<std::string>& warnings) {
  const std::string where =
      file + " line " + std::to_string(s.line) + ": material '" + s.name + "'";
  Material m;
  m.name = s.name;
  // d is the opaque fraction (Tr its complement, for exporters that write that instead): the
  // rest of the light passes through, through the filter colour Tf.
  const double opacity = s.d ? *s.d : s.tr ? 1 - *s.tr : 1;
  const Rgb filter = s.tf.value_or(Rgb::Ones());
  if ((filter.array() > 1).any())
    throw InputError(where + ": 'Tf' is above 1 (a filter cannot add light)");
  // Ke is the radiance of the emitting surface, as a renderer shows it; a Lambertian emitter of
  // radiance L has exitance M = pi L (docs/formats.md), and a scene's emission is M.
  if (s.ke) m.emission = std::numbers::pi * *s.ke;
  m.reflectance = opacity * s.kd.value_or(m.reflectance);
  if (reflects(s.illum) && s.ks) m.specular = opacity * *s.ks;
  Rgb passed = (1 - opacity) * filter;
  if (is_glass(s.illum) && s.ni && *s.ni > 1) {
    Refraction r;
    r.ior = Rgb::Constant(*s.ni);
    r.fresnel = s.illum == 7;
    // Glass given no dissolve passes what its filter passes.
    r.transmittance = s.d || s.tr ? passed : filter;
    if (r.fresnel) {
      const double reflected = std::pow((*s.ni - 1) / (*s.ni + 1), 2);
      passed = Rgb::Constant(1 - reflected);
    } else {
      passed = r.transmittance;
    }
    m.refraction = r;
  } else {
    m.transmittance = passed;
    // The Phong exponent n as the spread of a Gaussian lobe: cos^n(t) ~ exp(-n t^2 / 2), so
    // sigma = 1 / sqrt(n); from kMirrorExponent up, a mirror. A filter keeps a sharp mirror (a
    // lobe would make it a roughened pane, which scatters what it passes too).
    if (m.is_mirror() && !m.is_filter() && s.ns && *s.ns < kMirrorExponent)
      m.gloss = std::min(std::numbers::pi, 1 / std::sqrt(std::max(*s.ns, 1e-12)));
  }

  double scale = 1;
  for (int c = 0; c < 3; ++c) {
    const double sent = m.reflectance[c] + m.specular[c];
    if (sent > 1 - passed[c]) scale = std::min(scale, (1 - passed[c]) / sent);
    if (m.reflectance[c] > kMaxReflectance)
      scale = std::min(scale, kMaxReflectance / m.reflectance[c]);
  }
  if (scale < 1) {
    std::ostringstream msg;
    msg.precision(3);
    msg << where << ": reflects " << (m.reflectance + m.specular).maxCoeff()
        << " of the light it receives and passes " << passed.maxCoeff()
        << ", more than a surface can send on (the solution would not converge): Kd"
        << (m.is_mirror() ? " and Ks" : "") << " scaled by " << scale;
    warnings.push_back(msg.str());
    m.reflectance *= scale;
    m.specular *= scale;
  }
  return m;
}

}  // namespace

MaterialLibrary parse_material_library(std::string_view text, const std::string& file,
                                       std::vector<std::string>& warnings) {
  MaterialLibrary library;
  std::map<std::string, long long, std::less<>> defined_at;
  for (const MtlStatements& s : MtlParser(text, file, warnings).parse()) {
    if (const auto earlier = defined_at.find(s.name); earlier != defined_at.end()) {
      warnings.push_back(file + " line " + std::to_string(s.line) + ": material '" + s.name +
                         "' is defined again (first at line " + std::to_string(earlier->second) +
                         "); the later definition is used");
    }
    defined_at[s.name] = s.line;
    library[s.name] = translate(s, file, warnings);
  }
  return library;
}

}  // namespace rad
