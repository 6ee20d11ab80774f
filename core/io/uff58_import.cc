#include "core/io/uff58_import.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
#include <set>
#include <utility>

namespace gearpath {
namespace {

constexpr double kAbscissaTolerance = 1e-9;

std::string Num(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9g", value);
  return buffer;
}

bool Close(double a, double b) {
  return std::abs(a - b) <= kAbscissaTolerance * std::max({std::abs(a), std::abs(b), 1e-300});
}

// Same sample positions, to the tolerance.
bool SameAbscissa(const Uff58Record& x, const Uff58Record& y) {
  if (x.ordinate.size() != y.ordinate.size()) return false;
  if (x.even_abscissa && y.even_abscissa) {
    return Close(x.abscissa_start, y.abscissa_start) &&
           Close(x.abscissa_increment, y.abscissa_increment);
  }
  for (std::size_t i = 0; i < x.ordinate.size(); ++i) {
    if (!Close(x.AbscissaAt(i), y.AbscissaAt(i))) return false;
  }
  return true;
}

std::string DescribeAbscissa(const Uff58Record& r) {
  std::string s = std::to_string(r.ordinate.size()) + " points";
  if (r.even_abscissa) {
    return s + " from " + Num(r.abscissa_start) + " step " + Num(r.abscissa_increment);
  }
  if (r.ordinate.empty()) return s;
  return s + " uneven from " + Num(r.abscissa.front()) + " to " + Num(r.abscissa.back());
}

std::string DescribeRecord(std::size_t index, const Uff58Record& r) {
  return "record " + std::to_string(index) + " (response node " + std::to_string(r.response_node) +
         " " + UffDirectionName(r.response_direction) + ", reference node " +
         std::to_string(r.reference_node) + " " + UffDirectionName(r.reference_direction) + ")";
}

std::string DescribeDof(const UffDofAssignment& d) {
  return d.name + " (node " + std::to_string(d.node) + " " + UffDirectionName(d.direction) + ")";
}

const char* RoleKey(DofRole role) {
  switch (role) {
    case DofRole::kActive:
      return "a";
    case DofRole::kPassive:
      return "p";
    case DofRole::kMeasurement:
      return "m";
  }
  return "?";
}

}  // namespace

Result<CoupledSet> ImportCoupledSet(std::span<const Uff58Record> records,
                                    std::span<const UffDofAssignment> dofs) {
  // Validate the assignment and index it by (node, direction).
  std::map<std::pair<int, int>, std::size_t> by_dof;
  std::set<std::string> names;
  std::vector<std::size_t> role_members[3];
  for (std::size_t i = 0; i < dofs.size(); ++i) {
    const auto& d = dofs[i];
    const std::string at = "dofs[" + std::to_string(i) + "]";
    if (d.name.empty()) return Error{at + ": name must not be empty"};
    if (!names.insert(d.name).second) return Error{at + ": name \"" + d.name + "\" is used twice"};
    if (d.direction < 1 || d.direction > 3) {
      return Error{at + " (" + d.name + "): direction must be 1, 2 or 3 (+X, +Y, +Z), got " +
                   std::to_string(d.direction)};
    }
    if (!by_dof.emplace(std::pair{d.node, d.direction}, i).second) {
      return Error{at + " (" + d.name + "): node " + std::to_string(d.node) + " " +
                   UffDirectionName(d.direction) + " is assigned twice"};
    }
    role_members[static_cast<int>(d.role)].push_back(i);
  }
  const auto& a = role_members[static_cast<int>(DofRole::kActive)];
  const auto& p = role_members[static_cast<int>(DofRole::kPassive)];
  const auto& m = role_members[static_cast<int>(DofRole::kMeasurement)];
  if (a.empty()) return Error{"no DOF has the active (a) role"};
  if (p.empty()) return Error{"no DOF has the passive (p) role"};

  // Index the records by (response DOF, reference DOF).
  struct Entry {
    std::size_t record;
    double sign;
  };
  std::map<std::pair<std::size_t, std::size_t>, Entry> frf;
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> other;  // non-FRF records
  auto lookup = [&](int node, int direction) -> std::optional<std::pair<std::size_t, double>> {
    auto it = by_dof.find({node, std::abs(direction)});
    if (it == by_dof.end()) return std::nullopt;
    return std::pair{it->second, direction < 0 ? -1.0 : 1.0};
  };
  std::optional<std::size_t> reference_record;
  for (std::size_t k = 0; k < records.size(); ++k) {
    const auto& r = records[k];
    const auto resp = lookup(r.response_node, r.response_direction);
    const auto ref = lookup(r.reference_node, r.reference_direction);
    if (!resp || !ref) continue;
    const std::pair key{resp->first, ref->first};
    if (r.function_type != kUffFrequencyResponse) {
      other.emplace(key, k);
      continue;
    }
    if (auto it = frf.find(key); it != frf.end()) {
      return Error{DescribeRecord(k, r) + " duplicates " +
                   DescribeRecord(it->second.record, records[it->second.record]) +
                   ": two FRFs for response " + DescribeDof(dofs[key.first]) + ", reference " +
                   DescribeDof(dofs[key.second])};
    }
    if (reference_record && !SameAbscissa(r, records[*reference_record])) {
      return Error{"abscissa mismatch: " + DescribeRecord(k, r) + " has " + DescribeAbscissa(r) +
                   ", " + DescribeRecord(*reference_record, records[*reference_record]) + " has " +
                   DescribeAbscissa(records[*reference_record])};
    }
    if (!reference_record) reference_record = k;
    frf.emplace(key, Entry{k, resp->second * ref->second});
  }
  if (!reference_record) {
    return Error{"no FRF record (function type 4) connects two assigned DOFs"};
  }

  // The frequency axis.
  const Uff58Record& ref_record = records[*reference_record];
  const auto n = static_cast<Eigen::Index>(ref_record.ordinate.size());
  if (n == 0) return Error{DescribeRecord(*reference_record, ref_record) + " has no samples"};
  CoupledSet set;
  set.blocks.frequency_hz.resize(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    set.blocks.frequency_hz[k] = ref_record.AbscissaAt(static_cast<std::size_t>(k));
    if (!std::isfinite(set.blocks.frequency_hz[k]) ||
        (k > 0 && !(set.blocks.frequency_hz[k] > set.blocks.frequency_hz[k - 1]))) {
      return Error{DescribeRecord(*reference_record, ref_record) +
                   ": abscissa is not a strictly increasing frequency axis at sample " +
                   std::to_string(k)};
    }
  }

  auto to_coupled = [&](const std::vector<std::size_t>& members) {
    std::vector<CoupledDof> out;
    static constexpr const char* kAxis[] = {"x", "y", "z"};
    for (std::size_t i : members) {
      out.push_back({dofs[i].name, std::to_string(dofs[i].node), kAxis[dofs[i].direction - 1]});
    }
    return out;
  };
  set.active = to_coupled(a);
  set.passive = to_coupled(p);
  set.measurement = to_coupled(m);

  // Fills one block; `required` = false returns an empty block if no pair of it is measured.
  auto assemble = [&](const std::vector<std::size_t>& rows, const std::vector<std::size_t>& cols,
                      DofRole row_role, DofRole col_role, bool required,
                      std::vector<Eigen::MatrixXcd>* out) -> Status {
    const std::string block = std::string("H_") + RoleKey(row_role) + RoleKey(col_role);
    bool any = false;
    for (std::size_t r : rows) {
      for (std::size_t c : cols) any = any || frf.count({r, c}) > 0;
    }
    if (!required && !any) {
      out->clear();
      return Status::Ok();
    }
    out->assign(static_cast<std::size_t>(n),
                Eigen::MatrixXcd(static_cast<Eigen::Index>(rows.size()),
                                 static_cast<Eigen::Index>(cols.size())));
    for (std::size_t i = 0; i < rows.size(); ++i) {
      for (std::size_t j = 0; j < cols.size(); ++j) {
        auto it = frf.find({rows[i], cols[j]});
        if (it == frf.end()) {
          std::string message =
              "missing FRF for " + block + (required ? "" : " (partly measured)") + ": response " +
              DescribeDof(dofs[rows[i]]) + ", reference " + DescribeDof(dofs[cols[j]]);
          if (auto o = other.find({rows[i], cols[j]}); o != other.end()) {
            const auto& rec = records[o->second];
            message += "; " + DescribeRecord(o->second, rec) + " has function type " +
                       std::to_string(rec.function_type) + " (" +
                       UffFunctionTypeName(rec.function_type) +
                       "), expected 4 (frequency response function)";
          }
          return Error{message};
        }
        const auto& samples = records[it->second.record].ordinate;
        const double sign = it->second.sign;
        for (Eigen::Index k = 0; k < n; ++k) {
          (*out)[static_cast<std::size_t>(k)](static_cast<Eigen::Index>(i),
                                              static_cast<Eigen::Index>(j)) =
              sign * samples[static_cast<std::size_t>(k)];
        }
      }
    }
    return Status::Ok();
  };
  using R = DofRole;
  for (Status st : {assemble(a, a, R::kActive, R::kActive, true, &set.blocks.aa),
                    assemble(p, a, R::kPassive, R::kActive, true, &set.blocks.pa),
                    assemble(p, p, R::kPassive, R::kPassive, true, &set.blocks.pp),
                    assemble(a, p, R::kActive, R::kPassive, false, &set.blocks.ap)}) {
    if (!st) return Error{st.error()};
  }
  if (!m.empty()) {
    if (Status st = assemble(m, a, R::kMeasurement, R::kActive, true, &set.blocks.ma); !st) {
      return Error{st.error()};
    }
    if (Status st = assemble(m, p, R::kMeasurement, R::kPassive, true, &set.blocks.mp); !st) {
      return Error{st.error()};
    }
  }
  return set;
}

Result<TimeHistories> ExtractTimeHistories(std::span<const Uff58Record> records) {
  TimeHistories out;
  std::vector<std::size_t> picked;
  for (std::size_t k = 0; k < records.size(); ++k) {
    const auto& r = records[k];
    if (r.function_type != kUffTimeResponse) continue;
    const std::string which = DescribeRecord(k, r);
    if (!r.even_abscissa) return Error{which + ": time response must be evenly sampled"};
    if (!(r.abscissa_increment > 0) || !std::isfinite(r.abscissa_increment)) {
      return Error{which + ": sample interval " + Num(r.abscissa_increment) + " s is not positive"};
    }
    if (r.complex_ordinate) return Error{which + ": time response has complex samples"};
    if (r.ordinate.empty()) return Error{which + ": time response has no samples"};
    if (!picked.empty() && !SameAbscissa(r, records[picked.front()])) {
      return Error{"time base mismatch: " + which + " has " + DescribeAbscissa(r) + ", " +
                   DescribeRecord(picked.front(), records[picked.front()]) + " has " +
                   DescribeAbscissa(records[picked.front()])};
    }
    picked.push_back(k);
  }
  if (picked.empty()) return Error{"no time response record (function type 1) in the input"};
  const Uff58Record& first = records[picked.front()];
  out.sample_rate_hz = 1.0 / first.abscissa_increment;
  out.start_time_s = first.abscissa_start;
  const auto n = static_cast<Eigen::Index>(first.ordinate.size());
  out.samples.resize(n, static_cast<Eigen::Index>(picked.size()));
  for (std::size_t c = 0; c < picked.size(); ++c) {
    const auto& r = records[picked[c]];
    out.channels.push_back(
        {r.response_node, r.response_direction, r.id_lines[0], r.ordinate_axis.unit_label});
    for (Eigen::Index i = 0; i < n; ++i) {
      out.samples(i, static_cast<Eigen::Index>(c)) = r.ordinate[static_cast<std::size_t>(i)].real();
    }
  }
  return out;
}

}  // namespace gearpath
