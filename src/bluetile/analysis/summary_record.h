// A Summary's measures as a tree of named values, with the keys of `bluetile analyze`'s
// stats.json: the tool writes it as JSON, the Python module returns it as a dict. One serializer
// for both front ends, so their keys and numbers cannot drift apart.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "bluetile/analysis/summary.h"

namespace bluetile {

struct Record {
  enum class Kind { null, integer, real, text, reals, integers, object };
  Kind kind = Kind::null;
  std::int64_t integer = 0;
  double real = 0.0;               // not finite: JSON null, Python None
  std::string text;
  std::vector<double> reals;       // an array of numbers (not finite: JSON null; NaN in numpy)
  std::vector<std::int64_t> integers;
  std::vector<std::string> keys;   // an object's fields, in order
  std::vector<Record> values;

  static Record null_value() { return {}; }
  static Record of(double v);
  static Record of_integer(std::int64_t v);
  static Record of(std::string v);
  static Record of(std::vector<double> v);
  static Record of(std::vector<std::int64_t> v);
  static Record object();

  // Adds (or replaces) an object's field; returns *this.
  Record& set(const std::string& key, Record value);
  // The field `key` of an object, or nullptr.
  const Record* find(const std::string& key) const;
};

// stats.json's fields for one series: n, sets, boundary, nearest-neighbour distances (raw, x1000,
// relative), hexagonal_spacing, rho, average_min_distance, the per-set range of minima and
// per_set {rho, average_min_distance, nu_eff, omega, bond_order_local}, one value per set (several
// sets), mean_centroid_distance[_relative], nu_eff and omega (null when not measured) with
// omega_range_nu, bond_order {local, global}, discrepancy {CD, WD, MD, L2-star} (when measured), rdf_range_relative, rdf_bins, periodogram_size, and
// radial {frequency, nu, power, anisotropy_db, count}.
Record summary_record(const Summary& s);

}  // namespace bluetile
