// The geometry library's public umbrella header: RNG, rotations, boxes, convex regions, unions
// of convex pieces and their exact samplers (namespace prs::geometry; depends on Eigen only).
#pragma once

#include "geometry/box.h"
#include "geometry/random.h"
#include "geometry/region.h"
#include "geometry/rotation.h"
#include "geometry/sampling.h"
#include "geometry/union.h"
