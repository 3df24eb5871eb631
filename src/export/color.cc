// Colour parsing for the `color` property: a small table of names plus numeric forms. Written
// here because the forms (grey levels as strings, Python-style tuples) are the language's own.
#include "export/color.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <string>
#include <vector>

namespace prs::exporting {
namespace {

struct NamedColor {
  const char* name;
  unsigned rgb;  // 0xRRGGBB
};

// The CSS basic and common extended names, without spaces, lowercase.
constexpr std::array<NamedColor, 30> kNamedColors = {{
    {"black", 0x000000},    {"white", 0xffffff},     {"red", 0xff0000},
    {"green", 0x008000},    {"blue", 0x0000ff},      {"yellow", 0xffff00},
    {"cyan", 0x00ffff},     {"aqua", 0x00ffff},      {"magenta", 0xff00ff},
    {"fuchsia", 0xff00ff},  {"orange", 0xffa500},    {"purple", 0x800080},
    {"brown", 0x8b4513},    {"pink", 0xffc0cb},      {"grey", 0x808080},
    {"gray", 0x808080},     {"lightgrey", 0xd3d3d3}, {"lightgray", 0xd3d3d3},
    {"darkgrey", 0x404040}, {"darkgray", 0x404040},  {"silver", 0xc0c0c0},
    {"navy", 0x000080},     {"olive", 0x808000},     {"teal", 0x008080},
    {"maroon", 0x800000},   {"lime", 0x00ff00},      {"gold", 0xffd700},
    {"beige", 0xf5f5dc},    {"violet", 0xee82ee},    {"darkgreen", 0x006400},
}};

Rgba FromHex(unsigned rgb) {
  return {((rgb >> 16) & 0xff) / 255.0, ((rgb >> 8) & 0xff) / 255.0, (rgb & 0xff) / 255.0, 1.0};
}

std::string NormaliseName(std::string_view text) {
  std::string name;
  for (const char c : text) {
    if (c != ' ' && c != '_' && c != '-') name += char(std::tolower(static_cast<unsigned char>(c)));
  }
  return name;
}

std::optional<Rgba> FindNamedColor(std::string_view text) {
  const std::string name = NormaliseName(text);
  for (const NamedColor& entry : kNamedColors) {
    if (name == entry.name) return FromHex(entry.rgb);
  }
  if (name.size() == 7 && name[0] == '#') {
    unsigned rgb = 0;
    const auto [end, error] = std::from_chars(name.data() + 1, name.data() + 7, rgb, 16);
    if (error == std::errc() && end == name.data() + 7) return FromHex(rgb);
  }
  return std::nullopt;
}

// Numbers separated by spaces and/or commas, optionally inside one pair of brackets.
std::optional<std::vector<double>> SplitNumbers(std::string_view text) {
  std::string cleaned(text);
  for (char& c : cleaned) {
    if (c == ',' || c == '(' || c == ')' || c == '[' || c == ']') c = ' ';
  }
  std::vector<double> numbers;
  const char* p = cleaned.data();
  const char* end = p + cleaned.size();
  while (p < end) {
    if (*p == ' ' || *p == '\t') {
      ++p;
      continue;
    }
    double x = 0;
    const auto [stop, error] = std::from_chars(p, end, x);
    if (error != std::errc()) return std::nullopt;
    numbers.push_back(x);
    p = stop;
  }
  return numbers;
}

// One number: a grey level; three or four: RGB(A), on a 0-255 scale when any exceeds 1.
std::optional<Rgba> FromNumbers(std::vector<double> numbers) {
  if (numbers.size() == 1) numbers = {numbers[0], numbers[0], numbers[0]};
  if (numbers.size() != 3 && numbers.size() != 4) return std::nullopt;
  const double top = *std::max_element(numbers.begin(), numbers.end());
  const double low = *std::min_element(numbers.begin(), numbers.end());
  if (low < 0 || top > 255) return std::nullopt;
  const double scale = top > 1 ? 255.0 : 1.0;
  Rgba color{numbers[0] / scale, numbers[1] / scale, numbers[2] / scale, 1.0};
  if (numbers.size() == 4) color.a = numbers[3] / scale;
  return color;
}

std::optional<Rgba> FromElements(const std::vector<lang::Value>& elements) {
  std::vector<double> numbers;
  for (const lang::Value& element : elements) {
    if (!element.Is<double>()) return std::nullopt;
    numbers.push_back(element.As<double>());
  }
  if (numbers.size() < 3) return std::nullopt;  // a 1-tuple is not a colour
  return FromNumbers(std::move(numbers));
}

}  // namespace

std::optional<Rgba> ParseColorNumbers(std::vector<double> numbers) {
  return FromNumbers(std::move(numbers));
}

std::optional<Rgba> ParseColorText(std::string_view text) {
  if (auto named = FindNamedColor(text)) return named;
  if (auto numbers = SplitNumbers(text)) return FromNumbers(std::move(*numbers));
  return std::nullopt;
}

std::optional<Rgba> ParseColor(const lang::Value& value) {
  if (const auto* text = std::get_if<lang::StringPtr>(&value.data)) return ParseColorText(**text);
  if (const auto* grey = std::get_if<double>(&value.data)) {
    if (*grey < 0 || *grey > 1) return std::nullopt;
    return Rgba{*grey, *grey, *grey, 1.0};
  }
  if (const auto* v = std::get_if<Eigen::Vector3d>(&value.data))
    return FromNumbers({v->x(), v->y(), v->z()});
  if (const auto* t = std::get_if<std::shared_ptr<lang::TupleData>>(&value.data))
    return FromElements((*t)->elements);
  if (const auto* l = std::get_if<std::shared_ptr<lang::ListData>>(&value.data))
    return FromElements((*l)->elements);
  return std::nullopt;
}

}  // namespace prs::exporting
