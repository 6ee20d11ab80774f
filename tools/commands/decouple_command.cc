// `gearpath decouple`: coupled FRFs of the assembled gearbox -> the housing's decoupled FRFs, by
// virtual decoupling (seed Eq. 22 with --at p, Eq. 24 with --at m; core/frf/virtual_decoupling.h).
//
// Input: an FRF set with a `coupled` part, or a UFF 58 file of FRFs with a DOF role map
// (--dof NAME=NODE:DIR:ROLE, role a, p or m). Prints the condition number of (H_pa - H_aa), the
// matrix every bin inverts (worst, with its frequency, and the median), and writes the decoupled
// set with --out. Accuracy check in the seed's Table 3 layout (FRAC, Eq. 25; core/frf/frac.h):
// against "real values" (--reference: e.g. a physically decoupled set with the same rows and
// columns), and against neighbouring measurement points (--pair ROW=OTHER, OTHER being a row of
// --neighbours or of the result itself). A row's FRAC compares the whole row (the response at
// that point to every path's force) over the band, as the seed's FRAC(H_mp) does.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "core/frf/frac.h"
#include "core/frf/frf_set.h"
#include "core/frf/virtual_decoupling.h"
#include "core/io/frf_set_io.h"
#include "core/io/uff58.h"
#include "core/io/uff58_import.h"
#include "tools/commands/commands.h"
#include "tools/common/cli_checks.h"

namespace gearpath::tools {
namespace {

namespace fs = std::filesystem;

struct DecoupleOptions {
  std::string input;
  std::string at;                 // "p" (Eq. 22) or "m" (Eq. 24)
  std::vector<std::string> dofs;  // UFF input: NAME=NODE:DIR:ROLE
  std::string out;
  double max_condition = 0.0;
  std::string reference;           // FRF set of real values
  std::string neighbours;          // FRF set of neighbouring points
  std::vector<std::string> pairs;  // ROW=OTHER
  std::string band;                // "LO:HI" Hz
};

Result<UffDofAssignment> ParseDof(const std::string& text) {
  // NAME=NODE:DIR:ROLE, DIR in x/y/z or 1/2/3, ROLE in a/p/m.
  const std::size_t eq = text.find('=');
  const std::size_t c1 = text.find(':', eq == std::string::npos ? 0 : eq);
  const std::size_t c2 = c1 == std::string::npos ? c1 : text.find(':', c1 + 1);
  if (eq == std::string::npos || eq == 0 || c1 == std::string::npos || c2 == std::string::npos) {
    return Error{"--dof " + text + ": expected NAME=NODE:DIR:ROLE (e.g. p1x=12:x:p)"};
  }
  UffDofAssignment dof;
  dof.name = text.substr(0, eq);
  try {
    dof.node = std::stoi(text.substr(eq + 1, c1 - eq - 1));
  } catch (const std::exception&) {
    return Error{"--dof " + text + ": node \"" + text.substr(eq + 1, c1 - eq - 1) +
                 "\" is not an integer"};
  }
  const std::string dir = text.substr(c1 + 1, c2 - c1 - 1), role = text.substr(c2 + 1);
  if (dir == "x" || dir == "1")
    dof.direction = 1;
  else if (dir == "y" || dir == "2")
    dof.direction = 2;
  else if (dir == "z" || dir == "3")
    dof.direction = 3;
  else
    return Error{"--dof " + text + ": direction must be x, y, z (or 1, 2, 3), got \"" + dir + "\""};
  if (role == "a")
    dof.role = DofRole::kActive;
  else if (role == "p")
    dof.role = DofRole::kPassive;
  else if (role == "m")
    dof.role = DofRole::kMeasurement;
  else
    return Error{"--dof " + text + ": role must be a, p or m, got \"" + role + "\""};
  return dof;
}

// Row labels of a decoupled set: "<sensor>-<axis>".
std::vector<std::string> RowLabels(const FrfSet& set) {
  std::vector<std::string> out;
  for (const auto& c : set.channels) out.push_back(c.sensor + "-" + c.axis);
  return out;
}

// The whole row r of an FRF matrix as one vector (bin-major), with each bin's frequency repeated
// once per column, so Frac over it is the row FRAC of Eq. 25.
void RowVector(const FrfMatrix& m, Eigen::Index r, Eigen::VectorXd* f, Eigen::VectorXcd* v) {
  const Eigen::Index cols = m.inputs();
  f->resize(m.bins() * cols);
  v->resize(m.bins() * cols);
  for (Eigen::Index k = 0; k < m.bins(); ++k) {
    for (Eigen::Index c = 0; c < cols; ++c) {
      (*f)[k * cols + c] = m.frequency_hz[k];
      (*v)[k * cols + c] = m.at[static_cast<std::size_t>(k)](r, c);
    }
  }
}

Result<double> RowFrac(const FrfMatrix& a, Eigen::Index ra, const FrfMatrix& b, Eigen::Index rb,
                       double lo, double hi) {
  if (a.bins() != b.bins() || !a.frequency_hz.isApprox(b.frequency_hz, 1e-9)) {
    return Error{"the two sets are on different frequency axes"};
  }
  if (a.inputs() != b.inputs()) {
    return Error{"the two sets have " + std::to_string(a.inputs()) + " and " +
                 std::to_string(b.inputs()) + " columns (paths)"};
  }
  Eigen::VectorXd fa, fb;
  Eigen::VectorXcd va, vb;
  RowVector(a, ra, &fa, &va);
  RowVector(b, rb, &fb, &vb);
  return Frac(fa, va, vb, lo, hi);
}

int RunDecouple(const DecoupleOptions& opt) {
  auto bad = [](const std::string& why) {
    std::fprintf(stderr, "gearpath decouple: %s\n", why.c_str());
    return kExitBadInput;
  };
  const fs::path in(opt.input);
  if (!fs::exists(in)) return bad(opt.input + ": no such file or directory");

  FrfSet source;
  if (fs::is_directory(in)) {
    if (!opt.dofs.empty()) return bad("--dof maps UFF DOFs; an FRF set names its DOFs itself");
    Result<FrfSet> set = ReadFrfSet(in);
    if (!set) return bad(set.error());
    if (!set->coupled) return bad(opt.input + ": the set has no \"coupled\" part to decouple");
    source = std::move(*set);
  } else {
    if (opt.dofs.empty()) {
      return bad(
          "a UFF input needs the DOF roles: --dof NAME=NODE:DIR:ROLE for each a, p (and m) DOF");
    }
    std::vector<UffDofAssignment> dofs;
    for (const std::string& d : opt.dofs) {
      Result<UffDofAssignment> dof = ParseDof(d);
      if (!dof) return bad(dof.error());
      dofs.push_back(*dof);
    }
    Result<std::vector<Uff58Record>> records = ReadUff58(in);
    if (!records) return bad(records.error());
    Result<CoupledSet> coupled = ImportCoupledSet(*records, dofs);
    if (!coupled) return bad(opt.input + ": " + coupled.error());
    source.description = "decoupled from " + in.filename().string();
    source.coupled = std::move(*coupled);
  }
  const CoupledSet& coupled = *source.coupled;
  const bool at_m = opt.at == "m";
  if (at_m && !coupled.blocks.has_measurement_points()) {
    return bad("--at m (Eq. 24) needs measurement DOFs m with H_ma and H_mp; the input has none");
  }
  VirtualDecouplingOptions vo;
  vo.max_condition_number = opt.max_condition;
  Result<VirtualDecouplingResult> result = at_m ? DecoupleAtMeasurementPoints(coupled.blocks, vo)
                                                : DecoupleAtInterface(coupled.blocks, vo);
  if (!result) {
    std::fprintf(stderr, "gearpath decouple: %s\n", result.error().c_str());
    return kExitFailure;
  }
  const DecouplingConditionReport& rep = result->report;
  std::vector<double> sorted(rep.condition_number.data(),
                             rep.condition_number.data() + rep.condition_number.size());
  std::sort(sorted.begin(), sorted.end());
  std::printf("Eq. %s: H_d,%sp, %lld bins, %zu x %zu\n", at_m ? "24" : "22", at_m ? "m" : "p",
              static_cast<long long>(result->decoupled.bins()),
              static_cast<std::size_t>(result->decoupled.outputs()),
              static_cast<std::size_t>(result->decoupled.inputs()));
  std::printf(
      "condition number of (H_pa - H_aa): worst %.4g at %.6g Hz, median %.4g (limit %.3g)\n",
      rep.worst_condition_number, rep.worst_frequency_hz,
      sorted.empty() ? 0.0 : sorted[sorted.size() / 2], rep.limit);

  // The decoupled set: rows are the p (Eq. 22) or m (Eq. 24) DOFs, columns the p DOFs (paths).
  FrfSet out;
  out.description = source.description;
  out.quantity = source.quantity;
  out.unit = source.unit;
  out.decoupling = at_m ? "eq24" : "eq22";
  const std::vector<CoupledDof>& rows = at_m ? coupled.measurement : coupled.passive;
  for (const CoupledDof& d : rows) out.channels.push_back({d.node, d.direction});
  const bool keep_paths = source.paths.size() == coupled.passive.size();
  for (std::size_t i = 0; i < coupled.passive.size(); ++i) {
    const CoupledDof& d = coupled.passive[i];
    out.paths.push_back(keep_paths ? source.paths[i]
                                   : TransferPath{d.name, d.node, d.direction, {}});
  }
  out.decoupled = result->decoupled;
  out.coupled = source.coupled;

  // FRAC table (seed Table 3 layout).
  double lo = out.decoupled.frequency_hz.size() ? out.decoupled.frequency_hz[0] : 0.0;
  double hi = out.decoupled.frequency_hz.size()
                  ? out.decoupled.frequency_hz[out.decoupled.frequency_hz.size() - 1]
                  : 0.0;
  if (!opt.band.empty()) {
    const std::size_t colon = opt.band.find(':');
    try {
      if (colon == std::string::npos) throw std::invalid_argument("no colon");
      lo = std::stod(opt.band.substr(0, colon));
      hi = std::stod(opt.band.substr(colon + 1));
    } catch (const std::exception&) {
      return bad("--band " + opt.band + ": expected LO:HI in Hz, e.g. 50:2000");
    }
  }
  const std::vector<std::string> labels = RowLabels(out);
  auto find_row = [&](const std::vector<std::string>& names, const std::vector<CoupledDof>* dofs,
                      const std::string& key) -> Eigen::Index {
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (names[i] == key || (dofs && (*dofs)[i].name == key)) return static_cast<Eigen::Index>(i);
    }
    return -1;
  };
  std::vector<std::string> headers;
  std::vector<double> values;
  if (!opt.reference.empty()) {
    Result<FrfSet> ref = ReadFrfSet(opt.reference);
    if (!ref) return bad(ref.error());
    if (ref->decoupled.outputs() != out.decoupled.outputs()) {
      return bad(opt.reference + ": the reference has " + std::to_string(ref->decoupled.outputs()) +
                 " rows, the result " + std::to_string(out.decoupled.outputs()));
    }
    for (Eigen::Index r = 0; r < out.decoupled.outputs(); ++r) {
      Result<double> f = RowFrac(out.decoupled, r, ref->decoupled, r, lo, hi);
      if (!f)
        return bad(opt.reference + ": row " + labels[static_cast<std::size_t>(r)] + ": " +
                   f.error());
      headers.push_back(rows[static_cast<std::size_t>(r)].name + "/real value");
      values.push_back(*f);
    }
  }
  if (!opt.pairs.empty()) {
    FrfSet neighbours_storage;
    const FrfSet* other = &out;
    if (!opt.neighbours.empty()) {
      Result<FrfSet> n = ReadFrfSet(opt.neighbours);
      if (!n) return bad(n.error());
      if (n->decoupled.at.empty()) return bad(opt.neighbours + ": has no decoupled FRFs");
      neighbours_storage = std::move(*n);
      other = &neighbours_storage;
    }
    const std::vector<std::string> other_labels = RowLabels(*other);
    for (const std::string& p : opt.pairs) {
      const std::size_t eq = p.find('=');
      if (eq == std::string::npos) return bad("--pair " + p + ": expected ROW=OTHER");
      const std::string a = p.substr(0, eq), b = p.substr(eq + 1);
      const Eigen::Index ra = find_row(labels, &rows, a);
      if (ra < 0) {
        std::string known;
        for (std::size_t i = 0; i < labels.size(); ++i) known += (i ? ", " : "") + rows[i].name;
        return bad("--pair " + p + ": no row \"" + a + "\" in the result (rows: " + known + ")");
      }
      const Eigen::Index rb = find_row(other_labels, other == &out ? &rows : nullptr, b);
      if (rb < 0) {
        return bad("--pair " + p + ": no row \"" + b + "\" in " +
                   (other == &out ? std::string("the result") : opt.neighbours));
      }
      Result<double> f = RowFrac(out.decoupled, ra, other->decoupled, rb, lo, hi);
      if (!f) return bad("--pair " + p + ": " + f.error());
      headers.push_back(rows[static_cast<std::size_t>(ra)].name + "/" + b);
      values.push_back(*f);
    }
  }
  if (!headers.empty()) {
    std::printf("\nFRAC over %.6g..%.6g Hz (Eq. 25)\n", lo, hi);
    const std::string row_name = at_m ? "FRAC(H_d,mp)" : "FRAC(H_d,pp)";
    std::printf("%-14s", "");
    for (const auto& h : headers) std::printf("  %16s", h.c_str());
    std::printf("\n%-14s", row_name.c_str());
    for (double v : values) std::printf("  %16.5f", v);
    std::printf("\n");
  }

  if (!opt.out.empty()) {
    if (Status st = WriteFrfSet(out, opt.out); !st) {
      std::fprintf(stderr, "gearpath decouple: %s\n", st.error().c_str());
      return kExitFailure;
    }
    std::printf("wrote %s\n", opt.out.c_str());
  }
  return kExitOk;
}

}  // namespace

void AddDecoupleCommand(CLI::App& app, int& exit_code) {
  auto opt = std::make_shared<DecoupleOptions>();
  CLI::App* cmd = app.add_subcommand(
      "decouple",
      "Virtual decoupling of coupled FRFs (seed Eq. 22 at p, Eq. 24 at m): condition "
      "numbers, FRAC table (Table 3 layout), decoupled FRF set");
  cmd->add_option("input", opt->input, "FRF set with a coupled part, or a UFF 58 file of FRFs")
      ->required();
  cmd->add_option("--at", opt->at,
                  "p: responses at the interface (Eq. 22); m: at measurement "
                  "points (Eq. 24)")
      ->required()
      ->check(CLI::IsMember({"p", "m"}));
  cmd->add_option("--dof", opt->dofs, "UFF input: NAME=NODE:DIR:ROLE, role a, p or m (repeatable)");
  cmd->add_option("--out,-o", opt->out, "Write the decoupled FRF set here");
  cmd->add_option("--max-condition", opt->max_condition,
                  "Largest accepted condition number of (H_pa - H_aa); default 1/(n eps)")
      ->check(NonNegative());
  cmd->add_option("--reference", opt->reference,
                  "FRF set of real values (same rows) for the FRAC \"/real value\" columns");
  cmd->add_option("--neighbours", opt->neighbours,
                  "FRF set of neighbouring measurement points (rows named by --pair)");
  cmd->add_option("--pair", opt->pairs,
                  "ROW=OTHER: FRAC of result row ROW against row OTHER of --neighbours (or of "
                  "the result); rows by DOF name or SENSOR-AXIS (repeatable)");
  cmd->add_option("--band", opt->band, "FRAC band LO:HI in Hz (default: the whole axis)");
  cmd->callback([opt, &exit_code] {
    try {
      exit_code = RunDecouple(*opt);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "gearpath decouple: %s\n", e.what());
      exit_code = kExitFailure;
    }
  });
}

}  // namespace gearpath::tools
