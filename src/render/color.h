// Colour parsing for the `color` property: colour names ("blue", "grey"), grey levels ("0.5"
// or 0.5), RGB(A) triples in [0, 1] or [0, 255] (a tuple, a list, or "0.1 0.2 0.3"), and
// "#rrggbb". Hand-written: no Debian library names colours for us, and the rules are a page.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include "render/render.h"

namespace prs::render {

/// Reads a colour from text: a name (case-insensitive, "grey" and "gray" both), a grey level
/// in [0, 1], three or four numbers separated by spaces or commas, or "#rrggbb". Returns
/// nullopt when the text is none of these.
std::optional<Rgba> ParseColorText(std::string_view text);

/// Reads a colour from numbers: one (a grey level), three (RGB) or four (RGBA). Values above 1
/// mean the 0..255 scale (all of them then). Returns nullopt for another count, a negative
/// value or a value above 255.
std::optional<Rgba> ParseColorNumbers(const std::vector<double>& values);

}  // namespace prs::render
