#include "eval/closure_metrics.h"

#include <cmath>
#include <set>

#include "core/angles.h"

namespace semchain::eval {

LabelledCandidate LabelCandidate(const mapping::LoopClosureCandidate& candidate,
                                 const ClosureReference& reference,
                                 const ClosureLabelOptions& options) {
  LabelledCandidate labelled{candidate, ClosureLabel::kUnlabelled, 0.0, 0.0};
  if (candidate.from_scan < 0 || candidate.to_scan < 0) return labelled;
  const std::optional<Pose2> truth = reference.Relative(candidate.from_scan, candidate.to_scan);
  if (!truth) return labelled;
  const Pose2 error = truth->Between(candidate.relative);
  labelled.translation_error_m = std::hypot(error.x, error.y);
  labelled.rotation_error_rad = std::abs(NormalizeAngle(error.theta));
  const bool right = labelled.translation_error_m <= options.max_translation_meters &&
                     labelled.rotation_error_rad <= options.max_rotation_radians;
  labelled.label = right ? ClosureLabel::kTrue : ClosureLabel::kFalse;
  return labelled;
}

namespace {

void Count(const LabelledCandidate& c, StageCounts* counts) {
  ++counts->accepted;
  if (c.label == ClosureLabel::kTrue) ++counts->true_accepted;
  if (c.label == ClosureLabel::kFalse) ++counts->false_accepted;
  if (c.label == ClosureLabel::kUnlabelled) ++counts->unlabelled_accepted;
}

void Finish(int true_candidates, int true_searches, const std::set<int>& searches,
            StageCounts* counts) {
  const int labelled = counts->true_accepted + counts->false_accepted;
  if (labelled > 0) counts->precision = static_cast<double>(counts->true_accepted) / labelled;
  if (true_candidates > 0) {
    counts->recall = static_cast<double>(counts->true_accepted) / true_candidates;
  }
  counts->true_searches_accepted = static_cast<int>(searches.size());
  if (true_searches > 0) {
    counts->search_recall = static_cast<double>(searches.size()) / true_searches;
  }
}

bool Verified(const mapping::LoopClosureCandidate& c) {
  return c.verification == mapping::ClosureVerification::kAdded ||
         c.verification == mapping::ClosureVerification::kConfirmed;
}

}  // namespace

ClosureTable PrecisionRecall(const std::vector<LabelledCandidate>& candidates,
                             const std::vector<double>& thresholds, double min_weight) {
  ClosureTable table;
  table.candidates = static_cast<int>(candidates.size());
  std::set<int> true_searches;
  for (const LabelledCandidate& c : candidates) {
    if (c.label == ClosureLabel::kTrue) true_searches.insert(c.candidate.to);
    if (c.label == ClosureLabel::kTrue) ++table.true_candidates;
    if (c.label == ClosureLabel::kFalse) ++table.false_candidates;
    if (c.label == ClosureLabel::kUnlabelled) ++table.unlabelled;
  }
  table.true_searches = static_cast<int>(true_searches.size());
  for (const double threshold : thresholds) {
    ThresholdRow row;
    row.threshold = threshold;
    std::set<int> searches[3];  // per stage: nodes with a true candidate accepted
    const auto count = [&searches](const LabelledCandidate& c, int stage, StageCounts* counts) {
      Count(c, counts);
      if (c.label == ClosureLabel::kTrue) searches[stage].insert(c.candidate.to);
    };
    for (const LabelledCandidate& c : candidates) {
      if (c.candidate.score < threshold) continue;
      count(c, 0, &row.scored);
      if (!Verified(c.candidate)) continue;
      count(c, 1, &row.verified);
      if (c.candidate.in_graph && c.candidate.weight >= min_weight) count(c, 2, &row.back_end);
    }
    StageCounts* stages[3] = {&row.scored, &row.verified, &row.back_end};
    for (int stage = 0; stage < 3; ++stage) {
      Finish(table.true_candidates, table.true_searches, searches[stage], stages[stage]);
    }
    table.rows.push_back(row);
  }
  return table;
}

const char* ToString(ClosureLabel label) {
  switch (label) {
    case ClosureLabel::kTrue:
      return "true";
    case ClosureLabel::kFalse:
      return "false";
    case ClosureLabel::kUnlabelled:
      return "unlabelled";
  }
  return "?";
}

const char* ToString(mapping::ClosureVerification verification) {
  switch (verification) {
    case mapping::ClosureVerification::kNotReached:
      return "not_reached";
    case mapping::ClosureVerification::kAdded:
      return "added";
    case mapping::ClosureVerification::kConfirmed:
      return "confirmed";
    case mapping::ClosureVerification::kHeldBack:
      return "held_back";
  }
  return "?";
}

}  // namespace semchain::eval
