// The engine contract (engine.h), checked in one place. Every CentroidEngine calls
// validated_scene() on each scene at its entry, so all engines accept and refuse the same
// scenes with the same messages (STYLE: validate at the public entry, once).
#pragma once

#include <cstddef>
#include <string_view>

#include "bluetile/voronoi/engine.h"

namespace bluetile {

// The most sites a scene may hold: engines index sites with 32-bit integers and keep one value
// as a marker.
inline constexpr std::size_t kMaxSceneSites = 0xFFFFFFFEu;

// Checks `scene` against the contract and returns the scene to compute.
// Throws Error when:
// - a side of the domain is not a finite positive number;
// - the wanted range is not inside the sites (wanted_begin <= wanted_end <= sites.size());
// - a site has a NaN or infinite coordinate (the message names its index and value);
// - there are more than kMaxSceneSites sites;
// - a density that check_density (density_moments.h) refuses: a size that does not match its
//   texels, a texel negative or not finite, zero everywhere;
// - in a bounded domain, a site lies outside [0, W) x [0, H).
// In a periodic domain, sites outside [0, W) x [0, H) (a tile loop's neighbours one period away,
// a rounding just below 0) are wrapped onto it: the result is `scene` itself when every site is
// inside already, else a copy with wrapped sites, kept in `storage`. Cells are then those of the
// wrapped sites, in the same order, so their areas sum to the domain's area.
const Scene& validated_scene(const Scene& scene, Scene& storage);

// Throws Error unless a batch has one result per scene (every engine's compute checks it first:
// an `out` shorter than the scenes was written past, a crash in a release build).
void check_batch(std::string_view engine, std::size_t scenes, std::size_t results);

}  // namespace bluetile
