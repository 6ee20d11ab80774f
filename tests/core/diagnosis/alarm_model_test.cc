// AlarmModel: every transition rule on hand-made sequences, the healthy-stream alarm fraction
// against the renewal formula (Monte Carlo), flicker of a steady fault, the latched vote,
// option and state validation, allocation-free Update.
#include "core/diagnosis/alarm_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

// The counting operator new of this executable lives in robust_baseline_test.cc.
namespace diagnosis_alloc {
extern bool counting;
extern long allocations;
}  // namespace diagnosis_alloc

namespace gearpath {
namespace {

using S = FaultState;

AlarmModel Make(const AlarmOptions& o = {}) {
  auto m = AlarmModel::Create(o);
  EXPECT_TRUE(m.ok()) << (m.ok() ? "" : m.error());
  return std::move(m).value();
}

AlarmEvidence Block(double score, int vote = -1) { return {false, score, vote}; }

// Feeds scores (after one learning block) and returns the state after each.
std::vector<S> Feed(AlarmModel& m, const std::vector<double>& scores) {
  std::vector<S> out;
  for (double s : scores) out.push_back(m.Update(Block(s)).state);
  return out;
}

TEST(AlarmModelTest, LearningBlocksReportLearningAndTheFirstQuietBlockNoFault) {
  AlarmModel m = Make();
  EXPECT_EQ(m.status().state, S::kLearning);
  EXPECT_EQ(m.Update({true, 5.0, 1}).state, S::kLearning);  // scores ignored while learning
  EXPECT_EQ(m.Update({true, 5.0, 1}).blocks_in_state, 2);
  const AlarmStatus& st = m.Update(Block(0.2));
  EXPECT_EQ(st.state, S::kNoFault);
  EXPECT_EQ(st.blocks_in_state, 1);
  EXPECT_EQ(st.exceed_count, 0);
  EXPECT_EQ(st.window, 5);
}

TEST(AlarmModelTest, OneExceedanceSuspectsAndASecondWithinTheWindowAlarms) {
  AlarmModel m = Make();
  EXPECT_EQ(Feed(m, {0.1, 1.0, 0.2, 1.3}),
            (std::vector<S>{S::kNoFault, S::kSuspected, S::kSuspected, S::kAlarm}));
  EXPECT_EQ(m.status().exceed_count, 2);
  EXPECT_EQ(m.status().blocks_in_state, 1);
}

TEST(AlarmModelTest, SuspicionClearsAfterClearBlocksQuietBlocks) {
  AlarmModel m = Make();
  EXPECT_EQ(
      Feed(m, {1.5, 0.1, 0.1, 0.1, 0.1}),
      (std::vector<S>{S::kSuspected, S::kSuspected, S::kSuspected, S::kNoFault, S::kNoFault}));
  EXPECT_EQ(m.status().exceed_count, 0);  // the clear empties the window
}

TEST(AlarmModelTest, HysteresisCountsScoresOverTheClearLevelOnlyOnceActive) {
  AlarmModel m = Make();
  // In kNoFault 0.8 is no exceedance...
  EXPECT_EQ(Feed(m, {0.8, 0.8, 0.8}), (std::vector<S>{S::kNoFault, S::kNoFault, S::kNoFault}));
  EXPECT_EQ(m.status().exceed_count, 0);
  // ...once suspected it is: 1.2 then 0.8 makes two exceedances of the last five.
  EXPECT_EQ(Feed(m, {1.2, 0.8}), (std::vector<S>{S::kSuspected, S::kAlarm}));
}

TEST(AlarmModelTest, AlarmHoldsOverTheClearLevelAndClearsOnlyAfterConsecutiveQuietBlocks) {
  AlarmModel m = Make();
  Feed(m, {2.0, 2.0});
  ASSERT_EQ(m.status().state, S::kAlarm);
  // Scores between the clear level and 1 keep it; a quiet run broken by 0.75 starts over.
  EXPECT_EQ(Feed(m, {0.9, 0.71, 0.1, 0.1, 0.75, 0.1, 0.1}), (std::vector<S>(7, S::kAlarm)));
  EXPECT_EQ(m.status().blocks_in_state, 8);
  const AlarmStatus& st = m.Update(Block(0.1));  // third consecutive quiet block
  EXPECT_EQ(st.state, S::kNoFault);              // straight to kNoFault, never kSuspected
  EXPECT_EQ(st.blocks_in_state, 1);
}

TEST(AlarmModelTest, AfterAClearTheNextExceedanceOnlySuspects) {
  AlarmModel m = Make();
  Feed(m, {2.0, 2.0, 0.0, 0.0, 0.0});
  ASSERT_EQ(m.status().state, S::kNoFault);
  // The two old exceedances are still within the last 5 blocks but were emptied by the clear,
  // so kAlarm -> kNoFault -> kAlarm takes clear_blocks + alarm_k blocks, not 4.
  EXPECT_EQ(Feed(m, {2.0, 2.0}), (std::vector<S>{S::kSuspected, S::kAlarm}));
}

TEST(AlarmModelTest, ExceedancesOlderThanTheWindowDropOut) {
  AlarmOptions o;
  o.suspect_k = 2;
  o.alarm_k = 3;
  AlarmModel m = Make(o);
  // Two exceedances five blocks apart are never together in a window of five.
  EXPECT_EQ(Feed(m, {1.0, 0.0, 0.0, 0.0, 0.0, 1.0}), (std::vector<S>(6, S::kNoFault)));
  EXPECT_EQ(m.status().exceed_count, 1);
  // Three apart they are: the second suspects; a third alarms.
  EXPECT_EQ(Feed(m, {0.0, 0.0, 1.0, 1.0}),
            (std::vector<S>{S::kNoFault, S::kNoFault, S::kSuspected, S::kAlarm}));
}

TEST(AlarmModelTest, KOfNReachedAtOnceGoesStraightToAlarm) {
  AlarmOptions o;
  o.suspect_k = 2;
  o.alarm_k = 2;
  AlarmModel m = Make(o);
  EXPECT_EQ(Feed(m, {1.0, 0.0, 1.0}), (std::vector<S>{S::kNoFault, S::kNoFault, S::kAlarm}));
}

TEST(AlarmModelTest, AlarmNeedsTheCurrentBlockToExceedUnlessAlreadyInAlarm) {
  // A restored state that already holds alarm_k exceedances but is only suspected: a block
  // that does not exceed must not raise the alarm.
  AlarmModelState s;
  s.state = S::kSuspected;
  s.exceed_bits = 0b110;
  AlarmModel m = AlarmModel::FromState(s).value();
  EXPECT_EQ(m.Update(Block(0.5)).state, S::kSuspected);
  EXPECT_EQ(m.Update(Block(0.9)).state, S::kAlarm);
}

TEST(AlarmModelTest, NaNScoreHoldsTheStateAndTheQuietRun) {
  AlarmModel m = Make();
  Feed(m, {2.0, 2.0, 0.0, 0.0});
  EXPECT_EQ(m.Update(Block(NAN)).state, S::kAlarm);
  EXPECT_EQ(m.status().blocks_in_state, 4);
  EXPECT_EQ(m.Update(Block(0.0)).state, S::kNoFault);  // third quiet block
}

TEST(AlarmModelTest, LearningAgainResetsEverything) {
  AlarmModel m = Make();
  Feed(m, {2.0, 2.0});
  EXPECT_EQ(m.Update({true, 0.0, -1}).state, S::kLearning);
  EXPECT_EQ(m.status().latched_vote, -1);
  EXPECT_EQ(Feed(m, {2.0}), (std::vector<S>{S::kSuspected}));
}

TEST(AlarmModelTest, DetectionDelayIsAlarmKMinusOneBlocksAfterTheFirstExceedance) {
  AlarmOptions o;
  o.n = 8;
  o.alarm_k = 4;
  AlarmModel m = Make(o);
  const auto states = Feed(m, {0.0, 0.0, 3.0, 3.0, 3.0, 3.0});
  EXPECT_EQ(states[2], S::kSuspected);
  EXPECT_EQ(states[4], S::kSuspected);
  EXPECT_EQ(states[5], S::kAlarm);
}

TEST(AlarmModelTest, LatchedVoteBeatsAMinorityFlickerAndTiesGoToTheMostRecent) {
  AlarmModel m = Make();
  m.Update(Block(2.0, 3));
  EXPECT_EQ(m.status().latched_vote, 3);
  m.Update(Block(2.0, 1));
  EXPECT_EQ(m.status().latched_vote, 1);  // 3 vs 1, tie: the most recent
  m.Update(Block(2.0, 3));
  EXPECT_EQ(m.status().latched_vote, 3);
  m.Update(Block(2.0, 1));
  EXPECT_EQ(m.status().latched_vote, 1);  // 2 vs 2
  m.Update(Block(2.0, 3));
  m.Update(Block(2.0, 3));  // ring of 5: {1, 3, 1, 3, 3}
  EXPECT_EQ(m.status().latched_vote, 3);
  m.Update(Block(2.0, 1));  // {3, 1, 3, 3, 1}: 3 keeps the majority
  EXPECT_EQ(m.status().latched_vote, 3);
  m.Update(Block(2.0, -1));  // no localisation: not kept
  m.Update(Block(0.3, 7));   // quiet block: its vote is not kept
  EXPECT_EQ(m.status().latched_vote, 3);
  m.Update(Block(0.0, 7));
  m.Update(Block(0.0, 7));  // cleared
  EXPECT_EQ(m.status().state, S::kNoFault);
  EXPECT_EQ(m.status().latched_vote, -1);
}

// A fault on gear 2 localised right in 80 % of its blocks, on gear 0 or 4 otherwise. The
// latch is wrong only when gear 2 is not the plurality of the last 5 votes (~3 %), and it
// changes far less often than the raw vote (which changes in ~1/3 of the blocks).
TEST(AlarmModelTest, LatchedVoteOfAFaultWithAFlickeringMinorityStaysOnTheMajority) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  AlarmModel m = Make();
  int wrong = 0;
  int raw_wrong = 0;
  int changes = 0;
  int raw_changes = 0;
  int previous_raw = -1;
  int previous_latch = -1;
  const int blocks = 20000;
  for (int t = 0; t < blocks; ++t) {
    const double r = u(rng);
    const int vote = r < 0.8 ? 2 : (r < 0.9 ? 0 : 4);
    m.Update(Block(1.5, vote));
    const int latch = m.status().latched_vote;
    if (t >= 5) {
      raw_wrong += vote != 2 ? 1 : 0;
      wrong += latch != 2 ? 1 : 0;
      raw_changes += vote != previous_raw ? 1 : 0;
      changes += latch != previous_latch ? 1 : 0;
    }
    previous_raw = vote;
    previous_latch = latch;
  }
  std::printf("[ info ] votes wrong %.2f %% raw, %.2f %% latched; changes %d raw, %d latched\n",
              100.0 * raw_wrong / blocks, 100.0 * wrong / blocks, raw_changes, changes);
  EXPECT_LT(wrong, raw_wrong / 4);
  EXPECT_LT(changes, raw_changes / 5);
}

// Healthy stream: score = |z| / 1.959964 with z ~ N(0, 1), so p = P(score >= 1) = 0.05 and
// q = P(score >= 0.7) = P(|z| >= 1.372) = 0.170. ExpectedHealthyFractions gives the exact
// long-run fractions of the renewal process (alarm 7.7 %, suspected 10.3 %). 200 000 blocks
// hold ~3 500 alarm episodes; their lengths vary (mean 4.4 blocks, sd ~2), so the relative
// standard error of the alarm fraction is ~2 %: tolerance 8 % relative (4 sigma).
TEST(AlarmModelTest, HealthyAlarmFractionMatchesTheRenewalFormula) {
  const double z05 = 1.959963984540054;
  const double p = 0.05;
  const double q = std::erfc(0.7 * z05 / std::sqrt(2.0));
  const AlarmFractions expected = AlarmModel::ExpectedHealthyFractions(p, q, {});
  std::mt19937_64 rng(99);
  std::normal_distribution<double> g(0.0, 1.0);
  AlarmModel m = Make();
  const int blocks = 200000;
  int alarm = 0;
  int suspected = 0;
  for (int t = 0; t < blocks; ++t) {
    const S s = m.Update(Block(std::fabs(g(rng)) / z05)).state;
    alarm += s == S::kAlarm ? 1 : 0;
    suspected += s == S::kSuspected ? 1 : 0;
  }
  const double f_alarm = static_cast<double>(alarm) / blocks;
  const double f_suspected = static_cast<double>(suspected) / blocks;
  std::printf(
      "[ info ] p %.3f q %.4f: alarm %.4f (formula %.4f, c^2 p q %.4f), suspected %.4f "
      "(formula %.4f)\n",
      p, q, f_alarm, expected.alarm, 9.0 * p * q, f_suspected, expected.suspected);
  EXPECT_NEAR(f_alarm, expected.alarm, 0.08 * expected.alarm);
  EXPECT_NEAR(f_suspected, expected.suspected, 0.08 * expected.suspected);
}

// Without scores between the clear level and 1 (q = p) the hysteresis adds nothing and the
// alarm fraction is ~c^2 p^2, of the order of the textbook C(n, 2) p^2.
TEST(AlarmModelTest, HealthyAlarmFractionWithoutHysteresisMassMatchesTheFormula) {
  const double p = 0.05;
  const AlarmFractions expected = AlarmModel::ExpectedHealthyFractions(p, p, {});
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  AlarmModel m = Make();
  const int blocks = 200000;
  int alarm = 0;
  for (int t = 0; t < blocks; ++t) {
    const double score = u(rng) < p ? 1.0 + u(rng) : 0.7 * u(rng);
    alarm += m.Update(Block(score)).state == S::kAlarm ? 1 : 0;
  }
  const double f_alarm = static_cast<double>(alarm) / blocks;
  std::printf("[ info ] q = p = %.2f: alarm %.5f (formula %.5f, C(5,2) p^2 = %.5f)\n", p, f_alarm,
              expected.alarm, 10.0 * p * p);
  // ~1 000 episodes, ~3 blocks each: relative standard error ~3.5 %; tolerance 15 %.
  EXPECT_NEAR(f_alarm, expected.alarm, 0.15 * expected.alarm);
}

// A steady fault exceeding in 80 % of its blocks: score = 1 + 0.35 (0.8416 + z), so
// P(score < 1) = 0.2 and P(score < 0.7) = P(z < -1.699) = 0.045. More than one change in a
// 5-block window needs 3 consecutive blocks under 0.7 (~1e-4 per block, ~5 windows each).
TEST(AlarmModelTest, SteadyFaultFlipsAtMostOnceInFiveBlocks) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g(0.0, 1.0);
  AlarmModel m = Make();
  const int blocks = 200000;
  std::vector<S> states;
  states.reserve(blocks);
  for (int t = 0; t < blocks; ++t) {
    states.push_back(m.Update(Block(1.0 + 0.35 * (0.8416 + g(rng)))).state);
  }
  std::size_t onset = 0;
  while (onset < states.size() && states[onset] != S::kAlarm) ++onset;
  ASSERT_LT(onset, 10u);
  long windows = 0;
  long calm = 0;
  long changes = 0;
  for (std::size_t t = onset + 1; t + 5 <= states.size(); ++t) {
    int c = 0;  // changes into each of the 5 blocks t .. t + 4
    for (std::size_t i = t; i < t + 5; ++i) c += states[i] != states[i - 1] ? 1 : 0;
    ++windows;
    calm += c <= 1 ? 1 : 0;
    changes += states[t] != states[t - 1] ? 1 : 0;
  }
  const double fraction = static_cast<double>(calm) / static_cast<double>(windows);
  std::printf(
      "[ info ] steady fault: %.4f %% of 5-block windows with <= 1 change, %ld changes "
      "in %ld blocks\n",
      100.0 * fraction, changes, windows);
  EXPECT_GE(fraction, 0.99);
}

TEST(AlarmModelTest, InvalidOptionsAreRejectedNamingTheField) {
  auto error_of = [](const AlarmOptions& o) {
    auto r = AlarmModel::Create(o);
    return r.ok() ? std::string("accepted") : r.error();
  };
  AlarmOptions o;
  o.n = 0;
  EXPECT_EQ(error_of(o), "alarm model: n must be in [1, 64], got 0");
  o = {};
  o.n = 65;
  EXPECT_EQ(error_of(o), "alarm model: n must be in [1, 64], got 65");
  o = {};
  o.alarm_k = 6;
  EXPECT_EQ(error_of(o), "alarm model: alarm_k must be in [1, n = 5], got 6");
  o = {};
  o.suspect_k = 3;
  EXPECT_EQ(error_of(o), "alarm model: suspect_k must be in [1, alarm_k = 2], got 3");
  o = {};
  o.suspect_k = 0;
  EXPECT_EQ(error_of(o), "alarm model: suspect_k must be in [1, alarm_k = 2], got 0");
  o = {};
  o.clear_level = 1.2;
  EXPECT_EQ(error_of(o), "alarm model: clear_level must be in (0, 1], got 1.200000");
  o = {};
  o.clear_level = NAN;
  EXPECT_EQ(error_of(o), "alarm model: clear_level must be in (0, 1], got nan");
  o = {};
  o.clear_blocks = 0;
  EXPECT_EQ(error_of(o), "alarm model: clear_blocks must be >= 1, got 0");
}

TEST(AlarmModelTest, StateRoundTripsAndInvalidStateIsNamed) {
  AlarmModel a = Make();
  a.Update(Block(0.0));
  a.Update(Block(2.0, 4));
  a.Update(Block(0.1, 1));
  const AlarmModelState s = a.State();
  EXPECT_EQ(s.state, S::kSuspected);
  EXPECT_EQ(s.exceed_bits, 0b10u);
  EXPECT_EQ(s.quiet_run, 1);
  EXPECT_EQ(s.votes, (std::vector<int>{4}));
  auto b = AlarmModel::FromState(s);
  ASSERT_TRUE(b.ok()) << b.error();
  EXPECT_EQ(b->status().latched_vote, 4);
  for (double score : {0.0, 0.9, 0.0, 0.0, 1.5, 1.5, 0.1}) {
    const AlarmStatus x = a.Update(Block(score, 2));
    const AlarmStatus y = b->Update(Block(score, 2));
    EXPECT_EQ(x.state, y.state);
    EXPECT_EQ(x.exceed_count, y.exceed_count);
    EXPECT_EQ(x.latched_vote, y.latched_vote);
    EXPECT_EQ(x.blocks_in_state, y.blocks_in_state);
  }

  auto error_of = [](const AlarmModelState& st) {
    auto r = AlarmModel::FromState(st);
    return r.ok() ? std::string("accepted") : r.error();
  };
  AlarmModelState bad = s;
  bad.options.alarm_k = 9;
  EXPECT_EQ(error_of(bad), "alarm model state: options.alarm_k must be in [1, n = 5], got 9");
  bad = s;
  bad.state = static_cast<S>(7);
  EXPECT_EQ(error_of(bad), "alarm model state: state is not a FaultState, got 7");
  bad = s;
  bad.exceed_bits = 1u << 5;
  EXPECT_EQ(error_of(bad), "alarm model state: exceed_bits has bits beyond the window n = 5");
  bad = s;
  bad.votes = {1, 2, 3, 4, 5, 6};
  EXPECT_EQ(error_of(bad), "alarm model state: votes must hold at most n = 5 entries, got 6");
  bad = s;
  bad.votes = {1, -1};
  EXPECT_EQ(error_of(bad), "alarm model state: votes[1] must be >= 0, got -1");
  bad = s;
  bad.quiet_run = -1;
  EXPECT_EQ(error_of(bad), "alarm model state: quiet_run must be >= 0, got -1");
}

TEST(AlarmModelTest, ResetGoesBackToLearning) {
  AlarmModel m = Make();
  Feed(m, {2.0, 2.0});
  m.Reset();
  EXPECT_EQ(m.status().state, S::kLearning);
  EXPECT_EQ(m.State().exceed_bits, 0u);
  EXPECT_EQ(Feed(m, {2.0}), (std::vector<S>{S::kSuspected}));
}

TEST(AlarmModelTest, ExpectedFractionsAreNaNOutsideTheirValidity) {
  AlarmOptions o;
  o.alarm_k = 3;
  EXPECT_TRUE(std::isnan(AlarmModel::ExpectedHealthyFractions(0.05, 0.1, o).alarm));
  EXPECT_TRUE(std::isnan(AlarmModel::ExpectedHealthyFractions(0.2, 0.1, {}).alarm));  // q < p
  // Small p = q: ~c^2 p^2.
  const double p = 1e-3;
  EXPECT_NEAR(AlarmModel::ExpectedHealthyFractions(p, p, {}).alarm, 9.0 * p * p, 0.02 * 9 * p * p);
}

TEST(AlarmModelTest, UpdateAllocatesNothing) {
  AlarmOptions o;
  o.n = 64;
  o.alarm_k = 10;
  AlarmModel m = Make(o);
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0.0, 2.0);
  std::vector<double> scores(5000);
  for (double& s : scores) s = u(rng);
  diagnosis_alloc::allocations = 0;
  diagnosis_alloc::counting = true;
  m.Update({true, 0.0, -1});
  int t = 0;
  for (double s : scores) m.Update(Block(s, t++ % 7));
  m.Update(Block(NAN));
  m.Reset();
  diagnosis_alloc::counting = false;
  EXPECT_EQ(diagnosis_alloc::allocations, 0);
  // The counter is live (see robust_baseline_test.cc): one allocation is seen.
  diagnosis_alloc::allocations = 0;
  diagnosis_alloc::counting = true;
  void* probe = ::operator new(16);
  diagnosis_alloc::counting = false;
  ::operator delete(probe);
  EXPECT_EQ(diagnosis_alloc::allocations, 1);
}

}  // namespace
}  // namespace gearpath
