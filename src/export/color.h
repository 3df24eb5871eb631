// Reading an object's `color` property into RGBA, shared by every exporter and the renderer: colour names, grey levels, RGB triples. The accepted forms are listed in
// docs/export.md.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include "lang/value.h"

namespace prs::exporting {

/// A colour with components in [0, 1].
struct Rgba {
  double r = 0.7, g = 0.7, b = 0.7, a = 1.0;  // the default: light grey
};

/// Parses colour text:
/// - a name, case-insensitive: the CSS basic colours (black, white, red, green, blue, yellow,
///   cyan, magenta, orange, purple, brown, pink, grey/gray, silver, navy, olive, teal, maroon,
///   lime, ...), plus "light grey" style spellings with or without a space;
/// - a grey level, "0.5" (0 black, 1 white);
/// - three or four numbers, "0.1 0.2 0.3" or "0.1, 0.2, 0.3" (in [0, 1], or all in [0, 255]
///   when any exceeds 1);
/// - "#rrggbb".
/// Returns nullopt for anything else, or for numbers out of range.
std::optional<Rgba> ParseColorText(std::string_view text);

/// Reads numbers as a colour: one (a grey level), three (RGB) or four (RGBA), all in [0, 1], or
/// all on the 0..255 scale when any exceeds 1. Returns nullopt for another count or a number
/// out of range.
std::optional<Rgba> ParseColorNumbers(std::vector<double> numbers);

/// Parses a `color` property value: text as ParseColorText, a number as a grey level, or a
/// vector, tuple or list of three or four numbers. Returns nullopt for any other value.
std::optional<Rgba> ParseColor(const lang::Value& value);

}  // namespace prs::exporting
