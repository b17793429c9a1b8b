// The seam check (tiling/seam_check.h) as the table wang --check and wang-check print.
#pragma once

#include <string>

#include "bluetile/tiling/seam_check.h"

namespace bluetile::cli {

// One row per level prefix: the closest distances across and within tiles, in tile units and
// in hexagonal spacings, and the closest pair across a seam.
std::string seam_report(const SeamCheck& check);

}  // namespace bluetile::cli
