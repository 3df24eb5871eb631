// Colour names, grey levels, number lists and hex codes to linear RGBA (see color.h).
#include "render/color.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <string>

namespace prs::render {
namespace {

struct NamedColor {
  const char* name;
  Rgba rgba;
};

// The common names (CSS-like values, softened a little so shading stays readable).
constexpr NamedColor kNamedColors[] = {
    {"red", {0.85f, 0.15f, 0.12f, 1}},
    {"green", {0.2f, 0.65f, 0.25f, 1}},
    {"blue", {0.15f, 0.3f, 0.85f, 1}},
    {"yellow", {0.95f, 0.85f, 0.15f, 1}},
    {"orange", {0.95f, 0.55f, 0.1f, 1}},
    {"purple", {0.55f, 0.25f, 0.7f, 1}},
    {"pink", {0.95f, 0.6f, 0.7f, 1}},
    {"brown", {0.5f, 0.32f, 0.18f, 1}},
    {"white", {0.95f, 0.95f, 0.95f, 1}},
    {"black", {0.08f, 0.08f, 0.08f, 1}},
    {"grey", {0.5f, 0.5f, 0.5f, 1}},
    {"gray", {0.5f, 0.5f, 0.5f, 1}},
    {"cyan", {0.1f, 0.75f, 0.8f, 1}},
    {"magenta", {0.8f, 0.2f, 0.7f, 1}},
    {"silver", {0.75f, 0.75f, 0.75f, 1}},
    {"beige", {0.9f, 0.85f, 0.7f, 1}},
    // Less common CSS names, at their CSS values.
    {"navy", {0, 0, 0.5f, 1}},
    {"teal", {0, 0.5f, 0.5f, 1}},
    {"olive", {0.5f, 0.5f, 0, 1}},
    {"maroon", {0.5f, 0, 0, 1}},
    {"lime", {0, 1, 0, 1}},
    {"gold", {1, 0.84f, 0, 1}},
    {"violet", {0.93f, 0.51f, 0.93f, 1}},
    {"indigo", {0.29f, 0, 0.51f, 1}},
    {"turquoise", {0.25f, 0.88f, 0.82f, 1}},
    {"salmon", {0.98f, 0.5f, 0.45f, 1}},
    {"tan", {0.82f, 0.71f, 0.55f, 1}},
    {"khaki", {0.94f, 0.9f, 0.55f, 1}},
    {"lightgrey", {0.83f, 0.83f, 0.83f, 1}},
    {"lightgray", {0.83f, 0.83f, 0.83f, 1}},
    {"darkgrey", {0.66f, 0.66f, 0.66f, 1}},
    {"darkgray", {0.66f, 0.66f, 0.66f, 1}},
    {"lightblue", {0.68f, 0.85f, 0.9f, 1}},
    {"darkblue", {0, 0, 0.55f, 1}},
    {"darkgreen", {0, 0.39f, 0, 1}},
    {"darkred", {0.55f, 0, 0, 1}},
    {"skyblue", {0.53f, 0.81f, 0.92f, 1}},
};

std::string ToLower(std::string_view text) {
  std::string lower(text);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return lower;
}

std::string_view Trim(std::string_view text) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front())))
    text.remove_prefix(1);
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back())))
    text.remove_suffix(1);
  return text;
}

// "0.1 0.2, 0.3" -> {0.1, 0.2, 0.3}; nullopt when a piece is not a number.
std::optional<std::vector<double>> SplitNumbers(std::string_view text) {
  std::vector<double> values;
  size_t i = 0;
  while (i < text.size()) {
    if (std::isspace(static_cast<unsigned char>(text[i])) || text[i] == ',') {
      ++i;
      continue;
    }
    double value = 0;
    const auto [stop, error] = std::from_chars(text.data() + i, text.data() + text.size(), value);
    if (error != std::errc()) return std::nullopt;
    values.push_back(value);
    i = stop - text.data();
  }
  return values;
}

std::optional<Rgba> ParseHex(std::string_view text) {
  if (text.size() != 7) return std::nullopt;
  unsigned value = 0;
  const auto [stop, error] = std::from_chars(text.data() + 1, text.data() + 7, value, 16);
  if (error != std::errc() || stop != text.data() + 7) return std::nullopt;
  return Rgba{((value >> 16) & 0xff) / 255.0f, ((value >> 8) & 0xff) / 255.0f,
              (value & 0xff) / 255.0f, 1.0f};
}

}  // namespace

std::optional<Rgba> ParseColorNumbers(const std::vector<double>& values) {
  if (values.size() != 1 && values.size() != 3 && values.size() != 4) return std::nullopt;
  const double largest = *std::max_element(values.begin(), values.end());
  const double smallest = *std::min_element(values.begin(), values.end());
  if (smallest < 0 || largest > 255) return std::nullopt;
  const double scale = largest > 1 ? 1.0 / 255.0 : 1.0;
  auto at = [&](size_t i) { return static_cast<float>(values[i] * scale); };
  if (values.size() == 1) return Rgba{at(0), at(0), at(0), 1.0f};
  return Rgba{at(0), at(1), at(2), values.size() == 4 ? at(3) : 1.0f};
}

std::optional<Rgba> ParseColorText(std::string_view text) {
  const std::string lower = ToLower(Trim(text));
  if (lower.empty()) return std::nullopt;
  if (lower[0] == '#') return ParseHex(lower);
  for (const NamedColor& named : kNamedColors) {
    if (lower == named.name) return named.rgba;
  }
  if (auto values = SplitNumbers(lower)) return ParseColorNumbers(*values);
  return std::nullopt;
}

}  // namespace prs::render
