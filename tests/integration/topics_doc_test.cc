// docs/topics.md against the contract and against what gearpathd publishes (issue 12: "every
// field in docs/topics.md matches the IDL and the published values").
//
// 1. The page's field tables (one per topic) against idl/gearpath.idl, parsed here from the
//    text: every field of every topic (nested fields as `paths[i].share`, `band.level`) is
//    documented with its IDL type, bound and key, and the page documents no field the IDL lacks;
//    every enumerator and every constant (with its value) is on the page.
// 2. One published block against the page's definitions: a healthy block of the simulated
//    Table-1 gearbox after the baseline, every result topic of that block checked with the
//    formulas and orders the page states (shares summing to 1, enhancement_percent = 100 rec /
//    raw, indicators as sums of their harmonics, shaft rates in Hz from the tooth counts, the
//    indicator names in the documented order, the block score as the largest set score, ...).
//    The expected figures come from the configuration and the block the test sent, not from
//    the daemon's code.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <numeric>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "tests/integration/gearpathd_fixture.h"

namespace gearpath::testing {
namespace {

std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string Trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

// `sets[i].values[k].name` -> `sets[].values[].name`; `raw_harmonics[5]` -> `raw_harmonics[]`.
std::string NormaliseField(const std::string& name) {
  return std::regex_replace(name, std::regex(R"(\[[^\]]*\])"), "[]");
}

// ---- The IDL, from its text ------------------------------------------------------------------

struct IdlField {
  std::string type;  // normalised as the page writes it: uint64, string<64>, sequence<T, 32>
  bool key = false;
};

struct Idl {
  std::map<std::string, long> constants;
  std::map<std::string, std::vector<std::string>> enums;
  // struct -> members in order: name (with [] for arrays), raw type, key
  struct Member {
    std::string name, type;
    bool key = false;
    std::string array_bound;
  };
  std::map<std::string, std::vector<Member>> structs;
  std::map<std::string, std::string> typedefs;  // Id -> string<ID_LENGTH>

  std::string Bound(const std::string& b) const {
    const std::string t = Trim(b);
    auto c = constants.find(t);
    return c != constants.end() ? std::to_string(c->second) : t;
  }

  // The page's spelling of an IDL type.
  std::string Normalise(const std::string& raw) const {
    std::string t = std::regex_replace(Trim(raw), std::regex(R"(\s+)"), " ");
    if (auto d = typedefs.find(t); d != typedefs.end()) return Normalise(d->second);
    if (t == "unsigned long long") return "uint64";
    if (t == "long long") return "int64";
    if (t == "unsigned long") return "uint32";
    if (t == "long") return "int32";
    std::smatch m;
    if (std::regex_match(t, m, std::regex(R"(string\s*<\s*(\w+)\s*>)"))) {
      return "string<" + Bound(m[1]) + ">";
    }
    if (std::regex_match(t, m, std::regex(R"(sequence\s*<\s*(.+)\s*,\s*(\w+)\s*>)"))) {
      return "sequence<" + Normalise(m[1]) + ", " + Bound(m[2]) + ">";
    }
    return t;
  }
};

Idl ParseIdl(const std::string& path) {
  const std::string text =
      std::regex_replace(ReadText(path), std::regex(R"(//[^\n]*)"), "");  // comments out
  Idl idl;
  const std::regex const_re(R"(const\s+[\w\s]+?\s+(\w+)\s*=\s*(\d+)\s*;)");
  for (auto m = std::sregex_iterator(text.begin(), text.end(), const_re);
       m != std::sregex_iterator(); ++m) {
    idl.constants[(*m)[1]] = std::stol((*m)[2]);
  }
  const std::regex typedef_re(R"(typedef\s+([^;]+?)\s+(\w+)\s*;)");
  for (auto m = std::sregex_iterator(text.begin(), text.end(), typedef_re);
       m != std::sregex_iterator(); ++m) {
    idl.typedefs[(*m)[2]] = (*m)[1];
  }
  const std::regex enum_re(R"(enum\s+(\w+)\s*\{([^}]*)\})");
  for (auto m = std::sregex_iterator(text.begin(), text.end(), enum_re);
       m != std::sregex_iterator(); ++m) {
    const std::string body = (*m)[2];
    const std::regex name_re(R"(\w+)");
    for (auto e = std::sregex_iterator(body.begin(), body.end(), name_re);
         e != std::sregex_iterator(); ++e) {
      idl.enums[(*m)[1]].push_back(e->str());
    }
  }
  const std::regex struct_re(R"(struct\s+(\w+)\s*\{([^}]*)\})");
  for (auto s = std::sregex_iterator(text.begin(), text.end(), struct_re);
       s != std::sregex_iterator(); ++s) {
    std::stringstream body((*s)[2].str());
    std::string statement;
    auto& members = idl.structs[(*s)[1]];
    while (std::getline(body, statement, ';')) {
      statement = Trim(std::regex_replace(statement, std::regex(R"(\s+)"), " "));
      if (statement.empty()) continue;
      Idl::Member member;
      if (statement.rfind("@key ", 0) == 0) {
        member.key = true;
        statement = statement.substr(5);
      }
      std::smatch m;
      EXPECT_TRUE(std::regex_match(statement, m, std::regex(R"((.+)\s+(\w+)\s*(\[(\w+)\])?)")))
          << "unparsed IDL member: " << statement;
      member.type = m[1];
      member.name = m[2];
      member.array_bound = m[4];
      members.push_back(member);
    }
  }
  return idl;
}

// Every documented row a topic's struct gives: nested structs flattened with `.`, sequences of
// structs with `[]` (the sequence itself is a row too), arrays as `name[]` of type `T[N]`.
void Flatten(const Idl& idl, const std::string& type, const std::string& prefix,
             std::map<std::string, IdlField>& out) {
  for (const Idl::Member& m : idl.structs.at(type)) {
    const std::string name = prefix + m.name;
    const std::string t = idl.Normalise(m.type);
    if (idl.structs.count(t)) {  // a nested struct: its fields
      Flatten(idl, t, name + ".", out);
      continue;
    }
    if (!m.array_bound.empty()) {
      out[name + "[]"] = {t + "[" + idl.Bound(m.array_bound) + "]", m.key};
      continue;
    }
    out[name] = {t, m.key};
    std::smatch s;
    const std::string element =
        std::regex_match(t, s, std::regex(R"(sequence<(\w+), \d+>)")) ? s[1].str() : std::string();
    if (idl.structs.count(element)) Flatten(idl, element, name + "[].", out);
  }
}

// ---- The page ----------------------------------------------------------------------------

struct DocRow {
  std::string type;  // the documented type of this field
  bool key = false;
  std::string meaning;
};

struct TopicsDoc {
  std::map<std::string, std::map<std::string, DocRow>> topics;  // struct -> field -> row
  std::map<std::string, std::string> bounds;                    // constant -> value text
  std::string text;
};

// Splits a table row on the `|` that are not escaped (`\|` is a pipe inside a cell).
std::vector<std::string> Cells(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  for (std::size_t i = 1; i < line.size(); ++i) {
    if (line[i] == '|' && line[i - 1] != '\\') {
      cells.push_back(Trim(cell));
      cell.clear();
    } else {
      cell += line[i];
    }
  }
  return cells;
}

std::vector<std::string> Backticked(const std::string& cell) {
  std::vector<std::string> out;
  const std::regex re("`([^`]+)`");
  for (auto m = std::sregex_iterator(cell.begin(), cell.end(), re); m != std::sregex_iterator();
       ++m) {
    out.push_back((*m)[1]);
  }
  return out;
}

TopicsDoc ParseTopicsDoc(const std::string& path) {
  TopicsDoc doc;
  doc.text = ReadText(path);
  std::stringstream lines(doc.text);
  std::string line, topic, table;  // table: "field", "bounds" or ""
  const std::regex topic_re(R"(^### `gearpath/(\w+)`)");
  while (std::getline(lines, line)) {
    std::smatch m;
    if (std::regex_search(line, m, topic_re)) {
      topic = m[1];
      table.clear();
      continue;
    }
    if (line.rfind("## ", 0) == 0 || line.rfind("### ", 0) == 0) topic.clear();
    if (line.rfind("| Field | Type |", 0) == 0) {
      table = topic.empty() ? "" : "field";
      continue;
    }
    if (line.rfind("| Constant | Value |", 0) == 0) {
      table = "bounds";
      continue;
    }
    if (line.rfind("|", 0) != 0) {
      table.clear();
      continue;
    }
    if (table.empty() || line.rfind("|---", 0) == 0 || line.rfind("| ---", 0) == 0) continue;
    const std::vector<std::string> cells = Cells(line);
    if (table == "bounds") {
      const auto name = Backticked(cells.at(0));
      if (!name.empty()) doc.bounds[name[0]] = cells.at(1);
      continue;
    }
    EXPECT_GE(cells.size(), 4u) << "topics.md row with fewer than 4 cells: " << line;
    if (cells.size() < 4) continue;
    const std::vector<std::string> names = Backticked(cells[0]);
    const std::vector<std::string> types = Backticked(cells[1]);
    const bool key = cells[1].find("**key**") != std::string::npos;
    EXPECT_FALSE(names.empty()) << "topics.md row without a field name: " << line;
    EXPECT_TRUE(types.size() == 1 || types.size() == names.size())
        << "topics.md row: " << names.size() << " fields but " << types.size()
        << " types: " << line;
    for (std::size_t i = 0; i < names.size() && !types.empty(); ++i) {
      const std::string field = NormaliseField(names[i]);
      EXPECT_EQ(doc.topics[topic].count(field), 0u) << topic << "." << field << " twice";
      doc.topics[topic][field] = {types.size() == 1 ? types[0] : types[i], key, cells[3]};
    }
  }
  return doc;
}

const std::string kIdlPath = GEARPATH_SOURCE_DIR "/idl/gearpath.idl";
const std::string kTopicsPath = GEARPATH_SOURCE_DIR "/docs/topics.md";

TEST(TopicsDoc, DocumentsEveryFieldOfEveryTopicWithItsIdlTypeAndKeyAndNoOther) {
  const Idl idl = ParseIdl(kIdlPath);
  const TopicsDoc doc = ParseTopicsDoc(kTopicsPath);
  // The topics are the keyed structs.
  std::set<std::string> idl_topics, doc_topics;
  for (const auto& [name, members] : idl.structs) {
    if (std::any_of(members.begin(), members.end(), [](const auto& m) { return m.key; })) {
      idl_topics.insert(name);
    }
  }
  for (const auto& [name, rows] : doc.topics) doc_topics.insert(name);
  ASSERT_EQ(idl_topics.size(), 8u) << "the IDL parse found the wrong topics";
  EXPECT_EQ(doc_topics, idl_topics);

  std::size_t compared = 0;
  for (const std::string& topic : idl_topics) {
    std::map<std::string, IdlField> fields;
    Flatten(idl, topic, "", fields);
    const auto documented = doc.topics.find(topic);
    if (documented == doc.topics.end()) continue;
    for (const auto& [name, field] : fields) {
      const auto row = documented->second.find(name);
      if (row == documented->second.end()) {
        ADD_FAILURE() << "gearpath/" << topic << ": IDL field " << name
                      << " is not documented in docs/topics.md";
        continue;
      }
      EXPECT_EQ(row->second.type, field.type) << "gearpath/" << topic << "." << name;
      EXPECT_EQ(row->second.key, field.key) << "gearpath/" << topic << "." << name << " key";
      ++compared;
    }
    for (const auto& [name, row] : documented->second) {
      EXPECT_EQ(fields.count(name), 1u) << "gearpath/" << topic << ": docs/topics.md documents "
                                        << name << ", which the IDL does not have";
    }
  }
  EXPECT_GE(compared, 100u);  // the eight topics have well over a hundred fields
}

TEST(TopicsDoc, NamesEveryEnumeratorAndEveryConstantWithItsValue) {
  const Idl idl = ParseIdl(kIdlPath);
  const TopicsDoc doc = ParseTopicsDoc(kTopicsPath);
  ASSERT_GE(idl.enums.size(), 6u);
  for (const auto& [name, values] : idl.enums) {
    for (const std::string& v : values) {
      EXPECT_NE(doc.text.find("`" + v + "`"), std::string::npos)
          << "enumerator " << name << "::" << v << " is not named in docs/topics.md";
    }
  }
  ASSERT_GE(idl.constants.size(), 14u);
  for (const auto& [name, value] : idl.constants) {
    const auto row = doc.bounds.find(name);
    if (row == doc.bounds.end()) {
      ADD_FAILURE() << "constant " << name << " is not in the bounds table of docs/topics.md";
      continue;
    }
    std::string digits;
    for (char c : row->second) {
      if (std::isdigit(static_cast<unsigned char>(c))) digits += c;
    }
    EXPECT_EQ(digits, std::to_string(value)) << name << ": the page says " << row->second;
  }
}

// ---- One published block against the page ------------------------------------------------

// The documented indicator names of a set, in order: the fixed list of the `values[k].name` row,
// then `sideband_<mesh>` per mesh of the group, then `exclusive_residual`.
std::vector<std::string> DocumentedFixedIndicatorNames(const TopicsDoc& doc) {
  const std::string meaning =
      doc.topics.at("ConditionIndicators").at("sets[].values[].name").meaning;
  std::vector<std::string> names;
  for (const std::string& n : Backticked(meaning.substr(0, meaning.find("then")))) {
    names.push_back(n);
  }
  return names;
}

constexpr int kLearningBlocks = 4;  // the fixture's baseline.learning_blocks

TEST_F(GearpathdOverDds, OnePublishedBlockMeetsTheDefinitionsOfDocsTopics) {
  const TopicsDoc doc = ParseTopicsDoc(kTopicsPath);
  const json& machine = config_["machines"][0];

  // The shaft rates from the tooth counts of the configured train (input shaft first).
  const json& train = machine["gear_train"];
  std::map<std::string, int> teeth;
  std::map<std::string, std::string> shaft_of_gear;
  for (const json& g : train["gears"]) teeth[g["name"]] = g["teeth"];
  for (const json& s : train["shafts"]) {
    for (const json& g : s["gears"]) shaft_of_gear[g] = s["name"];
  }
  std::vector<std::string> shaft_order;
  for (const json& s : train["shafts"]) shaft_order.push_back(s["name"]);
  const double speed_hz = 10.0;  // the simulator's 600 r/min
  std::map<std::string, double> rate{{shaft_order.at(0), speed_hz}};
  for (const json& stage : train["stages"]) {  // driver before driven, in stage order
    const std::string driver = stage["driver"], driven = stage["driven"];
    rate[shaft_of_gear.at(driven)] =
        rate.at(shaft_of_gear.at(driver)) * teeth.at(driver) / teeth.at(driven);
  }
  // Rate groups: distinct rates, in shaft order; the meshes of each group.
  std::vector<double> group_rates;
  for (const std::string& s : shaft_order) {
    if (std::none_of(group_rates.begin(), group_rates.end(),
                     [&](double r) { return std::abs(r - rate.at(s)) < 1e-9; })) {
      group_rates.push_back(rate.at(s));
    }
  }
  ASSERT_EQ(group_rates.size(), 2u);  // Table 1: 10 Hz and 7 Hz
  EXPECT_NEAR(group_rates[1], 7.0, 1e-12);

  // The baseline, then one block that is judged.
  GearboxSimulator sim = Table1Simulator(FaultType::kNone, "", 31);
  AccelBlock block;
  std::uint64_t seq = 1;
  for (; seq <= kLearningBlocks + 1; ++seq) {
    sim.NextBlock(block);
    block.sequence = seq;
    block.t0_ns = 1'700'000'000'000'000'000 + static_cast<std::int64_t>(seq) * 1'024'000'000;
    ASSERT_DOUBLE_EQ(block.speed_hz, speed_hz);
    Publish(block);
  }
  const std::uint64_t last = seq - 1;
  const std::int64_t t0 = block.t0_ns;
  ASSERT_TRUE(WaitStatus([&](const auto& m) { return m.blocks_processed == last; }, 90s))
      << last_status_.last_rejection_reason;
  EXPECT_EQ(last_status_.blocks_received, last);
  EXPECT_EQ(last_status_.blocks_rejected, 0u);
  auto of_block = [&](const auto& r) { return r.block_sequence == last; };
  auto dominant = WaitResult<gearpath_DominantPath>(*dominant_reader_, of_block, 10s);
  auto gear = WaitResult<gearpath_SuspectedGear>(*gear_reader_, of_block, 10s);
  auto envelope = WaitResult<gearpath_EnvelopeIndicators>(*indicators_reader_, of_block, 10s);
  auto condition = WaitResult<gearpath_ConditionIndicators>(*condition_reader_, of_block, 10s);
  ASSERT_TRUE(dominant && gear && envelope && condition);

  // "Every result carries block_sequence and block_t0_ns" of its block (ns since the epoch).
  for (auto [seq_seen, t0_seen] :
       {std::pair{(*dominant)->block_sequence, (*dominant)->block_t0_ns},
        std::pair{(*gear)->block_sequence, (*gear)->block_t0_ns},
        std::pair{(*envelope)->block_sequence, (*envelope)->block_t0_ns},
        std::pair{(*condition)->block_sequence, (*condition)->block_t0_ns}}) {
    EXPECT_EQ(seq_seen, last);
    EXPECT_EQ(t0_seen, t0);
  }

  auto set = daemon::BuiltinFrfSet("table1");
  ASSERT_TRUE(set.ok()) << set.error();

  // DominantPath: every path in FRF-set order; path_name == paths[path_index].name; shares in
  // [0, 1] summing to 1; the dominant path has the largest criterion; the daemon's default
  // criterion is CRITERION_SIDEBAND_ENERGY (configured "sideband_energy"), an excess >= 0 once
  // the baseline is known; the band within (0, Nyquist].
  {
    const auto& d = **dominant;
    const auto paths = dds::View(d.paths);
    ASSERT_EQ(paths.size(), set->paths.size());
    double sum = 0.0;
    for (std::size_t i = 0; i < paths.size(); ++i) {
      EXPECT_EQ(dds::GetString(paths[i].name), set->paths[i].name);
      EXPECT_GE(paths[i].share, 0.0);
      EXPECT_LE(paths[i].share, 1.0);
      EXPECT_GE(paths[i].criterion, 0.0);
      sum += paths[i].share;
    }
    EXPECT_NEAR(sum, 1.0, 1e-9);
    ASSERT_LT(d.path_index, paths.size());
    EXPECT_EQ(dds::GetString(d.path_name), dds::GetString(paths[d.path_index].name));
    for (const auto& p : paths) EXPECT_LE(p.criterion, paths[d.path_index].criterion);
    EXPECT_EQ(machine["analysis"]["dominant_path"]["criterion"], "sideband_energy");
    EXPECT_EQ(d.criterion, gearpath_CRITERION_SIDEBAND_ENERGY);
    EXPECT_GE(d.band_lo_hz, 0.0);
    EXPECT_LT(d.band_lo_hz, d.band_hi_hz);
    EXPECT_LE(d.band_hi_hz, kSampleRate / 2);
  }

  // SuspectedGear: judged (not LEARNING) after the baseline; confidence in [0, 1]; gear_name
  // empty when NO_FAULT, else among the candidates (if any) and its shaft's rate given in Hz.
  {
    const auto& g = **gear;
    EXPECT_NE(g.state, gearpath_LEARNING);
    EXPECT_GE(g.confidence, 0.0);
    EXPECT_LE(g.confidence, 1.0);
    const std::string name = std::string(dds::GetString(g.gear_name));
    if (g.state == gearpath_NO_FAULT) {
      EXPECT_EQ(name, "");
    } else {
      ASSERT_TRUE(shaft_of_gear.count(name)) << name;
      EXPECT_EQ(dds::GetString(g.shaft_name), shaft_of_gear.at(name));
      EXPECT_NEAR(g.characteristic_frequency_hz, rate.at(shaft_of_gear.at(name)), 1e-9);
      const auto candidates = dds::View(g.candidates);
      if (!candidates.empty()) {
        EXPECT_TRUE(std::any_of(candidates.begin(), candidates.end(),
                                [&](const auto& c) { return dds::GetString(c) == name; }));
      }
    }
    EXPECT_FALSE(dds::GetString(g.reason).empty());
  }

  // EnvelopeIndicators: one entry per shaft, input shaft first, at its rotation frequency in
  // Hz; each indicator the sum of its five SES harmonic amplitudes; enhancement_percent =
  // 100 x reconstructed / raw; thresholds learned (> 0); the speed and its source as sent;
  // the band inside (0, Nyquist).
  {
    const auto& e = **envelope;
    const auto shafts = dds::View(e.shafts);
    ASSERT_EQ(shafts.size(), shaft_order.size());
    for (std::size_t i = 0; i < shafts.size(); ++i) {
      const auto& s = shafts[i];
      const std::string name = std::string(dds::GetString(s.shaft_name));
      EXPECT_EQ(name, shaft_order[i]);
      EXPECT_NEAR(s.characteristic_frequency_hz, rate.at(shaft_order[i]), 1e-9) << name;
      const double raw_sum =
          std::accumulate(std::begin(s.raw_harmonics), std::end(s.raw_harmonics), 0.0);
      const double rec_sum = std::accumulate(std::begin(s.reconstructed_harmonics),
                                             std::end(s.reconstructed_harmonics), 0.0);
      EXPECT_NEAR(s.raw_indicator, raw_sum, 1e-12 * std::max(1.0, raw_sum)) << name;
      EXPECT_NEAR(s.reconstructed_indicator, rec_sum, 1e-12 * std::max(1.0, rec_sum)) << name;
      for (double h : s.raw_harmonics) EXPECT_GE(h, 0.0) << name;
      ASSERT_GT(s.raw_indicator, 0.0) << name;
      EXPECT_NEAR(s.enhancement_percent, 100.0 * s.reconstructed_indicator / s.raw_indicator,
                  1e-9 * s.enhancement_percent)
          << name;
      EXPECT_GT(s.raw_threshold, 0.0) << name;
      EXPECT_GT(s.reconstructed_threshold, 0.0) << name;
    }
    EXPECT_DOUBLE_EQ(e.speed_hz, speed_hz);
    EXPECT_EQ(e.speed_source, gearpath_SPEED_ACQUISITION_TACHOMETER);
    EXPECT_GT(e.band.width_hz, 0.0);
    EXPECT_GE(e.band.centre_hz - e.band.width_hz / 2, -1e-9);
    EXPECT_LE(e.band.centre_hz + e.band.width_hz / 2, kSampleRate / 2 + 1e-9);
    EXPECT_GE(e.band.level, 0.0);
    EXPECT_TRUE(std::isfinite(e.band.kurtosis));
  }

  // ConditionIndicators: sets signal-major, measured channels (FRF row order) then the paths'
  // contributions then their forces (FRF path order), the same rate groups in the same order
  // for every signal; each set's values named as the page lists them; contributions and forces
  // scored 0; the block score the largest set score, named by top_*; exceedances within the
  // window; the baseline complete.
  {
    const auto& c = **condition;
    EXPECT_GT(c.limit_z, 0.0);
    EXPECT_GT(c.clear_level, 0.0);
    EXPECT_LT(c.clear_level, 1.0);
    EXPECT_DOUBLE_EQ(c.clear_level, machine["analysis"]["alarm"]["clear_level"].get<double>());
    EXPECT_EQ(c.window, machine["analysis"]["alarm"]["window"].get<std::uint32_t>());
    EXPECT_LE(c.exceed_count, c.window);
    EXPECT_EQ(c.baseline_blocks_needed, std::uint32_t{kLearningBlocks});
    EXPECT_EQ(c.baseline_blocks_learned, c.baseline_blocks_needed);
    EXPECT_EQ(c.sets_omitted, 0u);
    EXPECT_EQ(c.values_omitted, 0u);

    std::vector<std::pair<int, std::string>> signals;  // source, signal: the documented order
    for (const auto& ch : set->channels)
      signals.push_back({gearpath_SIGNAL_MEASURED, ch.sensor + "/" + ch.axis});
    for (const auto& p : set->paths) signals.push_back({gearpath_SIGNAL_CONTRIBUTION, p.name});
    for (const auto& p : set->paths) signals.push_back({gearpath_SIGNAL_FORCE, p.name});
    const auto sets = dds::View(c.sets);
    ASSERT_EQ(sets.size(), signals.size() * group_rates.size());

    const std::vector<std::string> fixed = DocumentedFixedIndicatorNames(doc);
    ASSERT_EQ(fixed.size(), 14u) << "the documented list of indicator names changed";
    double best = -1.0;
    std::string best_signal, best_shaft;
    for (std::size_t i = 0; i < sets.size(); ++i) {
      const auto& s = sets[i];
      const auto& [source, signal] = signals[i / group_rates.size()];
      const double group_rate = group_rates[i % group_rates.size()];
      EXPECT_EQ(s.source, source) << i;
      EXPECT_EQ(dds::GetString(s.signal), signal) << i;
      EXPECT_NEAR(s.shaft_hz, group_rate, 1e-9) << i;
      const std::string shaft = std::string(dds::GetString(s.shaft));
      // "the (first) shaft turning at that rate"
      const auto first = std::find_if(
          shaft_order.begin(), shaft_order.end(),
          [&](const std::string& n) { return std::abs(rate.at(n) - group_rate) < 1e-9; });
      EXPECT_EQ(shaft, *first) << i;
      const double block_s = static_cast<double>(kBlockLength) / kSampleRate;
      EXPECT_GE(s.revolutions, 1) << i;
      EXPECT_LE(s.revolutions, static_cast<int>(std::floor(block_s * group_rate))) << i;

      // Names: the fixed list, sideband_<driver>-<driven> per mesh with a gear at this rate
      // (stage order), exclusive_residual.
      std::vector<std::string> expected = fixed;
      for (const json& stage : train["stages"]) {
        const std::string driver = stage["driver"], driven = stage["driven"];
        if (std::abs(rate.at(shaft_of_gear.at(driver)) - group_rate) < 1e-9 ||
            std::abs(rate.at(shaft_of_gear.at(driven)) - group_rate) < 1e-9) {
          expected.push_back("sideband_" + driver + "-" + driven);
        }
      }
      expected.push_back("exclusive_residual");
      std::vector<std::string> names;
      bool any_z = false;
      for (const auto& v : dds::View(s.values)) {
        names.emplace_back(dds::GetString(v.name));
        EXPECT_TRUE(std::isfinite(v.value)) << names.back();
        any_z = any_z || v.z != 0.0;
      }
      EXPECT_EQ(names, expected) << "set " << i << " (" << signal << " at " << group_rate << " Hz)";
      if (source == gearpath_SIGNAL_MEASURED) {
        EXPECT_TRUE(any_z) << "a judged measured set has z-scores";
        if (s.score > best) {
          best = s.score;
          best_signal = signal;
          best_shaft = shaft;
        }
      } else {
        EXPECT_EQ(s.score, 0.0) << "contributions and forces do not raise the score: " << i;
      }
    }
    EXPECT_DOUBLE_EQ(c.score, best);
    EXPECT_EQ(dds::GetString(c.top_signal), best_signal);
    EXPECT_EQ(dds::GetString(c.top_shaft), best_shaft);
    EXPECT_FALSE(dds::GetString(c.top_indicator).empty());
  }
}

}  // namespace
}  // namespace gearpath::testing
