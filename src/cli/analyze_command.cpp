// bluetile analyze: spectral and spatial statistics of point sets (DESIGN sections 5 and 6):
// stats.json, radial.csv, rdf.csv, report.txt (also printed), and points, spectrum, radial and
// rdf images as PNG and SVG in the output folder; optionally a one-page summary (PDF or SVG).
// One set; the mean over several (--average); several series side by side (--compare); or every
// prefix of a hierarchical set (--by-level); or the prefixes of a set in rank (row) order (--by-rank).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "bluetile/analysis/radial_power.h"
#include "bluetile/analysis/summary.h"
#include "bluetile/analysis/summary_record.h"
#include "bluetile/analysis/tiling_metrics.h"
#include "cli/analysis_budget.h"
#include "cli/commands.h"
#include "cli/file_options.h"
#include "cli/numeric_options.h"
#include "cli/output_names.h"
#include "cli/point_output.h"
#include "cli/progress.h"
#include "bluetile/core/error.h"
#include "bluetile/core/memory_budget.h"
#include "bluetile/core/output_file.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/point_file.h"
#include "bluetile/core/point_table.h"
#include "bluetile/core/text.h"
#include "bluetile/tiling/tiled_output.h"
#include "bluetile/drawing/figures.h"
#include "bluetile/io/image_file.h"
#include "bluetile/io/pdf.h"

namespace bluetile::cli {
namespace {

struct AnalyzeOptions {
  std::vector<std::string> inputs;
  std::string output;
  int size = 0;
  double bin_width = 1.0;
  bool average = false;
  bool compare = false;
  bool by_level = false;
  std::vector<std::string> by_rank;  // prefix sizes: counts K or fractions P/Q of N
  std::vector<std::string> labels;
  bool cells = false;
  std::string from;
  bool no_centroids = false;
  bool no_psa_measures = false;
  double time_limit_minutes = 10.0;
  bool bounded = false;
  bool wrap = false;
  std::string axis = "normalised";
  double rdf_range = 0.0;
  int rdf_bins = 0;
  std::string summary;
  int threads = 0;
  int image_size = 800;
  std::string title;
  bool no_discrepancy = false;
  std::vector<double> domain;  // x0 y0 x1 y1, or empty
  std::string psa_points;
};

// One curve of the analysis: a set, a mean over sets, or a prefix.
struct Series {
  std::string label;
  std::string input;
  int level = -1;
  std::size_t rank_prefix = 0;  // by rank: the first rank_prefix points
  double low_frequency = 0.0;   // by rank: LF (tiling_metrics.h; NaN for k <= 4)
  PointSet first;         // drawn in points.png
  std::size_t sets = 1;   // sets in the input (points.png shows the first)
  Summary summary;
};

// The tile boundaries inside the unit square, for points written by `bluetile tile --normalize`.
void tile_grid_lines(const TileGrid& grid, PointsFigure& figure) {
  // More lines than this would grey the picture out; a tiling that fine shows no tiles anyway.
  constexpr double kMaxLines = 256.0;
  if (1.0 / grid.spacing.x > kMaxLines || 1.0 / grid.spacing.y > kMaxLines) return;
  // At most kMaxLines + 1 steps: from an origin far off (1e20, a hand-edited header) k + 1 was k,
  // and the same line was added until memory ran out.
  const auto lines = [&](double origin, double spacing, std::vector<double>& out) {
    const double first = std::ceil(-origin / spacing);
    for (int i = 0; i <= static_cast<int>(kMaxLines) + 1; ++i) {
      const double at = origin + (first + i) * spacing;
      if (at > 1.0) break;
      if (out.empty() || at > out.back()) out.push_back(at);
    }
  };
  lines(grid.origin.x, grid.spacing.x, figure.grid_x);
  lines(grid.origin.y, grid.spacing.y, figure.grid_y);
}

// `bounded`: --bounded was given, which --wrap may not go with; a set declared bounded says so in
// the reader's message (kBoundedNotWrapped) and takes no hint.
std::string append_wrap_hint(const std::string& message, bool bounded) {
  if (message.find("is outside [") == std::string::npos || message.find(kBoundedNotWrapped) != std::string::npos)
    return message;
  if (message.find("is outside [0, 1)") != std::string::npos)
    return message + (bounded ? " (--domain X0 Y0 X1 Y1 rescales points made in another rectangle)"
                              : " (--domain X0 Y0 X1 Y1 rescales points made in another rectangle; --wrap wraps them "
                                "onto the torus)");
  return bounded ? message : message + " (--wrap wraps such points into --domain)";
}

std::vector<PointSet> read_sets(const std::string& path, const ReadOptions& read, bool bounded) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw Error(path + ": is a folder, not a point file");
  std::vector<PointSet> sets;
  try {
    sets = read_points_by_extension(path, read);
  } catch (const Error& e) {
    throw Error(append_wrap_hint(e.what(), bounded));
  }
  if (sets.empty()) throw Error(path + ": no points");
  for (const PointSet& s : sets) {
    if (s.points.size() < 2)
      throw Error(path + ": " + std::to_string(s.points.size()) + (s.points.size() == 1 ? " point" : " points") +
                  "; analysis needs at least 2 points per set");
  }
  return sets;
}

std::vector<std::vector<Point>> points_of(const std::vector<PointSet>& sets) {
  std::vector<std::vector<Point>> result;
  for (const PointSet& s : sets) result.push_back(s.points);
  return result;
}

nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

const char* boundary_name(Boundary b) { return b == Boundary::periodic ? "periodic" : "bounded"; }

// stats.json's value of a record (the library's serializer, summary_record.h): non-finite
// numbers as null.
nlohmann::json to_json(const Record& r) {
  switch (r.kind) {
    case Record::Kind::null: return nullptr;
    case Record::Kind::integer: return r.integer;
    case Record::Kind::real: return number(r.real);
    case Record::Kind::text: return r.text;
    case Record::Kind::reals: {
      nlohmann::json list = nlohmann::json::array();
      for (double v : r.reals) list.push_back(number(v));
      return list;
    }
    case Record::Kind::integers: return r.integers;
    case Record::Kind::object: {
      nlohmann::json object = nlohmann::json::object();
      for (std::size_t i = 0; i < r.keys.size(); ++i) object[r.keys[i]] = to_json(r.values[i]);
      return object;
    }
  }
  return nullptr;
}

nlohmann::json summary_json(const Summary& s) { return to_json(summary_record(s)); }

// radial.csv's and rdf.csv's numbers: 10 significant digits. The anisotropy alone may be
// undefined (annulus 0, which holds the one frequency k = 0, or an annulus of no power;
// radial_power.h): an empty field, as stats.json's null. Every other field must hold a number: a NaN there is refused with the file,
// its row and column, not written as an empty field that reads as "undefined".
std::string csv_field(double v) { return csv_number(v, 10); }
std::string csv_defined(double v, const std::string& file, std::size_t row, const char* column) {
  return csv_defined_number(v, 10, file + ": row " + std::to_string(row) + ", " + column);
}

// The same digits in the report's text, "-" where undefined.
std::string general(double v) { return std::isfinite(v) ? csv_number(v, 10) : "-"; }

std::string radial_csv(const std::vector<Series>& series, bool with_label) {
  std::string text = with_label ? "frequency,power,anisotropy_db,nu,set\n" : "frequency,power,anisotropy_db,nu\n";
  std::size_t row = 0;  // data rows from 1, as a spreadsheet shows them below the header
  for (const Series& s : series) {
    for (const Annulus& a : s.summary.radial) {
      ++row;
      text += csv_defined(a.frequency, "radial.csv", row, "frequency") + "," +
              csv_defined(a.power, "radial.csv", row, "power") + "," + csv_field(a.anisotropy_db) + "," +
              csv_defined(s.summary.nu(a.frequency), "radial.csv", row, "nu");
      text += with_label ? "," + s.label + "\n" : "\n";
    }
  }
  return text;
}

std::string rdf_csv(const std::vector<Series>& series, bool with_label) {
  std::string text = with_label ? "r,r_relative,g,set\n" : "r,r_relative,g\n";
  std::size_t row = 0;
  for (const Series& s : series) {
    const RadialDistribution& rdf = s.summary.rdf;
    for (std::size_t b = 0; b < rdf.g.size(); ++b) {
      ++row;
      text += csv_defined(rdf.radius(b), "rdf.csv", row, "r") + "," +
              csv_defined(rdf.radius(b) / rdf.hexagonal_spacing, "rdf.csv", row, "r_relative") + "," +
              csv_defined(rdf.g[b], "rdf.csv", row, "g");
      text += with_label ? "," + s.label + "\n" : "\n";
    }
  }
  return text;
}

// A measure in the report's tables and lines: "-" where it is undefined, never "nan".
std::string fixed(double v, int decimals) { return measure_text(v, decimals); }

std::string discrepancy_text(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

// The measures researchers quote, name and value, for the report, the summary page and tables.
std::vector<std::pair<std::string, std::string>> measure_rows(const Summary& s) {
  std::vector<std::pair<std::string, std::string>> rows = {
      {"points" + std::string(s.sets > 1 ? " (per set)" : ""), std::to_string(s.count)},
      {"distances", s.boundary == Boundary::periodic ? "periodic (torus)" : "bounded (unit square)"},
      {"rho = min NN distance / d_hex", fixed(s.nn.rho(), 4)},
      {"average min distance / d_hex", fixed(s.nn.rho_mean(), 4)},
      {"max NN distance / d_hex", fixed(s.nn.max / s.nn.hexagonal_spacing, 4)},
  };
  if (s.has_spectral_measures) {
    rows.push_back({"effective Nyquist frequency nu_eff", fixed(s.measures.nu_eff, 3)});
    rows.push_back({"oscillations Omega", fixed(s.measures.omega, 3)});
  }
  if (s.has_bond_order) {
    rows.push_back({"bond order |psi6| (local)", fixed(s.bond_order.local, 3)});
    rows.push_back({"bond order |<psi6>| (global)", fixed(s.bond_order.global, 3)});
  }
  if (s.has_discrepancy) {
    rows.push_back({"centred discrepancy CD^2", discrepancy_text(s.discrepancy.centred)});
    rows.push_back({"wrap-around discrepancy WD^2", discrepancy_text(s.discrepancy.wrap_around)});
    rows.push_back({"mixture discrepancy MD^2", discrepancy_text(s.discrepancy.mixture)});
    rows.push_back({"L2-star discrepancy", discrepancy_text(s.discrepancy.l2_star)});
  }
  if (s.has_centroid_distance)
    rows.push_back({"mean distance to centroid / d_hex", fixed(s.centroid_distance / s.nn.hexagonal_spacing, 4)});
  rows.push_back({"periodogram F", std::to_string(s.periodogram.size)});
  if (s.sets > 1) rows.push_back({"sets averaged", std::to_string(s.sets)});
  return rows;
}

// `default_rdf_range`: no --rdf-range, so the report says when psa's 8 was capped.
void report_series(std::ostringstream& out, const Series& series, bool default_rdf_range) {
  const Summary& s = series.summary;
  const double h = s.nn.hexagonal_spacing;
  out << series.label << ": " << s.count << " points";
  if (s.sets > 1) out << ", mean over " << s.sets << " sets";
  out << (s.boundary == Boundary::bounded ? ", bounded (Euclidean distances in the unit square)" : "") << "\n";
  char row[160];
  auto line = [&](const std::string& name, double scale, int decimals) {
    std::snprintf(row, sizeof row, "    %-36s %10.*f %10.*f %10.*f\n", name.c_str(), decimals, s.nn.min * scale, decimals,
                  s.nn.max * scale, decimals, s.nn.mean * scale);
    out << row;
  };
  std::snprintf(row, sizeof row, "  %-38s %10s %10s %10s\n",
                s.boundary == Boundary::periodic ? "nearest-neighbour distance (torus)" : "nearest-neighbour distance",
                "min", "max", "mean");
  out << row;
  line("raw", 1.0, 6);
  line("x1000 (the paper's table)", 1000.0, 2);
  line("/ hexagonal spacing " + fixed(h, 6), 1.0 / h, 4);
  if (s.sets > 1)
    out << "    per-set minimum ranges " << fixed(1000 * s.nn_min_lowest, 2) << " to "
        << fixed(1000 * s.nn_min_highest, 2) << " (x1000)\n";
  out << "  rho " << fixed(s.nn.rho(), 4) << ", average minimum distance " << fixed(s.nn.rho_mean(), 4)
      << " (in hexagonal spacings)\n";
  if (s.has_spectral_measures)
    out << "  effective Nyquist frequency nu_eff " << fixed(s.measures.nu_eff, 3) << ", oscillations Omega "
        << fixed(s.measures.omega, 3) << " (psa's definitions, from the RDF)\n";
  else if (s.boundary == Boundary::periodic)
    out << "  nu_eff, Omega: skipped (--no-psa-measures)\n";
  else
    out << "  nu_eff, Omega: periodic sets only (psa's definitions measure torus distances)\n";
  if (s.has_bond_order)
    out << "  bond-orientational order: local |psi6| " << fixed(s.bond_order.local, 3) << ", global |<psi6>| "
        << fixed(s.bond_order.global, 3) << " (1 = hexagonal lattice)\n";
  if (s.has_discrepancy)
    out << "  discrepancy (scipy.stats.qmc's): CD " << discrepancy_text(s.discrepancy.centred) << ", WD "
        << discrepancy_text(s.discrepancy.wrap_around) << ", MD " << discrepancy_text(s.discrepancy.mixture)
        << " (squared), L2-star " << discrepancy_text(s.discrepancy.l2_star) << "\n";
  if (s.has_centroid_distance)
    out << "  mean distance to cell centroid: " << general(s.centroid_distance) << " ("
        << fixed(s.centroid_distance / h, 4) << " hexagonal spacings; 0 = centroidal)\n";
  std::size_t peak = 1;
  for (std::size_t i = 1; i < s.radial.size(); ++i)
    if (s.radial[i].power > s.radial[peak].power) peak = i;
  if (peak < s.radial.size())
    out << "  periodogram F = " << s.periodogram.size << ": peak radial power " << fixed(s.radial[peak].power, 3)
        << " at |k| = " << general(s.radial[peak].frequency) << ", nu = " << fixed(s.nu(s.radial[peak].frequency), 3)
        << " (hexagonal lattice: nu = " << fixed(2.0 * std::sqrt(2.0 / std::sqrt(3.0)), 3) << ")\n";
  std::size_t rdf_peak = 0;
  for (std::size_t b = 0; b < s.rdf.g.size(); ++b)
    if (s.rdf.g[b] > s.rdf.g[rdf_peak]) rdf_peak = b;
  if (!s.rdf.g.empty()) {
    const double range = s.rdf.range() / h;
    const bool capped = default_rdf_range && range < kDefaultRdfRange * (1.0 - 1e-9);
    out << "  RDF peak g = " << fixed(s.rdf.g[rdf_peak], 3) << " at r = " << fixed(s.rdf.radius(rdf_peak) / h, 3)
        << " hexagonal spacings (range " << fixed(range, 2)
        << (capped ? ": the default " + number_text(kDefaultRdfRange) + " capped at half the square" : "") << ", "
        << s.rdf.g.size() << " bins)\n";
  }
  if (s.sets > 1)
    out << "  (anisotropy of a mean of " << s.sets << " periodograms: white noise sits at "
        << fixed(-10.0 * std::log10(static_cast<double>(s.sets)), 1) << " dB, not 0)\n";
}

// One row per series: the measures side by side (compare and by-level modes).
void report_table(std::ostringstream& out, const std::vector<Series>& series) {
  std::size_t width = 8;
  for (const Series& s : series) width = std::max(width, s.label.size());
  char row[256];
  std::snprintf(row, sizeof row, "%-*s %8s %8s %8s %8s %8s %8s\n", static_cast<int>(width), "", "N", "rho", "avg min",
                "nu_eff", "Omega", "psi6");
  out << row;
  for (const Series& s : series) {
    const Summary& m = s.summary;
    const std::string nu_eff = m.has_spectral_measures ? fixed(m.measures.nu_eff, 3) : "-";
    const std::string omega = m.has_spectral_measures ? fixed(m.measures.omega, 3) : "-";
    std::snprintf(row, sizeof row, "%-*s %8zu %8s %8s %8s %8s %8s\n", static_cast<int>(width), s.label.c_str(),
                  m.count, fixed(m.nn.rho(), 4).c_str(), fixed(m.nn.rho_mean(), 4).c_str(), nu_eff.c_str(), omega.c_str(),
                  m.has_bond_order ? fixed(m.bond_order.local, 3).c_str() : "-");
    out << row;
  }
  out << "\n";
}

// The table `psa --stats` prints (without CGAL), so figures paste beside psa's: its header, then
// per series the label and global and average minimum distance in hexagonal spacings, nu_eff
// and Omega, tab-separated with 3 decimals ("-" where a measure does not apply); psa's rows
// also carry two spaces before the first tab (its setw(3) pads the tab).
void report_psa_table(std::ostringstream& out, const std::vector<Series>& series) {
  char row[256];
  std::snprintf(row, sizeof row, "%-16s\tG-MD\tA-MD\tE-Nyq.\tOsci.\n", "File");
  out << row;
  for (const Series& s : series) {
    const Summary& m = s.summary;
    const bool spectral = m.has_spectral_measures;
    std::snprintf(row, sizeof row, "%-16s  \t%s\t%s\t%s\t%s\n", s.label.c_str(), fixed(m.nn.rho(), 3).c_str(),
                  fixed(m.nn.rho_mean(), 3).c_str(),
                  spectral ? fixed(m.measures.nu_eff, 3).c_str() : "-", spectral ? fixed(m.measures.omega, 3).c_str() : "-");
    out << row;
  }
  out << "\n";
}

// Each set of a series averaging several, one row per set, with report_table's columns.
void report_set_table(std::ostringstream& out, const Series& series) {
  const Summary& m = series.summary;
  if (m.per_set.empty()) return;
  out << series.label << ", per set:\n";
  const std::size_t width = std::max<std::size_t>(8, std::to_string(m.per_set.size() - 1).size() + 4);
  auto left = [&](const std::string& v) { return v + std::string(v.size() < width ? width - v.size() : 0, ' '); };
  auto right = [](const std::string& v) { return " " + std::string(v.size() < 8 ? 8 - v.size() : 0, ' ') + v; };
  auto value = [](double v, int decimals) { return std::isfinite(v) ? fixed(v, decimals) : std::string("-"); };
  out << "  " << left("set");
  for (const char* name : {"N", "rho", "avg min", "nu_eff", "Omega", "psi6"}) out << right(name);
  out << "\n";
  for (std::size_t k = 0; k < m.per_set.size(); ++k) {
    const SetMeasures& s = m.per_set[k];
    out << "  " << left(std::to_string(k)) << right(std::to_string(m.count)) << right(value(s.rho, 4))
        << right(value(s.average_min_distance, 4)) << right(value(s.nu_eff, 3)) << right(value(s.omega, 3))
        << right(value(s.bond_order, 3)) << "\n";
  }
  out << "\n";
}

// psa's plain text point file: the count, then one "x y" line per point (17 digits: exact).
std::string psa_text(const PointSet& set) {
  std::string text = std::to_string(set.points.size()) + "\n";
  char line[64];
  for (const Point& p : set.points) {
    std::snprintf(line, sizeof line, "%.17g %.17g\n", p.x, p.y);
    text += line;
  }
  return text;
}

// --domain X0 Y0 X1 Y1, checked: four finite numbers, X1 > X0 and Y1 > Y0.
std::optional<CoordinateBox> domain_option(const std::vector<double>& v) {
  if (v.empty()) return std::nullopt;
  auto text = [](double d) {
    char t[32];
    std::snprintf(t, sizeof t, "%.17g", d);
    return std::string(t);
  };
  if (v.size() != 4) throw Error("--domain needs four numbers X0 Y0 X1 Y1, got " + std::to_string(v.size()));
  for (double d : v)
    if (!std::isfinite(d)) throw Error("--domain: " + text(d) + " is not a finite number");
  if (!(v[2] > v[0])) throw Error("--domain: X1 = " + text(v[2]) + " must be greater than X0 = " + text(v[0]));
  if (!(v[3] > v[1])) throw Error("--domain: Y1 = " + text(v[3]) + " must be greater than Y0 = " + text(v[1]));
  if (!(v[2] - v[0] < std::numeric_limits<double>::infinity()) || !(v[3] - v[1] < std::numeric_limits<double>::infinity()))
    throw Error("--domain: the rectangle's sides overflow");
  return CoordinateBox{v[0], v[1], v[2], v[3]};
}

// The compare summary: every series' points, periodogram and row of the stdout table (not the
// last series alone).
void add_compare_series(SummaryPage& page, const std::vector<Series>& series, const std::vector<PointsFigure>& figures) {
  page.table_header = {"", "N", "rho", "avg min", "nu_eff", "Omega", "psi6"};
  for (std::size_t i = 0; i < series.size(); ++i) {
    const Summary& m = series[i].summary;
    SummaryPage::Series s;
    s.label = series[i].label;
    s.points = figures[i];
    s.periodogram = m.periodogram;
    s.row = {std::to_string(m.count), fixed(m.nn.rho(), 4), fixed(m.nn.rho_mean(), 4),
             m.has_spectral_measures ? fixed(m.measures.nu_eff, 3) : "-",
             m.has_spectral_measures ? fixed(m.measures.omega, 3) : "-",
             m.has_bond_order ? fixed(m.bond_order.local, 3) : "-"};
    page.series.push_back(std::move(s));
  }
}

// Boundary of the analysis: --bounded, or what the files declare ("# domain ..."), else periodic.
Boundary choose_boundary(const AnalyzeOptions& o, const std::vector<std::vector<PointSet>>& inputs) {
  std::optional<Boundary> declared;
  std::string declared_by;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    for (const PointSet& s : inputs[i]) {
      if (!s.declared_boundary) continue;
      if (declared && *declared != *s.declared_boundary)
        throw Error(o.inputs[i] + ": declares '# domain " + boundary_name(*s.declared_boundary) + "' but " + declared_by +
                    " declares '# domain " + boundary_name(*declared) + "': analyse them apart");
      declared = s.declared_boundary;
      declared_by = o.inputs[i];
    }
  }
  if (o.bounded && declared == Boundary::periodic)
    throw Error("--bounded, but " + declared_by + " declares '# domain periodic'");
  if (o.bounded) return Boundary::bounded;
  return declared.value_or(Boundary::periodic);
}

// Bytes per annulus of one series: its radial curve, the stats.json tree holding it, the CSV row
// and the plots' paths. Measured (peak RSS of 300 points at --bin-width 1e-3 and 1e-4, less that
// at 1, over the annuli: about 250) and rounded up.
constexpr double kAnalyzeBytesPerAnnulus = 400.0;

// Refuses, before the analysis, a --bin-width that makes more annuli than the limit or than the
// memory holds (every series has floor((F / 2) / w) of them, F the largest set's periodogram).
void check_annuli(const AnalyzeOptions& o, const std::vector<std::vector<PointSet>>& inputs, std::size_t rank_series) {
  std::size_t largest = 0;
  for (const auto& sets : inputs)
    for (const PointSet& s : sets) largest = std::max(largest, s.points.size());
  const int size = o.size > 0 ? o.size : default_periodogram_size(largest);
  const double annuli = annulus_count(size, o.bin_width);
  char width[32];
  std::snprintf(width, sizeof width, "%g", o.bin_width);
  if (annuli < 1.0)
    throw Error("--bin-width " + std::string(width) + " is wider than half the periodogram size F / 2 = " +
                std::to_string(size / 2) + ": no annulus fits");
  if (annuli > kMaxAnnuli) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "--bin-width %s is too narrow: %.3g annuli (F / 2 = %d over the width), more than the limit of %.0e",
                  width, annuli, size / 2, kMaxAnnuli);
    throw Error(text);
  }
  double series = 1.0;
  if (o.compare) series = static_cast<double>(inputs.size());
  if (o.by_level) series = static_cast<double>(std::set<int>(inputs[0][0].levels.begin(), inputs[0][0].levels.end()).size());
  if (rank_series > 0) series = static_cast<double>(rank_series);
  char what[160];
  std::snprintf(what, sizeof what, "--bin-width %s (%.0f annuli%s)", width, annuli,
                series > 1.0 ? (" in each of " + std::to_string(static_cast<long long>(series)) + " series").c_str() : "");
  check_memory(annuli * series * kAnalyzeBytesPerAnnulus, what);
}

// The output folder is created when missing, but not its parents: a typo must not make a tree.
void check_output_parent(const std::string& output) {
  std::filesystem::path folder = std::filesystem::path(output).lexically_normal();
  if (!folder.has_filename()) folder = folder.parent_path();  // "a/b/"
  const std::filesystem::path parent = folder.parent_path();
  std::error_code ec;
  if (parent.empty() || std::filesystem::exists(parent, ec)) return;
  throw Error(output + ": the folder '" + parent.string() + "' does not exist (analyze creates only the last folder of -o)");
}

// --psa-points: every set analysed (after --domain and --wrap) as psa's text, in input order; a
// name with "{}" gives one file per set (psa reads one set a file).
std::vector<std::pair<OutputFile*, const PointSet*>> declare_psa_points(const AnalyzeOptions& o,
                                                                        const std::vector<std::vector<PointSet>>& inputs,
                                                                        OutputSet& outputs) {
  std::vector<std::pair<OutputFile*, const PointSet*>> files;
  if (o.psa_points.empty()) return files;
  check_text_output_name("--psa-points", o.psa_points, "psa's point text");
  std::vector<const PointSet*> sets;
  for (const auto& file : inputs)
    for (const PointSet& set : file) sets.push_back(&set);
  if (o.psa_points.find("{}") == std::string::npos) {
    if (sets.size() > 1)
      throw Error("--psa-points '" + o.psa_points + "': the inputs hold " + std::to_string(sets.size()) +
                  " sets and psa reads one set a file: put {} in the name for one file per set");
    files.push_back({&outputs.add(o.psa_points, {.allow_stdout = true}), sets[0]});
    return files;
  }
  for (std::size_t k = 0; k < sets.size(); ++k)
    files.push_back({&outputs.add(set_file_name(o.psa_points, k, sets.size())), sets[k]});
  return files;
}

// --by-rank K...: each value a count (2 to N) or a fraction P/Q of the N points (rounded to the
// nearest count); sorted. Throws Error naming the value otherwise, and naming both values when two
// give the same prefix (merged without a word before: 1/3 1/3, or 1/3 and 33 of 100 points).
std::vector<std::size_t> rank_prefixes(const std::vector<std::string>& values, std::size_t n, const std::string& input) {
  std::vector<std::size_t> counts;
  std::map<std::size_t, std::string> given;  // each prefix and the value that gave it
  const WholeNumber one = whole(1), most = whole(kMaxCount);
  for (const std::string& text : values) {
    WholeNumber value;
    std::size_t count = 0;
    if (const std::size_t slash = text.find('/'); slash != std::string::npos) {
      WholeNumber below;
      std::string why = check_integer(std::string_view(text).substr(0, slash), one, most, value);
      if (why.empty()) why = check_integer(std::string_view(text).substr(slash + 1), one, most, below);
      if (!why.empty()) throw Error("--by-rank " + text + ": not a fraction P/Q of two integers from 1 to " + std::to_string(kMaxCount));
      if (value.magnitude > below.magnitude) throw Error("--by-rank " + text + ": a fraction of the points must be at most 1");
      count = static_cast<std::size_t>((n * value.magnitude + below.magnitude / 2) / below.magnitude);
    } else {
      if (!check_integer(text, one, most, value).empty())
        throw Error("--by-rank " + text + ": not a count or a fraction P/Q of the points");
      count = static_cast<std::size_t>(value.magnitude);
    }
    if (count > n)
      throw Error("--by-rank " + text + ": " + input + " holds " + std::to_string(n) + " points, fewer than " + std::to_string(count));
    if (count < 2)
      throw Error("--by-rank " + text + ": the first " + std::to_string(count) + " of " + std::to_string(n) +
                  " points; a prefix needs at least 2 to analyse" + (count == 1 && text == "1" ? " (the whole set is 1/1)" : ""));
    if (const auto [at, fresh] = given.emplace(count, text); !fresh)
      throw Error("--by-rank " + at->second + " and " + text + ": both give the first " + std::to_string(count) + " of " +
                  std::to_string(n) + " points; give each prefix once");
    counts.push_back(count);
  }
  std::sort(counts.begin(), counts.end());
  return counts;
}

// LF of a prefix (the mean over sets for several), from its summary's mean periodogram when that
// holds every frequency LF uses (LF is linear in the periodogram).
double prefix_low_frequency(const std::vector<std::vector<Point>>& prefixes, const Summary& summary) {
  const std::size_t k = prefixes[0].size();
  if (summary.periodogram.size >= tiling_metrics_periodogram_size(k))
    return measure_tiling(prefixes[0], summary.periodogram, 0, 0).low_frequency;
  double sum = 0.0;
  for (const std::vector<Point>& p : prefixes) sum += measure_tiling(p, 0, 0).low_frequency;
  return sum / static_cast<double>(prefixes.size());
}

// The prefix series of --by-rank: the first K points of every set, for each K (several sets: the
// mean over them, as --average takes it).
std::vector<Series> rank_series(const std::vector<PointSet>& sets, const std::vector<std::size_t>& prefixes,
                                const std::string& input, const SummaryOptions& options) {
  std::vector<Series> series;
  for (std::size_t k : prefixes) {
    std::vector<std::vector<Point>> prefix;
    for (const PointSet& set : sets)
      prefix.emplace_back(set.points.begin(), set.points.begin() + static_cast<std::ptrdiff_t>(k));
    Series s{"first " + std::to_string(k), input, -1, k, 0.0, sets[0], sets.size(), summarize(prefix, options)};
    s.low_frequency = prefix_low_frequency(prefix, s.summary);
    s.first.points.resize(k);
    if (s.first.has_levels()) s.first.levels.resize(k);
    series.push_back(std::move(s));
  }
  return series;
}

// The by-rank table: report_table's columns with the prefix's share of N and LF.
void report_rank_table(std::ostringstream& out, const std::vector<Series>& series, std::size_t n) {
  char row[256];
  std::snprintf(row, sizeof row, "%-12s %8s %8s %8s %8s %8s %8s %8s\n", "prefix", "k / N", "rho", "LF", "avg min",
                "nu_eff", "Omega", "psi6");
  out << row;
  for (const Series& s : series) {
    const Summary& m = s.summary;
    const std::string nu_eff = m.has_spectral_measures ? fixed(m.measures.nu_eff, 3) : "-";
    const std::string omega = m.has_spectral_measures ? fixed(m.measures.omega, 3) : "-";
    std::snprintf(row, sizeof row, "%-12s %8.4f %8s %8s %8s %8s %8s %8s\n", s.label.c_str(),
                  static_cast<double>(s.rank_prefix) / static_cast<double>(n), fixed(m.nn.rho(), 4).c_str(),
                  fixed(s.low_frequency, 4).c_str(), fixed(m.nn.rho_mean(), 4).c_str(), nu_eff.c_str(), omega.c_str(),
                  m.has_bond_order ? fixed(m.bond_order.local, 3).c_str() : "-");
    out << row;
  }
  out << "LF: mean periodogram over integer frequencies f with 0 < |f|^2 < k / 4 (white noise 1)\n";
  if (std::any_of(series.begin(), series.end(), [](const Series& s) { return std::isnan(s.low_frequency); }))
    out << "LF \"-\": k <= 4, whose band holds no frequency (null in stats.json)\n";
  out << "\n";
}

// run_analyze's steps, in its order: check the options, declare the outputs, read the inputs,
// compute the series of the chosen mode, draw, then write. Every check comes before any work.

// The option checks that need no file, in the order they are reported.
void check_options(const AnalyzeOptions& o) {
  const bool by_rank = !o.by_rank.empty();
  if ((o.average ? 1 : 0) + (o.compare ? 1 : 0) + (o.by_level ? 1 : 0) + (by_rank ? 1 : 0) > 1)
    throw Error("choose one of --average, --compare, --by-level and --by-rank");
  if (o.size != 0 && (o.size < 2 || o.size % 2 != 0))
    throw Error("--size " + std::to_string(o.size) + ": expected 0 (from N) or an even number from 2 to 65536");
  if (!(o.bin_width > 0.0) || !std::isfinite(o.bin_width))
    throw Error("--bin-width " + number_text(o.bin_width) + ": expected a positive number");
  if (!o.labels.empty() && o.labels.size() != o.inputs.size())
    throw Error("--label needs one label per input (" + std::to_string(o.inputs.size()) + ")");
}

// What --summary writes.
constexpr OutputFormat kSummaryFormats[] = {OutputFormat::pdf, OutputFormat::svg};

// --summary's format: "pdf", "svg", or "" without --summary.
std::string summary_format(const AnalyzeOptions& o) {
  std::string format;
  if (!o.summary.empty()) {
    format = output_format("--summary", o.summary, kSummaryFormats) == OutputFormat::pdf ? "pdf" : "svg";
    if (format == "pdf" && !pdf_unavailable_reason().empty())
      throw Error(o.summary + ": " + pdf_unavailable_reason());
  }
  return format;
}

// Every output of the folder, and --summary's file (null without it).
struct AnalyzeFiles {
  OutputSet outputs;
  OutputFile* stats = nullptr;
  OutputFile* radial = nullptr;
  OutputFile* rdf = nullptr;
  OutputFile* points_png = nullptr;
  OutputFile* spectrum_png = nullptr;
  OutputFile* radial_png = nullptr;
  OutputFile* rdf_png = nullptr;
  OutputFile* points_svg = nullptr;
  OutputFile* spectrum_svg = nullptr;
  OutputFile* radial_svg = nullptr;
  OutputFile* rdf_svg = nullptr;
  OutputFile* report = nullptr;
  OutputFile* summary = nullptr;
};

// Every output is declared, and so checked, before any work; they appear together at the end.
void declare_outputs(const AnalyzeOptions& o, const CLI::App& command, AnalyzeFiles& files) {
  OutputSet& outputs = files.outputs;
  add_declared_inputs(outputs, command);
  check_output_parent(o.output);
  outputs.add_folder(o.output);
  const std::filesystem::path dir(o.output);
  auto output = [&](const std::string& name) { return &outputs.add((dir / name).string()); };
  files.stats = output("stats.json");
  files.radial = output("radial.csv");
  files.rdf = output("rdf.csv");
  files.points_png = output("points.png");
  files.spectrum_png = output("spectrum.png");
  files.radial_png = output("radial.png");
  files.rdf_png = output("rdf.png");
  files.points_svg = output("points.svg");
  files.spectrum_svg = output("spectrum.svg");
  files.radial_svg = output("radial.svg");
  files.rdf_svg = output("rdf.svg");
  files.report = output("report.txt");
  files.summary = o.summary.empty() ? nullptr : &outputs.add(o.summary);
}

struct AnalyzeInputs {
  std::vector<std::vector<PointSet>> sets;  // per input file
  std::size_t total_sets = 0;
  std::vector<std::size_t> prefixes;  // --by-rank's counts, sorted
  Boundary boundary = Boundary::periodic;
  std::vector<Point> from;  // --from: where each point started
};

// Reads and checks every input before anything is computed.
AnalyzeInputs read_inputs(const AnalyzeOptions& o) {
  const bool by_rank = !o.by_rank.empty();
  AnalyzeInputs in;
  std::vector<std::vector<PointSet>>& inputs = in.sets;
  ReadOptions read;
  read.wrap = o.wrap;
  read.domain = domain_option(o.domain);
  // The torus's wrap and the square's edges do not go together.
  if (o.wrap && o.bounded)
    throw Error("--wrap wraps points onto the torus, and --bounded measures them in the square: give one");
  for (const std::string& path : o.inputs) inputs.push_back(read_sets(path, read, o.bounded));
  for (const auto& sets : inputs) in.total_sets += sets.size();
  const std::string files = std::to_string(o.inputs.size()) + (o.inputs.size() == 1 ? " file" : " files");
  // --by-level takes one set; of the modes that take several, --by-rank is the one that measures
  // prefixes (bluetile progressive writes its rows level by level, so level boundaries are counts).
  if (o.by_level && in.total_sets > 1)
    throw Error("--by-level analyses one set, but " + std::to_string(in.total_sets) + " point sets are given (" + files +
                "): --by-rank K... averages the first K rows over the sets (rows in level order, as bluetile "
                "progressive writes them: K at the level boundaries gives the level prefixes), --average the whole sets");
  if (!o.average && !o.compare && !by_rank && in.total_sets > 1)
    throw Error(std::to_string(in.total_sets) + " point sets given (" + files +
                "): use --average to analyse their mean (with a table of each set), --compare to plot them together "
                "or --by-rank to average their prefixes");
  if (o.by_level && !inputs[0][0].has_levels())
    throw Error(o.inputs[0] + ": --by-level needs a level column (x y level)");
  if (by_rank) in.prefixes = rank_prefixes(o.by_rank, inputs[0][0].points.size(), o.inputs[0]);
  if (by_rank) {
    // The prefixes of several sets are averaged: every set must have the first one's size.
    for (std::size_t i = 0; i < inputs.size(); ++i)
      for (std::size_t k = 0; k < inputs[i].size(); ++k)
        if (inputs[i][k].points.size() != inputs[0][0].points.size())
          throw Error(o.inputs[i] + ": set " + std::to_string(k) + " has " + std::to_string(inputs[i][k].points.size()) +
                      " points and the first " + std::to_string(inputs[0][0].points.size()) +
                      "; --by-rank averages the prefixes of sets of one size");
  }
  in.boundary = choose_boundary(o, inputs);
  if (o.cells && in.boundary == Boundary::bounded)
    throw Error("--cells draws periodic Voronoi cells: not for a bounded set");
  if (!o.from.empty()) {
    try {
      // A table or CSV by its extension, as --input (an .npy was "binary data (NUL byte)"); text as
      // one set, its '#' lines comments.
      const std::string extension = o.from == "-" ? "" : file_extension(o.from);
      if (extension == ".npy" || extension == ".bpt" || extension == ".csv" || extension == ".rps") {
        std::vector<PointSet> sets = read_points_by_extension(o.from, read);
        if (sets.size() != 1)
          throw Error(o.from + ": holds " + std::to_string(sets.size()) + " sets; --from needs one");
        in.from = std::move(sets[0].points);
      } else {
        in.from = read_point_file(o.from, read).points;
      }
    } catch (const Error& e) {
      throw Error(append_wrap_hint(e.what(), o.bounded));
    }
    if (in.from.size() != inputs[0][0].points.size())
      throw Error(o.from + ": --from has " + std::to_string(in.from.size()) + " points but the input has " +
                  std::to_string(inputs[0][0].points.size()));
  }
  return in;
}

// The estimate, before any work: a set too large for psa's O(N^2) measures or for the memory
// is refused with what it would take.
void check_budget(const AnalyzeOptions& o, const AnalyzeInputs& in) {
  const std::vector<std::vector<PointSet>>& inputs = in.sets;
  std::vector<AnalysisJob> jobs;
  if (o.compare) {
    for (const auto& sets : inputs) jobs.push_back({sets[0].points.size(), sets.size(), o.size});
  } else if (o.by_level) {
    std::vector<int> levels = inputs[0][0].levels;
    std::sort(levels.begin(), levels.end());
    for (std::size_t i = 0; i < levels.size(); ++i)
      if (i + 1 == levels.size() || levels[i + 1] != levels[i]) jobs.push_back({i + 1, 1, o.size});
  } else if (!o.by_rank.empty()) {
    for (std::size_t k : in.prefixes) jobs.push_back({k, in.total_sets, o.size});
  } else {
    jobs.push_back({inputs[0][0].points.size(), in.total_sets, o.size});
  }
  // An RDF range asked for beyond half the square is refused here, for the smallest set analysed,
  // rather than by the analysis after the other measures (radial_distribution refuses it too).
  if (o.rdf_range > 0.0) {
    std::size_t fewest = jobs.front().count;
    for (const AnalysisJob& job : jobs) fewest = std::min(fewest, job.count);
    const double limit = 0.5 / hexagonal_spacing(static_cast<double>(fewest));
    if (o.rdf_range > limit * (1.0 + 1e-12))
      throw Error("--rdf-range " + number_text(o.rdf_range) + ": at most " + fixed_text(limit, 2) +
                  " hexagonal spacings for " + std::to_string(fewest) +
                  " points (half the square; beyond it a torus annulus overlaps itself)");
  }
  if (in.boundary == Boundary::periodic) check_analysis_budget(jobs, !o.no_psa_measures, o.time_limit_minutes, !o.no_discrepancy);
  else check_analysis_budget(jobs, false, o.time_limit_minutes, !o.no_discrepancy);
}

// Input i's label: its --label, else its file name without the extension.
std::string input_label(const AnalyzeOptions& o, std::size_t i) {
  return o.labels.empty() ? std::filesystem::path(o.inputs[i]).stem().string() : o.labels[i];
}

SummaryOptions summary_options(const AnalyzeOptions& o, Boundary boundary) {
  SummaryOptions options;
  options.size = o.size;
  options.bin_width = o.bin_width;
  options.centroids = !o.no_centroids;
  options.spectral_measures = !o.no_psa_measures;
  options.discrepancy = !o.no_discrepancy;
  options.boundary = boundary;
  options.rdf.range = o.rdf_range;
  options.rdf.bins = static_cast<std::size_t>(o.rdf_bins);
  return options;
}

// The series of the chosen mode, each summarised: one per input (--compare), per level prefix
// (--by-level), per rank prefix (--by-rank), or one for the set or the mean of the sets. `bar`
// is the terminal's progress bar, closed after each summary.
std::vector<Series> compute_series(const AnalyzeOptions& o, const AnalyzeInputs& in, const SummaryOptions& options,
                                   std::unique_ptr<Progress>& bar) {
  const std::vector<std::vector<PointSet>>& inputs = in.sets;
  std::vector<Series> series;
  if (o.compare) {
    for (std::size_t i = 0; i < inputs.size(); ++i) {
      auto sets = points_of(inputs[i]);
      series.push_back({input_label(o, i), o.inputs[i], -1, 0, 0.0, inputs[i][0], inputs[i].size(), summarize(sets, options)});
      bar.reset();
    }
  } else if (o.by_level) {
    const PointSet& set = inputs[0][0];
    std::vector<LevelSummary> levels = summarize_levels(set.points, set.levels, options);
    for (LevelSummary& l : levels) {
      std::string label = l.level == 0 ? "level 0" : "levels 0-" + std::to_string(l.level);
      series.push_back({label, o.inputs[0], l.level, 0, 0.0, set, 1, std::move(l.summary)});
    }
    bar.reset();
  } else if (!o.by_rank.empty()) {
    std::vector<PointSet> sets;
    for (const auto& file : inputs) sets.insert(sets.end(), file.begin(), file.end());
    series = rank_series(sets, in.prefixes, o.inputs[0], options);
    bar.reset();
  } else {
    std::vector<std::vector<Point>> sets;
    for (const auto& file : inputs)
      for (const PointSet& s : file) sets.push_back(s.points);
    std::string label = inputs.size() == 1 ? input_label(o, 0) : "mean of " + std::to_string(sets.size()) + " sets";
    if (!o.labels.empty() && o.labels.size() == 1) label = o.labels[0];
    series.push_back({label, o.inputs[0], -1, 0, 0.0, inputs[0][0], sets.size(), summarize(sets, options)});
    bar.reset();
  }
  return series;
}

// Every image and the summary page, rendered before anything is written.
struct AnalyzeDrawings {
  Canvas points_png, spectrum_png, radial_png, rdf_png;
  SvgDocument points_svg, spectrum_svg, radial_svg, rdf_svg;
  std::optional<SvgDocument> summary;
};

AnalyzeDrawings draw_series(const AnalyzeOptions& o, const std::vector<Series>& series, const AnalyzeInputs& in,
                            FrequencyAxis axis) {
  const bool by_rank = !o.by_rank.empty();
  const Boundary boundary = in.boundary;
  const std::vector<Point>& from = in.from;
  const bool several = series.size() > 1;
  std::vector<Canvas> point_images, spectrum_images;
  std::vector<SvgDocument> point_svgs, spectrum_svgs;
  std::vector<std::string> captions;
  std::vector<PointsFigure> figures;
  for (const Series& s : series) {
    PointsFigure figure;
    figure.periodic = boundary == Boundary::periodic;
    if (o.by_level) {
      for (std::size_t i = 0; i < s.first.points.size(); ++i) {
        if (s.first.levels[i] > s.level) continue;
        figure.points.push_back(s.first.points[i]);
        figure.levels.push_back(s.first.levels[i]);
      }
    } else {
      figure.points = s.first.points;
      if (s.first.has_levels()) figure.levels = s.first.levels;
      figure.from = from;
      if (by_rank && !from.empty()) figure.from.resize(s.rank_prefix);
    }
    if (s.sets > 1) figure.note = "set 1 of " + std::to_string(s.sets) + " (the analysis covers all " + std::to_string(s.sets) + ")";
    figure.cells = o.cells;
    if (std::optional<TileGrid> grid = declared_tile_grid(s.first)) tile_grid_lines(*grid, figure);
    const int size = several ? o.image_size * 2 / 3 : o.image_size;
    point_images.push_back(draw_points(figure, size));
    point_svgs.push_back(points_svg(figure, size));
    spectrum_images.push_back(draw_spectrum(s.summary.periodogram, several ? 512 : 1024, several ? 384 : 512));
    spectrum_svgs.push_back(spectrum_svg(s.summary.periodogram, several ? 512 : 1024, several ? 384 : 512));
    // By-level prefixes each have their own frequency range: say which.
    captions.push_back(o.by_level || by_rank ? s.label + ", F = " + std::to_string(s.summary.periodogram.size) : s.label);
    figures.push_back(std::move(figure));
  }
  Canvas points_png = several ? montage(point_images, captions) : point_images[0];
  Canvas spectrum_png = several ? montage(spectrum_images, captions) : spectrum_images[0];
  SvgDocument points_doc = several ? montage_svg(point_svgs, captions) : point_svgs[0];
  SvgDocument spectrum_doc = several ? montage_svg(spectrum_svgs, captions) : spectrum_svgs[0];
  std::vector<RadialCurve> curves;
  std::vector<RdfCurve> rdf_curves;
  for (const Series& s : series) {
    curves.push_back({s.label, s.summary.radial, s.summary.count});
    rdf_curves.push_back({s.label, s.summary.rdf});
  }
  std::string title = !several ? series[0].label + ": " + std::to_string(series[0].summary.count) + " points"
                               : (o.by_level ? "prefixes of " + input_label(o, 0)
                                  : by_rank  ? "rank prefixes of " + input_label(o, 0)
                                             : "comparison");
  if (!o.title.empty())
    title = o.title;
  else if (!several && series[0].summary.sets > 1)
    title = "mean over " + std::to_string(series[0].summary.sets) + " sets of " +
            std::to_string(series[0].summary.count) + " points";
  // White noise averaged over M sets: anisotropy about -10 log10(M) dB (Lagae & Dutré 2008).
  double reference = 0.0;
  if (std::all_of(series.begin(), series.end(), [&](const Series& s) { return s.summary.sets == series[0].summary.sets; }))
    reference = -10.0 * std::log10(static_cast<double>(series[0].summary.sets));
  const Plot radial = radial_plot(curves, title, reference, axis);
  const Plot rdf = rdf_plot(rdf_curves, title);
  Canvas radial_png = render_plot(radial, 900, 760);
  Canvas rdf_png = render_plot(rdf, 900, 480);
  SvgDocument radial_svg = render_plot_svg(radial, 900, 760);
  SvgDocument rdf_svg = render_plot_svg(rdf, 900, 480);

  std::optional<SvgDocument> summary_doc;
  if (!o.summary.empty()) {
    const Series& s = series.back();  // by level: the whole set
    SummaryPage page;
    page.title = o.title.empty() ? (several && !o.by_level && !by_rank ? "comparison" : title) : o.title;
    page.subtitle = "bluetile analyze";
    for (const std::string& input : o.inputs) page.subtitle += " " + input;
    page.points = figures.back();
    if (page.points.note.empty()) page.points.note = s.label;
    page.periodogram = s.summary.periodogram;
    page.radial = curves;
    page.rdf = rdf_curves;
    page.axis = axis;
    page.anisotropy_reference = reference;
    page.measures = measure_rows(s.summary);
    if (o.compare) add_compare_series(page, series, figures);
    summary_doc = summary_page(page);
  }
  return {std::move(points_png),     std::move(spectrum_png), std::move(radial_png), std::move(rdf_png),
          std::move(points_doc),     std::move(spectrum_doc), std::move(radial_svg), std::move(rdf_svg),
          std::move(summary_doc)};
}

nlohmann::json stats_json(const AnalyzeOptions& o, const std::vector<Series>& series, Boundary boundary,
                          FrequencyAxis axis) {
  const bool by_rank = !o.by_rank.empty();
  nlohmann::json stats;
  stats["mode"] = o.compare ? "compare" : o.by_level ? "by-level" : by_rank ? "by-rank" : o.average ? "average" : "single";
  if (!o.compare) {
    // One set, a mean, or the whole leveled set (its last prefix); compare mode has no single
    // set to describe, so its figures are only under "compare", each with its label.
    stats.update(summary_json(series.back().summary));
    stats["label"] = series.back().label;
  }
  stats["boundary"] = boundary_name(boundary);
  stats["inputs"] = o.inputs;
  stats["bin_width"] = o.bin_width;
  stats["frequency_axis"] = axis == FrequencyAxis::normalised ? "nu = |k| / (sqrt(N) / 2)" : "|k|";
  if (o.compare || o.by_level) {
    nlohmann::json list = nlohmann::json::array();
    for (const Series& s : series) {
      nlohmann::json j = summary_json(s.summary);
      j["label"] = s.label;
      if (o.by_level) j["level"] = s.level;
      else j["input"] = s.input;
      list.push_back(std::move(j));
    }
    stats[o.compare ? "compare" : "levels"] = std::move(list);
  }
  if (by_rank) {
    nlohmann::json list = nlohmann::json::array();
    for (const Series& s : series) {
      nlohmann::json j = summary_json(s.summary);
      j["label"] = s.label;
      j["rank_prefix"] = s.rank_prefix;
      j["low_frequency"] = number(s.low_frequency);
      list.push_back(std::move(j));
    }
    stats["ranks"] = std::move(list);
  }
  const std::vector<std::string> images = {"points.png", "points.svg", "spectrum.png", "spectrum.svg",
                                           "radial.png", "radial.svg", "rdf.png",      "rdf.svg"};
  stats["images"] = images;
  return stats;
}

// report.txt, which the tool prints too. `n`: the points of the first set (--by-rank's N).
std::string report_text(const AnalyzeOptions& o, const std::vector<Series>& series, std::size_t n) {
  const bool by_rank = !o.by_rank.empty();
  const bool several = series.size() > 1;
  std::ostringstream report;
  report << "bluetile analyze";
  for (const std::string& in : o.inputs) report << " " << in;
  report << "\n\n";
  if (by_rank) report_rank_table(report, series, n);
  else if (several) report_table(report, series);
  for (const Series& s : series) {
    report_series(report, s, o.rdf_range == 0.0);
    report << "\n";
    if (!by_rank) report_set_table(report, s);  // by rank: one table per prefix would repeat every set
  }
  if (series.back().summary.count == 1000) {
    report << "The paper (section 2, N = 1000, x1000): dart throwing min 21.64 max 33.44, Lloyd 80 iterations\n"
              "min 24.86 max 32.33. Compare minima and the ordering; its max column does not reproduce\n"
              "(docs/DESIGN.md, section 5: we get about 36).\n\n";
  }
  report << "As psa --stats prints them:\n";
  report_psa_table(report, series);
  if (!o.by_level && !by_rank && series[0].sets > 1 && !o.compare)
    report << "points.png and points.svg show the first of the " << series[0].sets << " sets.\n";
  report << "written: stats.json radial.csv rdf.csv report.txt points spectrum radial rdf (.png .svg)";
  if (!o.summary.empty()) report << ", " << o.summary;
  if (!o.psa_points.empty()) report << ", " << o.psa_points << " (psa's text)";
  report << "\n";
  return report.str();
}

void run_analyze(const AnalyzeOptions& o, const CLI::App& command) {
  if (o.threads > 0) set_thread_count(static_cast<std::size_t>(o.threads));
  check_options(o);
  // Its PNGs are drawn at the end: the image plugin is loaded now, so that a limit that leaves it
  // too little memory is said before the analysis, not after it (README, "What a failed or
  // interrupted run leaves behind").
  load_image_plugin();
  const FrequencyAxis axis = o.axis == "integer" ? FrequencyAxis::integer : FrequencyAxis::normalised;
  const std::string format = summary_format(o);
  AnalyzeFiles files;
  declare_outputs(o, command, files);
  const AnalyzeInputs in = read_inputs(o);
  check_annuli(o, in.sets, in.prefixes.size());
  const std::vector<std::pair<OutputFile*, const PointSet*>> psa_files = declare_psa_points(o, in.sets, files.outputs);
  check_budget(o, in);

  SummaryOptions options = summary_options(o, in.boundary);
  std::unique_ptr<Progress> bar;
  // On a terminal: the step under way, and the periodogram's progress.
  bool counting = false;  // the bar counts the periodogram's work (else it names a step)
  options.step = [&](const char* name) {
    counting = false;
    bar = std::make_unique<Progress>("analyze:", 0);
    bar->update(0, name);
  };
  options.progress = [&](std::size_t done, std::size_t total) {
    if (!bar || !counting) {
      counting = true;
      bar = std::make_unique<Progress>("periodogram", static_cast<long long>(total));
    }
    bar->update(static_cast<long long>(done));
  };
  const std::vector<Series> series = compute_series(o, in, options, bar);
  const AnalyzeDrawings drawings = draw_series(o, series, in, axis);
  const nlohmann::json stats = stats_json(o, series, in.boundary, axis);
  const std::string report = report_text(o, series, in.sets[0][0].points.size());

  const std::vector<Series> tables = o.compare ? series : std::vector<Series>{series.back()};
  files.stats->write(stats.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
  files.radial->write(radial_csv(tables, o.compare));
  files.rdf->write(rdf_csv(tables, o.compare));
  write_image(*files.points_png, drawings.points_png);
  write_image(*files.spectrum_png, drawings.spectrum_png);
  write_image(*files.radial_png, drawings.radial_png);
  write_image(*files.rdf_png, drawings.rdf_png);
  files.points_svg->write(drawings.points_svg.str());
  files.spectrum_svg->write(drawings.spectrum_svg.str());
  files.radial_svg->write(drawings.radial_svg.str());
  files.rdf_svg->write(drawings.rdf_svg.str());
  if (files.summary) {
    if (format == "pdf") write_pdf(*drawings.summary, *files.summary);
    else files.summary->write(drawings.summary->str());
  }
  files.report->write(report);
  for (const auto& [file, set] : psa_files) file->write(psa_text(*set));
  files.outputs.publish();
  // Standard output holds the points of --psa-points - alone; the report goes to stderr then.
  const bool stdout_taken =
      std::any_of(psa_files.begin(), psa_files.end(), [](const auto& file) { return file.first->is_stdout(); });
  (stdout_taken ? std::cerr : std::cout) << report << std::flush;
}

}  // namespace

void add_analyze_command(CLI::App& app) {
  auto o = std::make_shared<AnalyzeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "analyze",
      "Spectrum, radial power, anisotropy, RDF, nu_eff, Omega and nearest-neighbour statistics of point sets (psa's "
      "conventions)");
  add_input_option(cmd, "-i,--input", o->inputs, InputKind::points,
                   "Point file(s), by extension: .npy, .bpt, .csv (header x,y or x,y,level), psa's .rps, else by content (.npy or .bpt bytes, else text); a "
                   "file may hold several sets (text: separated by '#' lines)")
      ->required();
  add_output_folder_option(cmd, "-o,--output", o->output, "Output folder (created if missing; its parent must exist)")
      ->required();
  add_integer_option(cmd, "--size", o->size, 0, 65536,
                     "Periodogram size F (even): frequencies -F/2..F/2-1; default (0) 2 floor(5 sqrt(N))");
  add_real_option(cmd, "--bin-width", o->bin_width, {0.0, 65536.0, true, false}, "Annulus width in integer frequencies");
  cmd->add_option("--axis", o->axis, "Frequency axis of the plots: normalised (nu = |k| / (sqrt(N) / 2)) or integer")
      ->check(CLI::IsMember({"normalised", "integer"}))
      ->capture_default_str();
  cmd->add_flag("--average", o->average, "Analyse the mean over all sets of all inputs (equal sizes)");
  cmd->add_flag("--compare", o->compare, "One series per input file (its sets averaged), plotted together");
  cmd->add_flag("--by-level", o->by_level, "Analyse every prefix (levels 0..l) of a hierarchical set");
  cmd->add_option("--by-rank", o->by_rank,
                  "Analyse the first K points of a set whose rows are in rank order, for each K: a count, or a "
                  "fraction P/Q of the points (1/16: the first N/16, rounded); with LF in the table. Several sets "
                  "(of one size): the mean over their prefixes")
      ->expected(1, 1000);
  cmd->add_option("--label", o->labels, "Legend label per input (default: file names)");
  cmd->add_flag("--bounded", o->bounded,
                "The sets were made in the bounded unit square: Euclidean distances, edge-corrected RDF (also "
                "chosen by a '# domain bounded' line in the file)");
  cmd->add_flag("--wrap", o->wrap,
                "Wrap points outside [0, 1) (or --domain) onto the torus (else they are an error; not with --bounded or "
                "a set declared bounded)");
  cmd->add_option("--domain", o->domain,
                  "X0 Y0 X1 Y1: the rectangle the points were made in, rescaled onto the unit torus (a non-square "
                  "one is stretched); points outside are an error (or wrapped with --wrap)")
      ->expected(4)
      ->allow_extra_args(false);
  add_output_option(cmd, "--psa-points", o->psa_points, {.extension = ".txt", .standard_output = true},
                    "Also write the points analysed (after --domain) as psa's plain text (N, then 'x y' lines) to this "
                    "file; {} in the name is the set index, one file per set");
  add_real_option(cmd, "--rdf-range", o->rdf_range, {0.0, 1e6, true},
                  "Largest RDF distance in hexagonal spacings, at most half the square (0.5 / d_hex: 4.65 at N = 100); "
                  "default psa's 8, capped at half the square for N < 296 (the report gives the range used)")
      ->default_str(number_text(kDefaultRdfRange));
  add_integer_option(cmd, "--rdf-bins", o->rdf_bins, 1, 1000000, "RDF histogram bins (default N / 8 within 32..1000, psa's)")
      ->default_str("N / 8");
  add_output_option(cmd, "--summary", o->summary, {.formats = kSummaryFormats},
                    "Also write a one-page summary (points, spectrum, radial power, anisotropy, RDF, measures) to this "
                    ".pdf or .svg file");
  cmd->add_flag("--cells", o->cells, "Draw the periodic Voronoi cells in points.png");
  add_input_option(cmd, "--from", o->from, InputKind::points,
                   "Draw each point's move from its position in this file (same count and order)");
  cmd->add_flag("--no-centroids", o->no_centroids, "Skip the mean distance of the sites to their exact cell centroids");
  cmd->add_flag("--no-psa-measures", o->no_psa_measures,
                "Skip nu_eff and Omega by psa's definitions: their RDF takes every pair closer than 0.25, O(N^2) (about "
                "half an hour at 10^6 points on 2 cores)");
  cmd->add_flag("--no-discrepancy", o->no_discrepancy,
                "Skip the centred, wrap-around, mixture and L2-star discrepancies (scipy.stats.qmc's): every pair, O(N^2)");
  add_real_option(cmd, "--time-limit", o->time_limit_minutes, {0.0, 1e7, true, false},
                  "Refuse up front when the estimated analysis time exceeds this many minutes");
  cmd->add_option("--title", o->title, "Title of radial.png and of the summary");
  add_integer_option(cmd, "--image-size", o->image_size, 64, 8192,
                     "Side of points.png in pixels (two thirds of it per set side by side)");
  add_threads_option(cmd, o->threads);
  cmd->callback([o, cmd] { run_analyze(*o, *cmd); });
}

}  // namespace bluetile::cli
