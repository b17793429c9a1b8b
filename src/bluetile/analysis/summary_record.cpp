// The one serializer of a Summary (stats.json's keys); see summary_record.h.
#include "bluetile/analysis/summary_record.h"

#include <limits>

namespace bluetile {

Record Record::of(double v) {
  Record r;
  r.kind = Kind::real;
  r.real = v;
  return r;
}

Record Record::of_integer(std::int64_t v) {
  Record r;
  r.kind = Kind::integer;
  r.integer = v;
  return r;
}

Record Record::of(std::string v) {
  Record r;
  r.kind = Kind::text;
  r.text = std::move(v);
  return r;
}

Record Record::of(std::vector<double> v) {
  Record r;
  r.kind = Kind::reals;
  r.reals = std::move(v);
  return r;
}

Record Record::of(std::vector<std::int64_t> v) {
  Record r;
  r.kind = Kind::integers;
  r.integers = std::move(v);
  return r;
}

Record Record::object() {
  Record r;
  r.kind = Kind::object;
  return r;
}

Record& Record::set(const std::string& key, Record value) {
  kind = Kind::object;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    if (keys[i] == key) {
      values[i] = std::move(value);
      return *this;
    }
  }
  keys.push_back(key);
  values.push_back(std::move(value));
  return *this;
}

const Record* Record::find(const std::string& key) const {
  for (std::size_t i = 0; i < keys.size(); ++i)
    if (keys[i] == key) return &values[i];
  return nullptr;
}

namespace {

Record min_max_mean(double min, double max, double mean) {
  return Record::object().set("min", Record::of(min)).set("max", Record::of(max)).set("mean", Record::of(mean));
}

Record count_of(std::size_t v) { return Record::of_integer(static_cast<std::int64_t>(v)); }

}  // namespace

Record summary_record(const Summary& s) {
  const double h = s.nn.hexagonal_spacing;
  Record r = Record::object();
  r.set("n", count_of(s.count));
  r.set("sets", count_of(s.sets));
  r.set("boundary", Record::of(std::string(s.boundary == Boundary::periodic ? "periodic" : "bounded")));
  r.set("nn_min", Record::of(s.nn.min));
  r.set("nn_max", Record::of(s.nn.max));
  r.set("nn_mean", Record::of(s.nn.mean));
  r.set("nn_x1000", min_max_mean(1000.0 * s.nn.min, 1000.0 * s.nn.max, 1000.0 * s.nn.mean));
  r.set("nn_relative", min_max_mean(s.nn.min / h, s.nn.max / h, s.nn.mean / h));
  r.set("hexagonal_spacing", Record::of(h));
  r.set("rho", Record::of(s.nn.rho()));
  r.set("average_min_distance", Record::of(s.nn.rho_mean()));
  if (s.sets > 1) {
    r.set("nn_min_lowest", Record::of(s.nn_min_lowest));
    r.set("nn_min_highest", Record::of(s.nn_min_highest));
  }
  if (s.has_centroid_distance) {
    r.set("mean_centroid_distance", Record::of(s.centroid_distance));
    r.set("mean_centroid_distance_relative", Record::of(s.centroid_distance / h));
  }
  // psa's definitions, from the RDF-derived radial power (spectral_measures.h); null for a
  // bounded set (psa's measures need torus distances) or when skipped.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  r.set("nu_eff", Record::of(s.has_spectral_measures ? s.measures.nu_eff : nan));
  r.set("omega", Record::of(s.has_spectral_measures ? s.measures.omega : nan));
  if (s.has_spectral_measures)
    r.set("omega_range_nu", Record::of(std::vector<double>{s.measures.omega_from_nu, s.measures.omega_to_nu}));
  if (s.has_bond_order)
    r.set("bond_order",
          Record::object().set("local", Record::of(s.bond_order.local)).set("global", Record::of(s.bond_order.global)));
  if (!s.per_set.empty()) {
    // Each set's own measures, under the keys above: {rho, average_min_distance, nu_eff, omega,
    // bond_order_local}, null where not measured.
    Record list = Record::object();
    std::vector<double> rho, amd, nu_eff, omega, psi6;
    for (const SetMeasures& m : s.per_set) {
      rho.push_back(m.rho);
      amd.push_back(m.average_min_distance);
      nu_eff.push_back(m.nu_eff);
      omega.push_back(m.omega);
      psi6.push_back(m.bond_order);
    }
    list.set("rho", Record::of(std::move(rho)));
    list.set("average_min_distance", Record::of(std::move(amd)));
    list.set("nu_eff", Record::of(std::move(nu_eff)));
    list.set("omega", Record::of(std::move(omega)));
    list.set("bond_order_local", Record::of(std::move(psi6)));
    r.set("per_set", std::move(list));
  }
  if (s.has_discrepancy)
    // scipy.stats.qmc.discrepancy's method names and values (CD, WD, MD squared; L2-star not).
    r.set("discrepancy", Record::object()
                             .set("CD", Record::of(s.discrepancy.centred))
                             .set("WD", Record::of(s.discrepancy.wrap_around))
                             .set("MD", Record::of(s.discrepancy.mixture))
                             .set("L2-star", Record::of(s.discrepancy.l2_star)));
  r.set("rdf_range_relative", Record::of(s.rdf.range() / h));
  r.set("rdf_bins", count_of(s.rdf.g.size()));
  r.set("periodogram_size", Record::of_integer(s.periodogram.size));
  std::vector<double> frequency, nu, power, anisotropy;
  std::vector<std::int64_t> count;
  for (const Annulus& a : s.radial) {
    frequency.push_back(a.frequency);
    nu.push_back(s.nu(a.frequency));
    power.push_back(a.power);
    anisotropy.push_back(a.anisotropy_db);
    count.push_back(static_cast<std::int64_t>(a.count));
  }
  r.set("radial", Record::object()
                      .set("frequency", Record::of(std::move(frequency)))
                      .set("nu", Record::of(std::move(nu)))
                      .set("power", Record::of(std::move(power)))
                      .set("anisotropy_db", Record::of(std::move(anisotropy)))
                      .set("count", Record::of(std::move(count))));
  return r;
}

}  // namespace bluetile
