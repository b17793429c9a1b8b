// Wang-tile sample sets: Lloyd relaxation with multiple edge constraints (Hiller, Deussen, Keller
// 2001, section 3). Every tile of a set holds a point set; the sets are relaxed together, each
// point moving by the mean of its Lloyd displacements over the configurations of neighbouring
// tiles its tile can be placed in (wang_step.h), so that any two tiles whose edges fit sit side by
// side without a seam. Jacobi steps; a point never leaves its own tile square. Two short steps
// refine what the averaging leaves: lattice decorrelation (wang_lattice.h) against the peaks a
// tiling puts on the tile lattice, and seam spacing (wang_seams.h) for the closest pairs across
// seams.
//
// Levels (hierarchical sets that tile): level 0 is relaxed as above; each further level adds
// points to every tile, relaxed around the fixed earlier levels of its own tile and of its
// neighbours, under the same constraints. Every point gets a level and a rank, its place in the
// tile's progressive order (wang_ranks.h). Points are stored in rank order.
#pragma once

#include <cstdint>
#include <functional>

#include <string_view>

#include "bluetile/relax/band_fill.h"
#include "bluetile/relax/void_order.h"
#include "bluetile/tiling/tile_set.h"
#include "bluetile/voronoi/engine.h"

namespace bluetile {

enum class WangStrategy : std::uint8_t { exact, instances, rounds };

std::string_view wang_strategy_name(WangStrategy strategy);

// farthest and voids rank a relaxed level's points (wang_ranks.h); fill builds every level after
// the first without relaxation, point by point in rank order (band_fill.h), level 0 relaxed and
// ranked by farthest point as before.
enum class RankOrder : std::uint8_t { farthest, voids, fill };

struct WangIteration {
  int level = 0;
  int iteration = 0;       // 1-based; warm-start iterations come first, counted in `warm`
  bool warm = false;       // a periodic iteration of each tile alone
  double max_displacement = 0.0;   // tile units
  double mean_displacement = 0.0;
  double energy = 0.0;     // sum of mean cell second moments (constrained) or of second moments (warm)
  std::size_t scenes = 0, cells = 0, regrown = 0;
};

// The two steps that refine a level after (and during) its constrained iterations.
struct WangRefinement {
  // Lattice decorrelation (wang_lattice.h): gradient steps of at most lattice_step hexagonal
  // spacings over the low band and, in level 0, the mid band: lattice_steps_per_iteration after
  // each constrained iteration of the second half, then lattice_iterations after the last
  // (0: none). At 52 points per tile they take C_mid from 30-40 to 8 (docs/RESULTS.md, Wang tiles).
  int lattice_steps_per_iteration = 3;
  int lattice_iterations = 5;
  double lattice_step = 0.005;
  // Seam spacing after them (wang_seams.h): this many repulsion steps (0: none) for pairs closer
  // than the spacing, in hexagonal spacings of the tile's points: seam_spacing in level 0,
  // later_seam_spacing in the levels after it, whose new points, squeezed between fixed ones,
  // cannot all reach 0.80 (a target they cannot reach leaves them worse spread than a lower
  // one). With these defaults wang8 sets of 13 and 52 points reach seamX 0.80 and X/W 1.00 with
  // their low-frequency power unchanged.
  int seam_iterations = 20;
  double seam_spacing = 0.80;
  double later_seam_spacing = 0.65;
  // Lattice steps for the fill order's filled levels (wang_lattice.h, decorrelate_filled_level),
  // on levels of at most filled_lattice_up_to points per tile (a step costs about 1.6 T n^2
  // phases; corner81's peaks from 192 per tile up meet 4 without them). On corner81 they take the
  // lattice peak from 32 to 128 per tile from 4.2-8.0 to 1.6-2.5 (24 per tile: 7.7 to 4.05), at a
  // spacing of 0.62 instead of the fill's 0.66 and 2-20 % more low-frequency power (docs/RESULTS.md,
  // "Lattice steps for filled levels").
  int filled_lattice_steps = 150;
  double filled_lattice_spacing = 0.62;
  std::size_t filled_lattice_up_to = 128;
};

struct WangLevelOptions {
  std::size_t add = 0;        // points each tile gains in this level (>= 1)
  // Constrained iterations: 100 bring the low frequencies of 52-point tiles below untiled
  // Lloyd's; they also make the tiles phase-lock (lattice peaks grow), which the interleaved
  // lattice steps offset (docs/RESULTS.md, Wang tiles).
  int iterations = 100;
  int warm_iterations = 10;   // periodic iterations of each tile alone before them (0: none)
  WangStrategy strategy = WangStrategy::exact;
  int period = 16;            // instances: torus tiling size
  std::uint64_t seed = 1;     // this level's seed (placement, instances, rounds)
  // Points are kept this far inside their tile square (tile units; 0: anywhere in [0,1)).
  double edge_margin = 0.0;
  WangRefinement refine{};  // the lattice and seam spacing steps
  // The order of the level's points (wang_ranks.h): farthest point, or by voids with a kernel of
  // void_sigma hexagonal spacings of the prefix; or fill, the default: levels after the first
  // filled point by point (band_fill.h), every prefix above level 0 at rho 0.66 and about half the
  // low-frequency power of farthest's between the boundaries (docs/RESULTS.md, "Every prefix").
  RankOrder rank_order = RankOrder::fill;
  double void_sigma = 0.5;
  FillOptions fill{};  // the fill order's floor, window and grid; its seed is set from `seed`
  std::function<void(const WangIteration&)> on_iteration{};
  // After each lattice step of a filled level (refine.filled_lattice_steps).
  std::function<void(int done, int total)> on_filled_lattice_step{};
};

// An empty set of `kind`: every tile with its colours and no points.
TileSet empty_tile_set(TileSetKind kind);

// Adds one level to every tile of `set` (all tiles must have the same number of points): places
// options.add new points per tile, relaxes them, ranks them after the existing points, and appends
// them in rank order. Existing points, levels and ranks stay bit for bit.
void add_wang_level(CentroidEngine& engine, TileSet& set, const WangLevelOptions& options);

struct WangOptions {
  TileSetKind kind = TileSetKind::wang8;
  std::size_t points = 52;  // points per tile in level 0
  int levels = 1;
  double ratio = 2.0;       // each further level brings a tile's count to round(ratio * count)
  std::uint64_t seed = 1;
  // Iterations, strategy, margin and callback of every level (add and seed are set per level).
  WangLevelOptions level{};
};

// The values the tool's options and the Python module's arguments accept, defined once. More
// points per tile than kMaxWangPoints is almost surely a mistyped option (the largest sets of
// docs/RESULTS.md have 2048) and keeps memory sane; the step and spacing ranges are in hexagonal
// spacings of the tile's points.
inline constexpr std::size_t kMaxWangPoints = 1'000'000;
inline constexpr int kMaxWangLevels = 32;
inline constexpr int kMinWangPeriod = 2, kMaxWangPeriod = 1024;
inline constexpr int kMaxWangIterations = 100'000'000;
inline constexpr double kMaxWangRatio = 1e8;
inline constexpr double kMaxEdgeMargin = 0.25;  // tile units
inline constexpr int kMaxLatticeSteps = 100'000, kMaxLatticeStepsPerIteration = 1000, kMaxSeamSteps = 100'000;
inline constexpr double kMinLatticeStep = 0.0001, kMaxLatticeStep = 0.1;
inline constexpr double kMinSeamSpacing = 0.01, kMaxSeamSpacing = 2.0;  // and the filled levels' spacing

// Throws Error naming the first field outside those ranges ("points: expected 1 to 1000000, got
// 0"), by the Python module's names of the fields.
void validate(const WangOptions& options);

// Names of the strategies and rank orders as the front ends spell them; the parsers throw Error
// naming the field, the value and the list.
// "auto" is exact, but instances for corner81: with 9 tiles fitting each edge and 27 each corner,
// a point near a corner of a tile of fewer than about 200 points meets more neighbour
// configurations than the exact strategy's limit (65536).
WangStrategy parse_wang_strategy(const std::string& name, TileSetKind kind);
RankOrder parse_wang_rank_order(const std::string& name);
const char* wang_rank_order_name(RankOrder order);

// The settings that only some runs use, by the Python module's names of the fields (the tool's
// options are the same with "--" and "-" for "_"): ratio (levels 2 or more), period (the
// instances strategy), void_sigma (the voids order), lattice_step (lattice steps, after or during
// the iterations), seam_spacing (seam steps), level_seam_spacing (seam steps in relaxed later
// levels: not the fill order's, which are filled), filled_lattice_steps (filled levels: the fill
// order and levels 2 or more), filled_lattice_spacing and filled_lattice_up_to (filled levels with
// lattice steps). The front ends refuse such a setting where a run would not use it, rather than
// drop it without a word, and the tool's made-by line names each only where it was used.
inline constexpr std::string_view kConditionalWangSettings[] = {
    "ratio", "period", "void_sigma", "lattice_step", "seam_spacing", "level_seam_spacing",
    "filled_lattice_steps", "filled_lattice_spacing", "filled_lattice_up_to"};
// Whether a run with `options` uses `setting`, one of kConditionalWangSettings (Error otherwise).
bool wang_setting_used(const WangOptions& options, std::string_view setting);

// A whole set: level 0, then levels 1 .. levels-1. The seed of level l is derive_seed(seed, l), so
// a set with more levels starts with the same points as one with fewer.
TileSet relax_wang_tiles(CentroidEngine& engine, const WangOptions& options);

}  // namespace bluetile
