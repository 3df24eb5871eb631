// How the paper's naive baseline counts a failed `require` (its Table II): a requirement that
// compares where objects are is a relative-position violation, one that puts something inside a
// region a containment violation, anything else stays a plain requirement. Only the form of the
// expression is read, never its values, so the answer is the same in every scene.
#pragma once

#include "lang/ast.h"
#include "lang/scene.h"

namespace prs::lang {

/// The rejection kind a failed `require CONDITION` counts as in naive mode:
/// - kContainment: `P in R`, or a `.contains(...)` call (`space.contains(tray)`);
/// - kRelativePosition: a comparison (`<`, `<=`, `>`, `>=`, `==`, `!=`, chained or not) one of
///   whose operands reads a position: `.x`, `.y`, `.z`, `.position`, or `distance from`;
/// - for `A and B` / `A or B`: the kind both sides share, if they share one;
/// - kRequirement otherwise (including `not ...`, whose meaning the form does not tell).
RejectionKind ClassifyRequirement(const Expr& condition);

}  // namespace prs::lang
