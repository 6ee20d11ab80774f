#include "core/io/frf_set_io.h"

#include <cmath>
#include <complex>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <system_error>
#include <utility>
#include <vector>

#include "core/io/json_read.h"
#include "core/io/npy.h"

namespace gearpath {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;
using Blocks = std::vector<Eigen::MatrixXcd>;

constexpr char kFrequencyFile[] = "frequency_hz.npy";
constexpr char kDecoupledFile[] = "H_decoupled.npy";
constexpr const char* kDecouplings[] = {"eq22", "eq24", "physical", "model"};

std::string Num(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.12g", value);
  return buffer;
}

std::string Quoted(const std::string& s) { return "\"" + s + "\""; }

std::string Shape(const std::vector<std::size_t>& shape) {
  std::string s = "(";
  for (std::size_t i = 0; i < shape.size(); ++i) s += (i ? ", " : "") + std::to_string(shape[i]);
  return s + (shape.size() == 1 ? ",)" : ")");
}

bool IsDirection(const std::string& d) { return d == "x" || d == "y" || d == "z"; }

bool IsDecoupling(const std::string& d) {
  for (const char* known : kDecouplings) {
    if (d == known) return true;
  }
  return false;
}

std::optional<FrfQuantity> ParseQuantity(const std::string& s) {
  if (s == "accelerance") return FrfQuantity::kAccelerance;
  if (s == "mobility") return FrfQuantity::kMobility;
  if (s == "receptance") return FrfQuantity::kReceptance;
  return std::nullopt;
}

// Why the frequency axis is unusable, or nothing. `what` names it in the message.
std::optional<std::string> CheckFrequencyAxis(const Eigen::VectorXd& f, const std::string& what) {
  if (f.size() == 0) return what + " has no bins";
  for (Eigen::Index k = 0; k < f.size(); ++k) {
    if (!std::isfinite(f[k]))
      return what + ": non-finite value " + Num(f[k]) + " at index " + std::to_string(k);
    if (f[k] < 0)
      return what + ": negative frequency " + Num(f[k]) + " Hz at index " + std::to_string(k);
    if (k > 0 && !(f[k] > f[k - 1])) {
      return what + ": not strictly increasing at index " + std::to_string(k) + " (" + Num(f[k]) +
             " Hz after " + Num(f[k - 1]) + " Hz)";
    }
  }
  return std::nullopt;
}

// Why a per-frequency block list does not fit (bins x rows x cols) or holds non-finite values.
std::optional<std::string> CheckBlocks(const Blocks& blocks, const Eigen::VectorXd& f,
                                       Eigen::Index rows, Eigen::Index cols,
                                       const std::string& what, const std::string& dims) {
  if (static_cast<Eigen::Index>(blocks.size()) != f.size()) {
    return what + " has " + std::to_string(blocks.size()) + " frequency bins, expected " +
           std::to_string(f.size());
  }
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    const auto& m = blocks[k];
    if (m.rows() != rows || m.cols() != cols) {
      return what + " at bin " + std::to_string(k) + " is " + std::to_string(m.rows()) + " x " +
             std::to_string(m.cols()) + ", expected " + std::to_string(rows) + " x " +
             std::to_string(cols) + " " + dims;
    }
    for (Eigen::Index i = 0; i < rows; ++i) {
      for (Eigen::Index j = 0; j < cols; ++j) {
        if (!std::isfinite(m(i, j).real()) || !std::isfinite(m(i, j).imag())) {
          return what + ": non-finite value at [" + std::to_string(k) + ", " + std::to_string(i) +
                 ", " + std::to_string(j) + "] (frequency " + Num(f[static_cast<Eigen::Index>(k)]) +
                 " Hz)";
        }
      }
    }
  }
  return std::nullopt;
}

std::optional<std::string> CheckDofs(const std::vector<CoupledDof>& dofs, const std::string& key,
                                     std::set<std::string>* names) {
  for (std::size_t i = 0; i < dofs.size(); ++i) {
    const std::string at = key + "[" + std::to_string(i) + "]";
    if (dofs[i].name.empty()) return at + ".name must not be empty";
    if (!names->insert(dofs[i].name).second) {
      return at + ".name " + Quoted(dofs[i].name) + " is used by another DOF";
    }
    if (dofs[i].node.empty()) return at + ".node must not be empty";
    if (!IsDirection(dofs[i].direction)) {
      return at + ".direction must be \"x\", \"y\" or \"z\", got " + Quoted(dofs[i].direction);
    }
  }
  return std::nullopt;
}

bool HasDecoupled(const FrfSet& set) {
  return set.decoupled.bins() > 0 || !set.decoupled.at.empty();
}

// ---- reading ----

// Typed access to manifest keys; remembers the first error, phrased with the key path.
class Manifest {
 public:
  explicit Manifest(std::string file) : file_(std::move(file)) {}

  static std::string Path(const std::string& prefix, const std::string& key) {
    return prefix.empty() ? key : prefix + "." + key;
  }

  // Returns the member or nullptr; records "missing key" if required.
  const Json* Get(const Json& obj, const std::string& prefix, const std::string& key,
                  bool required) {
    auto it = obj.find(key);
    if (it == obj.end()) {
      if (required) Fail("missing key " + Quoted(Path(prefix, key)));
      return nullptr;
    }
    return &*it;
  }

  bool Type(const Json& value, const std::string& path, Json::value_t type, const char* name) {
    const bool match =
        type == Json::value_t::number_integer ? value.is_number_integer() : value.type() == type;
    if (!match) Fail("key " + Quoted(path) + " must be " + name + ", got " + value.type_name());
    return match;
  }

  bool String(const Json& obj, const std::string& prefix, const std::string& key, std::string* out,
              bool required = true) {
    const Json* v = Get(obj, prefix, key, required);
    if (!v) return !required;
    if (!Type(*v, Path(prefix, key), Json::value_t::string, "a string")) return false;
    *out = v->get<std::string>();
    return true;
  }

  const Json* Array(const Json& obj, const std::string& prefix, const std::string& key,
                    bool required = true) {
    const Json* v = Get(obj, prefix, key, required);
    if (v && !Type(*v, Path(prefix, key), Json::value_t::array, "an array")) return nullptr;
    return v;
  }

  const Json* Object(const Json& obj, const std::string& prefix, const std::string& key,
                     bool required = true) {
    const Json* v = Get(obj, prefix, key, required);
    if (v && !Type(*v, Path(prefix, key), Json::value_t::object, "an object")) return nullptr;
    return v;
  }

  // A file name from the manifest must stay inside the set directory.
  bool FileName(const Json& obj, const std::string& prefix, const std::string& key,
                std::string* out, bool required = true) {
    if (!String(obj, prefix, key, out, required)) return false;
    if (out->empty() && !required) return true;
    const fs::path p(*out);
    bool escapes = p.empty() || p.is_absolute();
    for (const auto& part : p) escapes = escapes || part == "..";
    if (escapes) {
      Fail("key " + Quoted(Path(prefix, key)) + " must name a file inside the set directory, got " +
           Quoted(*out));
      return false;
    }
    return true;
  }

  void Fail(const std::string& message) {
    if (!failed_) error_ = file_ + ": " + message;
    failed_ = true;
  }
  bool failed() const { return failed_; }
  Error error() const { return Error{error_}; }

 private:
  std::string file_;
  std::string error_;
  bool failed_ = false;
};

bool ReadDofList(Manifest& m, const Json& dofs, const std::string& prefix, const std::string& key,
                 bool required, std::vector<CoupledDof>* out) {
  const Json* list = m.Array(dofs, prefix, key, required);
  if (!list) return !m.failed();
  const std::string path = Manifest::Path(prefix, key);
  for (std::size_t i = 0; i < list->size(); ++i) {
    const std::string at = path + "[" + std::to_string(i) + "]";
    const Json& item = (*list)[i];
    if (!m.Type(item, at, Json::value_t::object, "an object")) return false;
    CoupledDof dof;
    if (!m.String(item, at, "name", &dof.name) || !m.String(item, at, "node", &dof.node) ||
        !m.String(item, at, "direction", &dof.direction)) {
      return false;
    }
    out->push_back(std::move(dof));
  }
  return true;
}

// Reads an (n_freq, rows, cols) complex128 array into per-frequency matrices.
Result<Blocks> ReadBlocks(const fs::path& file, const std::string& key, const Eigen::VectorXd& f,
                          std::size_t rows, std::size_t cols, const std::string& dims) {
  if (!fs::exists(file)) {
    return Error{file.string() + ": missing array file (named by manifest key " + Quoted(key) +
                 ")"};
  }
  auto array = ReadNpy<std::complex<double>>(file);
  if (!array) return Error{array.error()};
  const std::vector<std::size_t> expected = {static_cast<std::size_t>(f.size()), rows, cols};
  if (array->shape != expected) {
    return Error{file.string() + ": shape " + Shape(array->shape) +
                 " does not match the manifest: expected " + Shape(expected) + " " + dims};
  }
  Blocks blocks(expected[0],
                Eigen::MatrixXcd(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols)));
  const std::complex<double>* p = array->data.data();
  for (std::size_t k = 0; k < expected[0]; ++k) {
    for (std::size_t i = 0; i < rows; ++i) {
      for (std::size_t j = 0; j < cols; ++j, ++p) {
        if (!std::isfinite(p->real()) || !std::isfinite(p->imag())) {
          return Error{file.string() + ": non-finite value at index [" + std::to_string(k) + ", " +
                       std::to_string(i) + ", " + std::to_string(j) + "] (frequency " +
                       Num(f[static_cast<Eigen::Index>(k)]) + " Hz)"};
        }
        blocks[k](static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = *p;
      }
    }
  }
  return blocks;
}

// ---- writing ----

Status WriteBlocks(const fs::path& file, const Blocks& blocks) {
  const std::size_t rows = blocks.empty() ? 0 : static_cast<std::size_t>(blocks[0].rows());
  const std::size_t cols = blocks.empty() ? 0 : static_cast<std::size_t>(blocks[0].cols());
  std::vector<std::complex<double>> data;
  data.reserve(blocks.size() * rows * cols);
  for (const auto& m : blocks) {
    for (Eigen::Index i = 0; i < m.rows(); ++i) {
      for (Eigen::Index j = 0; j < m.cols(); ++j) data.push_back(m(i, j));
    }
  }
  return WriteNpy<std::complex<double>>(file, data, {blocks.size(), rows, cols});
}

Json DofsJson(const std::vector<CoupledDof>& dofs) {
  Json list = Json::array();
  for (const auto& d : dofs) {
    list.push_back({{"name", d.name}, {"node", d.node}, {"direction", d.direction}});
  }
  return list;
}

}  // namespace

const char* FrfQuantityName(FrfQuantity quantity) noexcept {
  switch (quantity) {
    case FrfQuantity::kAccelerance:
      return "accelerance";
    case FrfQuantity::kMobility:
      return "mobility";
    case FrfQuantity::kReceptance:
      return "receptance";
  }
  return "unknown";
}

const char* FrfQuantitySiUnit(FrfQuantity quantity) noexcept {
  switch (quantity) {
    case FrfQuantity::kAccelerance:
      return "m/s^2/N";
    case FrfQuantity::kMobility:
      return "m/s/N";
    case FrfQuantity::kReceptance:
      return "m/N";
  }
  return "?";
}

Status ValidateFrfSet(const FrfSet& set) {
  const std::string si = FrfQuantitySiUnit(set.quantity);
  if (set.unit != si) {
    return Error{"unit " + Quoted(set.unit) + " does not match quantity " +
                 Quoted(FrfQuantityName(set.quantity)) + " (expected " + Quoted(si) + ")"};
  }
  const bool has_decoupled = HasDecoupled(set);
  if (!has_decoupled && !set.coupled) {
    return Error{"neither \"decoupled\" nor \"coupled\" is present: a set needs at least one"};
  }
  if (!set.decoupling.empty() && !IsDecoupling(set.decoupling)) {
    return Error{"decoupling must be \"eq22\", \"eq24\", \"physical\" or \"model\", got " +
                 Quoted(set.decoupling)};
  }
  std::set<std::string> names;
  for (std::size_t i = 0; i < set.paths.size(); ++i) {
    const auto& p = set.paths[i];
    const std::string at = "paths[" + std::to_string(i) + "]";
    if (p.name.empty()) return Error{at + ".name must not be empty"};
    if (!names.insert(p.name).second) {
      return Error{at + ".name " + Quoted(p.name) + " is used by another path"};
    }
    if (!IsDirection(p.direction)) {
      return Error{at + ".direction must be \"x\", \"y\" or \"z\", got " + Quoted(p.direction)};
    }
  }
  std::set<std::pair<std::string, std::string>> channels;
  for (std::size_t i = 0; i < set.channels.size(); ++i) {
    const auto& c = set.channels[i];
    const std::string at = "channels[" + std::to_string(i) + "]";
    if (c.sensor.empty()) return Error{at + ".sensor must not be empty"};
    if (!IsDirection(c.axis)) {
      return Error{at + ".axis must be \"x\", \"y\" or \"z\", got " + Quoted(c.axis)};
    }
    if (!channels.insert({c.sensor, c.axis}).second) {
      return Error{at + " (" + c.sensor + " " + c.axis + ") duplicates another channel"};
    }
  }
  if (has_decoupled) {
    if (set.decoupling.empty()) return Error{"decoupling must be given when decoupled is present"};
    if (set.paths.empty()) return Error{"paths is empty but decoupled is present"};
    if (set.channels.empty()) return Error{"channels is empty but decoupled is present"};
    const auto& f = set.decoupled.frequency_hz;
    if (auto why = CheckFrequencyAxis(f, "frequency")) return Error{*why};
    if (auto why = CheckBlocks(set.decoupled.at, f, static_cast<Eigen::Index>(set.channels.size()),
                               static_cast<Eigen::Index>(set.paths.size()), "decoupled",
                               "(n_channels x n_paths)")) {
      return Error{*why};
    }
  }
  if (set.coupled) {
    const CoupledSet& c = *set.coupled;
    std::set<std::string> dof_names;
    if (c.active.empty()) return Error{"coupled.dofs.a is empty"};
    if (c.passive.empty()) return Error{"coupled.dofs.p is empty"};
    for (auto [list, key] :
         {std::pair{&c.active, "coupled.dofs.a"}, std::pair{&c.passive, "coupled.dofs.p"},
          std::pair{&c.measurement, "coupled.dofs.m"}}) {
      if (auto why = CheckDofs(*list, key, &dof_names)) return Error{*why};
    }
    const auto& f = c.blocks.frequency_hz;
    if (auto why = CheckFrequencyAxis(f, "frequency")) return Error{*why};
    if (has_decoupled && f != set.decoupled.frequency_hz) {
      return Error{"decoupled and coupled must share one frequency axis; they differ"};
    }
    const auto na = static_cast<Eigen::Index>(c.active.size());
    const auto np = static_cast<Eigen::Index>(c.passive.size());
    const auto nm = static_cast<Eigen::Index>(c.measurement.size());
    struct Check {
      const Blocks* blocks;
      Eigen::Index rows, cols;
      const char* what;
      const char* dims;
    };
    std::vector<Check> checks = {{&c.blocks.aa, na, na, "coupled.blocks.aa", "(n_a x n_a)"},
                                 {&c.blocks.pa, np, na, "coupled.blocks.pa", "(n_p x n_a)"},
                                 {&c.blocks.pp, np, np, "coupled.blocks.pp", "(n_p x n_p)"}};
    if (c.blocks.has_ap()) {
      checks.push_back({&c.blocks.ap, na, np, "coupled.blocks.ap", "(n_a x n_p)"});
    }
    if (c.blocks.ma.empty() != c.blocks.mp.empty()) {
      return Error{"coupled.blocks.ma and coupled.blocks.mp must be given together"};
    }
    if (nm > 0 && !c.blocks.has_measurement_points()) {
      return Error{"coupled.dofs.m lists " + std::to_string(nm) +
                   " DOFs but coupled.blocks.ma/mp are absent"};
    }
    if (nm == 0 && c.blocks.has_measurement_points()) {
      return Error{"coupled.blocks.ma/mp are present but coupled.dofs.m is empty"};
    }
    if (nm > 0) {
      checks.push_back({&c.blocks.ma, nm, na, "coupled.blocks.ma", "(n_m x n_a)"});
      checks.push_back({&c.blocks.mp, nm, np, "coupled.blocks.mp", "(n_m x n_p)"});
    }
    for (const Check& check : checks) {
      if (auto why =
              CheckBlocks(*check.blocks, f, check.rows, check.cols, check.what, check.dims)) {
        return Error{*why};
      }
    }
  }
  return Status::Ok();
}

Result<FrfSet> ReadFrfSet(const fs::path& dir) {
  const fs::path manifest_path = dir / kFrfSetManifestName;
  const std::string mf = manifest_path.string();
  if (!std::ifstream(manifest_path)) {
    return Error{mf + ": missing manifest (not an FRF set directory?)"};
  }
  // Bounded, exception-free parse: 1e999 or a manifest nested 100 000 deep is an error.
  Result<Json> parsed = ReadJsonFile<Json>(manifest_path);
  if (!parsed) return Error{parsed.error()};
  const Json root = std::move(parsed.value());
  Manifest m(mf);
  if (!root.is_object()) return Error{mf + ": the manifest must be a JSON object"};

  FrfSet set;
  std::string format;
  if (!m.String(root, "", "format", &format)) return m.error();
  if (format != kFrfSetFormatName) {
    return Error{mf + ": format: expected " + Quoted(kFrfSetFormatName) + ", got " +
                 Quoted(format)};
  }
  const Json* version = m.Get(root, "", "format_version", true);
  if (!version ||
      !m.Type(*version, "format_version", Json::value_t::number_integer, "an integer")) {
    return m.error();
  }
  if (version->get<long long>() != kFrfFormatVersion) {
    return Error{mf + ": format_version " + std::to_string(version->get<long long>()) +
                 " is not supported (this reader reads version " +
                 std::to_string(kFrfFormatVersion) + ")"};
  }
  set.format_version = kFrfFormatVersion;
  std::string quantity;
  if (!m.String(root, "", "description", &set.description, false) ||
      !m.String(root, "", "quantity", &quantity) || !m.String(root, "", "unit", &set.unit) ||
      !m.String(root, "", "decoupling", &set.decoupling, false)) {
    return m.error();
  }
  const auto q = ParseQuantity(quantity);
  if (!q) {
    return Error{mf + ": quantity: unknown value " + Quoted(quantity) +
                 " (expected \"accelerance\", \"mobility\" or \"receptance\")"};
  }
  set.quantity = *q;

  const Json* frequency = m.Object(root, "", "frequency");
  std::string frequency_file, frequency_unit;
  if (!frequency || !m.FileName(*frequency, "frequency", "file", &frequency_file) ||
      !m.String(*frequency, "frequency", "unit", &frequency_unit)) {
    return m.error();
  }
  if (frequency_unit != "Hz") {
    return Error{mf + ": frequency.unit must be \"Hz\", got " + Quoted(frequency_unit)};
  }

  const Json* paths = m.Array(root, "", "paths");
  if (!paths) return m.error();
  for (std::size_t i = 0; i < paths->size(); ++i) {
    const std::string at = "paths[" + std::to_string(i) + "]";
    const Json& item = (*paths)[i];
    if (!m.Type(item, at, Json::value_t::object, "an object")) return m.error();
    TransferPath path;
    if (!m.String(item, at, "name", &path.name) || !m.String(item, at, "bearing", &path.bearing) ||
        !m.String(item, at, "direction", &path.direction)) {
      return m.error();
    }
    const Json* gears = m.Array(item, at, "gears");
    if (!gears) return m.error();
    for (std::size_t g = 0; g < gears->size(); ++g) {
      const std::string gat = at + ".gears[" + std::to_string(g) + "]";
      if (!m.Type((*gears)[g], gat, Json::value_t::string, "a string")) return m.error();
      path.gears.push_back((*gears)[g].get<std::string>());
    }
    set.paths.push_back(std::move(path));
  }
  const Json* channels = m.Array(root, "", "channels");
  if (!channels) return m.error();
  for (std::size_t i = 0; i < channels->size(); ++i) {
    const std::string at = "channels[" + std::to_string(i) + "]";
    const Json& item = (*channels)[i];
    if (!m.Type(item, at, Json::value_t::object, "an object")) return m.error();
    ResponseChannel channel;
    if (!m.String(item, at, "sensor", &channel.sensor) ||
        !m.String(item, at, "axis", &channel.axis)) {
      return m.error();
    }
    set.channels.push_back(std::move(channel));
  }

  const Json* decoupled = m.Object(root, "", "decoupled", false);
  if (m.failed()) return m.error();
  std::string decoupled_file;
  if (decoupled && !m.FileName(*decoupled, "decoupled", "file", &decoupled_file)) return m.error();

  const Json* coupled = m.Object(root, "", "coupled", false);
  if (m.failed()) return m.error();
  if (!decoupled && !coupled) {
    return Error{mf +
                 ": neither \"decoupled\" nor \"coupled\" is present: a set needs at least one"};
  }
  // Metadata first (cheap, and its messages are the most useful), arrays after.
  std::optional<CoupledSet> coupled_set;
  struct BlockFiles {
    std::string aa, pa, pp, ap, ma, mp;
  } files;
  if (coupled) {
    coupled_set.emplace();
    const Json* dofs = m.Object(*coupled, "coupled", "dofs");
    if (!dofs || !ReadDofList(m, *dofs, "coupled.dofs", "a", true, &coupled_set->active) ||
        !ReadDofList(m, *dofs, "coupled.dofs", "p", true, &coupled_set->passive) ||
        !ReadDofList(m, *dofs, "coupled.dofs", "m", false, &coupled_set->measurement)) {
      return m.error();
    }
    const Json* blocks = m.Object(*coupled, "coupled", "blocks");
    const std::string b = "coupled.blocks";
    if (!blocks || !m.FileName(*blocks, b, "aa", &files.aa) ||
        !m.FileName(*blocks, b, "pa", &files.pa) || !m.FileName(*blocks, b, "pp", &files.pp) ||
        !m.FileName(*blocks, b, "ap", &files.ap, false) ||
        !m.FileName(*blocks, b, "ma", &files.ma, false) ||
        !m.FileName(*blocks, b, "mp", &files.mp, false)) {
      return m.error();
    }
    if (files.ma.empty() != files.mp.empty()) {
      return Error{mf + ": coupled.blocks.ma and coupled.blocks.mp must be given together"};
    }
    if (!coupled_set->measurement.empty() && files.ma.empty()) {
      return Error{mf + ": coupled.dofs.m lists " +
                   std::to_string(coupled_set->measurement.size()) +
                   " DOFs but coupled.blocks.ma/mp are absent"};
    }
    if (coupled_set->measurement.empty() && !files.ma.empty()) {
      return Error{mf + ": coupled.blocks.ma/mp are present but coupled.dofs.m is empty or absent"};
    }
  }
  if (decoupled) {
    if (set.paths.empty()) return Error{mf + ": paths is empty but decoupled is present"};
    if (set.channels.empty()) return Error{mf + ": channels is empty but decoupled is present"};
    if (set.decoupling.empty()) {
      return Error{mf + ": missing key \"decoupling\" (required when decoupled is present)"};
    }
  }
  // The remaining metadata checks (directions, duplicates, unit) are shared with the writer.
  {
    FrfSet probe = set;
    probe.decoupled.frequency_hz = Eigen::VectorXd::Zero(1);
    probe.decoupled.at.assign(1,
                              Eigen::MatrixXcd::Zero(static_cast<Eigen::Index>(set.channels.size()),
                                                     static_cast<Eigen::Index>(set.paths.size())));
    if (!decoupled) probe.decoupled = FrfMatrix{};
    if (coupled_set) {
      CoupledSet c = *coupled_set;
      const auto na = static_cast<Eigen::Index>(c.active.size());
      const auto np = static_cast<Eigen::Index>(c.passive.size());
      const auto nm = static_cast<Eigen::Index>(c.measurement.size());
      c.blocks.frequency_hz = Eigen::VectorXd::Zero(1);
      c.blocks.aa.assign(1, Eigen::MatrixXcd::Zero(na, na));
      c.blocks.pa.assign(1, Eigen::MatrixXcd::Zero(np, na));
      c.blocks.pp.assign(1, Eigen::MatrixXcd::Zero(np, np));
      if (nm > 0) {
        c.blocks.ma.assign(1, Eigen::MatrixXcd::Zero(nm, na));
        c.blocks.mp.assign(1, Eigen::MatrixXcd::Zero(nm, np));
      }
      probe.coupled = std::move(c);
    }
    if (Status st = ValidateFrfSet(probe); !st) return Error{mf + ": " + st.error()};
  }

  // Arrays.
  const fs::path freq_path = dir / frequency_file;
  if (!fs::exists(freq_path)) {
    return Error{freq_path.string() +
                 ": missing array file (named by manifest key \"frequency.file\")"};
  }
  auto freq = ReadNpy<double>(freq_path);
  if (!freq) return Error{freq.error()};
  if (freq->shape.size() != 1) {
    return Error{freq_path.string() + ": shape " + Shape(freq->shape) +
                 " is not 1-D: expected (n_freq,)"};
  }
  Eigen::VectorXd f = Eigen::Map<const Eigen::VectorXd>(
      freq->data.data(), static_cast<Eigen::Index>(freq->data.size()));
  if (auto why = CheckFrequencyAxis(f, freq_path.string())) return Error{*why};

  if (decoupled) {
    auto blocks = ReadBlocks(dir / decoupled_file, "decoupled.file", f, set.channels.size(),
                             set.paths.size(), "(n_freq, n_channels, n_paths)");
    if (!blocks) return Error{blocks.error()};
    set.decoupled.frequency_hz = f;
    set.decoupled.at = std::move(blocks.value());
  }
  if (coupled_set) {
    CoupledSet& c = *coupled_set;
    const std::size_t na = c.active.size(), np = c.passive.size(), nm = c.measurement.size();
    struct Load {
      const std::string* file;
      const char* key;
      std::size_t rows, cols;
      const char* dims;
      Blocks* out;
    };
    std::vector<Load> loads = {
        {&files.aa, "coupled.blocks.aa", na, na, "(n_freq, n_a, n_a)", &c.blocks.aa},
        {&files.pa, "coupled.blocks.pa", np, na, "(n_freq, n_p, n_a)", &c.blocks.pa},
        {&files.pp, "coupled.blocks.pp", np, np, "(n_freq, n_p, n_p)", &c.blocks.pp}};
    if (!files.ap.empty()) {
      loads.push_back({&files.ap, "coupled.blocks.ap", na, np, "(n_freq, n_a, n_p)", &c.blocks.ap});
    }
    if (!files.ma.empty()) {
      loads.push_back({&files.ma, "coupled.blocks.ma", nm, na, "(n_freq, n_m, n_a)", &c.blocks.ma});
      loads.push_back({&files.mp, "coupled.blocks.mp", nm, np, "(n_freq, n_m, n_p)", &c.blocks.mp});
    }
    for (const Load& load : loads) {
      auto blocks = ReadBlocks(dir / *load.file, load.key, f, load.rows, load.cols, load.dims);
      if (!blocks) return Error{blocks.error()};
      *load.out = std::move(blocks.value());
    }
    c.blocks.frequency_hz = f;
    set.coupled = std::move(coupled_set);
  }
  return set;
}

Status WriteFrfSet(const FrfSet& set, const fs::path& dir) {
  const std::string where = "cannot write FRF set to " + dir.string() + ": ";
  if (Status st = ValidateFrfSet(set); !st) return Error{where + st.error()};
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) return Error{where + "cannot create directory: " + ec.message()};
  // Remove a previous manifest first, so a crash below never leaves it naming new arrays.
  fs::remove(dir / kFrfSetManifestName, ec);

  const bool has_decoupled = HasDecoupled(set);
  const Eigen::VectorXd& f =
      has_decoupled ? set.decoupled.frequency_hz : set.coupled->blocks.frequency_hz;
  std::vector<double> freq(f.data(), f.data() + f.size());
  if (Status st = WriteNpy<double>(dir / kFrequencyFile, freq, {freq.size()}); !st) return st;

  Json manifest;
  manifest["format"] = kFrfSetFormatName;
  manifest["format_version"] = kFrfFormatVersion;
  manifest["description"] = set.description;
  manifest["quantity"] = FrfQuantityName(set.quantity);
  manifest["unit"] = set.unit;
  if (!set.decoupling.empty()) manifest["decoupling"] = set.decoupling;
  manifest["frequency"] = {{"file", kFrequencyFile}, {"unit", "Hz"}};
  manifest["paths"] = Json::array();
  for (const auto& p : set.paths) {
    manifest["paths"].push_back(
        {{"name", p.name}, {"bearing", p.bearing}, {"direction", p.direction}, {"gears", p.gears}});
  }
  manifest["channels"] = Json::array();
  for (const auto& c : set.channels) {
    manifest["channels"].push_back({{"sensor", c.sensor}, {"axis", c.axis}});
  }
  if (has_decoupled) {
    if (Status st = WriteBlocks(dir / kDecoupledFile, set.decoupled.at); !st) return st;
    manifest["decoupled"] = {{"file", kDecoupledFile}};
  }
  if (set.coupled) {
    const CoupledSet& c = *set.coupled;
    Json dofs = {{"a", DofsJson(c.active)}, {"p", DofsJson(c.passive)}};
    if (!c.measurement.empty()) dofs["m"] = DofsJson(c.measurement);
    Json blocks = Json::object();
    std::vector<std::pair<const char*, const Blocks*>> present = {
        {"aa", &c.blocks.aa}, {"pa", &c.blocks.pa}, {"pp", &c.blocks.pp}};
    if (c.blocks.has_ap()) present.push_back({"ap", &c.blocks.ap});
    if (c.blocks.has_measurement_points()) {
      present.push_back({"ma", &c.blocks.ma});
      present.push_back({"mp", &c.blocks.mp});
    }
    for (const auto& [key, data] : present) {
      const std::string file = std::string("H_") + key + ".npy";
      if (Status st = WriteBlocks(dir / file, *data); !st) return st;
      blocks[key] = file;
    }
    manifest["coupled"] = {{"dofs", dofs}, {"blocks", blocks}};
  }
  // Names are checked by ValidateFrfSet, but a name that is not UTF-8 must be an error, not
  // a json::type_error thrown out of the writer.
  Result<std::string> text = DumpJson(manifest, 2, where + kFrfSetManifestName);
  if (!text) return Error{text.error()};
  std::ofstream out(dir / kFrfSetManifestName, std::ios::trunc);
  out << *text << "\n";
  out.close();
  if (!out) return Error{where + "write error on " + kFrfSetManifestName};
  return Status::Ok();
}

}  // namespace gearpath
